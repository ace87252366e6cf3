/* problems_graph_test.c - scenes with joints and OBJ line graphs: the scene
 * reader builds the rods, joints, constraints and loads the file says, and
 * every bad input (JSON joints, the "graph" block, the OBJ file it names)
 * gets ONE line "FILE: $.path: reason" (OBJ problems with the OBJ file and
 * line inside the reason).  Scenes are parsed from memory with the label
 * "DATA_DIR/scene.json", so OBJ paths resolve against DATA_DIR.
 * argv[1]: tests/data/obj.  ' stands for " in the scene texts. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"
#include "testutil.h"

static char label[1024];
static const char *data_dir;

#define MS                                       \
  "'materials': {'m': {'E': 1e3, 'nu': 0.25}}, " \
  "'sections': {'s': {'shape': 'circle', 'radius': 0.01}}"
#define GRAPH(obj, extra)                                                        \
  "'graph': {'obj': '" obj "', 'edges_per_rod': 4, 'material': 'm', 'section': " \
  "'s'" extra "}"

static char *unquote(const char *s) {
  size_t n = strlen(s);
  char *t = malloc(n + 1);
  for (size_t i = 0; i <= n; i++) t[i] = s[i] == '\'' ? '"' : s[i];
  return t;
}

static rn_scene *parse(rn_context *ctx, const char *text, rn_status *st) {
  char *t = unquote(text);
  rn_scene *s = NULL;
  *st = rn_scene_parse(ctx, label, t, strlen(t), &s);
  free(t);
  return s;
}

/* The 2 x 2 grid with rigid joints, a clamped and a displaced joint. */
static void check_square(rn_context *ctx) {
  rn_status st;
  rn_scene *s =
      parse(ctx,
            "{" MS ", " GRAPH("square_2x2.obj", ", 'joint_model': 'rigid', 'd1': [0, 0, "
                                                "1]") ", 'constraints': [{'type': "
                                                      "'displace', 'joint': 'v9', "
                                                      "'value': "
                                                      "[0.1, 0, 0]}, {'type': 'clamp', "
                                                      "'joint': 'v1'}, {'type': 'pin', "
                                                      "'joint': 'v9'}], 'loads': "
                                                      "[{'type': 'force', 'joint': 'v5', "
                                                      "'value': [0, 0, 2]}, {'type': "
                                                      "'moment', 'joint': 'v5', 'value': "
                                                      "[0, 0, 1]}]}",
            &st);
  CHECK_STATUS(st, RN_OK);
  if (!s) {
    fprintf(stderr, "%s\n", rn_context_last_error(ctx));
    return;
  }
  rn_network *net = rn_scene_network(s);
  CHECK(rn_network_num_rods(net) == 12);
  CHECK(rn_network_num_joints(net) == 9);
  for (int r = 0; r < 12; r++) {
    char name[16];
    snprintf(name, sizeof name, "e%d", r + 1);
    CHECK(rn_scene_find_rod(s, name) == r);
    CHECK(rn_network_rod_num_vertices(net, r) == 5);
  }
  /* e1 runs from OBJ vertex 1 to 2; e12 (the last polyline) from 6 to 9 */
  double x[15];
  CHECK_STATUS(rn_network_rod_initial_vertices(net, 0, x), RN_OK);
  CHECK(x[0] == 0 && x[1] == 0 && x[3] == 0.25 && x[12] == 1 && x[13] == 0);
  CHECK_STATUS(rn_network_rod_initial_vertices(net, 11, x), RN_OK);
  CHECK(x[0] == 2 && x[1] == 1 && x[12] == 2 && x[13] == 2);
  static const int valence[9] = {2, 3, 2, 3, 4, 3, 2, 3, 2};
  for (int j = 0; j < 9; j++) {
    char name[16];
    snprintf(name, sizeof name, "v%d", j + 1);
    CHECK(rn_scene_find_joint(s, name) == j);
    CHECK(strcmp(rn_network_joint_name(net, j), name) == 0);
    CHECK(rn_network_joint_valence(net, j) == valence[j]);
    CHECK(rn_network_joint_model(net, j) == RN_JOINT_RIGID);
  }
  /* 12 rods x (3 interior vertices + 4 angles) + 9 rigid joints x 6
   * - clamp v1 (6) - pin v9 (3) */
  CHECK(rn_network_num_dofs(net) == 12 * 13 + 9 * 6 - 9);
  double p[3], p0[3];
  CHECK_STATUS(rn_network_joint_position(net, 8, p), RN_OK);
  CHECK_STATUS(rn_scene_joint_initial_position(s, 8, p0), RN_OK);
  CHECK(p[0] == 2.1 && p[1] == 2 && p0[0] == 2 && p0[1] == 2);
  CHECK_STATUS(rn_scene_joint_initial_position(s, 9, p0), RN_ERR_RANGE);
  rn_scene_destroy(&s);
}

/* The tripod (one elastic joint, free feet) plus an explicit brace joined to
 * two feet by explicit joints. */
static void check_mixed(rn_context *ctx) {
  rn_status st;
  rn_scene *s = parse(
      ctx,
      "{" MS ", " GRAPH(
          "tripod.obj",
          "") ", 'rods': [{'name': 'brace', 'material': "
              "'m', 'section': 's', 'vertices': [[1, 0, 0], [-0.5, 0.8660254037844386, "
              "0]]}],"
              " 'joints': [{'name': 'f2', 'model': 'rigid', 'ends': [{'rod': 'e1', "
              "'end': "
              "'end'}, {'rod': 'brace', 'end': 'start'}]}, {'name': 'f3', 'ends': "
              "[{'rod': "
              "'brace', 'end': 'end'}, {'rod': 'e2', 'end': 'end'}]}],"
              " 'constraints': [{'type': 'clamp', 'rod': 'e3', 'end': 'end'}, {'type': "
              "'pin', 'joint': 'f2'}, {'type': 'clamp', 'joint': 'f3'}]}",
      &st);
  CHECK_STATUS(st, RN_OK);
  if (!s) {
    fprintf(stderr, "%s\n", rn_context_last_error(ctx));
    return;
  }
  rn_network *net = rn_scene_network(s);
  CHECK(rn_network_num_rods(net) == 4);
  CHECK(rn_network_num_joints(net) == 3);
  CHECK(rn_scene_find_rod(s, "brace") == 3);
  CHECK(rn_scene_find_joint(s, "v1") == 0 && rn_scene_find_joint(s, "f3") == 2);
  CHECK(rn_network_joint_valence(net, 0) == 3);
  CHECK(rn_network_joint_model(net, 0) == RN_JOINT_ELASTIC);
  CHECK(rn_network_joint_model(net, 1) == RN_JOINT_RIGID);
  CHECK(rn_network_joint_model(net, 2) == RN_JOINT_ELASTIC);
  /* e1..e3: 3 interior vertices + 4 angles each, e3 also its free foot (3),
   * of which its clamped last edge fixes 7 (two vertices, one angle); brace:
   * 1 angle; v1 (elastic) 3; f2 (rigid) 6 - 3 pinned; f3 (clamped) 0 */
  CHECK(rn_network_num_dofs(net) == 3 * 13 + 3 - 7 + 1 + 3 + 3);
  rn_scene_destroy(&s);
}

/* Component pins and displacements on joints and rod vertices: the fixed
 * components leave the reduced vector, the displacement moves the joint. */
static void check_components(rn_context *ctx) {
  static const char *const scenes[2] = {
      "{" MS ", " GRAPH("square_2x2.obj", "") "}",
      "{" MS ", " GRAPH(
          "square_2x2.obj",
          "") ", 'constraints': [{'type': 'pin', "
              "'joint': 'v9', 'components': ['x']}, {'type': 'displace', 'joint': 'v9', "
              "'value': [0.25, 0, 0], 'components': ['x']}, {'type': 'pin', 'joint': "
              "'v1', "
              "'components': ['y', 'z']}, {'type': 'pin', 'joint': 'v1', 'components': "
              "['z']}, "
              "{'type': 'pin', 'joint': 'v5'}, {'type': 'pin', 'joint': 'v5', "
              "'components': "
              "['x']}, {'type': 'pin', 'rod': 'e1', 'vertex': 1, 'components': ['z', "
              "'x']}, "
              "{'type': 'displace', 'rod': 'e1', 'vertex': 1, 'value': [0, 0, -0.5]}]}"};
  size_t n[2] = {0, 0};
  double p[3], p0[3];
  for (int k = 0; k < 2; k++) {
    rn_status st;
    rn_scene *s = parse(ctx, scenes[k], &st);
    CHECK_STATUS(st, RN_OK);
    if (!s) {
      fprintf(stderr, "%s\n", rn_context_last_error(ctx));
      return;
    }
    rn_network *net = rn_scene_network(s);
    n[k] = rn_network_num_dofs(net);
    if (k == 1) {
      double xyz[3 * 5];
      CHECK_STATUS(rn_network_joint_position(net, 8, p), RN_OK);
      CHECK_STATUS(rn_scene_joint_initial_position(s, 8, p0), RN_OK);
      CHECK(p[0] == p0[0] + 0.25 && p[1] == p0[1] && p[2] == p0[2]);
      CHECK_STATUS(rn_network_rod_vertices(net, 0, xyz), RN_OK);
      CHECK(xyz[5] == -0.5);
    }
    rn_scene_destroy(&s);
  }
  /* v9: x; v1: y, z; v5: all; e1 vertex 1: x, z */
  CHECK(n[1] == n[0] - 1 - 2 - 3 - 2);
}

typedef struct bad_case {
  const char *what, *scene;
  const char *where;  /* expected path after "LABEL: " */
  const char *reason; /* expected substring ("%s" = the data folder) */
} bad_case;

#define SQUARE(extra) "{" MS ", " GRAPH("square_2x2.obj", "") extra "}"
#define TRIPOD(extra) "{" MS ", " GRAPH("tripod.obj", "") extra "}"
#define ROD_A                                                                   \
  "{'name': 'a', 'material': 'm', 'section': 's', 'line': {'from': [0, 0, 0], " \
  "'to': [1, 0, 0], 'vertices': 3}}"
#define ROD_B                                                                   \
  "{'name': 'b', 'material': 'm', 'section': 's', 'line': {'from': [1, 0, 0], " \
  "'to': [1, 1, 0], 'vertices': 3}}"
#define ROD_C                                                                   \
  "{'name': 'c', 'material': 'm', 'section': 's', 'line': {'from': [2, 0, 0], " \
  "'to': [3, 0, 0], 'vertices': 3}}"
#define RODS(joints, extra) \
  "{" MS ", 'rods': [" ROD_A ", " ROD_B ", " ROD_C "], 'joints': [" joints "]" extra "}"
#define J_AB                                                                      \
  "{'name': 'j', 'model': 'rigid', 'ends': [{'rod': 'a', 'end': 'end'}, {'rod': " \
  "'b', 'end': 'start'}]}"

static const bad_case cases[] = {
    /* JSON joints */
    {"unknown model",
     RODS("{'name': 'j', 'model': 'welded', 'ends': [{'rod': 'a', 'end': 'end'}]}", ""),
     "$.joints[0].model",
     "unknown joint model \"welded\" (known: elastic, rigid, smooth)"},
    {"end used twice",
     RODS(J_AB ", {'name': 'k', 'ends': [{'rod': 'b', 'end': 'start'}]}", ""),
     "$.joints[1].ends[0]", "the start of rod \"b\" is already joined at joint \"j\""},
    {"end listed twice",
     RODS("{'name': 'j', 'ends': [{'rod': 'a', 'end': 'end'}, {'rod': 'a', 'end': "
          "'end'}]}",
          ""),
     "$.joints[0].ends[1]", "listed twice"},
    {"ends do not meet",
     RODS("{'name': 'j', 'ends': [{'rod': 'a', 'end': 'end'}, {'rod': 'c', 'end': "
          "'start'}]}",
          ""),
     "$.joints[0].ends[1]", "the rod ends do not meet: the start of rod \"c\""},
    {"unknown rod in a joint",
     RODS("{'name': 'j', 'ends': [{'rod': 'z', 'end': 'end'}]}", ""),
     "$.joints[0].ends[0].rod", "no rod named \"z\""},
    {"bad end", RODS("{'name': 'j', 'ends': [{'rod': 'a', 'end': 'middle'}]}", ""),
     "$.joints[0].ends[0].end", "expected \"start\" or \"end\""},
    {"no ends", RODS("{'name': 'j', 'ends': []}", ""), "$.joints[0].ends",
     "expected at least one rod end"},
    {"missing ends", RODS("{'name': 'j'}", ""), "$.joints[0]",
     "missing required key \"ends\""},
    {"joint without name", RODS("{'ends': [{'rod': 'a', 'end': 'end'}]}", ""),
     "$.joints[0]", "missing required key \"name\""},
    {"duplicate joint name",
     RODS(J_AB ", {'name': 'j', 'ends': [{'rod': 'c', 'end': 'end'}]}", ""),
     "$.joints[1].name", "duplicate joint name \"j\""},
    {"unknown joint key",
     RODS("{'name': 'j', 'stiffness': 1, 'ends': [{'rod': 'a', 'end': 'end'}]}", ""),
     "$.joints[0].stiffness", "unknown key"},
    {"coincident joints",
     RODS("{'name': 'j', 'ends': [{'rod': 'a', 'end': 'end'}]}, {'name': 'k', 'ends': "
          "[{'rod': 'b', 'end': 'start'}]}",
          ""),
     "$.joints[0]", "coincident"},
    /* constraints and loads on joints */
    {"unknown joint", RODS(J_AB, ", 'constraints': [{'type': 'clamp', 'joint': 'q'}]"),
     "$.constraints[0].joint", "no joint named \"q\" (joints: \"j\")"},
    {"no joints at all",
     "{" MS ", 'rods': [" ROD_A "], 'loads': [{'type': 'force', 'joint': 'q', 'value': "
     "[1, 0, 0]}]}",
     "$.loads[0].joint", "no joint named \"q\" (the scene has no joints)"},
    {"rod and joint",
     RODS(J_AB,
          ", 'constraints': [{'type': 'pin', 'joint': 'j', 'rod': 'a', 'vertex': 0}]"),
     "$.constraints[0]", "give either \"rod\" or \"joint\", not both"},
    {"joint clamp with end",
     RODS(J_AB, ", 'constraints': [{'type': 'clamp', 'joint': 'j', 'end': 'start'}]"),
     "$.constraints[0].end", "unknown key \"end\" (allowed here: type, joint)"},
    {"clamp a rod end at a joint",
     RODS(J_AB, ", 'constraints': [{'type': 'clamp', 'rod': 'b', 'end': 'start'}]"),
     "$.constraints[0].end",
     "the start of rod \"b\" belongs to joint \"j\": constrain the joint instead"},
    {"pin a joint vertex",
     RODS(J_AB, ", 'constraints': [{'type': 'pin', 'rod': 'a', 'vertex': -1}]"),
     "$.constraints[0].vertex", "vertex 2 of rod \"a\" belongs to joint \"j\""},
    {"displace a joint vertex",
     RODS(J_AB,
          ", 'constraints': [{'type': 'displace', 'rod': 'a', 'vertex': 2, 'value': "
          "[0, 0, 1]}]"),
     "$.constraints[0].vertex", "belongs to joint \"j\""},
    {"displace a free joint",
     RODS(J_AB,
          ", 'constraints': [{'type': 'displace', 'joint': 'j', 'value': [1, 0, 0]}]"),
     "$.constraints[0]", "joint \"j\" is not pinned or clamped"},
    {"rotate a pinned joint",
     RODS(J_AB, ", 'constraints': [{'type': 'pin', 'joint': 'j'}, {'type': 'displace', "
                "'joint': 'j', 'rotation': [0, 0, 1]}]"),
     "$.constraints[1]", "not clamped (a rotation needs a clamp)"},
    {"displace a joint by nothing",
     RODS(J_AB, ", 'constraints': [{'type': 'clamp', 'joint': 'j'}, {'type': 'displace', "
                "'joint': 'j'}]"),
     "$.constraints[1]", "give \"value\""},
    {"joint pin with a bad component",
     RODS(J_AB, ", 'constraints': [{'type': 'pin', 'joint': 'j', 'components': ['q']}]"),
     "$.constraints[0].components[0]", "expected a component \"x\", \"y\" or \"z\""},
    {"joint pin with no components",
     RODS(J_AB, ", 'constraints': [{'type': 'pin', 'joint': 'j', 'components': []}]"),
     "$.constraints[0].components", "expected a non-empty array"},
    {"joint pin with a duplicate component",
     RODS(J_AB,
          ", 'constraints': [{'type': 'pin', 'joint': 'j', 'components': ['y', 'y']}]"),
     "$.constraints[0].components[1]", "component \"y\" is listed twice"},
    {"joint clamp with components",
     RODS(J_AB,
          ", 'constraints': [{'type': 'clamp', 'joint': 'j', 'components': ['x']}]"),
     "$.constraints[0].components",
     "unknown key \"components\" (allowed here: type, joint)"},
    {"displace a joint along a free component",
     RODS(J_AB, ", 'constraints': [{'type': 'pin', 'joint': 'j', 'components': ['x', "
                "'y']}, {'type': 'displace', 'joint': 'j', 'value': [0, 0, 0.2]}]"),
     "$.constraints[1]",
     "joint \"j\" is not pinned in [\"z\"] (pinned: [\"x\", \"y\"]): add {\"type\": "
     "\"pin\", \"joint\": \"j\", \"components\": [\"z\"]}"},
    {"displace a joint outside its components",
     RODS(J_AB, ", 'constraints': [{'type': 'pin', 'joint': 'j'}, {'type': 'displace', "
                "'joint': 'j', 'value': [0, 0.1, 0.2], 'components': ['y']}]"),
     "$.constraints[1].value[2]", "does not list \"z\""},
    {"fix_theta on a joint",
     RODS(J_AB, ", 'constraints': [{'type': 'fix_theta', 'joint': 'j', 'edge': 0}]"),
     "$.constraints[0].joint", "unknown key \"joint\" (allowed here: type, rod, edge)"},
    {"force on a joint with vertex",
     RODS(J_AB,
          ", 'loads': [{'type': 'force', 'joint': 'j', 'vertex': 0, 'value': [1, 0, "
          "0]}]"),
     "$.loads[0].vertex", "unknown key \"vertex\""},
    {"moment on a joint without value",
     RODS(J_AB, ", 'loads': [{'type': 'moment', 'joint': 'j'}]"), "$.loads[0]",
     "missing required key \"value\""},
    {"force without target",
     RODS(J_AB, ", 'loads': [{'type': 'force', 'value': [1, 0, 0]}]"), "$.loads[0]",
     "missing required key \"rod\" (or \"joint\")"},
    /* the graph block */
    {"neither rods nor graph", "{" MS "}", "$",
     "missing required key \"rods\" (or \"graph\""},
    {"missing obj file", "{" MS ", " GRAPH("none.obj", "") "}", "$.graph.obj",
     "%s/none.obj: cannot open"},
    {"not a regular file", "{" MS ", " GRAPH(".", "") "}", "$.graph.obj",
     "%s/.: not a regular file"},
    {"empty obj name", "{" MS ", " GRAPH("", "") "}", "$.graph.obj",
     "expected a non-empty file name"},
    {"bad OBJ", "{" MS ", " GRAPH("bad_index.obj", "") "}", "$.graph.obj",
     "%s/bad_index.obj:6: vertex index 5 is out of range (the file defines 3 vertices)"},
    {"zero edges per rod",
     "{" MS ", 'graph': {'obj': 'tripod.obj', 'edges_per_rod': 0, 'material': 'm', "
     "'section': 's'}}",
     "$.graph.edges_per_rod", "expected an integer in [1, 1000000], got 0"},
    {"graph without material",
     "{" MS ", 'graph': {'obj': 'tripod.obj', 'edges_per_rod': 2, 'section': 's'}}",
     "$.graph", "missing required key \"material\""},
    {"graph unknown section",
     "{" MS ", 'graph': {'obj': 'tripod.obj', 'edges_per_rod': 2, "
     "'material': 'm', 'section': 'x'}}",
     "$.graph.section", "unknown section \"x\""},
    {"graph unknown key", "{" MS ", " GRAPH("tripod.obj", ", 'scale': 2") "}",
     "$.graph.scale", "unknown key \"scale\""},
    {"graph bad joint model",
     "{" MS ", " GRAPH("tripod.obj", ", 'joint_model': 'glue'") "}",
     "$.graph.joint_model", "unknown joint model \"glue\""},
    {"d1 parallel to a segment",
     "{" MS ", " GRAPH("square_2x2.obj", ", 'd1': [1, 0, 0]") "}", "$.graph.d1",
     "%s/square_2x2.obj:14: segment e1: the material axis d1 is parallel"},
    {"d1 zero", "{" MS ", " GRAPH("tripod.obj", ", 'd1': [0, 0, 0]") "}", "$.graph.d1",
     "zero vector"},
    {"graph rod name clash",
     TRIPOD(", 'rods': [{'name': 'e2', 'material': 'm', 'section': "
            "'s', 'vertices': [[5, 0, 0], [6, 0, 0]]}]"),
     "$.rods[0].name", "duplicate rod name \"e2\""},
    {"graph joint name clash",
     TRIPOD(", 'joints': [{'name': 'v1', 'ends': [{'rod': 'e1', 'end': 'end'}]}]"),
     "$.joints[0].name", "duplicate joint name \"v1\""},
    {"explicit joint at a graph joint",
     TRIPOD(", 'joints': [{'name': 'top', 'ends': [{'rod': 'e1', 'end': 'start'}]}]"),
     "$.joints[0].ends[0]", "the start of rod \"e1\" is already joined at joint \"v1\""},
    {"clamp a graph rod at a graph joint",
     TRIPOD(", 'constraints': [{'type': 'clamp', 'rod': 'e2', 'end': 'start'}]"),
     "$.constraints[0].end", "the start of rod \"e2\" belongs to joint \"v1\""},
    {"unknown graph joint", SQUARE(", 'constraints': [{'type': 'pin', 'joint': 'v10'}]"),
     "$.constraints[0].joint", "no joint named \"v10\""},
    {"coincident graph joints", "{" MS ", " GRAPH("near_coincident.obj", "") "}",
     "$.graph", "%s/near_coincident.obj:3: joint v1: "},
};

static void check_case(rn_context *ctx, const bad_case *c) {
  rn_status st;
  rn_scene *s = parse(ctx, c->scene, &st);
  const char *msg = rn_context_last_error(ctx);
  char where[1200], reason[1200];
  snprintf(where, sizeof where, "%s: %s: ", label, c->where);
  const char *mark = strstr(c->reason, "%s"); /* the data folder */
  if (mark)
    snprintf(reason, sizeof reason, "%.*s%s%s", (int)(mark - c->reason), c->reason,
             data_dir, mark + 2);
  else
    snprintf(reason, sizeof reason, "%s", c->reason);
  int ok = st < 0 && s == NULL && strncmp(msg, where, strlen(where)) == 0 &&
           strstr(msg, reason) != NULL && strchr(msg, '\n') == NULL;
  CHECK(ok);
  if (!ok) fprintf(stderr, "case '%s': status %d, message: %s\n", c->what, (int)st, msg);
  rn_scene_destroy(&s);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: problems_graph_test DATA_DIR\n");
    return 2;
  }
  data_dir = argv[1];
  snprintf(label, sizeof label, "%s/scene.json", data_dir);
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  check_square(ctx);
  check_mixed(ctx);
  check_components(ctx);
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) check_case(ctx, &cases[i]);
  rn_context_destroy(&ctx);
  return rn_test_finish("problems_graph");
}

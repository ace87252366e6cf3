/* problems_scene_errors_test.c - every class of bad scene gets a non-zero
 * status and ONE line "bad.json: $.json.path: reason" (malformed JSON:
 * "bad.json:LINE:COL: ...").  Scenes are written with ' for " (swapped at
 * run time) to keep them readable. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"
#include "testutil.h"

#define MS                                          \
  "'materials': {'steel': {'E': 1e7, 'nu': 0.5}}, " \
  "'sections': {'wire': {'shape': 'circle', 'radius': 0.01}}"
#define ROD_BODY                             \
  "'material': 'steel', 'section': 'wire', " \
  "'line': {'from': [0, 0, 0], 'to': [1, 0, 0], 'vertices': 11}"
#define ROD "{'name': 'beam', " ROD_BODY "}"
#define SCENE(extra) "{" MS ", 'rods': [" ROD "]" extra "}"
#define WITH_ROD(rod) "{" MS ", 'rods': [" rod "]}"
/* a periodic cell: the rod's end at the image [1, 0] of its start */
#define CELL(vectors, extra)                                           \
  "{'periodic': {'vectors': " vectors extra "}, " MS ", 'rods': [" ROD \
  "], 'joints': [{'name': 'j', 'ends': [{'rod': 'beam', 'end': "       \
  "'start'}, {'rod': 'beam', 'end': 'end', 'image': [1, 0]}]}]}"
#define SQUARE "[[1, 0, 0], [0, 1, 0]]"
#define WITH_IMAGE(per, image)                                                         \
  "{" per MS ", 'rods': [" ROD "], 'joints': [{'name': 'j', 'ends': [{'rod': 'beam', " \
  "'end': 'start'}, {'rod': 'beam', 'end': 'end', 'image': " image "}]}]}"
#define WITH_MAT(mat)                                                 \
  "{'materials': {'steel': " mat "}, 'sections': {'wire': {'shape': " \
  "'circle', 'radius': 0.01}}, 'rods': [" ROD "]}"
#define WITH_SEC(sec)                                            \
  "{'materials': {'steel': {'E': 1e7, 'nu': 0.5}}, 'sections': " \
  "{'wire': " sec "}, 'rods': [" ROD "]}"

typedef struct bad_case {
  const char *what;
  const char *scene;  /* ' stands for " */
  const char *where;  /* expected prefix after "bad.json" (path or :line:) */
  const char *reason; /* expected substring of the reason */
} bad_case;

static const bad_case cases[] = {
    /* malformed JSON */
    {"syntax error", "{'materials': {,}}", ":1:17: ", "malformed JSON"},
    {"second line", "{\n  'rods': [1,, 2]}", ":2:14: ", "malformed JSON"},
    {"truncated", "{'rods': [", ":1:11: ", "unexpected end of file"},
    {"trailing garbage", SCENE("") " x", ":", "malformed JSON"},
    {"empty file", "  \n ", ": ", "the file is empty"},
    {"NaN literal", "{'a': NaN}", ":1:", "malformed JSON"},
    /* structure */
    {"root not an object", "[1]", ": $: ", "expected an object, got an array of 1"},
    {"unknown top-level key", SCENE(", 'rodz': []"),
     ": $.rodz: ", "unknown key \"rodz\""},
    {"case-sensitive keys", "{" MS ", 'Rods': []}", ": $.Rods: ", "unknown key"},
    {"missing rods", "{" MS "}", ": $: ", "missing required key \"rods\""},
    {"missing materials", "{'rods': []}", ": $: ", "missing required key \"materials\""},
    {"duplicate key", "{" MS ", 'rods': [" ROD "], 'rods': [" ROD "]}",
     ": $.rods: ", "duplicate key \"rods\""},
    {"empty rods", "{" MS ", 'rods': []}", ": $.rods: ", "expected at least one rod"},
    {"rods not an array", "{" MS ", 'rods': {}}",
     ": $.rods: ", "expected an array, got an object"},
    {"rod not an object", "{" MS ", 'rods': [3]}",
     ": $.rods[0]: ", "expected an object, got 3"},
    {"constraints not an array", SCENE(", 'constraints': 1"),
     ": $.constraints: ", "expected an array, got 1"},
    /* materials */
    {"no materials", "{'materials': {}, 'sections': {}, 'rods': []}",
     ": $.materials: ", "expected at least one material"},
    {"negative E", WITH_MAT("{'E': -1e7, 'nu': 0.3}"),
     ": $.materials.steel.E: ", "expected a number > 0, got -10000000"},
    {"zero G", WITH_MAT("{'E': 1e7, 'G': 0}"),
     ": $.materials.steel.G: ", "expected a number > 0, got 0"},
    {"E as a string", WITH_MAT("{'E': 'big', 'nu': 0.3}"),
     ": $.materials.steel.E: ", "got the string \"big\""},
    {"infinite E", WITH_MAT("{'E': 1e999, 'nu': 0.3}"),
     ": $.materials.steel.E: ", "out of range"},
    {"nu and G", WITH_MAT("{'E': 1e7, 'nu': 0.3, 'G': 1e6}"),
     ": $.materials.steel: ", "exactly one of \"nu\""},
    {"neither nu nor G", WITH_MAT("{'E': 1e7}"),
     ": $.materials.steel: ", "exactly one of"},
    {"nu too large", WITH_MAT("{'E': 1e7, 'nu': 0.7}"), ": $.materials.steel.nu: ",
     "expected a number in (-1, 0.5], got 0.69999999999999996"},
    {"negative density", WITH_MAT("{'E': 1e7, 'nu': 0.3, 'density': -1}"),
     ": $.materials.steel.density: ", "expected a number >= 0"},
    {"unknown material key", WITH_MAT("{'E': 1e7, 'nu': 0.3, 'rho': 1}"),
     ": $.materials.steel.rho: ", "unknown key \"rho\""},
    /* sections */
    {"unknown shape", WITH_SEC("{'shape': 'square', 'side': 1}"),
     ": $.sections.wire.shape: ", "unknown shape \"square\""},
    {"negative radius", WITH_SEC("{'shape': 'circle', 'radius': -0.01}"),
     ": $.sections.wire.radius: ", "expected a number > 0, got -0.01"},
    {"hollow inner >= outer",
     WITH_SEC("{'shape': 'hollow_circle', 'outer_radius': 0.01, 'inner_radius': 0.02}"),
     ": $.sections.wire.inner_radius: ", "expected a number < outer_radius"},
    {"ellipse missing b", WITH_SEC("{'shape': 'ellipse', 'a': 0.01}"),
     ": $.sections.wire: ", "missing required key \"b\""},
    {"rectangle with radius",
     WITH_SEC("{'shape': 'rectangle', 'width': 1, 'height': 1, "
              "'radius': 1}"),
     ": $.sections.wire.radius: ", "unknown key \"radius\""},
    {"explicit missing J", WITH_SEC("{'A': 1, 'I11': 1, 'I22': 1}"),
     ": $.sections.wire: ", "missing required key \"J\""},
    {"explicit indefinite", WITH_SEC("{'A': 1, 'I11': 1, 'I22': 1, 'I12': 2, 'J': 1}"),
     ": $.sections.wire.I12: ", "not positive definite"},
    {"explicit negative I22", WITH_SEC("{'A': 1, 'I11': 1, 'I22': -1, 'J': 1}"),
     ": $.sections.wire.I22: ", "expected a number > 0"},
    /* rods */
    {"rod without name", WITH_ROD("{" ROD_BODY "}"),
     ": $.rods[0]: ", "missing required key \"name\""},
    {"empty rod name", WITH_ROD("{'name': '', " ROD_BODY "}"),
     ": $.rods[0].name: ", "non-empty"},
    {"duplicate rod name", WITH_ROD(ROD ", " ROD),
     ": $.rods[1].name: ", "duplicate rod name \"beam\""},
    {"unknown rod key", WITH_ROD("{'name': 'beam', 'colour': 'red', " ROD_BODY "}"),
     ": $.rods[0].colour: ", "unknown key \"colour\""},
    {"unknown material",
     WITH_ROD("{'name': 'b', 'material': 'stel', 'section': 'wire', "
              "'vertices': [[0,0,0],[1,0,0]]}"),
     ": $.rods[0].material: ", "unknown material \"stel\" (defined: \"steel\")"},
    {"unknown section",
     WITH_ROD("{'name': 'b', 'material': 'steel', 'section': 'wir', "
              "'vertices': [[0,0,0],[1,0,0]]}"),
     ": $.rods[0].section: ", "unknown section \"wir\""},
    {"line and vertices",
     WITH_ROD("{'name': 'b', " ROD_BODY ", 'vertices': [[0,0,0],[1,0,0]]}"),
     ": $.rods[0]: ", "exactly one of \"line\""},
    {"no geometry", WITH_ROD("{'name': 'b', 'material': 'steel', 'section': 'wire'}"),
     ": $.rods[0]: ", "exactly one of \"line\""},
    {"one vertex",
     WITH_ROD("{'name': 'b', 'material': 'steel', 'section': 'wire', "
              "'line': {'from': [0,0,0], 'to': [1,0,0], 'vertices': 1}}"),
     ": $.rods[0].line.vertices: ", "expected an integer >= 2, got 1"},
    {"fractional vertex count",
     WITH_ROD("{'name': 'b', 'material': 'steel', 'section': 'wire', "
              "'line': {'from': [0,0,0], 'to': [1,0,0], 'vertices': 2.5}}"),
     ": $.rods[0].line.vertices: ", "expected an integer >= 2, got 2.5"},
    {"from == to",
     WITH_ROD("{'name': 'b', 'material': 'steel', 'section': 'wire', "
              "'line': {'from': [1,2,3], 'to': [1,2,3], 'vertices': 5}}"),
     ": $.rods[0].line: ", "coincide"},
    {"short point",
     WITH_ROD("{'name': 'b', 'material': 'steel', 'section': 'wire', "
              "'line': {'from': [0,0], 'to': [1,0,0], 'vertices': 5}}"),
     ": $.rods[0].line.from: ", "expected an array of 3 numbers, got an array of 2"},
    {"zero-length edge",
     WITH_ROD("{'name': 'b', 'material': 'steel', 'section': 'wire', "
              "'vertices': [[0,0,0],[1,0,0],[1,0,0],[2,0,0]]}"),
     ": $.rods[0].vertices[2]: ", "edge 1 has zero length"},
    {"fold back",
     WITH_ROD("{'name': 'b', 'material': 'steel', 'section': 'wire', "
              "'vertices': [[0,0,0],[1,0,0],[0.5,0,0]]}"),
     ": $.rods[0].vertices[2]: ", "opposite directions"},
    {"single vertex list",
     WITH_ROD("{'name': 'b', 'material': 'steel', 'section': 'wire', "
              "'vertices': [[0,0,0]]}"),
     ": $.rods[0].vertices: ", "expected at least 2 vertices, got 1"},
    {"infinite coordinate",
     WITH_ROD("{'name': 'b', 'material': 'steel', 'section': 'wire', "
              "'vertices': [[0,0,0],[-1e400,0,0]]}"),
     ": $.rods[0].vertices[1][0]: ", "expected a finite number"},
    {"vertex not a point",
     WITH_ROD("{'name': 'b', 'material': 'steel', 'section': 'wire', "
              "'vertices': [[0,0,0],[1,0,0,4]]}"),
     ": $.rods[0].vertices[1]: ", "expected an array of 3 numbers, got an array of 4"},
    {"d1 parallel", WITH_ROD("{'name': 'b', " ROD_BODY ", 'd1': [2, 0, 0]}"),
     ": $.rods[0].d1: ", "parallel to the rod's first edge"},
    {"d1 zero", WITH_ROD("{'name': 'b', " ROD_BODY ", 'd1': [0, 0, 0]}"),
     ": $.rods[0].d1: ", "zero vector"},
    {"rest curvature size",
     WITH_ROD("{'name': 'b', " ROD_BODY ", 'rest': {'curvature': "
              "[[0,0],[0,0]]}}"),
     ": $.rods[0].rest.curvature: ",
     "expected 9 entries (one per interior vertex), got 2"},
    {"rest curvature pair",
     WITH_ROD("{'name': 'b', " ROD_BODY ", 'rest': {'curvature': "
              "[[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0,0],[0]]}}"),
     ": $.rods[0].rest.curvature[8]: ",
     "expected an array of 2 numbers, got an array of 1"},
    {"rest twist type", WITH_ROD("{'name': 'b', " ROD_BODY ", 'rest': {'twist': 1}}"),
     ": $.rods[0].rest.twist: ", "expected an array, got 1"},
    {"rest lengths size",
     WITH_ROD("{'name': 'b', " ROD_BODY ", 'rest': {'lengths': [1, 1]}}"),
     ": $.rods[0].rest.lengths: ", "expected 10 entries (one per edge), got 2"},
    {"rest length negative",
     WITH_ROD("{'name': 'b', " ROD_BODY ", 'rest': {'lengths': "
              "[1,1,1,-1,1,1,1,1,1,1]}}"),
     ": $.rods[0].rest.lengths[3]: ", "expected a number > 0, got -1"},
    {"rest unknown key", WITH_ROD("{'name': 'b', " ROD_BODY ", 'rest': {'strain': []}}"),
     ": $.rods[0].rest.strain: ", "unknown key"},
    {"edge range out of bounds",
     WITH_ROD("{'name': 'b', " ROD_BODY ", 'edge_properties': [{'edges': [0, 10], "
              "'material': 'steel'}]}"),
     ": $.rods[0].edge_properties[0].edges[1]: ", "edge index 10 is out of range"},
    {"edge range reversed",
     WITH_ROD("{'name': 'b', " ROD_BODY ", 'edge_properties': [{'edges': [5, 2], "
              "'material': 'steel'}]}"),
     ": $.rods[0].edge_properties[0].edges: ", "first edge 5 comes after last edge 2"},
    {"edge range length",
     WITH_ROD("{'name': 'b', " ROD_BODY ", 'edge_properties': [{'edges': [5], "
              "'material': 'steel'}]}"),
     ": $.rods[0].edge_properties[0].edges: ", "expected [first, last]"},
    {"edge properties empty",
     WITH_ROD("{'name': 'b', " ROD_BODY ", 'edge_properties': [{'edge': -1}]}"),
     ": $.rods[0].edge_properties[0]: ", "give \"material\" and/or \"section\""},
    {"edge properties section",
     WITH_ROD("{'name': 'b', " ROD_BODY
              ", 'edge_properties': [{'edge': 3, 'section': 'x'}]}"),
     ": $.rods[0].edge_properties[0].section: ", "unknown section \"x\""},
    /* constraints */
    {"clamp on a missing rod",
     SCENE(", 'constraints': [{'type': 'clamp', 'rod': 'bam', "
           "'end': 'start'}]"),
     ": $.constraints[0].rod: ", "no rod named \"bam\" (rods: \"beam\")"},
    {"clamp without rod", SCENE(", 'constraints': [{'type': 'clamp', 'end': 'start'}]"),
     ": $.constraints[0]: ", "missing required key \"rod\""},
    {"clamp bad end",
     SCENE(", 'constraints': [{'type': 'clamp', 'rod': 'beam', "
           "'end': 'middle'}]"),
     ": $.constraints[0].end: ", "expected \"start\" or \"end\", got \"middle\""},
    {"unknown constraint", SCENE(", 'constraints': [{'type': 'weld', 'rod': 'beam'}]"),
     ": $.constraints[0].type: ", "unknown constraint type \"weld\""},
    {"constraint without type", SCENE(", 'constraints': [{'rod': 'beam'}]"),
     ": $.constraints[0]: ", "missing required key \"type\""},
    {"pin out of range",
     SCENE(", 'constraints': [{'type': 'pin', 'rod': 'beam', 'vertex': 11}]"),
     ": $.constraints[0].vertex: ", "vertex index 11 is out of range for rod \"beam\""},
    {"pin negative out of range",
     SCENE(", 'constraints': [{'type': 'pin', 'rod': 'beam', 'vertex': -12}]"),
     ": $.constraints[0].vertex: ", "vertex index -12 is out of range"},
    {"pin fractional",
     SCENE(", 'constraints': [{'type': 'pin', 'rod': 'beam', 'vertex': 1.5}]"),
     ": $.constraints[0].vertex: ", "expected an integer"},
    {"fix_theta out of range",
     SCENE(", 'constraints': [{'type': 'fix_theta', 'rod': 'beam', 'edge': 10}]"),
     ": $.constraints[0].edge: ", "edge index 10 is out of range"},
    {"displace a free end",
     SCENE(", 'constraints': [{'type': 'displace', 'rod': 'beam', 'end': 'end', "
           "'value': [0, 0, 1]}]"),
     ": $.constraints[0]: ", "the end of rod \"beam\" is not clamped"},
    {"displace a free vertex",
     SCENE(", 'constraints': [{'type': 'pin', 'rod': 'beam', 'vertex': 4}, "
           "{'type': 'displace', 'rod': 'beam', 'vertex': 5, 'value': [0, 0, 1]}]"),
     ": $.constraints[1]: ", "vertex 5 of rod \"beam\" is free"},
    {"rotate a vertex",
     SCENE(", 'constraints': [{'type': 'pin', 'rod': 'beam', 'vertex': 5}, "
           "{'type': 'displace', 'rod': 'beam', 'vertex': 5, 'rotation': [0, 0, 1]}]"),
     ": $.constraints[1].rotation: ", "a rotation applies to a clamped end"},
    {"displace nothing",
     SCENE(", 'constraints': [{'type': 'clamp', 'rod': 'beam', 'end': 'start'}, "
           "{'type': 'displace', 'rod': 'beam', 'end': 'start'}]"),
     ": $.constraints[1]: ", "give \"value\""},
    {"displace end and vertex",
     SCENE(", 'constraints': [{'type': 'displace', 'rod': 'beam', 'end': 'start', "
           "'vertex': 0, 'value': [0,0,0]}]"),
     ": $.constraints[0]: ", "exactly one of \"end\""},
/* "components" of a pin / displace on a rod vertex */
#define PIN5(comp) "{'type': 'pin', 'rod': 'beam', 'vertex': 5, 'components': " comp "}"
/* A pin of vertex 5 with components comp, an error at components`at`. */
#define COMP(what, comp, at, reason)                    \
  {                                                     \
    what, SCENE(", 'constraints': [" PIN5(comp) "]"),   \
        ": $.constraints[0].components" at ": ", reason \
  }
    COMP("components empty", "[]", "",
         "expected a non-empty array of distinct components \"x\", \"y\", \"z\", got an "
         "array of 0"),
    COMP("components a string", "'x'", "", "expected a non-empty array"),
    COMP("components an object", "{'x': 1}", "", "expected a non-empty array"),
    COMP("components null", "null", "", "expected a non-empty array"),
    COMP("components duplicate", "['x', 'z', 'x']", "[2]",
         "component \"x\" is listed twice"),
    COMP("components unknown letter", "['x', 'w']", "[1]",
         "expected a component \"x\", \"y\" or \"z\", got the string \"w\""),
    COMP("components upper case", "['X']", "[0]", "expected a component"),
    COMP("components joined letters", "['xy']", "[0]", "expected a component"),
    COMP("components empty string", "['']", "[0]", "expected a component"),
    COMP("components a number", "[0]", "[0]",
         "expected a component \"x\", \"y\" or \"z\", got 0"),
#undef COMP
    {"components on a clamp",
     SCENE(", 'constraints': [{'type': 'clamp', 'rod': 'beam', 'end': 'start', "
           "'components': ['x']}]"),
     ": $.constraints[0].components: ", "unknown key \"components\""},
    {"components on fix_theta",
     SCENE(", 'constraints': [{'type': 'fix_theta', 'rod': 'beam', 'edge': 0, "
           "'components': ['x']}]"),
     ": $.constraints[0].components: ", "unknown key \"components\""},
    {"components on a clamped end's motion",
     SCENE(", 'constraints': [{'type': 'clamp', 'rod': 'beam', 'end': 'start'}, "
           "{'type': 'displace', 'rod': 'beam', 'end': 'start', 'value': [1, 0, 0], "
           "'components': ['x']}]"),
     ": $.constraints[1].components: ",
     "\"components\" applies to a pinned vertex or joint"},
    {"displace along a free component",
     SCENE(", 'constraints': [" PIN5("['x']") ", {'type': 'displace', 'rod': 'beam', "
                                              "'vertex': 5, 'value': [0.1, 0.5, 0]}]"),
     ": $.constraints[1]: ",
     "vertex 5 of rod \"beam\" is not pinned in [\"y\"] (pinned: [\"x\"]): add "
     "{\"type\": \"pin\", \"rod\": \"beam\", \"vertex\": 5, \"components\": [\"y\"]}"},
    {"displace components not pinned",
     SCENE(", 'constraints': [" PIN5(
         "['x']") ", {'type': 'displace', 'rod': 'beam', "
                  "'vertex': 5, 'value': [0, 0, 0], 'components': ['x', 'z']}]"),
     ": $.constraints[1]: ", "is not pinned in [\"z\"] (pinned: [\"x\"])"},
    {"displace value outside components",
     SCENE(", 'constraints': [" PIN5("['x', 'y']") ", {'type': 'displace', 'rod': "
                                                   "'beam', 'vertex': 5, 'value': [0.1, "
                                                   "0.5, 0], 'components': ['x']}]"),
     ": $.constraints[1].value[1]: ",
     "the displacement along y is 0.5, but \"components\" does not list \"y\""},
    {"displace bad components",
     SCENE(", 'constraints': [" PIN5(
         "['x']") ", {'type': 'displace', 'rod': 'beam', "
                  "'vertex': 5, 'value': [0.1, 0, 0], 'components': ['x', 'x']}]"),
     ": $.constraints[1].components[1]: ", "listed twice"},
#undef PIN5
    /* loads */
    {"unknown load", SCENE(", 'loads': [{'type': 'pressure', 'value': 1}]"),
     ": $.loads[0].type: ", "unknown load type \"pressure\""},
    {"force without value",
     SCENE(", 'loads': [{'type': 'force', 'rod': 'beam', 'vertex': -1}]"),
     ": $.loads[0]: ", "missing required key \"value\""},
    {"force value length",
     SCENE(
         ", 'loads': [{'type': 'force', 'rod': 'beam', 'vertex': -1, 'value': [0, 1]}]"),
     ": $.loads[0].value: ", "expected an array of 3 numbers, got an array of 2"},
    {"force infinite",
     SCENE(", 'loads': [{'type': 'force', 'rod': 'beam', 'vertex': -1, 'value': [0, 0, "
           "1e999]}]"),
     ": $.loads[0].value[2]: ", "expected a finite number"},
    {"moment on a missing vertex",
     SCENE(", 'loads': [{'type': 'moment', 'rod': 'beam', 'vertex': 20, 'value': [0, 0, "
           "1]}]"),
     ": $.loads[0].vertex: ", "vertex index 20 is out of range"},
    {"unknown moment model",
     SCENE(", 'loads': [{'type': 'moment', 'rod': 'beam', 'vertex': -1, 'value': [0, 0, "
           "1], 'model': 'follower'}]"),
     ": $.loads[0].model: ",
     "unknown moment model \"follower\" (known: conservative, fixed)"},
    {"moment model not a string",
     SCENE(", 'loads': [{'type': 'moment', 'rod': 'beam', 'vertex': -1, 'value': [0, 0, "
           "1], 'model': 1}]"),
     ": $.loads[0].model: ", "expected a string"},
    {"model on a force",
     SCENE(", 'loads': [{'type': 'force', 'rod': 'beam', 'vertex': -1, 'value': [0, 0, "
           "1], 'model': 'fixed'}]"),
     ": $.loads[0].model: ", "unknown key \"model\""},
    {"unknown couple model on a joint",
     "{" MS ", 'rods': [" ROD ", {'name': 'b2', 'material': 'steel', 'section': 'wire', "
     "'line': {'from': [1, 0, 0], 'to': [1, 1, 0], 'vertices': 5}}], 'joints': [{'name': "
     "'j', 'ends': [{'rod': 'beam', 'end': 'end'}, {'rod': 'b2', 'end': 'start'}]}], "
     "'loads': [{'type': 'moment', 'joint': 'j', 'value': [0, 0, 1], 'model': "
     "'follower'}]}",
     ": $.loads[0].model: ",
     "unknown moment model \"follower\" (known: conservative, fixed)"},
    {"line load with vertex",
     SCENE(", 'loads': [{'type': 'line_load', 'rod': 'beam', 'vertex': 1, 'value': "
           "[0,0,1]}]"),
     ": $.loads[0].vertex: ", "unknown key \"vertex\""},
    {"gravity without density",
     SCENE(", 'loads': [{'type': 'gravity', 'value': [0, 0, -9.81]}]"),
     ": $.loads[0]: ", "no rod's material has a \"density\" > 0"},
    /* solver block */
    {"unknown solver", SCENE(", 'solver': {'method': 'newton'}"),
     ": $.solver.method: ", "unknown solver \"newton\""},
    {"unknown factorization", SCENE(", 'solver': {'factorization': 'lu'}"),
     ": $.solver.factorization: ", "unknown factorization \"lu\""},
    {"factorization not a string", SCENE(", 'solver': {'factorization': 2}"),
     ": $.solver.factorization: ", "expected a string"},
    {"unknown preconditioner", SCENE(", 'solver': {'preconditioner': 'ilu'}"),
     ": $.solver.preconditioner: ",
     "unknown preconditioner \"ilu\" (known: auto, factor, local, gathered, dd, muelu, "
     "ifpack2, frosch, dd-amg)"},
    {"predictor not a boolean", SCENE(", 'solver': {'predictor': 1}"),
     ": $.solver.predictor: ", "expected true or false"},
    {"zero iterations", SCENE(", 'solver': {'max_iterations': 0}"),
     ": $.solver.max_iterations: ", "expected an integer >= 1, got 0"},
    {"negative gtol", SCENE(", 'solver': {'gtol': -1e-9}"),
     ": $.solver.gtol: ", "expected a number > 0"},
    {"unknown solver key", SCENE(", 'solver': {'tolerance': 1}"),
     ": $.solver.tolerance: ", "unknown key"},
    /* periodic cells */
    {"periodic not an object", SCENE(", 'periodic': 1"),
     ": $.periodic: ", "expected an object"},
    {"periodic without vectors", SCENE(", 'periodic': {}"),
     ": $.periodic: ", "missing required key \"vectors\""},
    {"unknown periodic key", CELL(SQUARE, ", 'repeet': [2, 2]"),
     ": $.periodic.repeet: ", "unknown key"},
    {"one lattice vector", CELL("[[1, 0, 0]]", ""), ": $.periodic.vectors: ",
     "expected 2 lattice vectors (a 2D cell) or 3 (a 3D cell), got 1"},
    {"four lattice vectors", CELL("[[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1]]", ""),
     ": $.periodic.vectors: ", "got 4"},
    {"short lattice vector", CELL("[[1, 0, 0], [0, 1]]", ""),
     ": $.periodic.vectors[1]: ", "expected an array of 3 numbers"},
    {"degenerate cell", CELL("[[1, 0, 0], [2, 0, 0]]", ""),
     ": $.periodic.vectors: ", "degenerate"},
    {"2D cell out of plane", CELL("[[1, 0, 0], [0, 1, 0.5]]", ""),
     ": $.periodic.vectors: ", "must lie in the xy plane"},
    {"strain count", CELL(SQUARE, ", 'strain': [0.01, null]"),
     ": $.periodic.strain: ", "expected 3 strain components"},
    {"strain not a number", CELL(SQUARE, ", 'strain': [0.01, 'a', null]"),
     ": $.periodic.strain[1]: ", "expected a finite number"},
    {"stress count", CELL(SQUARE, ", 'stress': [1, 2]"),
     ": $.periodic.stress: ", "expected an array of 3 numbers"},
    {"repeat count", CELL(SQUARE, ", 'repeat': [2]"),
     ": $.periodic.repeat: ", "expected 2 repeat counts"},
    {"repeat zero", CELL(SQUARE, ", 'repeat': [2, 0]"),
     ": $.periodic.repeat[1]: ", "expected an integer"},
    {"repeat too large", CELL(SQUARE, ", 'repeat': [1000, 1000]"),
     ": $.periodic.repeat: ", "at most 100000"},
    {"image without a cell", WITH_IMAGE("", "[1, 0]"),
     ": $.joints[0].ends[1].image: ", "an image needs a periodic cell"},
    {"image count", WITH_IMAGE("'periodic': {'vectors': " SQUARE "}, ", "[1, 0, 0]"),
     ": $.joints[0].ends[1].image: ", "expected 2 lattice shifts"},
    {"image not an integer",
     WITH_IMAGE("'periodic': {'vectors': " SQUARE "}, ", "[0.5, 0]"),
     ": $.joints[0].ends[1].image[0]: ", "integer"},
    {"end not at its image",
     WITH_IMAGE("'periodic': {'vectors': " SQUARE "}, ", "[0, 1]"),
     ": $.joints[0].ends[1]: ", "do not meet"},
};

static char *unquote(const char *s) {
  size_t n = strlen(s);
  char *t = malloc(n + 1);
  for (size_t i = 0; i <= n; i++) t[i] = s[i] == '\'' ? '"' : s[i];
  return t;
}

static void check_case(rn_context *ctx, const bad_case *c) {
  char *text = unquote(c->scene);
  rn_scene *s = (rn_scene *)1;
  rn_status st = rn_scene_parse(ctx, "bad.json", text, strlen(text), &s);
  const char *msg = rn_context_last_error(ctx);
  char expect[256];
  snprintf(expect, sizeof expect, "bad.json%s", c->where);
  CHECK(st < 0);
  CHECK(s == NULL);
  CHECK(strncmp(msg, expect, strlen(expect)) == 0);
  CHECK(strstr(msg, c->reason) != NULL);
  CHECK(strchr(msg, '\n') == NULL);
  if (st >= 0 || strncmp(msg, expect, strlen(expect)) != 0 || !strstr(msg, c->reason))
    fprintf(stderr, "case '%s': status %d, message: %s\n", c->what, (int)st, msg);
  rn_scene_destroy(&s);
  free(text);
}

/* A NUL byte inside the text and very deep nesting. */
static void check_special(rn_context *ctx) {
  const char text[] = "{\"rods\": []}\0{}";
  rn_scene *s = NULL;
  CHECK(rn_scene_parse(ctx, "bad.json", text, sizeof text - 1, &s) == RN_ERR_PARSE);
  CHECK(strstr(rn_context_last_error(ctx), "bad.json:1:13: NUL byte") != NULL);
  size_t depth = 5000;
  char *deep = malloc(2 * depth + 1);
  for (size_t i = 0; i < depth; i++) {
    deep[i] = '[';
    deep[depth + i] = ']';
  }
  deep[2 * depth] = '\0';
  CHECK(rn_scene_parse(ctx, "bad.json", deep, 2 * depth, &s) == RN_ERR_PARSE);
  CHECK(strstr(rn_context_last_error(ctx), "malformed JSON") != NULL);
  free(deep);
  CHECK(rn_scene_load(ctx, "/nonexistent/dir/scene.json", &s) == RN_ERR_IO);
  CHECK(
      strstr(rn_context_last_error(ctx), "/nonexistent/dir/scene.json: cannot open: ") ==
      rn_context_last_error(ctx));
  CHECK(s == NULL);
}

int main(void) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) check_case(ctx, &cases[i]);
  check_special(ctx);
  /* The base scene itself is fine (the cases above each break one thing). */
  char *good = unquote(SCENE(", 'constraints': [{'type': 'clamp', 'rod': 'beam', "
                             "'end': 'start'}]"));
  rn_scene *s = NULL;
  CHECK_STATUS(rn_scene_parse(ctx, "good.json", good, strlen(good), &s), RN_OK);
  CHECK(s != NULL);
  rn_scene_destroy(&s);
  CHECK(s == NULL);
  free(good);
  rn_context_destroy(&ctx);
  return rn_test_finish("problems_scene_errors");
}

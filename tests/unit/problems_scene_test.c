/* problems_scene_test.c - the scene reader builds what the file says:
 * sizes, negative indices, per-edge properties, rest shape, loads, solver
 * block (checked through the energy terms at the initial state against
 * hand-computed values), and every example scene given on the command line
 * loads.  ' stands for " in the scene text. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"
#include "testutil.h"

static const char *scene_text =
    "{'description': 'reader test',"
    " 'materials': {'soft': {'E': 2, 'G': 1},"
    "               'heavy': {'E': 2, 'G': 1, 'density': 3}},"
    " 'sections': {'round': {'shape': 'circle', 'radius': 0.1},"
    "              'box': {'A': 0.5, 'I11': 2, 'I22': 3, 'I12': 0.5, 'J': 4}},"
    " 'rods': ["
    "  {'name': 's', 'material': 'soft', 'section': 'round',"
    "   'vertices': [[0, 0, 0], [1, 0, 0], [2, 0, 0]],"
    "   'edge_properties': [{'edge': -1, 'section': 'box'}],"
    "   'rest': {'lengths': [2, 2]}},"
    "  {'name': 'b', 'material': 'soft', 'section': 'box',"
    "   'vertices': [[0, 1, 0], [1, 1, 0], [2, 1, 0]], 'd1': [0, 0, 1],"
    "   'rest': {'curvature': [[0.3, -0.2]]}},"
    "  {'name': 't', 'material': 'soft', 'section': 'box',"
    "   'line': {'from': [0, 2, 0], 'to': [2, 2, 0], 'vertices': 3},"
    "   'rest': {'twist': [0.1]}},"
    "  {'name': 'g', 'material': 'heavy', 'section': 'round',"
    "   'line': {'from': [0, 3, 1], 'to': [2, 3, 1], 'vertices': 3}}],"
    " 'constraints': ["
    "  {'type': 'displace', 'rod': 's', 'vertex': -1, 'value': [0.5, 0, 0]},"
    "  {'type': 'pin', 'rod': 's', 'vertex': -1},"
    "  {'type': 'fix_theta', 'rod': 'b', 'edge': -1},"
    "  {'type': 'clamp', 'rod': 't', 'end': 'start'},"
    "  {'type': 'pin', 'rod': 'g', 'vertex': 0}],"
    " 'loads': ["
    "  {'type': 'force', 'rod': 's', 'vertex': -1, 'value': [1, 0, 0]},"
    "  {'type': 'gravity', 'value': [0, 0, -10]}],"
    " 'solver': {'method': 'rol-tr-tcg', 'max_iterations': 7, 'gtol': 1e-7,"
    "            'load_steps': 3, 'factorization': 'cholmod', 'preconditioner': "
    "'factor'}}";

static char *unquote(const char *s) {
  size_t n = strlen(s);
  char *t = malloc(n + 1);
  for (size_t i = 0; i <= n; i++) t[i] = s[i] == '\'' ? '"' : s[i];
  return t;
}

static void check_energy_terms(rn_network *net) {
  const double pi = 3.14159265358979323846, A_round = pi * 0.01;
  size_t n = rn_network_num_dofs(net);
  double *x = malloc(n * sizeof *x), E[RN_TERM_COUNT];
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_energy_terms(net, x, E), RN_OK);
  /* rod s: edge 0 (round) l = 1, lbar = 2; edge 1 (box, A = 0.5) l = 1.5
   * (last vertex displaced by 0.5), lbar = 2: 1/2 E A (l - lbar)^2 / lbar. */
  CHECK_REL(E[RN_TERM_STRETCH], 0.5 * 2 * A_round * 1.0 / 2 + 0.5 * 2 * 0.5 * 0.25 / 2,
            1e-13);
  /* rod b: 1/2 E kbar^T I kbar / vlen with vlen = 1. */
  CHECK_REL(E[RN_TERM_BEND], 0.5 * 2 * (2 * 0.09 + 2 * 0.5 * 0.3 * -0.2 + 3 * 0.04),
            1e-13);
  /* rod t: 1/2 G J taubar^2 / vlen. */
  CHECK_REL(E[RN_TERM_TWIST], 0.5 * 1 * 4 * 0.01, 1e-13);
  /* load potentials from the initial state: the force (1, 0, 0) on the last vertex
   * of s, displaced from x = 2 to 2.5: -0.5; gravity on g, which does not move:
   * 0. */
  CHECK_REL(E[RN_TERM_LOAD], -1.0 * (2.5 - 2.0), 1e-13);
  free(x);
}

static void check_reader(rn_context *ctx) {
  char *text = unquote(scene_text);
  rn_scene *s = NULL;
  CHECK_STATUS(rn_scene_parse(ctx, "reader.json", text, strlen(text), &s), RN_OK);
  free(text);
  if (!s) {
    fprintf(stderr, "%s\n", rn_context_last_error(ctx));
    return;
  }
  rn_network *net = rn_scene_network(s);
  CHECK(strcmp(rn_scene_label(s), "reader.json") == 0);
  CHECK(strcmp(rn_scene_description(s), "reader test") == 0);
  CHECK(rn_network_num_rods(net) == 4);
  CHECK(rn_scene_num_vertices(s) == 12);
  CHECK(rn_scene_find_rod(s, "t") == 2);
  CHECK(rn_scene_find_rod(s, "x") == -1);
  CHECK(strcmp(rn_network_rod_name(net, 3), "g") == 0);
  /* 4 rods x 11 DOFs - pin 3 - fix_theta 1 - clamp 7 - pin 3. */
  CHECK(rn_network_num_dofs(net) == 44 - 14);
  double xyz[9];
  CHECK_STATUS(rn_network_rod_vertices(net, 0, xyz), RN_OK);
  CHECK_NEAR(xyz[6], 2.5, 1e-15); /* vertex -1 displaced */
  CHECK_NEAR(xyz[0], 0.0, 1e-15);
  check_energy_terms(net);

  rn_solve_options opt;
  memset(&opt, 0, sizeof opt);
  opt.krylov_tol = 0.25;
  rn_scene_apply_solver(s, &opt);
  CHECK(opt.solver == RN_SOLVER_ROL_TR_TCG);
  CHECK(opt.max_iterations == 7);
  CHECK(opt.factorization == RN_FACTOR_CHOLMOD);
  CHECK(opt.preconditioner == RN_PRECOND_FACTOR);
  CHECK(opt.gtol_rel == 1e-7);
  CHECK(opt.load_steps == 3);
  CHECK(opt.krylov_tol == 0.25); /* not in the block: untouched */
  CHECK(opt.gtol_abs == 0.0);
  rn_scene_destroy(&s);
  CHECK(s == NULL);
  rn_scene_destroy(&s); /* NULL is fine */
  rn_scene_destroy(NULL);
}

/* The example: 101 vertices, clamp (7 DOFs), tip force. */
static void check_cantilever(rn_context *ctx, const char *path) {
  rn_scene *s = NULL;
  CHECK_STATUS(rn_scene_load(ctx, path, &s), RN_OK);
  if (!s) return;
  rn_network *net = rn_scene_network(s);
  CHECK(rn_network_num_rods(net) == 1);
  CHECK(rn_network_rod_num_vertices(net, 0) == 101);
  CHECK(rn_network_num_dofs(net) == 4 * 101 - 1 - 7);
  size_t n = rn_network_num_dofs(net);
  double *x = malloc(n * sizeof *x), E[RN_TERM_COUNT];
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_energy_terms(net, x, E), RN_OK);
  CHECK_NEAR(E[RN_TERM_STRETCH] + E[RN_TERM_BEND] + E[RN_TERM_TWIST], 0.0, 1e-30);
  CHECK_NEAR(E[RN_TERM_LOAD], 0.0, 1e-30); /* tip at z = 0 */
  double d1[3 * 100];
  CHECK_STATUS(rn_network_rod_frames(net, 0, d1, NULL), RN_OK);
  CHECK_NEAR(d1[1], 1.0, 1e-15); /* "d1": [0, 1, 0] */
  free(x);
  rn_scene_destroy(&s);
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  check_reader(ctx);
  for (int i = 1; i < argc; i++) {
    rn_scene *s = NULL;
    rn_status st = rn_scene_load(ctx, argv[i], &s);
    CHECK_STATUS(st, RN_OK);
    if (st) fprintf(stderr, "%s\n", rn_context_last_error(ctx));
    CHECK(s && strcmp(rn_scene_label(s), argv[i]) == 0);
    CHECK(s && rn_scene_num_vertices(s) >= 2);
    if (s && strstr(argv[i], "cantilever.json")) check_cantilever(ctx, argv[i]);
    rn_scene_destroy(&s);
  }
  rn_context_destroy(&ctx);
  return rn_test_finish("problems_scene");
}

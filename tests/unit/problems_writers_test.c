/* problems_writers_test.c - the result JSON and VTK writers on a scene's
 * initial state (no solver needed): the JSON parses, holds every field with
 * the right values, and round-trips the coordinates exactly (%.17g).
 * argv: SCENE.json RESULT.json OUT.vtu (the .vtu is checked by
 * check_vtu.py in a dependent test). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cjson/cJSON.h>

#include "scene/result_json.h"
#include "scene/scene.h"
#include "testutil.h"
#include "scene/vtk.h"

static cJSON *read_json(const char *path) {
  FILE *f = fopen(path, "rb");
  if (!f) return NULL;
  static char buf[1 << 20];
  size_t n = fread(buf, 1, sizeof buf - 1, f);
  fclose(f);
  buf[n] = '\0';
  return cJSON_Parse(buf);
}

static double num(const cJSON *o, const char *key) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
  return cJSON_IsNumber(v) ? v->valuedouble : NAN;
}

static const char *str(const cJSON *o, const char *key) {
  const cJSON *v = cJSON_GetObjectItemCaseSensitive(o, key);
  return cJSON_IsString(v) ? v->valuestring : "";
}

static void check_rods(const cJSON *root, rn_network *net) {
  const cJSON *rods = cJSON_GetObjectItemCaseSensitive(root, "rods");
  CHECK(cJSON_GetArraySize(rods) == rn_network_num_rods(net));
  const cJSON *rod = cJSON_GetArrayItem(rods, 0);
  int nv = rn_network_rod_num_vertices(net, 0);
  CHECK(strcmp(str(rod, "name"), rn_network_rod_name(net, 0)) == 0);
  CHECK(num(rod, "num_vertices") == nv);
  const cJSON *verts = cJSON_GetObjectItemCaseSensitive(rod, "vertices");
  const cJSON *theta = cJSON_GetObjectItemCaseSensitive(rod, "theta");
  CHECK(cJSON_GetArraySize(verts) == nv);
  CHECK(cJSON_GetArraySize(theta) == nv - 1);
  double *x = malloc(3 * (size_t)nv * sizeof *x);
  CHECK_STATUS(rn_network_rod_vertices(net, 0, x), RN_OK);
  int exact = 1;
  for (int i = 0; i < nv; i++) {
    const cJSON *p = cJSON_GetArrayItem(verts, i);
    exact &= cJSON_GetArraySize(p) == 3;
    for (int k = 0; k < 3; k++)
      exact &= cJSON_GetArrayItem(p, k) &&
               cJSON_GetArrayItem(p, k)->valuedouble == x[3 * i + k];
  }
  CHECK(exact);
  for (int i = 0; i + 1 < nv; i++)
    CHECK(cJSON_GetArrayItem(theta, i)->valuedouble == 0.0);
  free(x);
}

int main(int argc, char **argv) {
  if (argc < 4) {
    fprintf(stderr, "usage: %s SCENE.json RESULT.json OUT.vtu\n", argv[0]);
    return 2;
  }
  rn_context *ctx = NULL;
  rn_scene *s = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  CHECK_STATUS(rn_scene_load(ctx, argv[1], &s), RN_OK);
  if (!s) return rn_test_finish("problems_writers");
  rn_network *net = rn_scene_network(s);
  static const long part_dofs[2] = {30, 40}, part_stencils[2] = {50, 60};
  rn_result_info info = {
      "max_iterations",
      "tr-minres",
      "sparse",
      "max_iterations",
      0,
      3,
      1,
      10,
      11,
      12,
      13,
      14,
      -0.125,
      1.0 / 3.0,
      2.5,
      0.75,
      2,
      1e-9,
      4.0,
      2e-8,
      3e-10,
      1.5,
      4e-9,
      "factor",
      "local minimum",
      2,
      part_dofs,
      part_stencils,
      7,
      1.25,
      12,
      0.5,
      0.25,
      0.125,
      {1, -2.5e-3, 40.0, 0, 2, 3, 0.5, RN_STABILITY_CHOLESKY, 0, 0.0, 1, 1, 0},
      NULL};
  remove(argv[2]);
  CHECK_STATUS(rn_result_write_json(ctx, argv[2], s, &info), RN_OK);
  CHECK_STATUS(rn_vtk_write(ctx, argv[3], s), RN_OK);
  cJSON *root = read_json(argv[2]);
  CHECK(root != NULL);
  if (root) {
    CHECK(strcmp(str(root, "status"), "max_iterations") == 0);
    CHECK(strcmp(str(root, "solver"), "tr-minres") == 0);
    CHECK(strcmp(str(root, "factorization"), "sparse") == 0);
    CHECK(num(root, "factorizations") == 12);
    {
      const cJSON *tm = cJSON_GetObjectItemCaseSensitive(root, "timing");
      CHECK(tm != NULL);
      CHECK(num(tm, "hessian_s") == 0.5);
      CHECK(num(tm, "preconditioner_setup_s") == 0.25);
      CHECK(num(tm, "preconditioner_apply_s") == 0.125);
    }
    const cJSON *stab = cJSON_GetObjectItemCaseSensitive(root, "stability");
    CHECK(cJSON_IsObject(stab));
    if (stab) {
      CHECK(cJSON_IsTrue(cJSON_GetObjectItemCaseSensitive(stab, "checked")));
      CHECK(cJSON_IsFalse(cJSON_GetObjectItemCaseSensitive(stab, "verified_minimum")));
      CHECK(num(stab, "lowest_eigenvalue") == -2.5e-3);
      CHECK(num(stab, "scale") == 40.0);
      CHECK(num(stab, "zero_modes") == 2);
      CHECK(num(stab, "symmetries") == 1);
      CHECK(num(stab, "soft_modes") == 1);
      CHECK(num(stab, "soft_positive") == 0);
      CHECK(num(stab, "factorizations") == 3);
      CHECK(num(stab, "time_s") == 0.5);
    }
    CHECK(strcmp(str(root, "preconditioner"), "factor") == 0);
    CHECK(strcmp(str(root, "finds"), "local minimum") == 0);
    CHECK(strcmp(str(root, "stop_reason"), "max_iterations") == 0);
    CHECK(strcmp(str(root, "scene"), argv[1]) == 0);
    CHECK(strcmp(str(root, "rodnet_version"), rn_version_string()) == 0);
    CHECK(cJSON_IsFalse(cJSON_GetObjectItemCaseSensitive(root, "converged")));
    CHECK(num(root, "energy") == -0.125);
    CHECK(num(root, "gradient_norm") == 1.0 / 3.0); /* %.17g round-trips */
    CHECK(num(root, "initial_gradient_norm") == 2.5);
    CHECK(num(root, "time_s") == 0.75);
    CHECK(num(root, "iterations") == 3);
    CHECK(num(root, "load_steps") == 1);
    CHECK(num(root, "predictor_steps") == 2);
    const cJSON *eq = cJSON_GetObjectItemCaseSensitive(root, "equilibrium");
    CHECK(num(eq, "force_residual") == 1e-9 && num(eq, "force_scale") == 4.0 &&
          num(eq, "force_tolerance") == 2e-8 && num(eq, "moment_residual") == 3e-10 &&
          num(eq, "moment_scale") == 1.5 && num(eq, "moment_tolerance") == 4e-9);
    CHECK(num(eq, "relative_force_residual") == 1e-9 / 4.0 &&
          num(eq, "relative_moment_residual") == 3e-10 / 1.5);
    CHECK(num(root, "load_factor") == 1.0);
    CHECK(num(root, "num_dofs") == (double)rn_network_num_dofs(net));
    const cJSON *ev = cJSON_GetObjectItemCaseSensitive(root, "evaluations");
    CHECK(num(ev, "energy") == 10 && num(ev, "gradient") == 11 && num(ev, "hvp") == 12 &&
          num(ev, "hessian") == 13 && num(ev, "krylov_iterations") == 14);
    const cJSON *terms = cJSON_GetObjectItemCaseSensitive(root, "energy_terms");
    CHECK(num(terms, "stretch") == 0 && num(terms, "bend") == 0 &&
          num(terms, "twist") == 0);
    CHECK(isfinite(num(terms, "load")));
    const cJSON *part = cJSON_GetObjectItemCaseSensitive(root, "partition");
    const cJSON *pd = cJSON_GetObjectItemCaseSensitive(part, "owned_dofs");
    const cJSON *ps = cJSON_GetObjectItemCaseSensitive(part, "owned_stencils");
    CHECK(num(part, "ranks") == 2 && num(part, "edge_cut") == 7 &&
          num(part, "imbalance") == 1.25);
    CHECK(cJSON_GetArraySize(pd) == 2 && cJSON_GetArrayItem(pd, 0)->valuedouble == 30 &&
          cJSON_GetArrayItem(pd, 1)->valuedouble == 40);
    CHECK(cJSON_GetArraySize(ps) == 2 && cJSON_GetArrayItem(ps, 0)->valuedouble == 50 &&
          cJSON_GetArrayItem(ps, 1)->valuedouble == 60);
    check_rods(root, net);
    cJSON_Delete(root);
  }
  /* A NaN in the result: no file, and the previous one is kept intact. */
  info.energy = NAN;
  CHECK_STATUS(rn_result_write_json(ctx, argv[2], s, &info), RN_ERR_NOT_FINITE);
  /* issue 22 item 2: the message names the file and the field */
  CHECK(strstr(rn_context_last_error(ctx), argv[2]) != NULL);
  CHECK(strstr(rn_context_last_error(ctx), "energy is nan (not a finite number); no file "
                                           "written") != NULL);
  root = read_json(argv[2]);
  CHECK(root != NULL && num(root, "energy") == -0.125);
  cJSON_Delete(root);
  char fresh[1024];
  snprintf(fresh, sizeof fresh, "%s.nan.json", argv[2]);
  remove(fresh);
  CHECK_STATUS(rn_result_write_json(ctx, fresh, s, &info), RN_ERR_NOT_FINITE);
  FILE *f = fopen(fresh, "rb");
  CHECK(f == NULL);
  if (f) fclose(f);
  /* issue 22 item 2: a state far out of range overflows the derived fields; the
   * VTK writer refuses it, naming the file, the array and the rod */
  info.energy = -0.125;
  size_t ndof = rn_network_num_dofs(net);
  double *x = malloc((ndof ? ndof : 1) * sizeof *x);
  CHECK(x != NULL && rn_network_get_dofs(net, x) == RN_OK);
  x[0] = 1e300;
  CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK);
  free(x);
  /* (the JSON writer stops earlier: the energy terms refuse such a state) */
  CHECK(rn_result_write_json(ctx, fresh, s, &info) != RN_OK);
  f = fopen(fresh, "rb");
  CHECK(f == NULL);
  if (f) fclose(f);
  char vtu[1024];
  snprintf(vtu, sizeof vtu, "%s.nan.vtu", argv[3]);
  remove(vtu);
  CHECK_STATUS(rn_vtk_write(ctx, vtu, s), RN_ERR_NOT_FINITE);
  CHECK(strstr(rn_context_last_error(ctx), vtu) != NULL);
  CHECK(strstr(rn_context_last_error(ctx), "array \"") != NULL);
  CHECK(strstr(rn_context_last_error(ctx), "of rod \"") != NULL);
  f = fopen(vtu, "rb");
  CHECK(f == NULL);
  if (f) fclose(f);
  rn_scene_destroy(&s);
  rn_context_destroy(&ctx);
  return rn_test_finish("problems_writers");
}

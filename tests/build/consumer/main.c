/* consumer.c - a small outside program using an installed rodnet: builds a
 * clamped 5-vertex rod with a tip load, finalizes it, and checks the DOF count,
 * the energy and gradient at rest and (when the library has the solver) that a
 * solve converges and moves the tip down.  Exit 0 on success. */
#include <math.h>
#include <rodnet.h>
#include <stdio.h>
#include <string.h>
#ifdef RN_HAVE_SOLVER
#include <rodnet_solve.h>
#endif

#define NV 5

static int fail(const char *what, rn_context *ctx) {
  fprintf(stderr, "consumer: %s failed: %s\n", what,
          ctx ? rn_context_last_error(ctx) : "");
  return 1;
}

static int check_rest(rn_network *net, rn_context *ctx) {
  /* 4 NV - 1 DOFs, minus the clamp (2 vertices and one angle). */
  size_t n = rn_network_num_dofs(net);
  if (n != 4 * NV - 1 - 7) return fail("num_dofs", ctx);
  double x[4 * NV], g[4 * NV], E = -1.0;
  if (rn_network_get_dofs(net, x) != RN_OK) return fail("get_dofs", ctx);
  if (rn_network_energy(net, x, &E) != RN_OK) return fail("energy", ctx);
  if (fabs(E) > 1e-12) return fail("energy at rest is zero", ctx);
  if (rn_network_gradient(net, x, &E, g) != RN_OK) return fail("gradient", ctx);
  /* At rest only the dead load contributes: |grad| = |f| = 0.39. */
  double gn = 0.0;
  for (size_t i = 0; i < n; ++i) gn += g[i] * g[i];
  if (fabs(sqrt(gn) - 0.39) > 1e-9) return fail("gradient at rest equals the load", ctx);
  printf("consumer: %zu dofs, energy at rest %g, |grad| %.6g\n", n, E, sqrt(gn));
  return 0;
}

#ifdef RN_HAVE_SOLVER
static int check_solve(rn_network *net, rn_context *ctx) {
  rn_solve_options opt;
  rn_solve_report rep;
  rn_solve_options_default(&opt);
  if (rn_solve(net, &opt, &rep) != RN_OK || !rep.converged) return fail("rn_solve", ctx);
  double xyz[3 * NV];
  if (rn_network_rod_vertices(net, 0, xyz) != RN_OK) return fail("rod_vertices", ctx);
  if (!(xyz[3 * NV - 1] < 0.0)) return fail("tip moves down", ctx);
  printf("consumer: solved in %d iterations, tip z = %.6g\n", rep.iterations,
         xyz[3 * NV - 1]);
  return 0;
}
#endif

int main(void) {
  if (strcmp(rn_version_string(), RODNET_VERSION_STRING) != 0) {
    fprintf(stderr, "consumer: header %s vs library %s\n", RODNET_VERSION_STRING,
            rn_version_string());
    return 1;
  }
  rn_context *ctx = NULL;
  rn_network *net = NULL;
  if (rn_context_create(&ctx) != RN_OK) return fail("context_create", NULL);
  double xyz[3 * NV] = {0};
  for (int i = 0; i < NV; ++i) xyz[3 * i] = 0.25 * i;
  const double d1[3] = {0, 1, 0}, f[3] = {0, 0, -0.39};
  rn_material mat;
  rn_section sec;
  int rod = -1, rc = 1;
  if (rn_network_create(ctx, &net) != RN_OK ||
      rn_network_add_rod(net, "beam", NV, xyz, d1, &rod) != RN_OK ||
      rn_material_from_E_nu(1.0e7, 0.5, 0.0, &mat) != RN_OK ||
      rn_section_circle(0.01, &sec) != RN_OK ||
      rn_network_set_material(net, rod, -1, &mat) != RN_OK ||
      rn_network_set_section(net, rod, -1, &sec) != RN_OK ||
      rn_network_clamp(net, rod, RN_START) != RN_OK ||
      rn_network_add_force(net, rod, -1, f) != RN_OK ||
      rn_network_finalize(net) != RN_OK) {
    rc = fail("building the rod", ctx);
  } else {
    rc = check_rest(net, ctx);
#ifdef RN_HAVE_SOLVER
    if (rc == 0) rc = check_solve(net, ctx);
#endif
  }
  rn_network_destroy(&net);
  rn_context_destroy(&ctx);
  if (rc == 0) printf("consumer: ok\n");
  return rc;
}

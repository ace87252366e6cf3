/* shim_equilibrium.c - the stopping test certifies equilibrium on a physical scale
 * (issue 8): a steel strip (E = 2e11, 10 x 1 mm, 0.3 m, 121 vertices) clamped at
 * both ends, its end clamp moved by (-0.06, 0, 0.04) in one step: the starting
 * gradient is about 5.5e7, and a test relative to it stopped at |g| = 0.035
 * (problems/scenes/strip_displaced.json is the same strip).  Checked:
 *  - converged by the gradient test with the force residual within its tolerance
 *    and below 1e-8 of the force scale (the reactions, about 82 N);
 *  - the reactions balance (no loads), and a solve along another path (no
 *    predictor) gives the same reactions (relative difference < 1e-7);
 *  - the report's scales: force scale = the largest reaction force, moment scale
 *    = the largest reaction moment or force scale times the strip's length;
 *  - gtol_abs is a requirement, not an alternative: an unreachable gtol_abs keeps
 *    the gradient test from passing;
 *  - every solver kind reports the residual on the same scale. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "shim_rods.h"

enum { NV = 121 };

static rn_network *strip(rn_context *ctx) {
  rn_network *net = NULL;
  rn_material m;
  rn_section s;
  int rod = -1;
  double xyz[3 * NV];
  const double d1[3] = {0, 1, 0}, disp[3] = {-0.06, 0.0, 0.04};
  for (int i = 0; i < NV; ++i)
    xyz[3 * i] = 0.3 * i / (NV - 1.0), xyz[3 * i + 1] = xyz[3 * i + 2] = 0.0;
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_material_from_E_nu(2e11, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_rectangle(0.01, 0.001, &s), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "strip", NV, xyz, d1, &rod), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, rod, RN_START), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, rod, RN_END), RN_OK);
  CHECK_STATUS(rn_network_displace_end(net, rod, RN_END, disp, NULL), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

static void reactions(rn_network *net, rn_reaction r[2]) {
  double *x = malloc(rn_network_num_dofs(net) * sizeof *x);
  CHECK(rn_network_num_supports(net) == 2);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_reactions(net, x, r, 2), RN_OK);
  free(x);
}

static double norm3(const double v[3]) {
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  rn_solve_options opt;
  rn_solve_report rep;
  rn_reaction r[2], r2[2];
  CHECK_STATUS(rn_runtime_initialize(&argc, &argv), RN_OK);
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  rn_solve_options_default(&opt);

  rn_network *net = strip(ctx);
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  printf(
      "strip: stop=%s its=%d |g|=%.3e (initial %.3e); force residual %.3e, scale %.3e, "
      "tolerance %.3e; moment residual %.3e, scale %.3e, tolerance %.3e\n",
      rn_solve_stop_name(rep.stop), rep.iterations, rep.gradient_norm,
      rep.initial_gradient_norm, rep.force_residual, rep.force_scale, rep.force_tolerance,
      rep.moment_residual, rep.moment_scale, rep.moment_tolerance);
  CHECK(rep.converged == 1 && rep.stop == RN_STOP_GRADIENT);
  CHECK(rep.initial_gradient_norm > 1e7);
  CHECK(rep.force_residual <= rep.force_tolerance &&
        rep.moment_residual <= rep.moment_tolerance);
  CHECK(rep.force_residual <= 1e-8 * rep.force_scale);
  CHECK(rep.force_tolerance >= 1e-9 * rep.force_scale &&
        rep.moment_tolerance >= 1e-9 * rep.moment_scale);
  reactions(net, r);
  double fbig = fmax(norm3(r[0].force), norm3(r[1].force));
  double mbig = fmax(norm3(r[0].moment), norm3(r[1].moment));
  double sum[3];
  for (int k = 0; k < 3; ++k) sum[k] = r[0].force[k] + r[1].force[k];
  printf("reactions: start (%.9g %.9g %.9g), end (%.9g %.9g %.9g); |sum| %.3e\n",
         r[0].force[0], r[0].force[1], r[0].force[2], r[1].force[0], r[1].force[1],
         r[1].force[2], norm3(sum));
  CHECK(fbig > 1.0 && norm3(sum) <= 1e-8 * fbig);
  CHECK_REL(rep.force_scale, fbig, 1e-12);
  CHECK_REL(rep.moment_scale, fmax(mbig, fbig * 0.3), 1e-12);

  /* an independent solve (no predictor: another path) gives the same reactions */
  rn_network_destroy(&net);
  net = strip(ctx);
  opt.predictor = 0;
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  CHECK(rep.converged == 1 && rep.stop == RN_STOP_GRADIENT);
  reactions(net, r2);
  double change = 0.0;
  for (int i = 0; i < 2; ++i)
    for (int k = 0; k < 3; ++k)
      change = fmax(change, fabs(r2[i].force[k] - r[i].force[k]));
  printf("without the predictor: its=%d, reactions differ by %.3e (relative %.3e)\n",
         rep.iterations, change, change / fbig);
  CHECK(change <= 1e-7 * fbig);
  rn_network_destroy(&net);

  /* gtol_abs is required as well */
  rn_solve_options_default(&opt);
  opt.gtol_abs = 1e-30;
  opt.max_iterations = 150;
  net = strip(ctx);
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  printf("gtol_abs 1e-30: stop=%s, converged=%d\n", rn_solve_stop_name(rep.stop),
         rep.converged);
  CHECK(rep.stop != RN_STOP_GRADIENT);
  rn_network_destroy(&net);

  /* every solver kind reports the same scale at a cantilever's equilibrium */
  const rn_solver_kind kinds[4] = {RN_SOLVER_TR_MINRES, RN_SOLVER_ROL_TR_TCG,
                                   RN_SOLVER_ROL_LS_NEWTON, RN_SOLVER_TR_KRYLOV};
  const double P = 0.3 * 3.0 * shim_cantilever_EI();
  for (int i = 0; i < 4; ++i) {
    rn_solve_options_default(&opt);
    opt.solver = kinds[i];
    net = shim_cantilever(ctx, P);
    CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
    printf("%-14s stop=%s force residual %.3e scale %.6g tolerance %.3e\n",
           rn_solver_name(kinds[i]), rn_solve_stop_name(rep.stop), rep.force_residual,
           rep.force_scale, rep.force_tolerance);
    CHECK(rep.converged == 1);
    CHECK_REL(rep.force_scale, P, 1e-6); /* the tip load = the clamp's reaction */
    CHECK(rep.stop != RN_STOP_GRADIENT || rep.force_residual <= rep.force_tolerance);
    rn_network_destroy(&net);
  }

  rn_context_destroy(&ctx);
  rn_runtime_finalize();
  return rn_test_finish("shim_equilibrium");
}

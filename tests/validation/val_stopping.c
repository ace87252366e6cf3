/* val_stopping.c - the default stopping test ends as accurately as the
 * discretisation and round-off allow (issue 22, "Convergence and stopping").
 *
 * Tip-loaded cantilevers (L = 1, E = 1e7, nu = 0.5, circle r = 0.01, clamped
 * at the start, alpha = P L^2 / EI = 1 and 5: the scenes of problems/scenes/)
 * with n = 11, 101, 1001 and 10^4 vertices, solved with default options; then
 * the same network solved on from there with the gradient test off (gtol_abs
 * 1e-300) and the step test at 1e-14: Newton steps until the iterate no longer
 * changes (or the trust radius collapses at round-off), the tightly converged
 * answer of the same discretisation.  Asserted: the default solve converged and
 * its tip is within 1e-9 L of that answer.  Before the round-off band needed two
 * iterates in a row (shim_cxx/newton/monitor.hpp) the default test stopped a Newton step
 * early wherever the floor set the tolerance: the alpha = 1 rod at 1,601
 * vertices ended 6.1e-6 from its tip (docs/solvers.md, "Stopping tests"). */
#include <math.h>
#include <stdio.h>

#include "testutil.h"
#include "valutil.h"

static void tip_of(const rn_network *net, double t[3]) { val_vertex(net, -1, t); }

static void one(rn_context *ctx, int nv, double alpha) {
  rn_material m;
  rn_section s;
  CHECK_STATUS(rn_material_from_E_nu(1e7, 0.5, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_circle(0.01, &s), RN_OK);
  const double L = 1.0, EI = m.E * s.I11, f[3] = {0.0, 0.0, -alpha * EI / (L * L)};
  rn_network *net = val_clamped_rod(ctx, nv - 1, L, &m, &s, f, NULL, 1);
  rn_solve_options opt;
  rn_solve_report rep, ref;
  rn_solve_options_default(&opt);
  opt.stability = 0;
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  CHECK(rep.converged == 1);
  double tip[3], tref[3];
  tip_of(net, tip);
  /* on from the default answer: the gradient test off, the step test tight */
  opt.gtol_abs = 1e-300;
  opt.step_tol = 1e-14;
  opt.max_iterations = 20;
  opt.max_load_cuts = 0;
  opt.predictor = 0;
  CHECK_STATUS(rn_solve(net, &opt, &ref), RN_OK);
  tip_of(net, tref);
  const double d = sqrt((tip[0] - tref[0]) * (tip[0] - tref[0]) +
                        (tip[1] - tref[1]) * (tip[1] - tref[1]) +
                        (tip[2] - tref[2]) * (tip[2] - tref[2]));
  printf("alpha %g, %5d vertices: default %2d iterations (stop %s, force residual "
         "%.2e, tolerance %.2e), tip (%.12f, %.12f), %.2e L from the tight answer "
         "(%d more iterations, stop %s)\n",
         alpha, nv, rep.iterations, rn_solve_stop_name(rep.stop), rep.force_residual,
         rep.force_tolerance, tip[0], tip[2], d / L, ref.iterations,
         rn_solve_stop_name(ref.stop));
  CHECK(d <= 1e-9 * L);
  rn_network_destroy(&net);
}

int main(void) {
  static const int ns[] = {11, 101, 1001, 10000};
  static const double alphas[] = {1.0, 5.0};
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  for (size_t a = 0; a < sizeof alphas / sizeof alphas[0]; ++a)
    for (size_t i = 0; i < sizeof ns / sizeof ns[0]; ++i) one(ctx, ns[i], alphas[a]);
  rn_context_destroy(&ctx);
  return rn_test_finish("val_stopping");
}

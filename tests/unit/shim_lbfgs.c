/* shim_lbfgs.c - RN_SOLVER_ROL_LBFGS (ROL limited-memory BFGS, line search):
 *  - its name parses and prints ("rol-lbfgs"), in rn_solver_from_name and as a
 *    scene's "method" (rn_scene_apply_solver is tested in problems);
 *  - on a short thick cantilever (11 vertices, r = 0.05: stretching only 400
 *    times stiffer than bending) at a moderate load (linear tip deflection
 *    0.05 L) it converges (by the step test: its steps, scaled like
 *    1/lambda_max of the Hessian, become tiny while the gradient is still 1e-7
 *    of the load) and reaches the TR-MINRES solution: DOFs to 1e-6 relative to
 *    the displacement, energy to 1e-9; on the slender 21-vertex cantilever of
 *    the other tests it needs thousands of iterations;
 *  - it uses gradients only: no Hessian, no Krylov iterations, no
 *    factorisations, and no Hessian-vector products but the stopping test's
 *    round-off probe (one per checked iterate); at least one gradient per
 *    iteration;
 *  - with an iteration limit far below what it needs it stops by max_iterations,
 *    not converged. */
#include <stdio.h>

#include "shim_rods.h"

/* 11 vertices, L = 1, r = 0.05, E = 1e7, tip load -P along z. */
static rn_network *thick_cantilever(rn_context *ctx, double P) {
  rn_section s;
  const double f[3] = {0.0, 0.0, -P};
  CHECK_STATUS(rn_section_circle(0.05, &s), RN_OK);
  return shim_clamped_rod(ctx, 11, 1.0, 0, &s, 1e7, f);
}

static rn_solve_report run(rn_context *ctx, rn_solver_kind kind, int max_iter, int cuts,
                           double P, double *x, double *x0, double *energy) {
  rn_network *net = thick_cantilever(ctx, P);
  rn_solve_options opt;
  rn_solve_report rep;
  rn_solve_options_default(&opt);
  opt.solver = kind;
  opt.max_iterations = max_iter;
  opt.max_load_cuts = cuts;
  opt.predictor = 0; /* the predictor factors the Hessian: compare the methods alone */
  if (x0) CHECK_STATUS(rn_network_get_dofs(net, x0), RN_OK);
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_energy(net, x, energy), RN_OK);
  printf("%-10s stop=%-14s its=%5d E=%.15e |g|=%.2e E-evals=%ld g-evals=%ld hvp=%ld "
         "hess=%ld krylov=%ld t=%.3fs\n",
         rn_solver_name(kind), rn_solve_stop_name(rep.stop), rep.iterations, *energy,
         rep.gradient_norm, rep.energy_evals, rep.gradient_evals, rep.hvp_evals,
         rep.hessian_evals, rep.krylov_iterations, rep.time_s);
  rn_network_destroy(&net);
  return rep;
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  rn_solver_kind k = RN_SOLVER_TR_MINRES;
  CHECK_STATUS(rn_runtime_initialize(&argc, &argv), RN_OK);
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  CHECK(strcmp(rn_solver_name(RN_SOLVER_ROL_LBFGS), "rol-lbfgs") == 0);
  CHECK_STATUS(rn_solver_from_name("rol-lbfgs", &k), RN_OK);
  CHECK(k == RN_SOLVER_ROL_LBFGS);
  CHECK(!rn_solver_is_distributed(RN_SOLVER_ROL_LBFGS));

  const double P = 0.05 * 3.0 * 1e7 * SHIM_PI * 625e-8 / 4.0; /* E I, r = 0.05 */
  rn_network *probe = thick_cantilever(ctx, P);
  size_t n = rn_network_num_dofs(probe);
  rn_network_destroy(&probe);
  double *x0 = calloc(n, sizeof(double)), *xr = calloc(n, sizeof(double));
  double *xl = calloc(n, sizeof(double)), er = 0.0, el = 0.0;
  rn_solve_report rr = run(ctx, RN_SOLVER_TR_MINRES, 200, 8, P, xr, x0, &er);
  rn_solve_report rl = run(ctx, RN_SOLVER_ROL_LBFGS, 20000, 8, P, xl, NULL, &el);
  CHECK(rr.converged && rl.converged);
  CHECK(rl.predictor_steps == 0);
  CHECK(rl.iterations > 0 && rl.load_steps == 1);
  CHECK(rl.hessian_evals == 0 && rl.krylov_iterations == 0);
  CHECK(rl.hvp_evals <= rl.iterations + rl.load_steps);
  CHECK(rl.factorizations == 0);
  CHECK(rl.gradient_evals >= rl.iterations && rl.energy_evals >= rl.iterations);
  const double d = shim_rel_diff(n, xl, xr, x0);
  printf("rol-lbfgs vs tr-minres: relative difference %.2e, energy %.2e\n", d,
         fabs(el / er - 1.0));
  CHECK(d <= 1e-6);
  CHECK_REL(el, er, 1e-9);

  /* An iteration limit far too small (no load cuts): stopped, not converged. */
  rn_solve_report rs = run(ctx, RN_SOLVER_ROL_LBFGS, 3, 0, P, xl, NULL, &el);
  CHECK(!rs.converged && rs.stop == RN_STOP_MAX_ITER);
  CHECK(rs.iterations == 3 && rs.load_steps == 1);
  free(x0);
  free(xr);
  free(xl);
  rn_context_destroy(&ctx);
  rn_runtime_finalize();
  return rn_test_finish("shim_lbfgs");
}

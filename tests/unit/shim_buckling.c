/* shim_buckling.c - TR-MINRES and TR-KRYLOV leave a saddle by negative curvature.
 *
 * A clamped-free column (21 vertices, L = 1 along z, rectangle 0.02 x 0.01,
 * E = 1e7) under a dead compressive tip load 1.3 x the Euler load
 * pi^2 E I_min / (4 L^2), starting exactly straight.  The gradient stays exactly
 * axial, so only the negative-curvature handling can leave the straight
 * (saddle) branch.  Checks:
 *  - the Hessian is positive definite at rest and indefinite at the straight
 *    compressed equilibrium (the load is above the discrete buckling load);
 *  - TR-MINRES converges to a state whose lowest Hessian eigenvalue is > 0,
 *    whose energy is below that of the straight equilibrium (found by a 1-D
 *    golden-section search over the uniform axial strain), and whose tip has
 *    moved sideways by more than 0.1 L;
 *  - the same with the sparse factorisations forced, rodnet's and CHOLMOD's
 *    (their failed factorisations drive the multiplier search and the inverse
 *    iteration): converged, stable, the same energy to 1e-10;
 *  - the same with the Newton-Krylov trust region (tr-krylov, factor
 *    preconditioner, and the default dd one): converged, stable, the same energy to
 *    1e-10. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "shim_rods.h"

enum { NV = 21 };

static rn_network *column(rn_context *ctx, double *P) {
  rn_section s;
  double f[3] = {0.0, 0.0, 0.0};
  CHECK_STATUS(rn_section_rectangle(0.02, 0.01, &s), RN_OK);
  *P = 1.3 * SHIM_PI * SHIM_PI * 1e7 * fmin(s.I11, s.I22) / 4.0;
  f[2] = -*P;
  return shim_clamped_rod(ctx, NV, 1.0, 2, &s, 1e7, f);
}

/* Straight state with uniform axial strain eps on the free edges: the non-zero
 * entries of the rest DOFs are the vertex heights z (x, y and theta vanish). */
static void straight_state(size_t n, const double *x0, double eps, double *x) {
  const double h = 1.0 / (NV - 1);
  for (size_t i = 0; i < n; ++i) x[i] = x0[i] != 0.0 ? x0[i] + eps * (x0[i] - h) : 0.0;
}

static double straight_energy(const rn_network *net, size_t n, const double *x0,
                              double eps, double *x) {
  double E = 0.0;
  straight_state(n, x0, eps, x);
  CHECK_STATUS(rn_network_energy(net, x, &E), RN_OK);
  return E;
}

/* Minimum of the energy over straight states (golden section on eps). */
static double straight_minimum(const rn_network *net, size_t n, const double *x0,
                               double *eps_min, double *x) {
  const double g = 0.5 * (sqrt(5.0) - 1.0);
  double a = -1e-3, b = 1e-3, c = b - g * (b - a), d = a + g * (b - a);
  double fc = straight_energy(net, n, x0, c, x), fd = straight_energy(net, n, x0, d, x);
  for (int it = 0; it < 200; ++it) {
    if (fc < fd) {
      b = d;
      d = c;
      fd = fc;
      c = b - g * (b - a);
      fc = straight_energy(net, n, x0, c, x);
    } else {
      a = c;
      c = d;
      fc = fd;
      d = a + g * (b - a);
      fd = straight_energy(net, n, x0, d, x);
    }
  }
  *eps_min = 0.5 * (a + b);
  return straight_energy(net, n, x0, *eps_min, x);
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  rn_network *net;
  rn_solve_report rep;
  rn_solve_options opt;
  size_t n;
  double P, eps, E_straight, E_final, lmin_rest, lmin_straight, lmin_final, side = 0.0;
  double *x0, *x;
  CHECK_STATUS(rn_runtime_initialize(&argc, &argv), RN_OK);
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  net = column(ctx, &P);
  n = rn_network_num_dofs(net);
  x0 = calloc(n, sizeof(double));
  x = calloc(n, sizeof(double));
  CHECK_STATUS(rn_network_get_dofs(net, x0), RN_OK);

  CHECK_STATUS(rn_hessian_min_eigenvalue(net, &lmin_rest), RN_OK);
  E_straight = straight_minimum(net, n, x0, &eps, x);
  CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK); /* tangents unchanged: frames valid */
  CHECK_STATUS(rn_hessian_min_eigenvalue(net, &lmin_straight), RN_OK);
  CHECK_STATUS(rn_network_set_dofs(net, x0), RN_OK);
  printf("P = %.6g, straight equilibrium: strain %.6e (-P/EA = %.6e), E = %.10e\n", P,
         eps, -P / (1e7 * 2e-4), E_straight);
  printf("lowest Hessian eigenvalue: at rest %.6e, straight compressed %.6e\n", lmin_rest,
         lmin_straight);
  CHECK(lmin_rest > 0.0);
  CHECK(lmin_straight < 0.0);

  rn_solve_options_default(&opt);
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  CHECK(rep.converged == 1);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_energy(net, x, &E_final), RN_OK);
  CHECK_STATUS(rn_hessian_min_eigenvalue(net, &lmin_final), RN_OK);
  for (size_t i = 0; i < n; ++i)
    if (x0[i] == 0.0) side = fmax(side, fabs(x[i])); /* x, y or theta moved */
  printf("tr-minres: stop=%s its=%d krylov=%ld E=%.10e lowest eigenvalue %.6e, "
         "largest sideways DOF %.4f\n",
         rn_solve_stop_name(rep.stop), rep.iterations, rep.krylov_iterations, E_final,
         lmin_final, side);
  CHECK(lmin_final > 0.0);
  CHECK(E_final < E_straight);
  CHECK(side > 0.1);

  for (int k = 0; k < 2; ++k) {
    const rn_factorization f = k == 0 ? RN_FACTOR_SPARSE : RN_FACTOR_CHOLMOD;
    rn_network_destroy(&net);
    net = column(ctx, &P);
    opt.factorization = f;
    CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
    CHECK(rep.converged == 1 && rep.factorization == f);
    CHECK_STATUS(rn_hessian_min_eigenvalue(net, &lmin_final), RN_OK);
    printf("tr-minres, %s factorisation: stop=%s its=%d krylov=%ld E=%.10e lowest "
           "eigenvalue %.6e\n",
           rn_factorization_name(f), rn_solve_stop_name(rep.stop), rep.iterations,
           rep.krylov_iterations, rep.energy, lmin_final);
    CHECK(lmin_final > 0.0);
    CHECK_REL(rep.energy, E_final, 1e-10);
  }

  /* the Newton-Krylov trust region leaves the saddle too, with the default (dd) and
   * with the factor preconditioner */
  for (int k = 0; k < 2; ++k) {
    const rn_preconditioner pk = k == 0 ? RN_PRECOND_AUTO : RN_PRECOND_FACTOR;
    rn_network_destroy(&net);
    net = column(ctx, &P);
    rn_solve_options_default(&opt);
    opt.solver = RN_SOLVER_TR_KRYLOV;
    opt.preconditioner = pk;
    CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
    CHECK(rep.converged == 1);
    CHECK(rep.preconditioner == (k == 0 ? RN_PRECOND_DD : RN_PRECOND_FACTOR));
    CHECK_STATUS(rn_hessian_min_eigenvalue(net, &lmin_final), RN_OK);
    printf("tr-krylov, %s: stop=%s its=%d krylov=%ld E=%.10e lowest eigenvalue %.6e\n",
           rn_preconditioner_name(rep.preconditioner), rn_solve_stop_name(rep.stop),
           rep.iterations, rep.krylov_iterations, rep.energy, lmin_final);
    CHECK(lmin_final > 0.0);
    CHECK_REL(rep.energy, E_final, 1e-10);
  }

  free(x0);
  free(x);
  rn_network_destroy(&net);
  rn_context_destroy(&ctx);
  rn_runtime_finalize();
  return rn_test_finish("shim_buckling");
}

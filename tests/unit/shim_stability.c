/* shim_stability.c - the stability report (rn_network_stability and
 * rn_solve_report.stability) against LAPACK dsyev on the dense reduced Hessian:
 *  (eigenvalues of the Jacobi-scaled Hessian D^{-1/2} H D^{-1/2}, D = |diag H|)
 *  - a loaded cantilever (banded path), solved by every solver kind: checked,
 *    verified minimum, no zero modes, the lowest eigenvalue within 1e-6 relative
 *    of dsyev's, scale = the scaled Hessian's infinity norm to 1e-12;
 *  - a free-floating unloaded quarter-circle rod: exactly 6 zero modes (3
 *    translations, 3 rotations; dsyev agrees on the count in the band
 *    1e-12 scale), verified, the lowest eigenvalue outside them = dsyev's 7th;
 *  - the straight compressed column above its buckling load solved by NOX, which
 *    stays on the straight (saddle) branch: converged but not a verified minimum,
 *    the lowest eigenvalue negative and equal to dsyev's;
 *  - a 4x4 grid of rigid joints (sparse path), every solver kind: verified,
 *    lowest eigenvalue as dsyev's; the same with the stability option off:
 *    checked = 0; an invalid option value is refused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "shim_networks.h"
#include "shim_rods.h"

/* Every eigenvalue (ascending, n of them, caller frees) and the infinity norm of
 * the Jacobi-scaled dense reduced Hessian D^{-1/2} H D^{-1/2} (D = |diag H|, floored
 * at 1e-20 of its largest entry) at the network's state. */
static double *dense_spectrum(const rn_network *net, double *norm_inf) {
  const size_t n = rn_network_num_dofs(net);
  double *x = calloc(n, sizeof(double)), *w = calloc(n, sizeof(double));
  int ni = (int)n, info = 0, lwork = 8 * (int)n;
  double *work = calloc((size_t)lwork, sizeof(double));
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  double *H = shim_dense_hessian(net, x), dmax = 0.0;
  double *d = calloc(n, sizeof(double));
  for (size_t i = 0; i < n; ++i) dmax = fmax(dmax, fabs(H[i + n * i]));
  for (size_t i = 0; i < n; ++i) d[i] = fmax(fabs(H[i + n * i]), 1e-20 * dmax);
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < n; ++j) H[i + n * j] /= sqrt(d[i] * d[j]);
  free(d);
  *norm_inf = 0.0;
  for (size_t i = 0; i < n; ++i) {
    double r = 0.0;
    for (size_t j = 0; j < n; ++j) r += fabs(H[i + n * j]);
    *norm_inf = fmax(*norm_inf, r);
  }
  dsyev_("N", "L", &ni, H, &ni, w, work, &lwork, &info, 1, 1);
  CHECK(info == 0);
  free(H);
  free(x);
  free(work);
  return w;
}

/* st against the dense spectrum: scale, zero modes, lowest eigenvalue outside. */
static void check_against_dense(const rn_network *net, const rn_stability *st,
                                const char *label) {
  const size_t n = rn_network_num_dofs(net);
  double norm_inf = 0.0;
  double *w = dense_spectrum(net, &norm_inf);
  size_t z = 0, first = 0;
  for (size_t i = 0; i < n; ++i) z += fabs(w[i]) <= 1e-12 * norm_inf;
  while (first < n && fabs(w[first]) <= 1e-12 * norm_inf) ++first;
  if (w[0] < -1e-12 * norm_inf) first = 0;
  if (st->symmetries >= 0) {
    /* separated: the symmetries are the band's eigenvalues nearest 0, the soft
     * modes the rest of the band; the lowest eigenvalue is the lowest of the
     * others (a soft one if any) */
    unsigned char *sym = calloc(n, 1);
    for (int k = 0; k < st->symmetries; ++k) {
      size_t best = n;
      for (size_t i = 0; i < n; ++i)
        if (!sym[i] && (best == n || fabs(w[i]) < fabs(w[best]))) best = i;
      if (best < n) sym[best] = 1;
    }
    first = 0;
    while (first < n && sym[first]) ++first;
    free(sym);
    CHECK((size_t)(st->symmetries + st->soft_modes) == z);
    CHECK(st->soft_positive >= 0 && st->soft_positive <= st->soft_modes);
    CHECK(st->zero_modes == st->symmetries + st->soft_modes - st->soft_positive);
    if (st->verified_minimum) CHECK(st->zero_modes == st->symmetries);
    if (st->soft_positive > 0) CHECK(w[first] > 0.0);
  }
  printf("%s: %zu DOFs, lowest %.10e (dsyev %.10e), scale %.6e, zero modes %d "
         "(dsyev %zu), verified %d, %ld factorisations, %.4f s\n",
         label, n, st->lowest_eigenvalue, w[first], st->scale, st->zero_modes, z,
         st->verified_minimum, st->factorizations, st->time_s);
  CHECK(st->checked == 1);
  CHECK_REL(st->scale, norm_inf, 1e-12);
  if (st->symmetries < 0) CHECK((size_t)st->zero_modes == z);
  CHECK(fabs(st->lowest_eigenvalue - w[first]) <= 1e-6 * fabs(w[first]));
  if (st->method == RN_STABILITY_LOBPCG)
    CHECK(st->factorizations == 0 && st->iterations >= 1);
  else
    CHECK(st->method == RN_STABILITY_CHOLESKY && st->factorizations >= 1);
  free(w);
}

static const rn_solver_kind kinds[5] = {RN_SOLVER_TR_MINRES, RN_SOLVER_ROL_TR_TCG,
                                        RN_SOLVER_ROL_LS_NEWTON, RN_SOLVER_TR_KRYLOV,
                                        RN_SOLVER_NOX};

static void cantilever(rn_context *ctx) {
  for (int k = 0; k < 5; ++k) {
    rn_network *net = shim_cantilever(ctx, 0.3 * 3.0 * shim_cantilever_EI());
    rn_solve_options opt;
    rn_solve_report rep;
    rn_solve_options_default(&opt);
    CHECK(opt.stability == 1);
    opt.solver = kinds[k];
    CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
    CHECK(rep.converged == 1);
    CHECK(rep.factorization == RN_FACTOR_BANDED);
    check_against_dense(net, &rep.stability, rn_solver_name(kinds[k]));
    CHECK(rep.stability.verified_minimum == 1 && rep.stability.zero_modes == 0);
    rn_stability again;
    CHECK_STATUS(rn_network_stability(net, &again), RN_OK);
    CHECK(again.verified_minimum == 1);
    CHECK_REL(again.lowest_eigenvalue, rep.stability.lowest_eigenvalue, 1e-12);
    rn_network_destroy(&net);
  }
}

/* A quarter circle of radius 1 (15 vertices), no supports, no loads. */
static rn_network *free_quarter_circle(rn_context *ctx) {
  enum { NV = 15 };
  rn_network *net = NULL;
  rn_material m;
  rn_section s;
  int rod = -1;
  double xyz[3 * NV];
  for (int i = 0; i < NV; ++i) {
    const double a = 0.5 * SHIM_PI * i / (NV - 1);
    xyz[3 * i] = cos(a);
    xyz[3 * i + 1] = sin(a);
    xyz[3 * i + 2] = 0.0;
  }
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_material_from_E_nu(1e7, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_rectangle(0.02, 0.01, &s), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "free", NV, xyz, NULL, &rod), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

static void free_rod(rn_context *ctx) {
  rn_network *net = free_quarter_circle(ctx);
  rn_stability st;
  CHECK_STATUS(rn_network_stability(net, &st), RN_OK);
  check_against_dense(net, &st, "free quarter circle");
  CHECK(st.zero_modes == 6);
  CHECK(st.symmetries == 6 && st.soft_modes == 0); /* 3 translations, 3 rotations */
  CHECK(st.verified_minimum == 1);
  rn_network_destroy(&net);
}

static rn_network *grid(rn_context *ctx) { return shimnet_grid(ctx, 4, 0.02); }

/* The clamped-free column of shim_buckling.c at 1.3 x its Euler load. */
static rn_network *column_above_buckling(rn_context *ctx) {
  rn_section s;
  double f[3] = {0.0, 0.0, 0.0};
  CHECK_STATUS(rn_section_rectangle(0.02, 0.01, &s), RN_OK);
  f[2] = -1.3 * SHIM_PI * SHIM_PI * 1e7 * fmin(s.I11, s.I22) / 4.0;
  return shim_clamped_rod(ctx, 21, 1.0, 2, &s, 1e7, f);
}

static void straight_column(rn_context *ctx) {
  rn_network *net = column_above_buckling(ctx);
  rn_solve_options opt;
  rn_solve_report rep;
  rn_solve_options_default(&opt);
  opt.solver = RN_SOLVER_NOX;
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  CHECK(rep.converged == 1);
  check_against_dense(net, &rep.stability, "nox, straight column above buckling");
  CHECK(rep.stability.verified_minimum == 0);
  CHECK(rep.stability.lowest_eigenvalue < 0.0);
  rn_network_destroy(&net);
}

static void grid_all_kinds(rn_context *ctx) {
  for (int k = 0; k < 5; ++k) {
    rn_network *net = grid(ctx);
    rn_solve_options opt;
    rn_solve_report rep;
    rn_solve_options_default(&opt);
    opt.solver = kinds[k];
    CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
    CHECK(rep.converged == 1);
    check_against_dense(net, &rep.stability, rn_solver_name(kinds[k]));
    CHECK(rep.stability.verified_minimum == 1);
    rn_network_destroy(&net);
  }
  rn_network *net = grid(ctx);
  rn_solve_options opt;
  rn_solve_report rep;
  rn_solve_options_default(&opt);
  opt.stability = 0;
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  CHECK(rep.converged == 1 && rep.stability.checked == 0);
  CHECK(rep.stability.verified_minimum == 0);
  opt.stability = 2;
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_ERR_ARG);
  CHECK_STATUS(rn_network_stability(net, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_stability(NULL, &rep.stability), RN_ERR_ARG);
  rn_network_destroy(&net);
}

/* The LOBPCG check forced (rn_solve_options.stability_method) on the scenes above,
 * against dsyev as the Cholesky check is (same tolerances): tr-krylov and nox
 * with their default (dd) preconditioner, tr-minres with it too. */
static void lobpcg_forced(rn_context *ctx) {
  const rn_solver_kind lk[3] = {RN_SOLVER_TR_KRYLOV, RN_SOLVER_NOX, RN_SOLVER_TR_MINRES};
  for (int k = 0; k < 3; ++k) {
    rn_solve_options opt;
    rn_solve_report rep;
    rn_solve_options_default(&opt);
    opt.solver = lk[k];
    opt.stability_method = RN_STABILITY_LOBPCG;
    char label[64];
    rn_network *net = shim_cantilever(ctx, 0.3 * 3.0 * shim_cantilever_EI());
    CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
    CHECK(rep.converged == 1);
    snprintf(label, sizeof label, "lobpcg, cantilever, %s", rn_solver_name(lk[k]));
    check_against_dense(net, &rep.stability, label);
    CHECK(rep.stability.verified_minimum == 1 && rep.stability.zero_modes == 0);
    rn_network_destroy(&net);
    net = grid(ctx);
    CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
    CHECK(rep.converged == 1);
    snprintf(label, sizeof label, "lobpcg, grid, %s", rn_solver_name(lk[k]));
    check_against_dense(net, &rep.stability, label);
    CHECK(rep.stability.verified_minimum == 1);
    rn_network_destroy(&net);
  }
  rn_solve_options opt;
  rn_solve_report rep;
  rn_solve_options_default(&opt);
  opt.solver = RN_SOLVER_TR_KRYLOV;
  opt.stability_method = RN_STABILITY_LOBPCG;
  rn_network *net = free_quarter_circle(ctx);
  opt.solver = RN_SOLVER_TR_MINRES; /* converges at once: the state is the rest state */
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  CHECK(rep.converged == 1);
  check_against_dense(net, &rep.stability, "lobpcg, free quarter circle");
  CHECK(rep.stability.zero_modes == 6 && rep.stability.verified_minimum == 1);
  rn_network_destroy(&net);
  net = column_above_buckling(ctx);
  opt.solver = RN_SOLVER_NOX;
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  CHECK(rep.converged == 1);
  check_against_dense(net, &rep.stability, "lobpcg, nox, straight column");
  CHECK(rep.stability.verified_minimum == 0 && rep.stability.lowest_eigenvalue < 0.0);
  rn_network_destroy(&net);
  opt.stability_method = 3;
  net = grid(ctx);
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_ERR_ARG);
  rn_network_destroy(&net);
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_runtime_initialize(&argc, &argv), RN_OK);
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  cantilever(ctx);
  free_rod(ctx);
  straight_column(ctx);
  grid_all_kinds(ctx);
  lobpcg_forced(ctx);
  rn_context_destroy(&ctx);
  rn_runtime_finalize();
  return rn_test_finish("shim_stability");
}

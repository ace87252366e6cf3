/* shim_solve.c - rn_solve on a clamped 21-vertex cantilever (circle r = 0.01,
 * E = 1e7, L = 1):
 *  - option defaults, names, invalid options and states give error statuses;
 *  - TR-MINRES at small loads agrees with the discrete linear solution
 *    H u = f (LAPACK dposv on the Hessian at rest) to O(load^2): the error at
 *    load P is 4x the error at P/2 (within 10 %) and below 2 % of |u|;
 *  - the three solver kinds converge at a large load (linear tip deflection
 *    0.3 L) and agree to 1e-8 relative (DOFs, against the displacement) and
 *    1e-10 (energy);
 *  - counters are non-zero and consistent with the progress callback;
 *  - rn_hessian_min_eigenvalue equals LAPACK dsyev's lowest eigenvalue of the
 *    dense Hessian (1e-9 relative).
 * Prints the MINRES iterations of every Newton step. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "shim_rods.h"

typedef struct progress_log {
  int calls, last_iteration, monotone, max_krylov;
  long krylov_sum;
  double last_energy, last_gnorm;
  char minres[512];
} progress_log;

static void on_progress(void *user, const rn_iteration_info *info) {
  progress_log *log = user;
  size_t len = strlen(log->minres);
  if (log->calls > 0 && info->iteration < log->last_iteration) log->monotone = 0;
  log->calls++;
  log->last_iteration = info->iteration;
  log->krylov_sum += info->krylov_iterations;
  if (info->krylov_iterations > log->max_krylov)
    log->max_krylov = info->krylov_iterations;
  log->last_energy = info->energy;
  log->last_gnorm = info->gradient_norm;
  if (info->iteration > 0 && len + 8 < sizeof log->minres)
    snprintf(log->minres + len, sizeof log->minres - len, " %d", info->krylov_iterations);
}

static void test_names_and_options(rn_context *ctx) {
  rn_solve_options opt;
  rn_solve_report rep;
  rn_solver_kind k = RN_SOLVER_ROL_TR_TCG;
  rn_network *net = NULL;

  rn_solve_options_default(&opt);
  CHECK(opt.solver == RN_SOLVER_TR_MINRES);
  CHECK(opt.max_iterations == 200 && opt.krylov_max_iterations == 500);
  CHECK(opt.gtol_rel == 1e-9 && opt.gtol_abs == 0.0 && opt.step_tol == 1e-12);
  CHECK(opt.energy_tol == 0.0 && opt.krylov_tol == 1e-10);
  CHECK(opt.initial_radius == 0.0 && opt.load_steps == 0 && opt.max_load_cuts == 8);
  CHECK(opt.progress == NULL);

  CHECK(strcmp(rn_solver_name(RN_SOLVER_TR_MINRES), "tr-minres") == 0);
  CHECK(strcmp(rn_solver_name(RN_SOLVER_ROL_TR_TCG), "rol-tr-tcg") == 0);
  CHECK(strcmp(rn_solver_name(RN_SOLVER_ROL_LS_NEWTON), "rol-ls-newton") == 0);
  CHECK(strcmp(rn_solver_name(RN_SOLVER_TR_KRYLOV), "tr-krylov") == 0);
  CHECK_STATUS(rn_solver_from_name("tr-krylov", &k), RN_OK);
  CHECK(k == RN_SOLVER_TR_KRYLOV);
  {
    rn_preconditioner pk = RN_PRECOND_FACTOR;
    CHECK(opt.preconditioner == RN_PRECOND_AUTO);
    CHECK(strcmp(rn_preconditioner_name(RN_PRECOND_AUTO), "auto") == 0);
    CHECK(strcmp(rn_preconditioner_name(RN_PRECOND_FACTOR), "factor") == 0);
    CHECK(strcmp(rn_preconditioner_name(RN_PRECOND_FROSCH), "frosch") == 0);
    CHECK(strcmp(rn_preconditioner_name(RN_PRECOND_DD_AMG), "dd-amg") == 0);
    CHECK(strcmp(rn_preconditioner_name((rn_preconditioner)9), "unknown") == 0);
    CHECK_STATUS(rn_preconditioner_from_name("auto", &pk), RN_OK);
    CHECK(pk == RN_PRECOND_AUTO);
    CHECK_STATUS(rn_preconditioner_from_name("factor", &pk), RN_OK);
    CHECK(pk == RN_PRECOND_FACTOR);
    CHECK_STATUS(rn_preconditioner_from_name("dd?", &pk), RN_ERR_ARG);
  }
  CHECK_STATUS(rn_solver_from_name("rol-ls-newton", &k), RN_OK);
  CHECK(k == RN_SOLVER_ROL_LS_NEWTON);
  CHECK_STATUS(rn_solver_from_name("tr-minres", &k), RN_OK);
  CHECK(k == RN_SOLVER_TR_MINRES);
  CHECK_STATUS(rn_solver_from_name("newton", &k), RN_ERR_ARG);
  CHECK_STATUS(rn_solver_from_name(NULL, &k), RN_ERR_ARG);
  CHECK(strcmp(rn_solve_stop_name(RN_STOP_GRADIENT), "gradient") == 0);
  CHECK(strcmp(rn_solve_stop_name(RN_STOP_STEP), "step") == 0);
  CHECK(strcmp(rn_solve_stop_name(RN_STOP_ENERGY), "energy") == 0);
  CHECK(strcmp(rn_solve_stop_name(RN_STOP_MAX_ITER), "max_iterations") == 0);
  CHECK(strcmp(rn_solve_stop_name(RN_STOP_RADIUS), "radius") == 0);
  CHECK(strcmp(rn_solve_stop_name(RN_STOP_FAILED), "failed") == 0);
  CHECK(strcmp(rn_solve_stop_name(RN_STOP_INTERRUPTED), "interrupted") == 0);
  CHECK(opt.interrupt == NULL);

  CHECK_STATUS(rn_solve(NULL, &opt, &rep), RN_ERR_ARG);
  CHECK(rep.status == RN_ERR_ARG && rep.converged == 0);

  /* Not finalized: an error status, no crash. */
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK(rn_solve(net, &opt, &rep) < 0);
  CHECK(rep.status < 0 && rep.stop == RN_STOP_FAILED);
  rn_network_destroy(&net);

  net = shim_cantilever(ctx, 1e-3);
  {
    rn_solve_options bad[8];
    for (int i = 0; i < 8; ++i) bad[i] = opt;
    bad[0].solver = (rn_solver_kind)7;
    bad[1].max_iterations = 0;
    bad[2].krylov_tol = 0.0;
    bad[3].krylov_tol = 1.5;
    bad[4].gtol_rel = NAN;
    bad[5].load_steps = -1;
    bad[6].initial_radius = -1.0;
    bad[7].krylov_max_iterations = 0;
    for (int i = 0; i < 8; ++i) {
      rn_context_clear_error(ctx);
      CHECK_STATUS(rn_solve(net, &bad[i], &rep), RN_ERR_ARG);
      CHECK(rep.status == RN_ERR_ARG && !rep.converged);
      CHECK(strstr(rn_context_last_error(ctx), "rn_solve") != NULL);
    }
  }
  /* Every DOF prescribed (a clamped 2-vertex rod): converged at once. */
  {
    rn_section sec;
    const double f[3] = {0.0, 0.0, -1.0};
    rn_network *fixed;
    CHECK_STATUS(rn_section_circle(0.01, &sec), RN_OK);
    fixed = shim_clamped_rod(ctx, 2, 1.0, 0, &sec, 1e7, f);
    CHECK(rn_network_num_dofs(fixed) == 0);
    CHECK_STATUS(rn_solve(fixed, NULL, &rep), RN_OK);
    CHECK(rep.converged == 1 && rep.stop == RN_STOP_GRADIENT && rep.iterations == 0);
    CHECK(rep.energy == 0.0);
    rn_network_destroy(&fixed);
  }
  /* Options NULL: the defaults. */
  CHECK_STATUS(rn_solve(net, NULL, &rep), RN_OK);
  CHECK(rep.converged == 1);
  /* A solve stopped by the iteration limit is not converged. */
  {
    rn_network *big = shim_cantilever(ctx, 0.5);
    opt.max_iterations = 2;
    opt.max_load_cuts = 0;
    CHECK_STATUS(rn_solve(big, &opt, &rep), RN_OK);
    CHECK(rep.stop == RN_STOP_MAX_ITER && rep.converged == 0 && rep.iterations == 2);
    rn_network_destroy(&big);
  }
  rn_network_destroy(&net);
}

/* rn_solve_options.interrupt: a flag set by the progress callback at iteration
 * stop_at stops every solver kind there (RN_STOP_INTERRUPTED, not converged, no
 * load cut, no stability check); a flag set before the solve stops it at its
 * first check.  The Python package's Ctrl-C rests on it. */
typedef struct interrupt_log {
  volatile int flag;
  int stop_at, calls;
} interrupt_log;

static void interrupt_at(void *user, const rn_iteration_info *info) {
  interrupt_log *log = user;
  log->calls++;
  if (info->iteration >= log->stop_at) log->flag = 1;
}

static void test_interrupt(rn_context *ctx) {
  const rn_solver_kind kinds[] = {RN_SOLVER_TR_MINRES,     RN_SOLVER_ROL_TR_TCG,
                                  RN_SOLVER_ROL_LS_NEWTON, RN_SOLVER_TR_KRYLOV,
                                  RN_SOLVER_NOX,           RN_SOLVER_ROL_LBFGS};
  for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; ++k) {
    rn_network *net = shim_cantilever(ctx, 0.5);
    rn_solve_options opt;
    rn_solve_report rep;
    interrupt_log log = {0, 2, 0};
    rn_solve_options_default(&opt);
    opt.solver = kinds[k];
    opt.progress = interrupt_at;
    opt.progress_user = &log;
    opt.interrupt = &log.flag;
    CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
    CHECK(rep.stop == RN_STOP_INTERRUPTED && rep.converged == 0);
    CHECK(rep.load_steps == 1 && rep.stability.checked == 0);
    CHECK(rep.iterations >= 1 && rep.iterations <= 3);
    if (rep.stop != RN_STOP_INTERRUPTED)
      fprintf(stderr, "  interrupt: %s stopped on %s after %d iterations\n",
              rn_solver_name(kinds[k]), rn_solve_stop_name(rep.stop), rep.iterations);
    rn_network_destroy(&net);
  }
  {
    rn_network *net = shim_cantilever(ctx, 0.5);
    rn_solve_options opt;
    rn_solve_report rep;
    const volatile int set = 1;
    rn_solve_options_default(&opt);
    opt.interrupt = &set;
    CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
    CHECK(rep.stop == RN_STOP_INTERRUPTED && rep.iterations == 0 && !rep.converged);
    rn_network_destroy(&net);
  }
}

/* The layout table of bindings (rn_abi_*): every field of the table at its
 * offset, unknown names refused. */
static void test_abi_table(void) {
  CHECK(rn_abi_sizeof("rn_solve_options") == sizeof(rn_solve_options));
  CHECK(rn_abi_sizeof("rn_solve_report") == sizeof(rn_solve_report));
  CHECK(rn_abi_sizeof("rn_cell_path_result") == sizeof(rn_cell_path_result));
  CHECK(rn_abi_sizeof("no_such_struct") == 0 && rn_abi_sizeof(NULL) == 0);
  CHECK(rn_abi_offsetof("rn_solve_options", "interrupt") ==
        (long)offsetof(rn_solve_options, interrupt));
  CHECK(rn_abi_offsetof("rn_solve_report", "stability") ==
        (long)offsetof(rn_solve_report, stability));
  CHECK(rn_abi_offsetof("rn_cell_path_result", "inst") ==
        (long)offsetof(rn_cell_path_result, inst));
  CHECK(rn_abi_offsetof("rn_solve_options", "nonsense") == -1);
  CHECK(rn_abi_offsetof(NULL, "x") == -1);
  CHECK(rn_abi_num_fields("rn_material") == 3 && rn_abi_num_fields("rn_section") == 5);
  CHECK(rn_abi_num_fields("rn_solve_options") == 20);
  CHECK(rn_abi_offsetof("rn_solve_options", "forcing") ==
        (long)offsetof(rn_solve_options, forcing));
}

/* Small-load cantilever against the discrete linear solution; returns
 * ||x - x0 - u|| for tip load P (u = H^{-1} f at rest). */
static double linear_error(rn_context *ctx, double P, double *rel) {
  rn_network *net = shim_cantilever(ctx, P);
  size_t n = rn_network_num_dofs(net);
  int ni = (int)n, one = 1, info = 0;
  double *x0 = calloc(n, sizeof(double)), *x = calloc(n, sizeof(double));
  double *u = calloc(n, sizeof(double)), *H, err = 0.0, un = 0.0;
  rn_solve_report rep;
  CHECK_STATUS(rn_network_get_dofs(net, x0), RN_OK);
  CHECK_STATUS(rn_network_gradient(net, x0, NULL, u), RN_OK);
  for (size_t i = 0; i < n; ++i) u[i] = -u[i]; /* f = -g at rest */
  H = shim_dense_hessian(net, x0);
  dposv_("L", &ni, &one, H, &ni, u, &ni, &info, 1);
  CHECK(info == 0);
  CHECK_STATUS(rn_solve(net, NULL, &rep), RN_OK);
  CHECK(rep.converged == 1);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  for (size_t i = 0; i < n; ++i) {
    err += (x[i] - x0[i] - u[i]) * (x[i] - x0[i] - u[i]);
    un += u[i] * u[i];
  }
  *rel = sqrt(err / un);
  free(H);
  free(x0);
  free(x);
  free(u);
  rn_network_destroy(&net);
  return sqrt(err);
}

static void test_linear_cantilever(rn_context *ctx) {
  const double P = 0.01 * 3.0 * shim_cantilever_EI(); /* linear tip deflection L / 100 */
  double rel1 = 0.0, rel2 = 0.0;
  const double e1 = linear_error(ctx, P, &rel1), e2 = linear_error(ctx, 0.5 * P, &rel2);
  printf("linear cantilever: |x - x0 - u| / |u| = %.3e at P, %.3e at P/2; ratio of "
         "errors %.3f\n",
         rel1, rel2, e1 / e2);
  CHECK(rel1 < 0.02);
  CHECK_NEAR(e1 / e2, 4.0, 0.4);
}

typedef struct kind_result {
  double *x, energy;
  rn_solve_report rep;
} kind_result;

static void solve_kind(rn_context *ctx, rn_solver_kind kind, double P, double **x0,
                       kind_result *res) {
  rn_network *net = shim_cantilever(ctx, P);
  size_t n = rn_network_num_dofs(net);
  rn_solve_options opt;
  progress_log log;
  memset(&log, 0, sizeof log);
  log.monotone = 1;
  rn_solve_options_default(&opt);
  opt.solver = kind;
  opt.progress = on_progress;
  opt.progress_user = &log;
  if (!*x0) {
    *x0 = calloc(n, sizeof(double));
    CHECK_STATUS(rn_network_get_dofs(net, *x0), RN_OK);
  }
  res->x = calloc(n, sizeof(double));
  CHECK_STATUS(rn_solve(net, &opt, &res->rep), RN_OK);
  CHECK_STATUS(rn_network_get_dofs(net, res->x), RN_OK);
  CHECK_STATUS(rn_network_energy(net, res->x, &res->energy), RN_OK);
  printf("%-14s stop=%-9s its=%2d E=%.15e |g|=%.2e krylov=%ld hvp=%ld hess=%ld "
         "E-evals=%ld g-evals=%ld t=%.3fs\n  Krylov iterations per Newton step:%s\n",
         rn_solver_name(kind), rn_solve_stop_name(res->rep.stop), res->rep.iterations,
         res->energy, res->rep.gradient_norm, res->rep.krylov_iterations,
         res->rep.hvp_evals, res->rep.hessian_evals, res->rep.energy_evals,
         res->rep.gradient_evals, res->rep.time_s, log.minres);
  /* Converged, counters non-zero and consistent with the progress callback. */
  CHECK(res->rep.status == RN_OK && res->rep.converged == 1);
  CHECK(res->rep.iterations > 0 && res->rep.load_steps == 1);
  CHECK(res->rep.energy_evals >= res->rep.iterations);
  CHECK(res->rep.gradient_evals >= 1 && res->rep.hessian_evals >= 1);
  CHECK(res->rep.hvp_evals >= res->rep.krylov_iterations);
  CHECK(res->rep.krylov_iterations >= res->rep.iterations);
  CHECK(res->rep.time_s > 0.0);
  CHECK(log.calls == res->rep.iterations + res->rep.load_steps);
  CHECK(log.last_iteration == res->rep.iterations && log.monotone);
  CHECK(log.krylov_sum == res->rep.krylov_iterations);
  CHECK(log.last_energy == res->rep.energy && log.last_gnorm == res->rep.gradient_norm);
  CHECK_REL(res->rep.energy, res->energy, 1e-14);
  CHECK_REL(res->rep.initial_gradient_norm, P, 1e-14); /* the tip force: the only load */
  CHECK(res->rep.gradient_norm <= 1e-9 * P || res->rep.stop != RN_STOP_GRADIENT);
  rn_network_destroy(&net);
}

static void test_solver_agreement(rn_context *ctx) {
  const double P = 0.3 * 3.0 * shim_cantilever_EI(); /* linear tip deflection 0.3 L */
  const rn_solver_kind kinds[4] = {RN_SOLVER_TR_MINRES, RN_SOLVER_ROL_TR_TCG,
                                   RN_SOLVER_ROL_LS_NEWTON, RN_SOLVER_TR_KRYLOV};
  kind_result res[4];
  double *x0 = NULL;
  size_t n;
  for (int k = 0; k < 4; ++k) solve_kind(ctx, kinds[k], P, &x0, &res[k]);
  {
    rn_network *net = shim_cantilever(ctx, P);
    n = rn_network_num_dofs(net);
    rn_network_destroy(&net);
  }
  /* A large deflection: the tip moves by a good fraction of L. */
  CHECK(fabs(res[0].x[n - 1] - x0[n - 1]) > 0.1);
  for (int k = 1; k < 4; ++k) {
    const double d = shim_rel_diff(n, res[k].x, res[0].x, x0);
    printf("%s vs tr-minres: relative difference %.2e, energy %.2e\n",
           rn_solver_name(kinds[k]), d, fabs(res[k].energy / res[0].energy - 1.0));
    CHECK(d <= 1e-8);
    CHECK_REL(res[k].energy, res[0].energy, 1e-10);
  }
  for (int k = 0; k < 4; ++k) free(res[k].x);
  free(x0);
}

static void test_min_eigenvalue(rn_context *ctx) {
  rn_network *net = shim_cantilever(ctx, 0.1);
  size_t n = rn_network_num_dofs(net);
  double *x = calloc(n, sizeof(double)), *H, lmin = 0.0, ldense;
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  H = shim_dense_hessian(net, x);
  ldense = shim_dense_min_eigenvalue((int)n, H);
  CHECK_STATUS(rn_hessian_min_eigenvalue(net, &lmin), RN_OK);
  printf("lowest Hessian eigenvalue at rest: banded %.15e, dense %.15e\n", lmin, ldense);
  CHECK(lmin > 0.0);
  CHECK_REL(lmin, ldense, 1e-9);
  CHECK_STATUS(rn_hessian_min_eigenvalue(net, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_hessian_min_eigenvalue(NULL, &lmin), RN_ERR_ARG);
  free(H);
  free(x);
  rn_network_destroy(&net);
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_runtime_initialize(&argc, &argv), RN_OK);
  CHECK_STATUS(rn_runtime_initialize(&argc, &argv), RN_OK); /* idempotent */
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  test_names_and_options(ctx);
  test_linear_cantilever(ctx);
  test_solver_agreement(ctx);
  test_min_eigenvalue(ctx);
  test_interrupt(ctx);
  test_abi_table();
  rn_context_destroy(&ctx);
  rn_runtime_finalize();
  return rn_test_finish("shim_solve");
}

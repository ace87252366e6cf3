/* shim_load_stepping.c - continuation in the load factor reaches the same
 * equilibrium as the direct solve (21-vertex cantilever, circle r = 0.01,
 * E = 1e7, tip load with linear deflection 0.3 L), compared on vertex positions
 * and material directors (1e-8 relative to the tip deflection):
 *  - load_steps = 4: four converged steps, load factor back at 1;
 *  - automatic stepping, forced to cut (max_iterations = 5 is too few for the
 *    full step): more than one step, intermediate load factors < 1 reported to
 *    the progress callback, converged at load factor 1;
 *  - fixed steps that fail stop at the first failed step (not converged, load
 *    factor of that step). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "shim_rods.h"

enum { NV = 21 };

typedef struct state {
  double xyz[3 * NV], d1[3 * (NV - 1)];
} state;

typedef struct lf_log {
  double min_lf;
  int calls;
} lf_log;

static void on_progress(void *user, const rn_iteration_info *info) {
  lf_log *log = user;
  if (log->calls == 0 || info->load_factor < log->min_lf) log->min_lf = info->load_factor;
  log->calls++;
}

static double load(void) { return 0.3 * 3.0 * shim_cantilever_EI(); }

/* Solve a fresh cantilever with opt; returns its physical state. */
static void solve(rn_context *ctx, const rn_solve_options *opt, rn_solve_report *rep,
                  state *st, double *lf) {
  rn_network *net = shim_cantilever(ctx, load());
  CHECK_STATUS(rn_solve(net, opt, rep), RN_OK);
  CHECK_STATUS(rn_network_rod_vertices(net, 0, st->xyz), RN_OK);
  CHECK_STATUS(rn_network_rod_frames(net, 0, st->d1, NULL), RN_OK);
  *lf = rn_network_load_factor(net);
  rn_network_destroy(&net);
}

/* max |a - b| over positions and directors, relative to the tip deflection. */
static double state_diff(const state *a, const state *b) {
  double d = 0.0;
  const double tip = fabs(b->xyz[3 * NV - 1]);
  for (int i = 0; i < 3 * NV; ++i) d = fmax(d, fabs(a->xyz[i] - b->xyz[i]));
  for (int i = 0; i < 3 * (NV - 1); ++i) d = fmax(d, fabs(a->d1[i] - b->d1[i]));
  return d / tip;
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  rn_solve_options opt;
  rn_solve_report rep;
  state ref, st;
  double lf = 0.0, d;
  lf_log log = {1.0, 0};
  CHECK_STATUS(rn_runtime_initialize(&argc, &argv), RN_OK);
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);

  rn_solve_options_default(&opt);
  solve(ctx, &opt, &rep, &ref, &lf);
  CHECK(rep.converged == 1 && rep.load_steps == 1 && lf == 1.0);
  printf("direct: its=%d, tip z = %.10f\n", rep.iterations, ref.xyz[3 * NV - 1]);
  CHECK(fabs(ref.xyz[3 * NV - 1]) > 0.1);

  opt.load_steps = 4;
  solve(ctx, &opt, &rep, &st, &lf);
  d = state_diff(&st, &ref);
  printf("4 fixed steps: its=%d, steps=%d, stop=%s, difference %.2e\n", rep.iterations,
         rep.load_steps, rn_solve_stop_name(rep.stop), d);
  CHECK(rep.converged == 1 && rep.load_steps == 4 && lf == 1.0);
  CHECK(d <= 1e-8);

  opt.load_steps = 0;
  opt.max_iterations = 5;
  opt.progress = on_progress;
  opt.progress_user = &log;
  solve(ctx, &opt, &rep, &st, &lf);
  d = state_diff(&st, &ref);
  printf("automatic, max_iterations 5: its=%d, steps=%d, smallest load factor %.4f, "
         "stop=%s, difference %.2e\n",
         rep.iterations, rep.load_steps, log.min_lf, rn_solve_stop_name(rep.stop), d);
  CHECK(rep.converged == 1 && rep.load_steps > 1 && lf == 1.0);
  CHECK(log.min_lf < 1.0);
  CHECK(d <= 1e-8);

  opt.load_steps = 2;
  opt.max_iterations = 2;
  opt.progress = NULL;
  solve(ctx, &opt, &rep, &st, &lf);
  CHECK(rep.converged == 0 && rep.stop == RN_STOP_MAX_ITER);
  CHECK(rep.load_steps == 1 && lf == 0.5 && rep.iterations == 2);

  rn_context_destroy(&ctx);
  rn_runtime_finalize();
  return rn_test_finish("shim_load_stepping");
}

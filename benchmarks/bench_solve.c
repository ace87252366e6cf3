/* bench_solve.c - time and iterations to solve the cantilever with rn_solve:
 * a straight rod of length 1 (E = 1e7, nu = 0.5, circle r = 0.01), clamped at the
 * start, dead tip load (0, 0, -0.39) at the last vertex (a large deflection:
 * P L^2 / (E I) = 4.97).
 *
 * Each repeat builds the network anew and times rn_solve alone.  A run that does
 * not converge makes the program fail (exit 1); timings are never asserted.
 *
 *   bench_solve [--sizes 101,401,3201] [--repeats N] [--solver NAME] [--load P]
 *               [--out FILE.csv]
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "rodnet_solve.h"

#define MAX_LIST 32

typedef struct bench_opts {
  long sizes[MAX_LIST];
  int n_sizes;
  int repeats;
  double load;
  rn_solver_kind solver;
  const char *out;
} bench_opts;

/* One solve; fills rep and the tip position tip[3].  Returns the wall time of rn_solve
 * or a negative value on failure. */
static double solve_once(rn_context *ctx, const bench_opts *o, long nv,
                         rn_solve_report *rep, double tip[3]) {
  rn_network *net = NULL;
  if (rn_bench_cantilever(ctx, RN_BENCH_STRAIGHT, (int)nv, o->load, &net)) return -1.0;
  rn_solve_options opt;
  rn_solve_options_default(&opt);
  opt.solver = o->solver;
  double t0 = rn_bench_now();
  rn_status s = rn_solve(net, &opt, rep);
  double t = rn_bench_now() - t0;
  double *xyz = malloc(3 * (size_t)nv * sizeof *xyz);
  if (!s && xyz) s = rn_network_rod_vertices(net, 0, xyz);
  if (!s && xyz) memcpy(tip, xyz + 3 * (nv - 1), 3 * sizeof *tip);
  free(xyz);
  rn_network_destroy(&net);
  if (s || !xyz) {
    rn_bench_report_error("rn_solve", ctx, s ? s : RN_ERR_ALLOC);
    return -1.0;
  }
  if (!rep->converged) {
    fprintf(stderr, "bench: %ld vertices: not converged (stop: %s, |g| = %.3e)\n", nv,
            rn_solve_stop_name(rep->stop), rep->gradient_norm);
    return -1.0;
  }
  return t;
}

static int bench_size(rn_context *ctx, const bench_opts *o, long nv, FILE *out) {
  double *t = malloc((size_t)o->repeats * sizeof *t), tip[3] = {0, 0, 0};
  rn_solve_report rep;
  memset(&rep, 0, sizeof rep);
  if (!t) return 1;
  for (int r = 0; r < o->repeats; ++r) {
    t[r] = solve_once(ctx, o, nv, &rep, tip);
    if (t[r] < 0.0) {
      free(t);
      return 1;
    }
  }
  double med, mn;
  rn_bench_stats(t, o->repeats, &med, &mn);
  free(t);
  /* Iteration counts are deterministic: those of the last repeat. */
  rn_bench_csv_begin(out, "solve", rn_solver_name(o->solver), nv, o->repeats, med, mn);
  fprintf(out, ",%.6g,%d,%ld,%ld,%ld,%d,%s,%.6e,%.6e,%.10e,%.10e,%.10e\n", o->load,
          rep.iterations, rep.krylov_iterations, rep.gradient_evals, rep.hvp_evals,
          rep.load_steps, rn_solve_stop_name(rep.stop), rep.gradient_norm, rep.energy,
          tip[0], tip[1], tip[2]);
  fflush(out);
  fprintf(stderr,
          "bench_solve: %5ld vertices  %.3f s (min %.3f)  %d Newton, %ld Krylov, "
          "tip (%.6f, %.6f, %.6f)\n",
          nv, med, mn, rep.iterations, rep.krylov_iterations, tip[0], tip[1], tip[2]);
  return 0;
}

static int usage(const char *msg) {
  fprintf(stderr,
          "bench_solve: %s\n"
          "usage: bench_solve [--sizes 101,401,3201] [--repeats N] [--solver NAME]\n"
          "                   [--load P] [--out FILE.csv]\n",
          msg);
  return 2;
}

static int parse_args(int argc, char **argv, bench_opts *o) {
  o->n_sizes = rn_bench_parse_list("101,401,3201", o->sizes, MAX_LIST);
  o->repeats = 3;
  o->load = 0.39;
  o->solver = RN_SOLVER_TR_MINRES;
  o->out = NULL;
  for (int i = 1; i < argc; ++i) {
    const char *a = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
    if (!strcmp(a, "--help") || !strcmp(a, "-h")) return usage("cantilever solve"), 1;
    if (!val) return usage("missing value after an option"), -1;
    if (!strcmp(a, "--sizes"))
      o->n_sizes = rn_bench_parse_list(val, o->sizes, MAX_LIST);
    else if (!strcmp(a, "--repeats"))
      o->repeats = atoi(val);
    else if (!strcmp(a, "--load"))
      o->load = atof(val);
    else if (!strcmp(a, "--solver")) {
      if (rn_solver_from_name(val, &o->solver)) return usage("unknown --solver"), -1;
    } else if (!strcmp(a, "--out"))
      o->out = val;
    else
      return usage("unknown option"), -1;
    ++i;
  }
  if (o->n_sizes < 0) return usage("bad --sizes"), -1;
  for (int k = 0; k < o->n_sizes; ++k)
    if (o->sizes[k] < 3 || o->sizes[k] > 10000000) return usage("sizes in [3, 1e7]"), -1;
  if (o->repeats < 1 || !isfinite(o->load)) return usage("bad --repeats/--load"), -1;
  return 0;
}

int main(int argc, char **argv) {
  bench_opts o;
  int rc = parse_args(argc, argv, &o);
  if (rc) return rc > 0 ? 0 : 2;
  FILE *out = o.out ? fopen(o.out, "w") : stdout;
  if (!out) {
    perror(o.out);
    return 1;
  }
  rn_context *ctx = NULL;
  if (rn_context_create(&ctx)) return 1;
  rn_bench_csv_header(out, "load,newton_iterations,krylov_iterations,gradient_evals,"
                           "hvp_evals,load_steps,stop,gradient_norm,energy,tip_x,tip_y,"
                           "tip_z");
  for (int k = 0; k < o.n_sizes && !rc; ++k) rc = bench_size(ctx, &o, o.sizes[k], out);
  rn_context_destroy(&ctx);
  if (out != stdout && fclose(out) != 0) rc = 1;
  return rc ? 1 : 0;
}

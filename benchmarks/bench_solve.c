/* bench_solve.c - time and iterations to solve the problems of issue 8 with rn_solve:
 *  - cantilever (default): a straight rod of length 1 (E = 1e7, nu = 0.5, circle
 *    r = 0.01), clamped at the start, dead tip load (0, 0, -P) at the last vertex,
 *    P = 0.39 by default (a large deflection: P L^2 / (E I) = 4.97); size = vertices;
 *  - arch: the 215-degree circular arch of problems/scenes/arch_p4.json (R = 1,
 *    EA R^2 / EI = 1e6, EI = 1 in plane, 100 EI out of plane and in torsion), hinged
 *    at its start, clamped at its end, dead crown load P EI/R^2 (--load, default 4);
 *    size = vertices (321: the 320 edges);
 *  - circle: the laterally stiff rod of problems/scenes/end_moment_circle.json,
 *    clamped, under the end moment P * 2 pi EI / L (--load, default 1: a full circle)
 *    applied at once; size = vertices.
 * CSV case: the solver name for the cantilever, "arch:SOLVER" / "circle:SOLVER" for
 * the others; "tip" is the last vertex (the crown for the arch).
 *
 * Each repeat builds the network anew and times rn_solve alone.  A run that does
 * not converge makes the program fail (exit 1); timings are never asserted.
 *
 *   bench_solve [--problem cantilever|arch|circle] [--sizes 101,401,3201]
 *               [--repeats N] [--solver NAME] [--load P] [--out FILE.csv]
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "rodnet_solve.h"

#define MAX_LIST 32

typedef enum bench_problem { CANTILEVER, ARCH, CIRCLE } bench_problem;

typedef struct bench_opts {
  long sizes[MAX_LIST];
  int n_sizes;
  int repeats;
  double load;
  int has_load;
  bench_problem problem;
  rn_solver_kind solver;
  const char *out;
} bench_opts;

/* A rod through xyz[3 nv] with E, nu and the section of the arch and circle scenes:
 * the round wire's I22 in the plane of bending (d1 = y normal to it), 100 I22 out of
 * plane (I11) and 200 I22 torsion (J). */
static rn_status stiff_rod(rn_context *ctx, int nv, const double *xyz, double E, double r,
                           rn_network **net) {
  const double d1[3] = {0.0, 1.0, 0.0}, pi = 3.14159265358979323846;
  rn_material mat;
  rn_section sec;
  int rod = -1;
  memset(&sec, 0, sizeof sec);
  sec.A = pi * r * r;
  sec.I22 = pi * r * r * r * r / 4.0;
  sec.I11 = 100.0 * sec.I22;
  sec.J = 200.0 * sec.I22;
  rn_status s = rn_network_create(ctx, net);
  if (!s) s = rn_network_add_rod(*net, "rod", nv, xyz, d1, &rod);
  if (!s) s = rn_material_from_E_nu(E, E > 1e8 ? 0.3 : 0.5, 0.0, &mat);
  if (!s) s = rn_network_set_material(*net, rod, -1, &mat);
  if (!s) s = rn_network_set_section(*net, rod, -1, &sec);
  return s;
}

/* The arch (see the top); *probe = the crown vertex. */
static rn_status build_arch(rn_context *ctx, int nv, double P, rn_network **net,
                            int *probe) {
  const double span = 215.0 * 3.14159265358979323846 / 180.0, r = 2e-3;
  const double E = 1.0 / (3.14159265358979323846 * r * r * r * r / 4.0); /* EI = 1 */
  const double f[3] = {0.0, 0.0, -P};
  double *xyz = malloc(3 * (size_t)nv * sizeof *xyz);
  if (!xyz) return RN_ERR_ALLOC;
  for (int i = 0; i < nv; ++i) {
    const double a = -0.5 * span + span * i / (nv - 1.0);
    xyz[3 * i] = sin(a), xyz[3 * i + 1] = 0.0, xyz[3 * i + 2] = cos(a);
  }
  *probe = (nv - 1) / 2;
  rn_status s = stiff_rod(ctx, nv, xyz, E, r, net);
  if (!s) s = rn_network_pin(*net, 0, 0);
  if (!s) s = rn_network_clamp(*net, 0, RN_END);
  if (!s) s = rn_network_add_force(*net, 0, *probe, f);
  if (!s) s = rn_network_finalize(*net);
  free(xyz);
  return s;
}

/* The end moment (see the top); *probe = the tip. */
static rn_status build_circle(rn_context *ctx, int nv, double frac, rn_network **net,
                              int *probe) {
  const double r = 0.01, E = 1e7, pi = 3.14159265358979323846;
  const double m[3] = {0.0, -frac * 2.0 * pi * E * pi * r * r * r * r / 4.0, 0.0};
  double *xyz = calloc(3 * (size_t)nv, sizeof *xyz);
  if (!xyz) return RN_ERR_ALLOC;
  for (int i = 0; i < nv; ++i) xyz[3 * i] = i / (nv - 1.0);
  *probe = nv - 1;
  rn_status s = stiff_rod(ctx, nv, xyz, E, r, net);
  if (!s) s = rn_network_clamp(*net, 0, RN_START);
  if (!s) s = rn_network_add_moment(*net, 0, -1, m);
  if (!s) s = rn_network_finalize(*net);
  free(xyz);
  return s;
}

static const char *problem_name(bench_problem p) {
  return p == ARCH ? "arch" : p == CIRCLE ? "circle" : "cantilever";
}

/* One solve; fills rep and the tip position tip[3].  Returns the wall time of rn_solve
 * or a negative value on failure. */
static double solve_once(rn_context *ctx, const bench_opts *o, long nv,
                         rn_solve_report *rep, double tip[3]) {
  rn_network *net = NULL;
  int probe = (int)nv - 1;
  if (o->problem == CANTILEVER) {
    if (rn_bench_cantilever(ctx, RN_BENCH_STRAIGHT, (int)nv, o->load, &net)) return -1.0;
  } else {
    rn_status bs = o->problem == ARCH ? build_arch(ctx, (int)nv, o->load, &net, &probe)
                                      : build_circle(ctx, (int)nv, o->load, &net, &probe);
    if (bs) {
      rn_bench_report_error("building the network", ctx, bs);
      rn_network_destroy(&net);
      return -1.0;
    }
  }
  rn_solve_options opt;
  rn_solve_options_default(&opt);
  opt.solver = o->solver;
  double t0 = rn_bench_now();
  rn_status s = rn_solve(net, &opt, rep);
  double t = rn_bench_now() - t0;
  double *xyz = malloc(3 * (size_t)nv * sizeof *xyz);
  if (!s && xyz) s = rn_network_rod_vertices(net, 0, xyz);
  if (!s && xyz) memcpy(tip, xyz + 3 * probe, 3 * sizeof *tip);
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
  char case_name[64];
  if (o->problem == CANTILEVER)
    snprintf(case_name, sizeof case_name, "%s", rn_solver_name(o->solver));
  else
    snprintf(case_name, sizeof case_name, "%s:%s", problem_name(o->problem),
             rn_solver_name(o->solver));
  rn_bench_csv_begin(out, "solve", case_name, nv, o->repeats, med, mn);
  fprintf(out, ",%.6g,%d,%ld,%ld,%ld,%d,%s,%.6e,%.6e,%.10e,%.10e,%.10e\n", o->load,
          rep.iterations, rep.krylov_iterations, rep.gradient_evals, rep.hvp_evals,
          rep.load_steps, rn_solve_stop_name(rep.stop), rep.gradient_norm, rep.energy,
          tip[0], tip[1], tip[2]);
  fflush(out);
  fprintf(stderr,
          "bench_solve: %s %5ld vertices  %.3f s (min %.3f)  %d Newton, %ld Krylov, "
          "tip (%.6f, %.6f, %.6f)\n",
          case_name, nv, med, mn, rep.iterations, rep.krylov_iterations, tip[0], tip[1],
          tip[2]);
  return 0;
}

static int set_load(void *opts, const char *v) {
  bench_opts *o = opts;
  o->load = atof(v);
  o->has_load = 1;
  return 0;
}

static int set_problem(void *opts, const char *v) {
  bench_opts *o = opts;
  if (!strcmp(v, "cantilever"))
    o->problem = CANTILEVER;
  else if (!strcmp(v, "arch"))
    o->problem = ARCH;
  else if (!strcmp(v, "circle"))
    o->problem = CIRCLE;
  else
    return -1;
  return 0;
}

static int set_solver(void *opts, const char *v) {
  return rn_solver_from_name(v, &((bench_opts *)opts)->solver) != RN_OK;
}

static const rn_bench_cli cli = {
    "bench_solve",
    "usage: bench_solve [--problem cantilever|arch|circle] [--sizes 101,401,3201]\n"
    "                   [--repeats N] [--solver NAME] [--load P] [--out FILE.csv]\n",
    "cantilever solve"};

static int parse_args(int argc, char **argv, void *opts) {
  bench_opts *o = opts;
  memset(o, 0, sizeof *o); /* problem cantilever, no --load */
  o->n_sizes = rn_bench_parse_list("101,401,3201", o->sizes, MAX_LIST);
  o->repeats = 3;
  o->load = 0.39;
  o->solver = RN_SOLVER_TR_MINRES;
  o->out = NULL;
  const rn_bench_option opt[] = {
      {"--sizes", RN_BENCH_LIST, o->sizes, &o->n_sizes, MAX_LIST, NULL, NULL},
      {"--repeats", RN_BENCH_INT, &o->repeats, NULL, 0, NULL, NULL},
      {"--load", RN_BENCH_CALL, NULL, NULL, 0, set_load, NULL},
      {"--problem", RN_BENCH_CALL, NULL, NULL, 0, set_problem, "unknown --problem"},
      {"--solver", RN_BENCH_CALL, NULL, NULL, 0, set_solver, "unknown --solver"},
      {"--out", RN_BENCH_STRING, &o->out, NULL, 0, NULL, NULL}};
  int rc = rn_bench_parse_args(argc, argv, opt, sizeof opt / sizeof *opt, o, &cli);
  if (rc) return rc;
  if (!o->has_load)
    o->load = o->problem == ARCH ? 4.0 : o->problem == CIRCLE ? 1.0 : 0.39;
  if (o->n_sizes < 0) return rn_bench_bad_args(&cli, "bad --sizes");
  for (int k = 0; k < o->n_sizes; ++k)
    if (o->sizes[k] < 3 || o->sizes[k] > 10000000)
      return rn_bench_bad_args(&cli, "sizes in [3, 1e7]");
  if (o->repeats < 1 || !isfinite(o->load))
    return rn_bench_bad_args(&cli, "bad --repeats/--load");
  return 0;
}

/* The problem at every size of --sizes. */
static int run_all(rn_bench_run *run, const void *opts) {
  const bench_opts *o = opts;
  int rc = 0;
  for (int k = 0; k < o->n_sizes && !rc; ++k)
    rc = bench_size(run->ctx, o, o->sizes[k], run->out);
  return rc;
}

static const rn_bench_program program = {
    parse_args,
    "load,newton_iterations,krylov_iterations,gradient_evals,hvp_evals,load_steps,stop,"
    "gradient_norm,energy,tip_x,tip_y,tip_z",
    run_all};

int main(int argc, char **argv) {
  bench_opts o = {0};
  return rn_bench_main(argc, argv, &program, &o, &o.out);
}

/* bench_lattice.c - rn_solve on the lattices of `rodnet generate`
 * (problems/generate/lattice.h): by default hexagonal honeycombs of 10x10, 30x30 and
 * 100x100 cells (period 1, 8 edges per rod, E = 1, nu = 0.3, circle r = 1/50) under a
 * uniaxial stretch of 1e-3 (both faces normal to x pinned, the max face displaced), with
 * rigid and with elastic joints; `--kind octet --cells 3 --load compress-z:1e-3` gives
 * the 3D octet block under compression.
 *
 * Each repeat writes the scene (next to the CSV, removed afterwards), loads it
 * with the scene reader, and times rn_solve alone (without the stability check of
 * the returned state, `rn_solve_options.stability = 0`).  Per Newton step the MINRES
 * iterations come from the progress callback.  A solve that does not converge
 * makes the program fail (exit 1); timings are never asserted.
 *
 *   bench_lattice [--kind honeycomb] [--cells 10,30,100] [--models rigid,elastic]
 *                 [--edges-per-rod 8] [--load stretch-x:1e-3] [--repeats N]
 *                 [--solver NAME] [--factorization auto|banded|sparse]
 *                 [--preconditioner NAME]
 *                 [--dump-system PREFIX] [--out FILE.csv]
 *
 * --dump-system writes, for each case, the Newton system at the initial state to
 * PREFIX-<case>-<cells>.bin for benchmarks/precond_study/precond_study.cpp (dump_system).
 */
#include <math.h>
#include <sys/resource.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "generate/lattice.h"
#include "generate/lattice_scene.h"
#include "rodnet_solve.h"
#include "scene/scene.h"

#define MAX_LIST 16

static double peak_rss_mb(void);

typedef struct bench_opts {
  rn_lattice_kind kind;
  long cells[MAX_LIST];
  int n_cells;
  int models[2], n_models;
  int edges_per_rod, repeats;
  rn_lattice_load_kind load;
  int load_axis;
  double load_value;
  const char *load_text;
  rn_solver_kind solver;
  rn_preconditioner preconditioner;
  rn_factorization factorization;
  const char *out, *dump;
} bench_opts;

/* MINRES iterations per Newton step, from the progress callback.  The first call
 * of each load step reports its starting point (no Krylov work) under the
 * iteration number of the previous call. */
typedef struct krylov_log {
  long steps, total;
  int max, calls, last;
} krylov_log;

static void on_progress(void *user, const rn_iteration_info *info) {
  krylov_log *log = user;
  const int start = log->calls == 0 || info->iteration == log->last;
  log->calls++;
  log->last = info->iteration;
  if (start) return;
  log->steps++;
  log->total += info->krylov_iterations;
  if (info->krylov_iterations > log->max) log->max = info->krylov_iterations;
}

typedef struct run_result {
  rn_solve_report rep;
  krylov_log log;
  size_t dofs;
  int rods, joints;
} run_result;

/* Writes the lattice scene to path; 0 if ok. */
static int write_scene(rn_context *ctx, const bench_opts *o, long cells, int model,
                       const char *path) {
  const int c[3] = {(int)cells, (int)cells, (int)cells};
  rn_lattice *lat = NULL;
  rn_lattice_scene sc;
  rn_status s = rn_lattice_build(ctx, o->kind, c, 1.0, &lat);
  memset(&sc, 0, sizeof sc);
  sc.description = "bench_lattice";
  sc.edges_per_rod = o->edges_per_rod;
  sc.joint_model = model;
  sc.E = 1.0;
  sc.nu = 0.3;
  sc.shape = RN_LSEC_CIRCLE;
  sc.section[0] = 1.0 / 50.0;
  sc.load = o->load;
  sc.load_axis = o->load_axis;
  sc.load_value = o->load_value;
  if (!s) s = rn_lattice_write_scene(ctx, path, lat, &sc);
  rn_lattice_destroy(&lat);
  if (s) rn_bench_report_error("lattice", ctx, s);
  return s ? -1 : 0;
}

/* Native binary dump of the Newton system at the current state: "RNSYS1\0\0", n,
 * nnz, rods (int64), rowptr[n + 1] (int64), col[nnz] (int32), H values[nnz], the
 * gradient[n] and the reduced DOFs of each rod (int64; rods come first in the
 * reduced vector).  A lattice rod has both ends at joints and no constraint of its
 * own: 4 nv - 7 reduced DOFs (checked: the joints' valences add up to twice the
 * rods).  0 if written. */
static int dump_system(const rn_network *net, const char *path) {
  const size_t n = rn_network_num_dofs(net);
  const int nr = rn_network_num_rods(net);
  size_t nnz = 0;
  const int64_t *rowptr = NULL;
  const int32_t *col = NULL;
  int64_t head[3], valence = 0;
  double *x = malloc((n + 1) * sizeof *x), *g = malloc((n + 1) * sizeof *g), *vals = NULL;
  int64_t *rod = malloc(((size_t)nr + 1) * sizeof *rod);
  FILE *f = NULL;
  int rc = -1;
  for (int j = 0; j < rn_network_num_joints(net); ++j)
    valence += rn_network_joint_valence(net, j);
  if (!x || !g || !rod || valence != 2 * (int64_t)nr ||
      rn_network_hessian_pattern(net, &nnz, &rowptr, &col))
    goto done;
  vals = malloc((nnz + 1) * sizeof *vals);
  if (!vals || rn_network_get_dofs(net, x) || rn_network_gradient(net, x, NULL, g) ||
      rn_network_hessian_values(net, x, vals))
    goto done;
  for (int r = 0; r < nr; ++r)
    rod[r] = 4 * (int64_t)rn_network_rod_num_vertices(net, r) - 7;
  head[0] = (int64_t)n;
  head[1] = (int64_t)nnz;
  head[2] = nr;
  f = fopen(path, "wb");
  if (f && fwrite("RNSYS1\0\0", 1, 8, f) == 8 && fwrite(head, sizeof *head, 3, f) == 3 &&
      fwrite(rowptr, sizeof *rowptr, n + 1, f) == n + 1 &&
      fwrite(col, sizeof *col, nnz, f) == nnz &&
      fwrite(vals, sizeof *vals, nnz, f) == nnz && fwrite(g, sizeof *g, n, f) == n &&
      fwrite(rod, sizeof *rod, (size_t)nr, f) == (size_t)nr)
    rc = 0;
  if (f && fclose(f) != 0) rc = -1;
done:
  if (rc) fprintf(stderr, "bench_lattice: cannot dump the system to %s\n", path);
  free(x);
  free(g);
  free(vals);
  free(rod);
  return rc;
}

/* One solve; returns the wall time of rn_solve or a negative value on failure. */
static double solve_once(rn_context *ctx, const bench_opts *o, long cells, int model,
                         const char *path, run_result *res) {
  rn_scene *scene = NULL;
  rn_solve_options opt;
  rn_status s;
  double t0, t;
  if (write_scene(ctx, o, cells, model, path)) return -1.0;
  s = rn_scene_load(ctx, path, &scene);
  remove(path);
  if (s) {
    rn_bench_report_error("rn_scene_load", ctx, s);
    return -1.0;
  }
  rn_network *net = rn_scene_network(scene);
  if (o->dump) {
    char dump[4096];
    snprintf(dump, sizeof dump, "%s-%s-%s-%ld.bin", o->dump,
             rn_lattice_kind_name(o->kind), model == RN_JOINT_RIGID ? "rigid" : "elastic",
             cells);
    if (dump_system(net, dump)) {
      rn_scene_destroy(&scene);
      return -1.0;
    }
  }
  res->dofs = rn_network_num_dofs(net);
  res->rods = rn_network_num_rods(net);
  res->joints = rn_network_num_joints(net);
  memset(&res->log, 0, sizeof res->log);
  rn_solve_options_default(&opt);
  opt.solver = o->solver;
  opt.preconditioner = o->preconditioner;
  opt.factorization = o->factorization;
  /* the solver alone: the stability check factors the whole Hessian and is
   * measured on its own (docs/solvers.md, "Stability") */
  opt.stability = 0;
  opt.progress = on_progress;
  opt.progress_user = &res->log;
  t0 = rn_bench_now();
  s = rn_solve(net, &opt, &res->rep);
  t = rn_bench_now() - t0;
  rn_scene_destroy(&scene);
  if (s) {
    rn_bench_report_error("rn_solve", ctx, s);
    return -1.0;
  }
  if (!res->rep.converged) {
    fprintf(stderr, "bench_lattice: %ld cells: not converged (stop: %s, |g| = %.3e)\n",
            cells, rn_solve_stop_name(res->rep.stop), res->rep.gradient_norm);
    return -1.0;
  }
  return t;
}

static const char *model_name(int model) {
  return model == RN_JOINT_RIGID ? "rigid" : "elastic";
}

static int bench_case(rn_context *ctx, const bench_opts *o, long cells, int model,
                      const char *path, FILE *out) {
  double *t = malloc((size_t)o->repeats * sizeof *t), med, mn;
  run_result res;
  char case_name[64];
  memset(&res, 0, sizeof res);
  if (!t) return 1;
  for (int r = 0; r < o->repeats; ++r) {
    t[r] = solve_once(ctx, o, cells, model, path, &res);
    if (t[r] < 0.0) {
      free(t);
      return 1;
    }
  }
  rn_bench_stats(t, o->repeats, &med, &mn);
  free(t);
  snprintf(case_name, sizeof case_name, "%s-%s", rn_lattice_kind_name(o->kind),
           model_name(model));
  /* Iteration counts are deterministic: those of the last repeat. */
  rn_bench_csv_begin(out, "lattice", case_name, (long)res.dofs, o->repeats, med, mn);
  fprintf(out,
          ",%s,%ld,%s,%d,%s,%d,%d,%s,%s,%d,%ld,%.4f,%d,%ld,%d,%s,%.6e,%.10e,%s,%.1f,%.4e,"
          "%.4e,%.4e\n",
          rn_lattice_kind_name(o->kind), cells, model_name(model), o->edges_per_rod,
          o->load_text, res.rods, res.joints, rn_solver_name(o->solver),
          rn_factorization_name(res.rep.factorization), res.rep.iterations,
          res.rep.krylov_iterations,
          res.log.steps ? (double)res.log.total / (double)res.log.steps : 0.0,
          res.log.max, res.rep.factorizations, res.rep.load_steps,
          rn_solve_stop_name(res.rep.stop), res.rep.gradient_norm, res.rep.energy,
          rn_preconditioner_name(res.rep.preconditioner), peak_rss_mb(),
          res.rep.hessian_seconds, res.rep.preconditioner_setup_seconds,
          res.rep.preconditioner_apply_seconds);
  fflush(out);
  fprintf(stderr,
          "bench_lattice: %s %ld^%d cells %-7s %8zu DOFs  %9.3f s (min %.3f)  %d "
          "Newton, %ld MINRES (%.2f per step, max %d), %ld factorisations\n",
          rn_lattice_kind_name(o->kind), cells, rn_lattice_kind_dimension(o->kind),
          model_name(model), res.dofs, med, mn, res.rep.iterations,
          res.rep.krylov_iterations,
          res.log.steps ? (double)res.log.total / (double)res.log.steps : 0.0,
          res.log.max, res.rep.factorizations);
  return 0;
}

/* Peak resident size of the process so far (MB). */
static double peak_rss_mb(void) {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return (double)ru.ru_maxrss / 1024.0;
}

/* "stretch-x:1e-3", "compress-z:1e-3", "grip-x:1e-3", "pull-y:0.1"
 * (docs/lattices.md); 0 if ok. */
static int parse_load(void *opts, const char *v) {
  bench_opts *o = opts;
  static const char *kinds[4] = {"stretch-", "compress-", "pull-", "grip-"};
  static const rn_lattice_load_kind load[4] = {RN_LLOAD_STRETCH, RN_LLOAD_STRETCH,
                                               RN_LLOAD_PULL, RN_LLOAD_GRIP};
  for (int k = 0; k < 4; ++k) {
    const size_t len = strlen(kinds[k]);
    char *end = NULL;
    double x;
    if (strncmp(v, kinds[k], len) != 0) continue;
    if (v[len] < 'x' || v[len] > 'z' || v[len + 1] != ':') return -1;
    x = strtod(v + len + 2, &end);
    if (end == v + len + 2 || *end || !isfinite(x)) return -1;
    o->load = load[k];
    o->load_axis = v[len] - 'x';
    o->load_value = k == 1 ? -x : x;
    o->load_text = v;
    return 0;
  }
  return -1;
}

static int parse_models(void *opts, const char *v) {
  bench_opts *o = opts;
  o->n_models = 0;
  if (!strcmp(v, "rigid") || !strcmp(v, "rigid,elastic") || !strcmp(v, "elastic,rigid"))
    o->models[o->n_models++] = RN_JOINT_RIGID;
  if (!strcmp(v, "elastic") || !strcmp(v, "rigid,elastic"))
    o->models[o->n_models++] = RN_JOINT_ELASTIC;
  if (!strcmp(v, "elastic,rigid")) {
    o->models[0] = RN_JOINT_ELASTIC;
    o->models[o->n_models++] = RN_JOINT_RIGID;
  }
  return o->n_models > 0 ? 0 : -1;
}

static int set_kind(void *o, const char *v) {
  return rn_lattice_kind_from_name(v, &((bench_opts *)o)->kind) != 0;
}

static int set_solver(void *o, const char *v) {
  return rn_solver_from_name(v, &((bench_opts *)o)->solver) != RN_OK;
}

static int set_factorization(void *o, const char *v) {
  return rn_factorization_from_name(v, &((bench_opts *)o)->factorization) != RN_OK;
}

static int set_preconditioner(void *o, const char *v) {
  return rn_preconditioner_from_name(v, &((bench_opts *)o)->preconditioner) != RN_OK;
}

static const rn_bench_cli cli = {
    "bench_lattice",
    "usage: bench_lattice [--kind honeycomb] [--cells 10,30,100]\n"
    "                     [--models rigid,elastic] [--edges-per-rod 8]\n"
    "                     [--load stretch-x:1e-3] [--repeats N] [--solver NAME]\n"
    "                     [--factorization auto|banded|sparse]\n"
    "                     [--preconditioner auto|factor|dd|muelu|ifpack2]\n"
    "                     [--dump-system PREFIX] [--out FILE.csv]\n",
    "lattice solve"};

static int parse_args(int argc, char **argv, void *opts) {
  bench_opts *o = opts;
  memset(o, 0, sizeof *o);
  o->kind = RN_LATTICE_HONEYCOMB;
  o->n_cells = rn_bench_parse_list("10,30,100", o->cells, MAX_LIST);
  parse_models(o, "rigid,elastic");
  o->edges_per_rod = 8;
  o->repeats = 1;
  parse_load(o, "stretch-x:1e-3");
  o->solver = RN_SOLVER_TR_MINRES;
  o->factorization = RN_FACTOR_AUTO;
  o->preconditioner = RN_PRECOND_AUTO;
  const rn_bench_option opt[] = {
      {"--kind", RN_BENCH_CALL, NULL, NULL, 0, set_kind, "unknown --kind"},
      {"--cells", RN_BENCH_LIST, o->cells, &o->n_cells, MAX_LIST, NULL, NULL},
      {"--models", RN_BENCH_CALL, NULL, NULL, 0, parse_models, "bad --models"},
      {"--edges-per-rod", RN_BENCH_INT, &o->edges_per_rod, NULL, 0, NULL, NULL},
      {"--load", RN_BENCH_CALL, NULL, NULL, 0, parse_load, "bad --load"},
      {"--repeats", RN_BENCH_INT, &o->repeats, NULL, 0, NULL, NULL},
      {"--solver", RN_BENCH_CALL, NULL, NULL, 0, set_solver, "unknown --solver"},
      {"--factorization", RN_BENCH_CALL, NULL, NULL, 0, set_factorization,
       "unknown --factorization"},
      {"--preconditioner", RN_BENCH_CALL, NULL, NULL, 0, set_preconditioner,
       "unknown --preconditioner"},
      {"--dump-system", RN_BENCH_STRING, &o->dump, NULL, 0, NULL, NULL},
      {"--out", RN_BENCH_STRING, &o->out, NULL, 0, NULL, NULL}};
  int rc = rn_bench_parse_args(argc, argv, opt, sizeof opt / sizeof *opt, o, &cli);
  if (rc) return rc;
  if (o->n_cells < 0) return rn_bench_bad_args(&cli, "bad --cells");
  if (o->repeats < 1 || o->edges_per_rod < 1)
    return rn_bench_bad_args(&cli, "bad --repeats/--edges");
  return 0;
}

/* Every lattice of --cells with every joint model of --models, on the solver's
 * runtime (initialised here without the command line, which holds no runtime
 * option: parse_args refuses every option it does not know). */
static int run_all(rn_bench_run *run, const void *opts) {
  const bench_opts *o = opts;
  char path[4096];
  int rc = rn_runtime_initialize(NULL, NULL) != RN_OK;
  snprintf(path, sizeof path, "%s.scene.json", o->out ? o->out : "bench_lattice");
  for (int k = 0; k < o->n_cells && !rc; ++k)
    for (int m = 0; m < o->n_models && !rc; ++m)
      rc = bench_case(run->ctx, o, o->cells[k], o->models[m], path, run->out);
  rn_runtime_finalize();
  return rc;
}

static const rn_bench_program program = {
    parse_args,
    "lattice,cells,joint_model,edges_per_rod,load,rods,joints,solver,factorization,"
    "newton_iterations,minres_iterations,minres_per_newton,minres_max,factorizations,"
    "load_steps,stop,gradient_norm,energy,preconditioner,peak_rss_mb,hessian_s,setup_s,"
    "apply_s",
    run_all};

int main(int argc, char **argv) {
  bench_opts o = {0};
  return rn_bench_main(argc, argv, &program, &o, &o.out);
}

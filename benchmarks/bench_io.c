/* bench_io.c - scene reading and result writing at 10^4 .. 10^6 vertices: the
 * parts of `rodnet solve` around the solver, timed separately on the lattices of
 * `rodnet generate` (problems/generate/lattice.h).
 *
 * Per lattice size: "generate" writes the JSON scene (rn_lattice_write_scene),
 * "read" loads it (rn_scene_load: parse, validate, build and finalize the
 * network), "solve" runs rn_solve once (only with --solve), "write_json" writes
 * the result JSON (rn_result_write_json) and "write_vtk" the .vtu
 * (rn_vtk_write) of the current state.  Each is repeated --repeats times (the
 * solve once); the files go next to the CSV and are removed at the end.  A
 * failing step or a solve that does not converge makes the program fail (exit 1);
 * timings are never asserted.
 *
 *   bench_io [--kind honeycomb] [--cells 21,66,208] [--edges-per-rod 8]
 *            [--load stretch-x:1e-3] [--repeats 3] [--solve] [--out FILE.csv]
 *
 * CSV: bench "io", case the step, size the number of vertices; extra columns:
 * lattice, cells, edges_per_rod, rods, joints, dofs, bytes (file size; 0 for the
 * solve), mb_per_s (bytes / median), newton_iterations (solve only).
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "bench_util.h"
#include "generate/lattice.h"
#include "generate/lattice_scene.h"
#include "scene/result_json.h"
#include "scene/scene.h"
#ifdef RN_HAVE_SOLVER
#include "rodnet_solve.h"
#endif
#include "scene/vtk.h"

#define MAX_LIST 32

typedef struct bench_opts {
  rn_lattice_kind kind;
  long cells[MAX_LIST];
  int n_cells, edges_per_rod, repeats, solve;
  rn_lattice_load_kind load;
  int load_axis;
  double load_value;
  const char *out;
} bench_opts;

/* What one lattice size measured. */
typedef struct io_case {
  long cells, vertices;
  int rods, joints;
  size_t dofs;
  const char *scene_path, *json_path, *vtk_path;
} io_case;

static long file_size(const char *path) {
  struct stat sb;
  return stat(path, &sb) == 0 ? (long)sb.st_size : 0;
}

static rn_status write_scene(rn_context *ctx, const bench_opts *o, long cells,
                             const char *path) {
  const int c[3] = {(int)cells, (int)cells, (int)cells};
  rn_lattice *lat = NULL;
  rn_lattice_scene sc;
  memset(&sc, 0, sizeof sc);
  sc.description = "bench_io";
  sc.edges_per_rod = o->edges_per_rod;
  sc.joint_model = RN_JOINT_RIGID;
  sc.E = 1.0;
  sc.nu = 0.3;
  sc.shape = RN_LSEC_CIRCLE;
  sc.section[0] = 0.02;
  sc.load = o->load;
  sc.load_axis = o->load_axis;
  sc.load_value = o->load_value;
  rn_status s = rn_lattice_build(ctx, o->kind, c, 1.0, &lat);
  if (!s) s = rn_lattice_write_scene(ctx, path, lat, &sc);
  rn_lattice_destroy(&lat);
  return s;
}

static void csv_row(FILE *out, const bench_opts *o, const io_case *c, const char *step,
                    int repeats, double med, double mn, long bytes, int newton) {
  rn_bench_csv_begin(out, "io", step, c->vertices, repeats, med, mn);
  fprintf(out, ",%s,%ld,%d,%d,%d,%zu,%ld,%.6g,%d\n", rn_lattice_kind_name(o->kind),
          c->cells, o->edges_per_rod, c->rods, c->joints, c->dofs, bytes,
          med > 0.0 ? (double)bytes / med / 1e6 : 0.0, newton);
  fflush(out);
  fprintf(stderr, "bench_io: %ld vertices %-10s %9.4f s (min %.4f)  %7.1f MB\n",
          c->vertices, step, med, mn, (double)bytes / 1e6);
}

static const char *const step_names[4] = {"generate", "read", "write_json", "write_vtk"};

/* Times step `what` (0 generate, 1 read, 2 write_json, 3 write_vtk) repeats times
 * into *med and *mn; *scene is the loaded scene (read replaces it). */
static int time_step(rn_context *ctx, const bench_opts *o, const io_case *c, int what,
                     rn_scene **scene, const rn_result_info *info, double *med,
                     double *mn) {
  double *t = malloc((size_t)o->repeats * sizeof *t);
  if (!t) return 1;
  for (int r = 0; r < o->repeats; ++r) {
    rn_status s = RN_OK;
    double t0 = rn_bench_now();
    if (what == 0)
      s = write_scene(ctx, o, c->cells, c->scene_path);
    else if (what == 1) {
      rn_scene_destroy(scene);
      s = rn_scene_load(ctx, c->scene_path, scene);
    } else if (what == 2)
      s = rn_result_write_json(ctx, c->json_path, *scene, info);
    else
      s = rn_vtk_write(ctx, c->vtk_path, *scene);
    t[r] = rn_bench_now() - t0;
    if (s) {
      rn_bench_report_error(step_names[what], ctx, s);
      free(t);
      return 1;
    }
  }
  rn_bench_stats(t, o->repeats, med, mn);
  free(t);
  return 0;
}

static int solve_step(rn_context *ctx, const io_case *c, rn_scene *scene,
                      rn_result_info *info, int *iterations, double *t) {
#ifdef RN_HAVE_SOLVER
  rn_solve_report report, *rep = &report;
  rn_solve_options opt;
  rn_solve_options_default(&opt);
  rn_scene_apply_solver(scene, &opt);
  double t0 = rn_bench_now();
  rn_status s = rn_solve(rn_scene_network(scene), &opt, rep);
  *t = rn_bench_now() - t0;
  if (s) {
    rn_bench_report_error("rn_solve", ctx, s);
    return 1;
  }
  if (!rep->converged) {
    fprintf(stderr, "bench_io: %ld vertices: not converged (stop: %s)\n", c->vertices,
            rn_solve_stop_name(rep->stop));
    return 1;
  }
  info->status = "converged";
  info->solver = rn_solver_name(opt.solver);
  info->factorization = rn_factorization_name(rep->factorization);
  info->stop = rn_solve_stop_name(rep->stop);
  info->converged = 1;
  info->iterations = rep->iterations;
  info->load_steps = rep->load_steps;
  info->predictor_steps = rep->predictor_steps;
  info->energy = rep->energy;
  info->gradient_norm = rep->gradient_norm;
  info->initial_gradient_norm = rep->initial_gradient_norm;
  info->time_s = rep->time_s;
  *iterations = rep->iterations;
  return 0;
#else
  (void)ctx, (void)c, (void)scene, (void)info, (void)iterations, (void)t;
  fprintf(stderr, "bench_io: --solve needs a build with the solver (RN_WITH_TRILINOS)\n");
  return 1;
#endif
}

static int bench_size(rn_context *ctx, const bench_opts *o, long cells, FILE *out) {
  char scene_path[4096], json_path[4096], vtk_path[4096];
  const char *base = o->out ? o->out : "bench_io";
  snprintf(scene_path, sizeof scene_path, "%s.scene.json", base);
  snprintf(json_path, sizeof json_path, "%s.result.json", base);
  snprintf(vtk_path, sizeof vtk_path, "%s.result.vtu", base);
  const char *paths[4] = {scene_path, scene_path, json_path, vtk_path};
  io_case c = {cells, 0, 0, 0, 0, scene_path, json_path, vtk_path};
  rn_scene *scene = NULL;
  rn_result_info info;
  double med[4] = {0}, mn[4] = {0};
  memset(&info, 0, sizeof info);
  info.status = "initial";
  info.solver = "none";
  info.stop = "none";
  int rc = time_step(ctx, o, &c, 0, &scene, &info, &med[0], &mn[0]);
  if (!rc) rc = time_step(ctx, o, &c, 1, &scene, &info, &med[1], &mn[1]);
  if (!rc) { /* the sizes are known once the scene is read */
    rn_network *net = rn_scene_network(scene);
    c.vertices = rn_scene_num_vertices(scene);
    c.rods = rn_network_num_rods(net);
    c.joints = rn_network_num_joints(net);
    c.dofs = rn_network_num_dofs(net);
    for (int k = 0; k < 2; ++k)
      csv_row(out, o, &c, step_names[k], o->repeats, med[k], mn[k], file_size(paths[k]),
              0);
  }
  if (!rc && o->solve) {
    double t = 0.0;
    int iterations = 0;
    rc = solve_step(ctx, &c, scene, &info, &iterations, &t);
    if (!rc) csv_row(out, o, &c, "solve", 1, t, t, 0, iterations);
  }
  for (int k = 2; k < 4 && !rc; ++k) {
    rc = time_step(ctx, o, &c, k, &scene, &info, &med[k], &mn[k]);
    if (!rc)
      csv_row(out, o, &c, step_names[k], o->repeats, med[k], mn[k], file_size(paths[k]),
              0);
  }
  rn_scene_destroy(&scene);
  remove(scene_path);
  remove(json_path);
  remove(vtk_path);
  return rc;
}

static int set_kind(void *o, const char *v) {
  return rn_lattice_kind_from_name(v, &((bench_opts *)o)->kind) != 0;
}

static const rn_bench_cli cli = {
    "bench_io",
    "usage: bench_io [--kind honeycomb] [--cells 21,66,208] [--edges-per-rod 8]\n"
    "                [--load stretch-x:1e-3] [--repeats 3] [--solve]\n"
    "                [--out FILE.csv]\n",
    "scene and result I/O"};

static int parse_args(int argc, char **argv, void *opts) {
  bench_opts *o = opts;
  memset(o, 0, sizeof *o);
  o->kind = RN_LATTICE_HONEYCOMB;
  o->n_cells = rn_bench_parse_list("21,66,208", o->cells, MAX_LIST);
  o->edges_per_rod = 8;
  o->repeats = 3;
  o->load = RN_LLOAD_STRETCH;
  o->load_value = 1e-3;
  const rn_bench_option opt[] = {
      {"--solve", RN_BENCH_FLAG, &o->solve, NULL, 0, NULL, NULL},
      {"--kind", RN_BENCH_CALL, NULL, NULL, 0, set_kind, "unknown --kind"},
      {"--cells", RN_BENCH_LIST, o->cells, &o->n_cells, MAX_LIST, NULL, NULL},
      {"--edges-per-rod", RN_BENCH_INT, &o->edges_per_rod, NULL, 0, NULL, NULL},
      {"--repeats", RN_BENCH_INT, &o->repeats, NULL, 0, NULL, NULL},
      {"--out", RN_BENCH_STRING, &o->out, NULL, 0, NULL, NULL}};
  int rc = rn_bench_parse_args(argc, argv, opt, sizeof opt / sizeof *opt, o, &cli);
  if (rc) return rc;
  if (o->n_cells < 1) return rn_bench_bad_args(&cli, "bad --cells");
  if (o->repeats < 1 || o->edges_per_rod < 1)
    return rn_bench_bad_args(&cli, "bad --repeats/--edges");
  return 0;
}

/* Every lattice size of --cells (then the solver's runtime, if a solve started it,
 * is finalised). */
static int run_all(rn_bench_run *run, const void *opts) {
  const bench_opts *o = opts;
  int rc = 0;
  for (int k = 0; k < o->n_cells && !rc; ++k)
    rc = bench_size(run->ctx, o, o->cells[k], run->out);
#ifdef RN_HAVE_SOLVER
  rn_runtime_finalize();
#endif
  return rc;
}

static const rn_bench_program program = {
    parse_args,
    "lattice,cells,edges_per_rod,rods,joints,dofs,bytes,mb_per_s,newton_iterations",
    run_all};

int main(int argc, char **argv) {
  bench_opts o = {0};
  return rn_bench_main(argc, argv, &program, &o, &o.out);
}

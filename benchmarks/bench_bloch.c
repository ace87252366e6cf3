/* bench_bloch.c - the lowest Bloch eigenvalue of periodic supercells at one wave
 * vector: the dense analysis (rn_cell_bloch_eigen, LAPACK zheevr, cells up to 4,000
 * Bloch DOFs) against the sparse one (rn_cell_bloch_lowest_sparse: shift-invert
 * Lanczos on the real form with the sparse Cholesky factor; docs/homogenization.md,
 * "Sparse Bloch eigenvalues"), on rep x rep supercells of a 2D lattice's unit cell
 * (rigid joints, square struts of side 0.05 of the bar length) at rest.
 *
 *   bench_bloch [--kind honeycomb] [--reps 2,4,8,16] [--edges-per-rod 8]
 *               [--xi 0.5,0] [--repeats 3] [--dense-max 4000] [--out FILE.csv]
 *
 * The wave vector is that of the supercell (xi = (0.5, 0) of a 2 x 2 supercell is
 * a wave vector (0.25, 0) of the cell).  CSV: bench "bloch", case "dense" or
 * "sparse", size the number of Bloch DOFs; extra columns: lattice, rep,
 * edges_per_rod, eigenvalue, lanczos_steps, rel_diff (|sparse - dense| / |dense|
 * where both ran, else empty).  Timings are never asserted.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "generate/periodic_cell.h"
#include "rodnet_solve.h"
#include "scene/scene.h"

#define MAX_LIST 16

typedef struct bench_opts {
  rn_lattice_kind kind;
  long reps[MAX_LIST];
  int n_reps, edges_per_rod, repeats, dense_max;
  const char *xi_s, *out;
  double xi[3];
} bench_opts;

/* The rep x rep supercell scene of the lattice's unit cell, loaded. */
static rn_status supercell(rn_context *ctx, const bench_opts *o, int rep,
                           const char *path, rn_scene **out) {
  rn_pcell prim, c;
  const int one[3] = {1, 1, 1}, r[3] = {rep, rep, 1};
  double L, V;
  rn_status st = rn_pcell_from_lattice(ctx, o->kind, one, 1.0, &prim);
  if (st) return st;
  rn_pcell_measures(&prim, &L, &V);
  const double l = L / prim.nbars;
  if ((st = rn_pcell_tile(ctx, &prim, r, &c))) {
    rn_pcell_free(&prim);
    return st;
  }
  rn_lattice_scene sc;
  memset(&sc, 0, sizeof sc);
  sc.description = "bench_bloch";
  sc.edges_per_rod = o->edges_per_rod;
  sc.joint_model = RN_JOINT_RIGID;
  sc.E = 1.0;
  sc.nu = 0.3;
  sc.shape = RN_LSEC_RECTANGLE;
  sc.section[0] = sc.section[1] = 0.05 * l;
  st = rn_pcell_write_scene(ctx, path, &c, &sc, NULL);
  if (!st) st = rn_scene_load(ctx, path, out);
  rn_pcell_free(&prim);
  rn_pcell_free(&c);
  return st;
}

typedef rn_status (*lowest_fn)(rn_network *net, const double *xi, double *eig,
                               int *steps);

static rn_status dense_lowest(rn_network *net, const double *xi, double *eig,
                              int *steps) {
  *steps = 0;
  return rn_cell_bloch_eigen(net, xi, RN_BLOCH_ALL, 1, eig, NULL);
}

static rn_status sparse_lowest(rn_network *net, const double *xi, double *eig,
                               int *steps) {
  return rn_cell_bloch_lowest_sparse(net, xi, RN_BLOCH_ALL, eig, NULL, steps, NULL);
}

/* Times f repeats times; 0, or 1 after printing the error. */
static int time_it(rn_bench_run *run, const bench_opts *o, rn_network *net, lowest_fn f,
                   double *eig, int *steps, double *med, double *mn) {
  double t[64];
  int nr = o->repeats < 64 ? o->repeats : 64;
  for (int k = 0; k < nr; ++k) {
    double t0 = rn_bench_now();
    rn_status st = f(net, o->xi, eig, steps);
    t[k] = rn_bench_now() - t0;
    if (st) {
      rn_bench_report_error("bench_bloch", run->ctx, st);
      return 1;
    }
  }
  rn_bench_stats(t, nr, med, mn);
  return 0;
}

static void row(rn_bench_run *run, const bench_opts *o, const char *method, size_t n,
                int rep, double med, double mn, double eig, int steps, double rel) {
  rn_bench_csv_begin(run->out, "bloch", method, (long)n, o->repeats, med, mn);
  fprintf(run->out, ",%s,%d,%d,%.17g,%d,", rn_lattice_kind_name(o->kind), rep,
          o->edges_per_rod, eig, steps);
  if (rel >= 0.0) fprintf(run->out, "%.3e", rel);
  fputc('\n', run->out);
  fflush(run->out);
}

static int bench_rep(rn_bench_run *run, const bench_opts *o, int rep) {
  char path[4096];
  const char *dir = o->out && strrchr(o->out, '/') ? o->out : "./";
  size_t dl = (size_t)(strrchr(dir, '/') - dir) + 1;
  snprintf(path, sizeof path, "%.*sbench_bloch_%d.json", (int)dl, dir, rep);
  rn_scene *sc = NULL;
  rn_status st = supercell(run->ctx, o, rep, path, &sc);
  remove(path);
  if (st) {
    rn_bench_report_error("bench_bloch", run->ctx, st);
    return 1;
  }
  rn_network *net = rn_scene_network(sc);
  size_t n = 0;
  rn_network_bloch_dofs(net, &n, NULL, NULL);
  double ed = NAN, es = NAN, med, mn;
  int steps = 0, rc = 0;
  if ((long)n <= o->dense_max) {
    if ((rc = time_it(run, o, net, dense_lowest, &ed, &steps, &med, &mn))) goto done;
    row(run, o, "dense", n, rep, med, mn, ed, 0, -1.0);
    fprintf(stderr, "bench_bloch: %d x %d, %zu Bloch DOFs: dense %.4f s\n", rep, rep, n,
            med);
  }
  if ((rc = time_it(run, o, net, sparse_lowest, &es, &steps, &med, &mn))) goto done;
  row(run, o, "sparse", n, rep, med, mn, es, steps,
      isnan(ed) ? -1.0 : fabs(es - ed) / fabs(ed));
  fprintf(stderr,
          "bench_bloch: %d x %d, %zu Bloch DOFs: sparse %.4f s (%d Lanczos steps)\n", rep,
          rep, n, med, steps);
done:
  rn_scene_destroy(&sc);
  return rc;
}

static int set_kind(void *o, const char *v) {
  return rn_lattice_kind_from_name(v, &((bench_opts *)o)->kind) != 0;
}

static const rn_bench_cli cli = {
    "bench_bloch",
    "usage: bench_bloch [--kind honeycomb] [--reps 2,4,8,16] [--edges-per-rod 8]\n"
    "                   [--xi 0.5,0] [--repeats 3] [--dense-max 4000] [--out FILE.csv]\n",
    "the lowest Bloch eigenvalue of supercells: dense against sparse"};

static int parse_args(int argc, char **argv, void *opts) {
  bench_opts *o = opts;
  memset(o, 0, sizeof *o);
  o->kind = RN_LATTICE_HONEYCOMB;
  o->n_reps = rn_bench_parse_list("2,4,8,16", o->reps, MAX_LIST);
  o->edges_per_rod = 8;
  o->repeats = 3;
  o->dense_max = 4000;
  o->xi_s = "0.5,0";
  const rn_bench_option opt[] = {
      {"--kind", RN_BENCH_CALL, NULL, NULL, 0, set_kind, "unknown --kind"},
      {"--reps", RN_BENCH_LIST, o->reps, &o->n_reps, MAX_LIST, NULL, NULL},
      {"--edges-per-rod", RN_BENCH_INT, &o->edges_per_rod, NULL, 0, NULL, NULL},
      {"--xi", RN_BENCH_STRING, &o->xi_s, NULL, 0, NULL, NULL},
      {"--repeats", RN_BENCH_INT, &o->repeats, NULL, 0, NULL, NULL},
      {"--dense-max", RN_BENCH_INT, &o->dense_max, NULL, 0, NULL, NULL},
      {"--out", RN_BENCH_STRING, &o->out, NULL, 0, NULL, NULL}};
  int rc = rn_bench_parse_args(argc, argv, opt, sizeof opt / sizeof *opt, o, &cli);
  if (rc) return rc;
  if (o->n_reps < 1) return rn_bench_bad_args(&cli, "bad --reps");
  for (int k = 0; k < o->n_reps; ++k)
    if (o->reps[k] < 1 || o->reps[k] > 200) return rn_bench_bad_args(&cli, "bad --reps");
  if (o->repeats < 1 || o->edges_per_rod < 1)
    return rn_bench_bad_args(&cli, "bad --repeats/--edges-per-rod");
  if (sscanf(o->xi_s, "%lf,%lf", &o->xi[0], &o->xi[1]) != 2 || !isfinite(o->xi[0]) ||
      !isfinite(o->xi[1]))
    return rn_bench_bad_args(&cli, "bad --xi (two numbers)");
  return 0;
}

static int run_all(rn_bench_run *run, const void *opts) {
  const bench_opts *o = opts;
  int rc = 0;
  for (int k = 0; k < o->n_reps && !rc; ++k) rc = bench_rep(run, o, (int)o->reps[k]);
  return rc;
}

static const rn_bench_program program = {
    parse_args, "lattice,rep,edges_per_rod,eigenvalue,lanczos_steps,rel_diff", run_all};

int main(int argc, char **argv) {
  bench_opts o = {0};
  return rn_bench_main(argc, argv, &program, &o, &o.out);
}

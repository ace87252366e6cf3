/* bench_contact.c - the cost of contact (docs/contact.md): wall time of one
 * evaluation of energy + gradient + assembled Hessian (rn_network_energy,
 * rn_network_gradient, rn_network_hessian_values) of the same state with
 * contact on and off.
 *
 * Cases:
 *   plectoneme  the clamped rod of hard_contact (L = 100, 100 edges, radius
 *               0.35, slack 3) twisted by --turns in --steps load steps with
 *               contact on; the evaluations at the last state, with contact and
 *               on a twin network without contact set to the same state;
 *   grid        --grid n rods along x under n rods along y (16 edges each),
 *               the layers at half the activation distance: n^2 crossings
 *               pressed together (every crossing an active pair), with and
 *               without contact;
 *   lattice     the scene --lattice FILE (a lattice with "contact", e.g.
 *               tests/data/contact/honeycomb_dense.json) solved by one
 *               rn_solve (automatic load steps) to its load factor 1 with
 *               contact; the evaluations at that state, with contact and on the
 *               scene read without its "contact" set to the same state.
 *
 *   bench_contact [--turns 40] [--steps 100] [--grid 8] [--repeats 9]
 *                 [--lattice FILE] [--out FILE.csv]
 *
 * CSV: bench "contact", case "<case>-<on|off>", size the number of edges; extra
 * columns contact (1/0), active_pairs, nnz (Hessian entries), us_median, us_min
 * (microseconds per energy + gradient + Hessian evaluation). */
#include <cjson/cJSON.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "rodnet_contact.h"
#include "rodnet_scene.h"
#include "rodnet_solve.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static int usage(const char *msg) {
  return rn_bench_usage("bench_contact", msg,
                        "usage: bench_contact [--turns T] [--steps N] [--grid n] "
                        "[--repeats R] [--lattice FILE] [--out FILE.csv]\n");
}

/* The plectoneme rod; contact on or off; the end's motion at load factor 1. */
static rn_status plectoneme_net(rn_context *ctx, double turns, int contact,
                                rn_network **net) {
  enum { NV = 101 };
  const double r = 0.35, I = M_PI * r * r * r * r / 4.0;
  double xyz[3 * NV], disp[3] = {-3.0, 0.0, 0.0}, rot[3] = {2.0 * M_PI * turns, 0, 0};
  double f[3] = {0.0, 4e-5, 0.0};
  rn_material m = {1.345 / I, 0.789 / (2.0 * I), 0.0};
  rn_section s;
  int rod;
  rn_status st;
  for (int i = 0; i < NV; ++i) {
    xyz[3 * i] = 100.0 * i / (NV - 1);
    xyz[3 * i + 1] = xyz[3 * i + 2] = 0.0;
  }
  if ((st = rn_section_circle(r, &s)) || (st = rn_network_create(ctx, net)) ||
      (st = rn_network_add_rod(*net, "rod", NV, xyz, NULL, &rod)) ||
      (st = rn_network_set_material(*net, 0, -1, &m)) ||
      (st = rn_network_set_section(*net, 0, -1, &s)) ||
      (st = rn_network_clamp(*net, 0, RN_START)) ||
      (st = rn_network_clamp(*net, 0, RN_END)) ||
      (st = rn_network_displace_end(*net, 0, RN_END, disp, rot)) ||
      (st = rn_network_add_force(*net, 0, NV / 2, f)) ||
      (contact && (st = rn_network_set_contact(*net, 0.1, 1.0, r))) ||
      (st = rn_network_set_load_factor(*net, 0.0)) || (st = rn_network_finalize(*net)))
    return st;
  return RN_OK;
}

/* Two layers of n rods (16 edges, length 2) crossing in a square grid. */
static rn_status grid_net(rn_context *ctx, int n, int contact, rn_network **net) {
  enum { NV = 17 };
  const double r = 0.01, dhat = 0.02, z = 2 * r + 0.5 * dhat;
  rn_material m = {1e6, 4e5, 0.0};
  rn_section s;
  rn_status st;
  double xyz[3 * NV];
  int rod;
  if ((st = rn_section_circle(r, &s)) || (st = rn_network_create(ctx, net))) return st;
  for (int layer = 0; layer < 2; ++layer)
    for (int k = 0; k < n; ++k) {
      const double c = -1.0 + (2.0 * k + 1.0) / n + 0.0625; /* off the vertices */
      for (int i = 0; i < NV; ++i) {
        double t = -1.0 + 2.0 * i / (NV - 1);
        xyz[3 * i] = layer ? c : t;
        xyz[3 * i + 1] = layer ? t : c - 0.0625;
        xyz[3 * i + 2] = layer ? z : 0.0;
      }
      int id = layer * n + k;
      if ((st = rn_network_add_rod(*net, NULL, NV, xyz, NULL, &rod)) ||
          (st = rn_network_set_material(*net, id, -1, &m)) ||
          (st = rn_network_set_section(*net, id, -1, &s)) ||
          (st = rn_network_clamp(*net, id, RN_START)))
        return st;
    }
  if (contact && (st = rn_network_set_contact(*net, dhat, 1.0, r))) return st;
  return rn_network_finalize(*net);
}

/* Median and minimum seconds of energy + gradient + Hessian at x. */
static rn_status time_eval(rn_network *net, const double *x, int repeats, double *med,
                           double *mn) {
  size_t n = rn_network_num_dofs(net), nnz;
  const int64_t *rp;
  const int32_t *cl;
  rn_status st = rn_network_hessian_pattern(net, &nnz, &rp, &cl);
  double *g = malloc((n ? n : 1) * sizeof(double)), *vals = malloc(nnz * sizeof(double));
  double *t = malloc((size_t)repeats * sizeof(double)), E;
  if (!g || !vals || !t) st = RN_ERR_ALLOC;
  for (int k = 0; k < repeats && !st; ++k) {
    double t0 = rn_bench_now();
    if (!(st = rn_network_energy(net, x, &E)) &&
        !(st = rn_network_gradient(net, x, &E, g)))
      st = rn_network_hessian_values(net, x, vals);
    t[k] = rn_bench_now() - t0;
  }
  if (!st) rn_bench_stats(t, repeats, med, mn);
  free(g);
  free(vals);
  free(t);
  return st;
}

static int row(FILE *f, const char *case_name, long edges, rn_network *net,
               const double *x, int contact, int repeats, rn_context *ctx) {
  double med = 0.0, mn = 0.0;
  size_t nnz;
  const int64_t *rp;
  const int32_t *cl;
  rn_contact_stats cs = {0.0, 0, 0.0, 0.0};
  rn_status st = time_eval(net, x, repeats, &med, &mn);
  if (!st) st = rn_network_hessian_pattern(net, &nnz, &rp, &cl);
  if (!st) st = rn_network_contact_stats(net, x, &cs);
  if (st) {
    rn_bench_report_error(case_name, ctx, st);
    return 1;
  }
  char name[64];
  snprintf(name, sizeof name, "%s-%s", case_name, contact ? "on" : "off");
  rn_bench_csv_begin(f, "contact", name, edges, repeats, med, mn);
  fprintf(f, ",%d,%zu,%zu,%.3f,%.3f\n", contact, cs.active, nnz, 1e6 * med, 1e6 * mn);
  fprintf(stderr, "%-12s contact %-3s active pairs %4zu nnz %8zu: %.1f us (min %.1f)\n",
          case_name, contact ? "on" : "off", cs.active, nnz, 1e6 * med, 1e6 * mn);
  return 0;
}

/* x = the state of on; the twin off set to it at load factor 1, its reference
 * frames updated there.  The first failing status, or RN_OK. */
static rn_status set_twin(rn_network *on, rn_network *off, double *x) {
  rn_status st;
  if (!(st = rn_network_get_dofs(on, x)) &&
      !(st = rn_network_set_load_factor(off, 1.0)) && !(st = rn_network_set_dofs(off, x)))
    st = rn_network_update_reference(off, x);
  return st;
}

/* The lattice scene at path with contact (on) and read again without its
 * "contact" (off). */
static rn_status lattice_scenes(rn_context *ctx, const char *path, rn_scene **on,
                                rn_scene **off) {
  rn_status st = rn_scene_load(ctx, path, on);
  if (st) return st;
  FILE *f = fopen(path, "rb");
  char *text = NULL, *plain = NULL;
  long len = -1;
  if (f && !fseek(f, 0, SEEK_END) && (len = ftell(f)) >= 0 && !fseek(f, 0, SEEK_SET) &&
      (text = malloc((size_t)len + 1)) && fread(text, 1, (size_t)len, f) == (size_t)len)
    text[len] = 0;
  else
    len = -1;
  if (f) fclose(f);
  cJSON *root = len >= 0 ? cJSON_Parse(text) : NULL;
  if (root) cJSON_DeleteItemFromObject(root, "contact");
  if (root) plain = cJSON_PrintUnformatted(root);
  st = plain ? rn_scene_parse(ctx, path, plain, strlen(plain), off) : RN_ERR_IO;
  cJSON_Delete(root);
  free(plain);
  free(text);
  return st;
}

/* Solves the lattice with contact (its contact state on the way is checked by
 * hard_contact_lattice, not here), sets the twin without contact to the final
 * state and writes both rows. */
static int lattice_rows(FILE *f, rn_context *ctx, const char *path, int repeats) {
  rn_scene *son = NULL, *soff = NULL;
  rn_status st = lattice_scenes(ctx, path, &son, &soff);
  rn_network *on = son ? rn_scene_network(son) : NULL;
  rn_network *off = soff ? rn_scene_network(soff) : NULL;
  long edges = 0;
  if (!st) {
    rn_solve_options opt;
    rn_solve_report rep;
    rn_solve_options_default(&opt);
    rn_scene_apply_solver(son, &opt);
    opt.stability = 0;
    if (!(st = rn_network_set_load_factor(on, 1.0)) && !(st = rn_solve(on, &opt, &rep)) &&
        !rep.converged)
      st = RN_ERR_SOLVER;
  }
  size_t n = on ? rn_network_num_dofs(on) : 0;
  double *x = malloc((n ? n : 1) * sizeof(double));
  if (!st && !x) st = RN_ERR_ALLOC;
  if (!st) st = set_twin(on, off, x);
  for (int ir = 0; on && ir < rn_network_num_rods(on); ++ir)
    edges += rn_network_rod_num_vertices(on, ir) - 1;
  int fail = st != RN_OK;
  if (fail) rn_bench_report_error("lattice", ctx, st);
  if (!fail) fail = row(f, "lattice", edges, on, x, 1, repeats, ctx);
  if (!fail) fail = row(f, "lattice", edges, off, x, 0, repeats, ctx);
  free(x);
  rn_scene_destroy(&son);
  rn_scene_destroy(&soff);
  return fail;
}

/* The plectoneme solved with contact in steps load steps, then both rows at its
 * last state.  0 if ok. */
static int plectoneme_rows(FILE *f, rn_context *ctx, double turns, long steps,
                           int repeats) {
  rn_network *on = NULL, *off = NULL;
  int fail = plectoneme_net(ctx, turns, 1, &on) || plectoneme_net(ctx, turns, 0, &off);
  size_t n = on ? rn_network_num_dofs(on) : 0;
  double *x = malloc((n ? n : 1) * sizeof(double));
  for (long k = 1; k <= steps && !fail; ++k) {
    rn_solve_options opt;
    rn_solve_report rep;
    rn_solve_options_default(&opt);
    opt.stability = 0;
    rn_status st = rn_network_set_load_factor(on, (double)k / (double)steps);
    if (!st) st = rn_solve(on, &opt, &rep);
    if (st) rn_bench_report_error("plectoneme solve", ctx, st);
    fail = st != RN_OK;
  }
  if (!fail) fail = set_twin(on, off, x) != RN_OK;
  if (!fail) fail = row(f, "plectoneme", 100, on, x, 1, repeats, ctx);
  if (!fail) fail = row(f, "plectoneme", 100, off, x, 0, repeats, ctx);
  rn_network_destroy(&on);
  rn_network_destroy(&off);
  free(x);
  return fail;
}

/* The grid of n x n crossings with and without contact, at its initial state. */
static int grid_rows(FILE *f, rn_context *ctx, int n, int repeats) {
  int fail = 0;
  for (int contact = 1; contact >= 0 && !fail; --contact) {
    rn_network *net = NULL;
    if (grid_net(ctx, n, contact, &net)) {
      rn_bench_report_error("grid", ctx, RN_ERR_ARG);
      return 1;
    }
    size_t m = rn_network_num_dofs(net);
    double *y = malloc((m ? m : 1) * sizeof(double));
    fail = !y || rn_network_get_dofs(net, y) ||
           row(f, "grid", 32 * n, net, y, contact, repeats, ctx);
    free(y);
    rn_network_destroy(&net);
  }
  return fail;
}

int main(int argc, char **argv) {
  double turns = 40.0;
  long steps = 100, grid = 8, repeats = 9;
  const char *out = NULL, *lattice = NULL;
  for (int i = 1; i < argc; ++i) {
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (!v) return usage("missing value");
    if (!strcmp(a, "--turns"))
      turns = atof(v);
    else if (!strcmp(a, "--steps"))
      steps = atol(v);
    else if (!strcmp(a, "--grid"))
      grid = atol(v);
    else if (!strcmp(a, "--repeats"))
      repeats = atol(v);
    else if (!strcmp(a, "--out"))
      out = v;
    else if (!strcmp(a, "--lattice"))
      lattice = v;
    else
      return usage("unknown option");
    ++i;
  }
  if (!(turns > 0.0) || steps < 1 || grid < 1 || grid > 64 || repeats < 1)
    return usage("bad value");
  FILE *f = out ? fopen(out, "w") : stdout;
  if (!f) return usage("cannot open --out");
  rn_context *ctx = NULL;
  int fail = rn_context_create(&ctx) != RN_OK;
  rn_bench_csv_header(f, "contact,active_pairs,nnz,us_median,us_min");
  /* plectoneme: solve with contact, evaluate both at its last state */
  if (!fail) fail = plectoneme_rows(f, ctx, turns, steps, (int)repeats);
  if (!fail) fail = grid_rows(f, ctx, (int)grid, (int)repeats);
  if (!fail && lattice) fail = lattice_rows(f, ctx, lattice, (int)repeats);
  rn_context_destroy(&ctx);
  if (out) fclose(f);
  return fail ? 1 : 0;
}

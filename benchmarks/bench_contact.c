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
 *               without contact.
 *
 *   bench_contact [--turns 40] [--steps 100] [--grid 8] [--repeats 9]
 *                 [--out FILE.csv]
 *
 * CSV: bench "contact", case "<case>-<on|off>", size the number of edges; extra
 * columns contact (1/0), active_pairs, nnz (Hessian entries), us_median, us_min
 * (microseconds per energy + gradient + Hessian evaluation). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "rodnet_contact.h"
#include "rodnet_solve.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static int usage(const char *msg) {
  fprintf(stderr,
          "bench_contact: %s\nusage: bench_contact [--turns T] [--steps N] [--grid n] "
          "[--repeats R] [--out FILE.csv]\n",
          msg);
  return 2;
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

int main(int argc, char **argv) {
  double turns = 40.0;
  long steps = 100, grid = 8, repeats = 9;
  const char *out = NULL;
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
    else
      return usage("unknown option");
    ++i;
  }
  if (!(turns > 0.0) || steps < 1 || grid < 1 || grid > 64 || repeats < 1)
    return usage("bad value");
  FILE *f = out ? fopen(out, "w") : stdout;
  if (!f) return usage("cannot open --out");
  rn_context *ctx = NULL;
  rn_network *on = NULL, *off = NULL;
  int fail = rn_context_create(&ctx) != RN_OK;
  rn_bench_csv_header(f, "contact,active_pairs,nnz,us_median,us_min");
  /* plectoneme: solve with contact, evaluate both at its last state */
  if (!fail)
    fail = plectoneme_net(ctx, turns, 1, &on) || plectoneme_net(ctx, turns, 0, &off);
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
  if (!fail)
    fail = rn_network_get_dofs(on, x) || rn_network_set_load_factor(off, 1.0) ||
           rn_network_set_dofs(off, x) || rn_network_update_reference(off, x);
  if (!fail) fail = row(f, "plectoneme", 100, on, x, 1, (int)repeats, ctx);
  if (!fail) fail = row(f, "plectoneme", 100, off, x, 0, (int)repeats, ctx);
  rn_network_destroy(&on);
  rn_network_destroy(&off);
  free(x);
  /* the grid of crossings */
  for (int contact = 1; contact >= 0 && !fail; --contact) {
    rn_network *net = NULL;
    if (grid_net(ctx, (int)grid, contact, &net)) {
      rn_bench_report_error("grid", ctx, RN_ERR_ARG);
      fail = 1;
      break;
    }
    size_t m = rn_network_num_dofs(net);
    double *y = malloc((m ? m : 1) * sizeof(double));
    fail = !y || rn_network_get_dofs(net, y) ||
           row(f, "grid", 32 * grid, net, y, contact, (int)repeats, ctx);
    free(y);
    rn_network_destroy(&net);
  }
  rn_context_destroy(&ctx);
  if (out) fclose(f);
  return fail ? 1 : 0;
}

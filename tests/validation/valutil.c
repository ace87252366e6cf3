#include "valutil.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "testutil.h"

static void die(const rn_network *net, rn_status s, const char *what) {
  fprintf(stderr, "%s failed: %s: %s\n", what, rn_status_name(s),
          net ? rn_context_last_error(rn_network_context(net)) : "");
  exit(1);
}

rn_network *val_clamped_rod(rn_context *ctx, int n, double L, const rn_material *m,
                            const rn_section *s, const double *tip_force,
                            const double *tip_moment, int finalize) {
  double h = L / (n - 0.5);
  double *xyz = malloc(sizeof(double) * 3 * (size_t)(n + 1));
  for (int i = 0; i <= n; ++i) {
    xyz[3 * i] = -0.5 * h + i * h;
    xyz[3 * i + 1] = 0.0;
    xyz[3 * i + 2] = 0.0;
  }
  rn_network *net = NULL;
  int rod;
  double d1[3] = {0, 1, 0};
  rn_status st = rn_network_create(ctx, &net);
  if (st) die(NULL, st, "rn_network_create");
  if ((st = rn_network_add_rod(net, "rod", n + 1, xyz, d1, &rod)))
    die(net, st, "add_rod");
  free(xyz);
  if ((st = rn_network_set_material(net, rod, -1, m))) die(net, st, "set_material");
  if ((st = rn_network_set_section(net, rod, -1, s))) die(net, st, "set_section");
  if ((st = rn_network_clamp(net, rod, RN_START))) die(net, st, "clamp");
  if (tip_force && (st = rn_network_add_force(net, rod, -1, tip_force)))
    die(net, st, "force");
  if (tip_moment && (st = rn_network_add_moment(net, rod, -1, tip_moment)))
    die(net, st, "moment");
  if (finalize && (st = rn_network_finalize(net))) die(net, st, "finalize");
  return net;
}

rn_solve_report val_solve(rn_network *net, int load_steps) {
  rn_solve_options opt;
  rn_solve_report rep;
  rn_solve_options_default(&opt);
  opt.load_steps = load_steps;
  rn_status st = rn_solve(net, &opt, &rep);
  if (st) die(net, st, "rn_solve");
  if (!rep.converged) {
    rn_test_fail(__FILE__, __LINE__,
                 "solve did not converge: stop=%s after %d iterations, |g|=%.3g",
                 rn_solve_stop_name(rep.stop), rep.iterations, rep.gradient_norm);
  }
  rn_test_checks++;
  return rep;
}

void val_vertex(const rn_network *net, int v, double x[3]) {
  int nv = rn_network_rod_num_vertices(net, 0);
  double *xyz = malloc(sizeof(double) * 3 * (size_t)nv);
  rn_network_rod_vertices(net, 0, xyz);
  if (v < 0) v += nv;
  for (int k = 0; k < 3; ++k) x[k] = xyz[3 * v + k];
  free(xyz);
}

double val_ellK(double k) {
  double a = 1.0, b = sqrt(1.0 - k * k);
  for (int i = 0; i < 60 && fabs(a - b) > 1e-16 * a; ++i) {
    double an = 0.5 * (a + b);
    b = sqrt(a * b);
    a = an;
  }
  return M_PI / (2.0 * a);
}

/* Carlson RF and RD by duplication. */
static double carlson_rf(double x, double y, double z) {
  for (int i = 0; i < 100; ++i) {
    double sx = sqrt(x), sy = sqrt(y), sz = sqrt(z);
    double lam = sx * sy + sy * sz + sz * sx;
    x = 0.25 * (x + lam);
    y = 0.25 * (y + lam);
    z = 0.25 * (z + lam);
    double mu = (x + y + z) / 3.0;
    double dx = 1 - x / mu, dy = 1 - y / mu, dz = 1 - z / mu;
    if (fmax(fabs(dx), fmax(fabs(dy), fabs(dz))) < 1e-4) {
      double e2 = dx * dy - dz * dz, e3 = dx * dy * dz;
      return (1 - e2 / 10 + e3 / 14 + e2 * e2 / 24 - 3 * e2 * e3 / 44) / sqrt(mu);
    }
  }
  return NAN;
}

static double carlson_rd(double x, double y, double z) {
  double sum = 0.0, fac = 1.0;
  for (int i = 0; i < 100; ++i) {
    double sx = sqrt(x), sy = sqrt(y), sz = sqrt(z);
    double lam = sx * sy + sy * sz + sz * sx;
    sum += fac / (sz * (z + lam));
    fac *= 0.25;
    x = 0.25 * (x + lam);
    y = 0.25 * (y + lam);
    z = 0.25 * (z + lam);
    double mu = (x + y + 3 * z) / 5.0;
    double dx = 1 - x / mu, dy = 1 - y / mu, dz = 1 - z / mu;
    if (fmax(fabs(dx), fmax(fabs(dy), fabs(dz))) < 1e-4) {
      double ea = dx * dy, eb = dz * dz, ec = ea - eb, ed = ea - 6 * eb,
             ee = ed + ec + ec;
      double s = 1 + ed * (-3.0 / 14 + 9.0 / 88 * ed - 4.5 / 26 * dz * ee) +
                 dz * (ee / 6 + dz * (-9.0 / 22 * ec + dz * 3.0 / 26 * ea));
      return 3 * sum + fac * s / (mu * sqrt(mu));
    }
  }
  return NAN;
}

double val_ellF(double phi, double k) {
  double s = sin(phi), c = cos(phi);
  return s * carlson_rf(c * c, 1 - k * k * s * s, 1.0);
}

double val_ellEinc(double phi, double k) {
  double s = sin(phi), c = cos(phi), q = 1 - k * k * s * s;
  return s * carlson_rf(c * c, q, 1.0) -
         k * k * s * s * s * carlson_rd(c * c, q, 1.0) / 3.0;
}

double val_ellE(double k) { return val_ellEinc(M_PI / 2, k); }

/* api_stretch_correction.c - rn_network_stretch_correction, the force
 * f(x, s) = sum_j (E A_j / lbar_j) r_j(s) dL_j/dx of the length every edge gets
 * from a step s beyond its linearisation, r_j(s) = L_j(x + s) - L_j(x) -
 * dL_j/dx . s, checked against the stretching energy alone
 * (rn_network_energy_terms, RN_TERM_STRETCH) at the rest state x, where every
 * L_j(x) = lbar_j and S(x + s) = sum_j (E A_j / 2 lbar_j) (dL_j/dx . s + r_j(s))^2:
 * the odd part of S along s is exactly the cross term, so
 *   e(h) = | (S(x + h s) - S(x - h s)) / 2h - s . (f(x, hs) + f(x, -hs)) / 2 |
 * is O(h^4) against terms of O(h^2): the relative error falls as h^2 (fitted
 * order in [1.9, 2.1] for h = 0.2 ... 3.1e-3, halving) on
 *  (a) a rod with a clamped end and a pinned vertex;
 *  (b) three rods and three joints with pinned, clamped and free joints, both
 *      joint models.
 * Also: f(x, hs) / h^2 tends to the closed form sum_j (E A_j / lbar_j)
 * (|d_j|^2 - (e_j . d_j)^2 / L_j^2) / (2 L_j) dL_j/dx (first order in h) on a
 * free rod, f = 0 for s = 0 and for a rigid translation, and the error paths
 * (NULL, NaN, a zero-length edge at x + s). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "testutil.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

enum { N_H = 7, NV = 6 };

static uint64_t rng = 20261201;

static double urand(void) { return rn_test_rand(&rng); }

static const double kE = 1e4, kR = 0.03;

static int add_rod(rn_network *net, double x0, double y0, double dx, double dy,
                   double *xyz) {
  rn_material m;
  rn_section s;
  int rod = -1;
  for (int i = 0; i < NV; ++i) {
    xyz[3 * i] = x0 + dx * i / (NV - 1);
    xyz[3 * i + 1] = y0 + dy * i / (NV - 1);
    xyz[3 * i + 2] = 0.03 * sin(1.3 * i);
  }
  CHECK_STATUS(rn_network_add_rod(net, NULL, NV, xyz, NULL, &rod), RN_OK);
  CHECK_STATUS(rn_material_from_E_nu(kE, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_circle(kR, &s), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
  return rod;
}

/* (a) a clamped end and a pinned vertex. */
static void build_rod(rn_network *net) {
  double xyz[3 * NV];
  int r = add_rod(net, 0.0, 0.0, 1.0, 0.2, xyz);
  CHECK_STATUS(rn_network_clamp(net, r, RN_START), RN_OK);
  CHECK_STATUS(rn_network_pin(net, r, 3), RN_OK);
}

/* (b) J0 pinned where three rods meet, J1 clamped, J2 free. */
static void build_joints(rn_network *net, rn_joint_model model) {
  double xyz[3 * NV];
  int r0 = add_rod(net, 0.0, 0.0, 1.0, 0.1, xyz),
      r1 = add_rod(net, 0.0, 0.0, -0.1, 1.0, xyz);
  int r2 = add_rod(net, 0.0, 0.0, -0.7, -0.7, xyz), j0 = -1, j1 = -1, j2 = -1;
  int rods0[3] = {r0, r1, r2}, ends0[3] = {RN_START, RN_START, RN_START};
  CHECK_STATUS(rn_network_add_joint(net, "J0", model, 3, rods0, ends0, &j0), RN_OK);
  CHECK_STATUS(rn_network_add_joint(net, "J1", model, 1, &r0, (int[]){RN_END}, &j1),
               RN_OK);
  CHECK_STATUS(rn_network_add_joint(net, "J2", model, 1, &r1, (int[]){RN_END}, &j2),
               RN_OK);
  CHECK_STATUS(rn_network_pin_joint(net, j0), RN_OK);
  CHECK_STATUS(rn_network_clamp_joint(net, j1), RN_OK);
}

static double stretch(const rn_network *net, const double *x, double h, const double *s,
                      double *xs) {
  double E[RN_TERM_COUNT];
  size_t n = rn_network_num_dofs(net);
  for (size_t i = 0; i < n; ++i) xs[i] = x[i] + h * s[i];
  CHECK_STATUS(rn_network_energy_terms(net, xs, E), RN_OK);
  return E[RN_TERM_STRETCH];
}

static void sweep(rn_network *net, const char *name) {
  size_t n = rn_network_num_dofs(net);
  double *x = malloc(n * sizeof(double)), *s = malloc(n * sizeof(double));
  double *hs = malloc(n * sizeof(double)), *fp = malloc(n * sizeof(double));
  double *fm = malloc(n * sizeof(double)), *xs = malloc(n * sizeof(double));
  double h[N_H], e[N_H], order;
  CHECK_STATUS(rn_network_set_load_factor(net, 0.0), RN_OK);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK); /* the rest state */
  for (size_t i = 0; i < n; ++i) s[i] = urand();
  for (int k = 0; k < N_H; ++k) {
    h[k] = 0.05 / pow(2.0, k);
    for (size_t i = 0; i < n; ++i) hs[i] = h[k] * s[i];
    CHECK_STATUS(rn_network_stretch_correction(net, x, hs, fp), RN_OK);
    for (size_t i = 0; i < n; ++i) hs[i] = -h[k] * s[i];
    CHECK_STATUS(rn_network_stretch_correction(net, x, hs, fm), RN_OK);
    double odd =
        (stretch(net, x, h[k], s, xs) - stretch(net, x, -h[k], s, xs)) / (2.0 * h[k]);
    double cross = 0.0;
    for (size_t i = 0; i < n; ++i) cross += 0.5 * s[i] * (fp[i] + fm[i]);
    e[k] = fabs(odd - cross) / fabs(cross);
  }
  order = rn_test_loglog_slope(N_H, h, e);
  printf("%-16s h = %.3g: e = %.3e ... h = %.3g: e = %.3e, order %.3f\n", name, h[0],
         e[0], h[N_H - 1], e[N_H - 1], order);
  CHECK(order >= 1.9 && order <= 2.1);
  /* no step: no force */
  for (size_t i = 0; i < n; ++i) hs[i] = 0.0;
  CHECK_STATUS(rn_network_stretch_correction(net, x, hs, fp), RN_OK);
  for (size_t i = 0; i < n; ++i) CHECK(fp[i] == 0.0);
  /* error paths */
  CHECK_STATUS(rn_network_stretch_correction(net, NULL, s, fp), RN_ERR_ARG);
  CHECK_STATUS(rn_network_stretch_correction(net, x, s, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_stretch_correction(NULL, x, s, fp), RN_ERR_ARG);
  hs[0] = NAN;
  CHECK_STATUS(rn_network_stretch_correction(net, x, hs, fp), RN_ERR_NOT_FINITE);
  free(x);
  free(s);
  free(hs);
  free(fp);
  free(fm);
  free(xs);
}

/* A free rod: reduced = full layout (x_0, theta^0, x_1, ...).  The closed-form
 * limit of f(x, hs) / h^2, first order in h; a rigid translation gives f = 0
 * (to round-off); an edge collapsed by the step is RN_DEGENERATE. */
static void free_rod(void) {
  rn_context *ctx = NULL;
  rn_network *net = NULL;
  double xyz[3 * NV];
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  add_rod(net, 0.1, -0.2, 0.9, 0.4, xyz);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  size_t n = rn_network_num_dofs(net);
  CHECK(n == 4 * NV - 1);
  double x[4 * NV - 1], s[4 * NV - 1], hs[4 * NV - 1], f[4 * NV - 1], lim[4 * NV - 1];
  double h[N_H], e[N_H], lbar[NV - 1];
  const double k = kE * M_PI * kR * kR; /* E A */
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_rod_rest_lengths(net, 0, lbar), RN_OK);
  for (size_t i = 0; i < n; ++i) s[i] = urand();
  memset(lim, 0, sizeof(lim));
  for (int j = 0; j < NV - 1; ++j) {
    double ed = 0.0, dd = 0.0, L = 0.0, ev[3];
    for (int c = 0; c < 3; ++c) {
      ev[c] = x[4 * (j + 1) + c] - x[4 * j + c];
      double d = s[4 * (j + 1) + c] - s[4 * j + c];
      ed += ev[c] * d;
      dd += d * d;
      L += ev[c] * ev[c];
    }
    L = sqrt(L);
    double t = k / lbar[j] * (dd - ed * ed / (L * L)) / (2.0 * L) / L;
    for (int c = 0; c < 3; ++c) {
      lim[4 * j + c] -= t * ev[c];
      lim[4 * (j + 1) + c] += t * ev[c];
    }
  }
  for (int q = 0; q < N_H; ++q) {
    h[q] = 1e-2 / pow(2.0, q);
    for (size_t i = 0; i < n; ++i) hs[i] = h[q] * s[i];
    CHECK_STATUS(rn_network_stretch_correction(net, x, hs, f), RN_OK);
    double d = 0.0, l = 0.0;
    for (size_t i = 0; i < n; ++i) {
      d = fmax(d, fabs(f[i] / (h[q] * h[q]) - lim[i]));
      l = fmax(l, fabs(lim[i]));
    }
    e[q] = d / l;
  }
  double order = rn_test_loglog_slope(N_H, h, e);
  printf("%-16s limit f/h^2: e = %.3e ... %.3e, order %.3f\n", "free rod", e[0],
         e[N_H - 1], order);
  CHECK(order >= 0.9 && order <= 1.1);
  /* rigid translation (and theta changes): no stretch */
  for (size_t i = 0; i < n; ++i) hs[i] = (i % 4 == 3) ? 0.3 : (double)(i % 4) - 0.7;
  CHECK_STATUS(rn_network_stretch_correction(net, x, hs, f), RN_OK);
  for (size_t i = 0; i < n; ++i) CHECK(fabs(f[i]) <= 1e-9 * k);
  /* the step moves vertex 1 onto vertex 0 */
  memset(hs, 0, sizeof(hs));
  for (int c = 0; c < 3; ++c) hs[4 + c] = x[c] - x[4 + c];
  CHECK_STATUS(rn_network_stretch_correction(net, x, hs, f), RN_DEGENERATE);
  rn_network_destroy(&net);
  rn_context_destroy(&ctx);
}

static void run(const char *name, void (*build)(rn_network *), rn_joint_model model,
                int joints) {
  rn_context *ctx = NULL;
  rn_network *net = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  if (joints)
    build_joints(net, model);
  else
    build(net);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  sweep(net, name);
  rn_network_destroy(&net);
  rn_context_destroy(&ctx);
}

int main(void) {
  free_rod();
  run("clamped rod", build_rod, RN_JOINT_RIGID, 0);
  run("joints rigid", NULL, RN_JOINT_RIGID, 1);
  run("joints elastic", NULL, RN_JOINT_ELASTIC, 1);
  return rn_test_finish("api_stretch_correction");
}

/* val_cantilever.c - tip-loaded cantilever.
 * (1) small load: tip deflection P L^3 / (3 E I) with second-order
 *     convergence under refinement (mid-edge clamp, VALIDATION.md 0.2);
 * (2) large deflection (alpha = P L^2 / EI = 2): elastica from elliptic
 *     integrals (Bisshopp & Drucker), cross-checked by ODE shooting, and the
 *     DER tip error against the planar-DER table of VALIDATION.md 1.3. */
#include <math.h>
#include <stdio.h>

#include "testutil.h"
#include "valutil.h"

/* Elastica tip displacement (dh/L, dv/L) for alpha, elliptic integrals. */
static void elastica_elliptic(double alpha, double *dh, double *dv) {
  double lo = 1e-12, hi = M_PI / 2 - 1e-12, th0 = 0;
  for (int it = 0; it < 200; ++it) { /* bisection on the tip slope */
    th0 = 0.5 * (lo + hi);
    double k = sqrt((1 + sin(th0)) / 2), phi1 = asin(1 / (k * sqrt(2.0)));
    double f = val_ellK(k) - val_ellF(phi1, k) - sqrt(alpha);
    if (f > 0)
      hi = th0; /* K - F decreases? check sign by bracketing */
    else
      lo = th0;
  }
  double k = sqrt((1 + sin(th0)) / 2), phi1 = asin(1 / (k * sqrt(2.0)));
  *dh = 1 - sqrt(2 * sin(th0) / alpha);
  *dv = 1 - (2 / sqrt(alpha)) * (val_ellE(k) - val_ellEinc(phi1, k));
}

/* Same by shooting: theta'' = -alpha cos(theta), theta(0) = 0, theta'(1) = 0. */
static void shoot(double alpha, double c, double *dth1, double *x1, double *y1) {
  int N = 20000;
  double h = 1.0 / N, th = 0, w = c, x = 0, y = 0;
  for (int i = 0; i < N; ++i) {
    /* RK4 on (th, w, x, y) */
    double k1t = w, k1w = -alpha * cos(th), k1x = cos(th), k1y = sin(th);
    double t2 = th + 0.5 * h * k1t, w2 = w + 0.5 * h * k1w;
    double k2t = w2, k2w = -alpha * cos(t2), k2x = cos(t2), k2y = sin(t2);
    double t3 = th + 0.5 * h * k2t, w3 = w + 0.5 * h * k2w;
    double k3t = w3, k3w = -alpha * cos(t3), k3x = cos(t3), k3y = sin(t3);
    double t4 = th + h * k3t, w4 = w + h * k3w;
    double k4t = w4, k4w = -alpha * cos(t4), k4x = cos(t4), k4y = sin(t4);
    th += h / 6 * (k1t + 2 * k2t + 2 * k3t + k4t);
    w += h / 6 * (k1w + 2 * k2w + 2 * k3w + k4w);
    x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    y += h / 6 * (k1y + 2 * k2y + 2 * k3y + k4y);
  }
  *dth1 = w;
  *x1 = x;
  *y1 = y;
}

static void elastica_shooting(double alpha, double *dh, double *dv) {
  double lo = 0, hi = alpha, c = 0, w, x, y;
  for (int it = 0; it < 80; ++it) {
    c = 0.5 * (lo + hi);
    shoot(alpha, c, &w, &x, &y);
    if (w > 0)
      hi = c;
    else
      lo = c;
  }
  shoot(alpha, c, &w, &x, &y);
  *dh = 1 - x;
  *dv = y;
}

int main(void) {
  rn_context *ctx;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  rn_material m;
  rn_section s;
  CHECK_STATUS(rn_material_from_E_nu(1e7, 0.5, 0.0, &m), RN_OK);

  /* (1) small load: alpha = 1e-4, r = 0.01, L = 1 */
  CHECK_STATUS(rn_section_circle(0.01, &s), RN_OK);
  double EI = m.E * s.I11, L = 1.0, P = 1e-4 * EI / (L * L);
  double dref = P * L * L * L / (3 * EI);
  int ns[4] = {10, 20, 40, 80};
  double hs[4], err[4];
  for (int i = 0; i < 4; ++i) {
    double f[3] = {0, 0, -P}, tip[3];
    rn_network *net = val_clamped_rod(ctx, ns[i], L, &m, &s, f, NULL, 1);
    val_solve(net, 0);
    val_vertex(net, -1, tip);
    hs[i] = L / (ns[i] - 0.5);
    err[i] = fabs(-tip[2] - dref) / dref;
    printf("small load n=%d: deflection %.10e (PL^3/3EI %.10e) rel err %.3e\n", ns[i],
           -tip[2], dref, err[i]);
    rn_network_destroy(&net);
  }
  double order = rn_test_loglog_slope(4, hs, err);
  printf("small-load cantilever: convergence order %.3f\n", order);
  CHECK(order > 1.9 && order < 2.1);
  CHECK(err[3] < 1e-4);

  /* (2) elastica, alpha = 2: two references must agree */
  double alpha = 2.0, dh_e, dv_e, dh_s, dv_s;
  elastica_elliptic(alpha, &dh_e, &dv_e);
  elastica_shooting(alpha, &dh_s, &dv_s);
  printf("elastica alpha=2: elliptic (%.12f, %.12f), shooting (%.12f, %.12f)\n", dh_e,
         dv_e, dh_s, dv_s);
  CHECK_NEAR(dh_e, dh_s, 1e-9);
  CHECK_NEAR(dv_e, dv_s, 1e-9);
  /* linear limit sanity: dv ~ alpha / 3 for small alpha */
  double dh0, dv0;
  elastica_elliptic(1e-3, &dh0, &dv0);
  CHECK_REL(dv0, 1e-3 / 3, 1e-3);

  /* DER: thin rod (EA L^2 / EI = 4e6) so extensibility is negligible. */
  CHECK_STATUS(rn_section_circle(1e-3, &s), RN_OK);
  EI = m.E * s.I11;
  P = alpha * EI / (L * L);
  /* planar DER with mid-edge clamp, VALIDATION.md 1.3 */
  const double table[4] = {3.68e-3, 8.82e-4, 2.16e-4, 5.32e-5};
  for (int i = 0; i < 4; ++i) {
    double f[3] = {0, 0, -P}, tip[3];
    rn_network *net = val_clamped_rod(ctx, ns[i], L, &m, &s, f, NULL, 1);
    val_solve(net, 0);
    val_vertex(net, -1, tip);
    double eh = (L - tip[0]) / L - dh_e, ev = -tip[2] / L - dv_e;
    err[i] = sqrt(eh * eh + ev * ev);
    printf("elastica n=%d: tip error/L %.4e (planar DER table %.3e)\n", ns[i], err[i],
           table[i]);
    CHECK_REL(err[i], table[i], 0.02);
    rn_network_destroy(&net);
  }
  order = rn_test_loglog_slope(3, hs + 1, err + 1);
  printf("elastica alpha=2: convergence order %.3f\n", order);
  CHECK(order > 1.95 && order < 2.15);
  rn_context_destroy(&ctx);
  return rn_test_finish("val_cantilever");
}

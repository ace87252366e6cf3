/* kernels_contact.c - the contact kernels of contact.c: segment-segment
 * distances against closed forms in the point-point, point-edge and edge-edge
 * regimes (and parallel edges); the squared distance and the barrier energy's
 * gradient and Hessian against central differences with an h-sweep showing
 * second order, in every regime, at random configurations; Hessian symmetry;
 * invariance under rigid motions; the continuous collision check (tunnelling
 * motions caught, separating and rigid motions certified). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "rnk.h"
#include "testutil.h"

static uint64_t rng = 0xc0417ac7ULL;
static double rnd(void) { return rn_test_rand(&rng); }

static double dist(const double x[12]) {
  double d2 = -1.0;
  CHECK_STATUS(rnk_segment_distance2(x, &d2, NULL, NULL), RNK_OK);
  return sqrt(d2);
}

static void set(double *x, double a0, double a1, double a2, double b0, double b1,
                double b2, double c0, double c1, double c2, double d0, double d1,
                double d2) {
  const double v[12] = {a0, a1, a2, b0, b1, b2, c0, c1, c2, d0, d1, d2};
  memcpy(x, v, sizeof v);
}

static void closed_forms(void) {
  double x[12];
  /* edge-edge: perpendicular segments crossing at height 0.3 */
  set(x, -1, 0, 0, 1, 0, 0, 0.2, -1, 0.3, 0.2, 1, 0.3);
  CHECK_NEAR(dist(x), 0.3, 1e-15);
  /* skew edges: lines (t, 0, 0) and (0, s, 1) + (s, 0, 0) ... distance 1 */
  set(x, -1, 0, 0, 1, 0, 0, -0.5, -0.5, 1, 0.5, 0.5, 1);
  CHECK_NEAR(dist(x), 1.0, 1e-15);
  /* point-edge: the end (2, 0.5, 0) of a far segment over the middle of edge 0 */
  set(x, -1, 0, 0, 1, 0, 0, 0.25, 0.5, 0, 0.25, 3, 0);
  CHECK_NEAR(dist(x), 0.5, 1e-15);
  /* point-point: ends 0.7 apart along a diagonal */
  set(x, 0, 0, 0, -1, 0, 0, 0.7 / sqrt(2.0), 0.7 / sqrt(2.0), 0, 1, 2, 0);
  CHECK_NEAR(dist(x), 0.7, 1e-15);
  /* parallel, overlapping: distance 0.4 */
  set(x, 0, 0, 0, 1, 0, 0, 0.5, 0.4, 0, 1.5, 0.4, 0);
  CHECK_NEAR(dist(x), 0.4, 1e-15);
  /* parallel, disjoint along the line: end to end 0.5 */
  set(x, 0, 0, 0, 1, 0, 0, 1.3, 0.4, 0, 2.3, 0.4, 0);
  CHECK_NEAR(dist(x), 0.5, 1e-15);
  /* a zero-length edge is degenerate */
  double d2;
  set(x, 0, 0, 0, 0, 0, 0, 1, 0, 0, 2, 0, 0);
  CHECK_STATUS(rnk_segment_distance2(x, &d2, NULL, NULL), RNK_DEGENERATE);
  /* barrier: zero beyond dhat, degenerate at contact, energy value */
  rnk_contact_param p = {0.2, 0.1, 3.0};
  double E;
  set(x, -1, 0, 0, 1, 0, 0, 0.2, -1, 0.35, 0.2, 1, 0.35); /* gap 0.15 > dhat */
  CHECK_STATUS(rnk_contact_energy(x, &p, &E), RNK_OK);
  CHECK(E == 0.0);
  set(x, -1, 0, 0, 1, 0, 0, 0.2, -1, 0.25, 0.2, 1, 0.25); /* gap 0.05 */
  CHECK_STATUS(rnk_contact_energy(x, &p, &E), RNK_OK);
  CHECK_NEAR(E, -3.0 * 0.05 * 0.05 * log(0.5), 1e-15);
  set(x, -1, 0, 0, 1, 0, 0, 0.2, -1, 0.15, 0.2, 1, 0.15); /* gap -0.05 */
  CHECK_STATUS(rnk_contact_energy(x, &p, &E), RNK_DEGENERATE);
}

/* Squared distance (which = 0) or barrier energy (1), with derivatives. */
static void eval(int which, const rnk_contact_param *p, const double *x, double *E,
                 double *g, double *H) {
  if (which == 0) {
    CHECK_STATUS(rnk_segment_distance2(x, E, g, H), RNK_OK);
    return;
  }
  CHECK_STATUS(rnk_contact_grad(x, p, E, g), RNK_OK);
  if (H) CHECK_STATUS(rnk_contact_hess(x, p, H), RNK_OK);
}

/* Central differences of E and g along random directions, h = 1e-3 / 2^s. */
static void fd_sweep(int which, const rnk_contact_param *p, const double *x,
                     const char *name) {
  double g[12], H[144], E, hmax = 0.0, asym = 0.0;
  eval(which, p, x, &E, g, H);
  for (int i = 0; i < 144; ++i) hmax = fmax(hmax, fabs(H[i]));
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) asym = fmax(asym, fabs(H[12 * i + j] - H[12 * j + i]));
  CHECK(asym <= 1e-13 * hmax);
  CHECK(hmax > 0.0);
  for (int dir = 0; dir < 3; ++dir) {
    double v[12], Hv[12], gv = 0.0, nv = 0.0, ng = 0.0, nh = 0.0;
    for (int i = 0; i < 12; ++i) {
      v[i] = rnd();
      nv += v[i] * v[i];
    }
    for (int i = 0; i < 12; ++i) v[i] /= sqrt(nv);
    rnk_block_mv(12, H, v, Hv);
    for (int i = 0; i < 12; ++i) {
      gv += g[i] * v[i];
      ng += g[i] * g[i];
      nh += Hv[i] * Hv[i];
    }
    double hs[5], eg[5], eh[5];
    for (int s = 0; s < 5; ++s) {
      double h = 1e-3 / pow(2.0, s), xp[12], xm[12], Ep, Em, gp[12], gm[12], err = 0.0;
      for (int i = 0; i < 12; ++i) {
        xp[i] = x[i] + h * v[i];
        xm[i] = x[i] - h * v[i];
      }
      eval(which, p, xp, &Ep, gp, NULL);
      eval(which, p, xm, &Em, gm, NULL);
      hs[s] = h;
      eg[s] = fabs((Ep - Em) / (2 * h) - gv) / (sqrt(ng) + 1e-300);
      for (int i = 0; i < 12; ++i) {
        double d = (gp[i] - gm[i]) / (2 * h) - Hv[i];
        err += d * d;
      }
      eh[s] = sqrt(err) / (sqrt(nh) + 1e-300);
    }
    double sg = rn_test_loglog_slope(5, hs, eg), sh = rn_test_loglog_slope(5, hs, eh);
    if (eg[0] > 1e-10) {
      if (!(sg > 1.8 && sg < 2.3))
        rn_test_fail(__FILE__, __LINE__,
                     "%s gradient FD order %.3f (errors %.3g .. %.3g)", name, sg, eg[0],
                     eg[4]);
      rn_test_checks++;
    }
    CHECK(eg[4] < 1e-6);
    if (eh[0] > 1e-10) {
      if (!(sh > 1.8 && sh < 2.3))
        rn_test_fail(__FILE__, __LINE__, "%s Hessian FD order %.3f (errors %.3g .. %.3g)",
                     name, sh, eh[0], eh[4]);
      rn_test_checks++;
    }
    CHECK(eh[4] < 1e-6);
  }
}

/* Random configurations of each regime, the second segment placed so that
 * its closest points sit well inside the regime (no boundary within the
 * sweep); the gap inside the barrier's range. */
static void regimes(void) {
  rnk_contact_param p = {0.1, 0.2, 2.5};
  for (int trial = 0; trial < 20; ++trial) {
    double x[12], a[3], b[3], n[3], u[3];
    for (int k = 0; k < 3; ++k) {
      a[k] = rnd();
      b[k] = rnd();
    }
    rn_test_cross3(a, b, n);
    rn_test_normalize3(n);
    rn_test_normalize3(a);
    rn_test_cross3(n, a, u); /* a, u, n orthonormal */
    double off = p.radius + 0.3 * p.dhat + 0.5 * p.dhat * fabs(rnd());
    double ang = 0.4 + 0.8 * fabs(rnd());
    double s0 = 0.3 + 0.4 * fabs(rnd());
    /* edge-edge: edge 0 along a (length 1.3), edge 1 at angle ang in the plane
     * at height off */
    for (int k = 0; k < 3; ++k) {
      double c = s0 * 1.3 * a[k] + off * n[k];
      double d = cos(ang) * a[k] + sin(ang) * u[k];
      x[k] = 0.0;
      x[3 + k] = 1.3 * a[k];
      x[6 + k] = c - 0.6 * d;
      x[9 + k] = c + 0.9 * d;
    }
    fd_sweep(0, &p, x, "distance2, edge-edge");
    fd_sweep(1, &p, x, "barrier, edge-edge");
    /* point-edge: q0 above the interior of edge 0, q1 farther away */
    for (int k = 0; k < 3; ++k) {
      double c = s0 * 1.3 * a[k] + off * n[k];
      x[6 + k] = c;
      x[9 + k] = c + 0.8 * n[k] + 0.3 * u[k];
    }
    fd_sweep(0, &p, x, "distance2, point-edge");
    fd_sweep(1, &p, x, "barrier, point-edge");
    /* point-point: q0 beyond the end p1 along a direction away from both */
    double w[3];
    for (int k = 0; k < 3; ++k) w[k] = 0.7 * a[k] + 0.5 * n[k] + 0.2 * u[k];
    rn_test_normalize3(w);
    for (int k = 0; k < 3; ++k) {
      x[6 + k] = x[3 + k] + off * w[k];
      x[9 + k] = x[6 + k] + 0.9 * w[k] + 0.2 * u[k];
    }
    fd_sweep(0, &p, x, "distance2, point-point");
    fd_sweep(1, &p, x, "barrier, point-point");
    /* parallel edges (the boundary cases stand in for the edge-edge regime) */
    for (int k = 0; k < 3; ++k) {
      x[6 + k] = 0.4 * a[k] + off * n[k];
      x[9 + k] = 1.9 * a[k] + off * n[k];
    }
    double gap;
    CHECK_STATUS(rnk_contact_gap(x, p.radius, &gap), RNK_OK);
    CHECK_NEAR(gap, off - p.radius, 1e-14);
  }
}

static void rigid_invariance(void) {
  rnk_contact_param p = {0.1, 0.2, 2.5};
  double x[12], y[12], R[9], Ex, Ey;
  set(x, -1, 0.1, 0, 1, 0, 0.05, 0.2, -1, 0.22, 0.25, 1, 0.2);
  const double th = 0.7, c = cos(th), s = sin(th);
  const double Rm[9] = {c, -s, 0, s * 0.6, c * 0.6, -0.8, s * 0.8, c * 0.8, 0.6};
  memcpy(R, Rm, sizeof R);
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k)
      y[3 * i + k] = R[3 * k] * x[3 * i] + R[3 * k + 1] * x[3 * i + 1] +
                     R[3 * k + 2] * x[3 * i + 2] + 0.3 * (k + 1);
  CHECK_STATUS(rnk_contact_energy(x, &p, &Ex), RNK_OK);
  CHECK_STATUS(rnk_contact_energy(y, &p, &Ey), RNK_OK);
  CHECK(Ex > 0.0);
  CHECK_NEAR(Ey, Ex, 1e-13 * Ex);
}

static void ccd(void) {
  double x0[12], x1[12];
  int hit = -1;
  /* the second segment passes straight through the first: both ends clear */
  set(x0, -1, 0, 0, 1, 0, 0, 0, -1, 0.5, 0, 1, 0.5);
  set(x1, -1, 0, 0, 1, 0, 0, 0, -1, -0.5, 0, 1, -0.5);
  CHECK_STATUS(rnk_contact_ccd(x0, x1, 0.1, 0.2, &hit), RNK_OK);
  CHECK(hit == 1);
  /* moving apart */
  set(x1, -1, 0, 0, 1, 0, 0, 0, -1, 1.5, 0, 1, 1.5);
  CHECK_STATUS(rnk_contact_ccd(x0, x1, 0.1, 0.2, &hit), RNK_OK);
  CHECK(hit == 0);
  /* both translated far together (no relative motion) */
  for (int i = 0; i < 12; ++i) x1[i] = x0[i] + (i % 3 == 1 ? 50.0 : 0.0);
  CHECK_STATUS(rnk_contact_ccd(x0, x1, 0.1, 0.2, &hit), RNK_OK);
  CHECK(hit == 0);
  /* sliding past sideways at a clear height: certified */
  set(x1, -1, 0, 0, 1, 0, 0, 3, -1, 0.5, 3, 1, 0.5);
  CHECK_STATUS(rnk_contact_ccd(x0, x1, 0.1, 0.2, &hit), RNK_OK);
  CHECK(hit == 0);
  /* a rotation of the second segment that sweeps through the first, its
   * end positions on either side and clear */
  set(x0, -1, 0, 0, 1, 0, 0, 0.5, 0, -1, 0.5, 0, 1);
  set(x1, -1, 0, 0, 1, 0, 0, -0.5, 0, -1, -0.5, 0, 1);
  CHECK_STATUS(rnk_contact_ccd(x0, x1, 0.1, 0.2, &hit), RNK_OK);
  CHECK(hit == 1);
}

int main(void) {
  closed_forms();
  regimes();
  rigid_invariance();
  ccd();
  return rn_test_finish("kernels_contact");
}

/* contact.c - rod-rod contact between two segments: the squared distance
 * between segments in its point-point, point-edge and edge-edge regimes with
 * exact gradient and Hessian, the barrier of incremental potential contact on
 * the gap (distance minus the sum of the radii), and a conservative-advancement
 * continuous collision check of a linear motion of the pair.
 *
 * Distance.  With x = (p0, p1, q0, q1), the squared distance is
 * d2(x) = min over (s, t) in [0,1]^2 of g(x, s, t) = |r|^2,
 * r = (1 - s) p0 + s p1 - (1 - t) q0 - t q1.  In each regime the bounded
 * parameters sit at 0 or 1 and the free ones (set u) minimise g, so by the
 * envelope theorem grad d2 = g_x and Hess d2 = g_xx - g_xu g_uu^-1 g_ux, exactly
 * the derivatives of that regime's closed form (|p - q|^2, the point-line or
 * the line-line distance).  The regime is the one of the box-constrained
 * minimiser; the edge-edge regime is used only when the edges are not nearly
 * parallel (sin^2 of their angle above RNK_CONTACT_PARALLEL), otherwise the
 * minimum over the four boundary cases (point-edge), which for parallel edges
 * is the distance. */
#include <math.h>

#include "rnk.h"
#include "rodq.h"

/* Parameters and regime of the closest points. */
typedef struct seg_closest {
  double s, t;
  int fs, ft; /* 1: the parameter is free (interior) */
} seg_closest;

static double clamp01(double v) { return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v); }

/* Value of g at (s, t) from the quadratic's coefficients. */
static double quad(double a, double b, double c, double d, double e, double ww, double s,
                   double t) {
  return a * s * s - 2.0 * b * s * t + c * t * t + 2.0 * d * s - 2.0 * e * t + ww;
}

/* The box-constrained minimiser of g (a, c > 0). */
static seg_closest closest(const double *x) {
  double e0[3], e1[3], w[3];
  for (int k = 0; k < 3; ++k) {
    e0[k] = x[3 + k] - x[k];
    e1[k] = x[9 + k] - x[6 + k];
    w[k] = x[k] - x[6 + k];
  }
  const double a = rq_dot3(e0, e0), b = rq_dot3(e0, e1), c = rq_dot3(e1, e1);
  const double d = rq_dot3(e0, w), e = rq_dot3(e1, w), ww = rq_dot3(w, w);
  const double det = a * c - b * b;
  seg_closest best = {0.0, 0.0, 0, 0};
  if (det > RNK_CONTACT_PARALLEL * a * c) {
    double s = (b * e - c * d) / det, t = (a * e - b * d) / det;
    if (s > 0.0 && s < 1.0 && t > 0.0 && t < 1.0) {
      best.s = s;
      best.t = t;
      best.fs = best.ft = 1;
      return best;
    }
  }
  /* the four sides of the box: s = 0, s = 1 (t free), t = 0, t = 1 (s free) */
  double gbest = INFINITY;
  for (int side = 0; side < 4; ++side) {
    seg_closest cand;
    if (side < 2) {
      cand.s = (double)side;
      cand.t = clamp01((e + b * cand.s) / c);
      cand.fs = 0;
      cand.ft = cand.t > 0.0 && cand.t < 1.0;
    } else {
      cand.t = (double)(side - 2);
      cand.s = clamp01((b * cand.t - d) / a);
      cand.ft = 0;
      cand.fs = cand.s > 0.0 && cand.s < 1.0;
    }
    double gv = quad(a, b, c, d, e, ww, cand.s, cand.t);
    if (gv < gbest) {
      gbest = gv;
      best = cand;
    }
  }
  return best;
}

int rnk_segment_distance2(const double x[12], double *d2, double *g, double *H) {
  double e0[3], e1[3], r[3];
  for (int k = 0; k < 3; ++k) {
    e0[k] = x[3 + k] - x[k];
    e1[k] = x[9 + k] - x[6 + k];
  }
  const double a = rq_dot3(e0, e0), b = rq_dot3(e0, e1), c = rq_dot3(e1, e1);
  if (!(a > 0.0) || !(c > 0.0)) return RNK_DEGENERATE;
  const seg_closest cl = closest(x);
  const double cf[4] = {1.0 - cl.s, cl.s, -(1.0 - cl.t), -cl.t};
  for (int k = 0; k < 3; ++k)
    r[k] = cf[0] * x[k] + cf[1] * x[3 + k] + cf[2] * x[6 + k] + cf[3] * x[9 + k];
  *d2 = rq_dot3(r, r);
  if (g)
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) g[3 * i + k] = 2.0 * cf[i] * r[k];
  if (!H) return RNK_OK;
  /* g_xx */
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j)
      H[12 * i + j] = (i % 3 == j % 3) ? 2.0 * cf[i / 3] * cf[j / 3] : 0.0;
  /* columns of g_xu for the free parameters and the matrix g_uu */
  double G[2][12], U[2][2];
  int nf = 0;
  const double ds[4] = {-1.0, 1.0, 0.0, 0.0}, dt[4] = {0.0, 0.0, -1.0, 1.0};
  int fidx[2];
  if (cl.fs) fidx[nf++] = 0;
  if (cl.ft) fidx[nf++] = 1;
  for (int m = 0; m < nf; ++m)
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k)
        G[m][3 * i + k] = fidx[m] == 0 ? 2.0 * (cf[i] * e0[k] + ds[i] * r[k])
                                       : -2.0 * (cf[i] * e1[k] + dt[i] * r[k]);
  const double Ufull[2][2] = {{2.0 * a, -2.0 * b}, {-2.0 * b, 2.0 * c}};
  for (int m = 0; m < nf; ++m)
    for (int l = 0; l < nf; ++l) U[m][l] = Ufull[fidx[m]][fidx[l]];
  if (nf == 1) {
    const double inv = 1.0 / U[0][0];
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j) H[12 * i + j] -= G[0][i] * G[0][j] * inv;
  } else if (nf == 2) {
    const double det = U[0][0] * U[1][1] - U[0][1] * U[1][0];
    const double Ui[2][2] = {{U[1][1] / det, -U[0][1] / det},
                             {-U[1][0] / det, U[0][0] / det}};
    for (int i = 0; i < 12; ++i)
      for (int j = 0; j < 12; ++j) {
        double s = 0.0;
        for (int m = 0; m < 2; ++m)
          for (int l = 0; l < 2; ++l) s += G[m][i] * Ui[m][l] * G[l][j];
        H[12 * i + j] -= s;
      }
  }
  return RNK_OK;
}

/* Barrier b(y) = -kappa (y - h)^2 log(y / h) on 0 < y < h and its first two
 * derivatives; zero for y >= h. */
static void barrier(double y, const rnk_contact_param *p, double b[3]) {
  const double h = p->dhat, k = p->kappa;
  if (y >= h) {
    b[0] = b[1] = b[2] = 0.0;
    return;
  }
  const double l = log(y / h), u = y - h;
  b[0] = -k * u * u * l;
  b[1] = -k * (2.0 * u * l + u * u / y);
  b[2] = -k * (2.0 * l + 4.0 * u / y - u * u / (y * y));
}

/* The common body: E, optionally gradient and Hessian (ord 0, 1, 2). */
static int contact_eval(const double x[12], const rnk_contact_param *p, int ord,
                        double *E, double *g, double *H) {
  double d2, gd[12], Hd[144], bb[3];
  int rc = rnk_segment_distance2(x, &d2, ord >= 1 ? gd : NULL, ord >= 2 ? Hd : NULL);
  if (rc != RNK_OK) return rc;
  const double D = sqrt(d2), gap = D - p->radius;
  if (!(gap > 0.0)) return RNK_DEGENERATE; /* interpenetration */
  barrier(gap, p, bb);
  if (E) *E = bb[0];
  if (g)
    for (int i = 0; i < 12; ++i) g[i] = bb[1] * gd[i] / (2.0 * D);
  if (ord >= 2) {
    /* D_x = d2_x / (2D); D_xx = d2_xx / (2D) - d2_x d2_x^T / (4 D^3) */
    const double c1 = bb[1] / (2.0 * D), c2 = bb[2] / (4.0 * d2) - bb[1] / (4.0 * d2 * D);
    for (int i = 0; i < 144; ++i) H[i] = 0.0;
    if (bb[1] != 0.0 || bb[2] != 0.0)
      for (int i = 0; i < 12; ++i)
        for (int j = 0; j < 12; ++j)
          H[12 * i + j] = c1 * Hd[12 * i + j] + c2 * gd[i] * gd[j];
  }
  return RNK_OK;
}

int rnk_contact_energy(const double x[12], const rnk_contact_param *p, double *E) {
  return contact_eval(x, p, 0, E, NULL, NULL);
}

int rnk_contact_grad(const double x[12], const rnk_contact_param *p, double *E,
                     double g[12]) {
  return contact_eval(x, p, 1, E, g, NULL);
}

int rnk_contact_hess(const double x[12], const rnk_contact_param *p, double H[144]) {
  return contact_eval(x, p, 2, NULL, NULL, H);
}

int rnk_contact_gap(const double x[12], double radius, double *gap) {
  double d2;
  int rc = rnk_segment_distance2(x, &d2, NULL, NULL);
  if (rc == RNK_OK) *gap = sqrt(d2) - radius;
  return rc;
}

int rnk_contact_ccd(const double x0[12], const double x1[12], double radius, double dhat,
                    int *hit) {
  enum { MAX_ITER = 256 };
  const double eta = 0.1;
  double dx[12], xt[12], gap, vmax = 0.0;
  int rc;
  for (int i = 0; i < 12; ++i) dx[i] = x1[i] - x0[i];
  /* bound on the rate of change of the distance: the largest relative motion
   * of an end of one segment against an end of the other */
  for (int i = 0; i < 2; ++i)
    for (int j = 2; j < 4; ++j) {
      double v[3];
      for (int k = 0; k < 3; ++k) v[k] = dx[3 * i + k] - dx[3 * j + k];
      double n = sqrt(rq_dot3(v, v));
      if (n > vmax) vmax = n;
    }
  *hit = 1;
  if ((rc = rnk_contact_gap(x0, radius, &gap)) != RNK_OK) return rc;
  if (!(gap > 0.0)) return RNK_OK;
  const double thr = eta * (gap < dhat ? gap : dhat);
  double t = 0.0;
  for (int it = 0; it < MAX_ITER && gap >= 2.0 * thr; ++it) {
    /* the gap stays above thr on [t, t + (gap - thr) / vmax] */
    if (!(vmax > 0.0) || t + (gap - thr) / vmax >= 1.0) {
      *hit = 0;
      return RNK_OK;
    }
    t += (gap - thr) / vmax;
    for (int i = 0; i < 12; ++i) xt[i] = x0[i] + t * dx[i];
    if ((rc = rnk_contact_gap(xt, radius, &gap)) != RNK_OK) return rc;
  }
  return RNK_OK; /* below 2 thr, or not certified within MAX_ITER: a hit */
}

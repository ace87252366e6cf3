/* frameq.h - closed-form derivatives of functions of one edge's material
 * frame given by its (unnormalised) quaternion h = q(t) (x) g(theta)
 * (rodq.h), and of rotations given by rotation vectors; internal to kernels/
 * (joint and couple kernels; docs/energy.md "Closed forms of the joints").
 *
 * The chain h -> y = (t[3], theta) -> (e[3], theta):
 *   dh/dt_i = D_i = (t_hat_i, t_hat x e_i) (x) g,  dh/dtheta = h (x) X / 2,
 *   d2h/dt dt = 0, d2h/dt_i dtheta = D_i (x) X / 2, d2h/dtheta2 = -h / 4,
 * and t = e / |e| (rq_project, rq_curv_add). */
#ifndef RODNET_FRAMEQ_H
#define RODNET_FRAMEQ_H

#include "rodq.h"

/* Columns J[i] = dh/dy_i (i = 0..2 tangent, 3 angle) of an edge. */
RQ_INLINE void fq_dh_dy(const rq_edge *E, double J[4][4]) {
  RQ_UNROLL for (int k = 0; k < 3; ++k) {
    const double *th = E->th;
    double kq[4] = {th[k], 0.0, 0.0, 0.0};
    kq[1 + (k + 1) % 3] = th[(k + 2) % 3];
    kq[1 + (k + 2) % 3] = -th[(k + 1) % 3];
    rq_qmul(kq, E->g, J[k]);
  }
  rq_mulX(E->h, J[3]);
  RQ_UNROLL for (int k = 0; k < 4; ++k) J[3][k] *= 0.5;
}

/* Gradient in y of a function of h with dE/dh = gam. */
RQ_INLINE void fq_grad_y(double J[4][4], const double gam[4], double gy[4]) {
  RQ_UNROLL for (int i = 0; i < 4; ++i) gy[i] = rq_qdot(J[i], gam);
}

/* Hessian in y from dE/dh = gam and d2E/dh2 = Gam: J^T Gam J plus gam .
 * d2h/dy2 (theta row and column). */
RQ_INLINE void fq_hess_y(const rq_edge *E, double J[4][4], const double gam[4],
                         double Gam[4][4], double Hy[4][4]) {
  double GJ[4][4], gX[4];
  RQ_UNROLL for (int c = 0; c < 4; ++c) RQ_UNROLL for (int i = 0; i < 4; ++i) GJ[c][i] =
      Gam[i][0] * J[c][0] + Gam[i][1] * J[c][1] + Gam[i][2] * J[c][2] +
      Gam[i][3] * J[c][3];
  RQ_UNROLL for (int c = 0; c < 4; ++c) RQ_UNROLL for (int d = c; d < 4; ++d) Hy[c][d] =
      Hy[d][c] = rq_qdot(J[c], GJ[d]);
  /* gam . (D_i (x) X) / 2 = -(gam (x) X) . D_i / 2 */
  rq_mulX(gam, gX);
  RQ_UNROLL for (int i = 0; i < 3; ++i) {
    double s = -0.5 * rq_qdot(gX, J[i]);
    Hy[i][3] += s;
    Hy[3][i] += s;
  }
  Hy[3][3] -= 0.25 * rq_qdot(gam, E->h);
}

/* Davenport's matrix: <B, R(p)> = p^T K p / |p|^2 for the rotation R(p) of a
 * quaternion p (B row-major). */
RQ_INLINE void fq_davenport(const double B[9], double K[4][4]) {
  double tr = B[0] + B[4] + B[8];
  double z[3] = {B[7] - B[5], B[2] - B[6], B[3] - B[1]};
  K[0][0] = tr;
  RQ_UNROLL for (int i = 0; i < 3; ++i) {
    K[0][1 + i] = K[1 + i][0] = z[i];
    RQ_UNROLL for (int j = 0; j < 3; ++j) K[1 + i][1 + j] =
        B[3 * i + j] + B[3 * j + i] - (i == j ? tr : 0.0);
  }
}

/* f = h^T K h / |h|^2: value, gradient and Hessian in h added to f, gam, Gam
 * (Gam may be NULL). */
RQ_INLINE double fq_rayleigh_add(double K[4][4], const double h[4], double gam[4],
                                 double Gam[4][4]) {
  double Kh[4], n = rq_qdot(h, h), in = 1.0 / n;
  RQ_UNROLL for (int i = 0; i < 4; ++i) Kh[i] =
      K[i][0] * h[0] + K[i][1] * h[1] + K[i][2] * h[2] + K[i][3] * h[3];
  double f = rq_qdot(h, Kh) * in, gf[4];
  RQ_UNROLL for (int i = 0; i < 4; ++i) gf[i] = 2.0 * (Kh[i] - f * h[i]) * in;
  if (gam) RQ_UNROLL for (int i = 0; i < 4; ++i) gam[i] += gf[i];
  if (Gam)
    RQ_UNROLL for (int i = 0; i < 4; ++i) RQ_UNROLL for (int j = 0; j < 4; ++j)
        Gam[i][j] +=
        (2.0 * (K[i][j] - (i == j ? f : 0.0)) - 2.0 * (h[i] * gf[j] + gf[i] * h[j])) * in;
  return f;
}

/* Rotation matrix (row-major) of the unit quaternion h / |h|. */
RQ_INLINE void fq_quat_matrix(const double h[4], double R[9]) {
  double in = 1.0 / rq_qdot(h, h), w = h[0], x = h[1], y = h[2], z = h[3];
  R[0] = (w * w + x * x - y * y - z * z) * in;
  R[4] = (w * w - x * x + y * y - z * z) * in;
  R[8] = (w * w - x * x - y * y + z * z) * in;
  R[1] = 2.0 * (x * y - w * z) * in;
  R[3] = 2.0 * (x * y + w * z) * in;
  R[2] = 2.0 * (x * z + w * y) * in;
  R[6] = 2.0 * (x * z - w * y) * in;
  R[5] = 2.0 * (y * z - w * x) * in;
  R[7] = 2.0 * (y * z + w * x) * in;
}

/* Quaternion (any positive scale) of a rotation matrix R (row-major). */
RQ_INLINE void fq_matrix_quat(const double R[9], double p[4]) {
  rnk_frame f = {{R[0], R[3], R[6]}, {R[1], R[4], R[7]}};
  rq_frame_quat(&f, p);
}

/* Unit quaternion P(w) of the rotation exp([w]) and its first and second
 * derivatives in w: P = (a(s), b(s) w), s = |w|^2, a = cos(r/2),
 * b = sin(r/2)/r (series for s <= 4, closed forms beyond). */
typedef struct fq_rot {
  double P[4];
  double dP[3][4];
  double d2P[3][3][4];
} fq_rot;

/* Taylor coefficients in s of a, a', a'', b, b', b'' (13 terms: the
 * remainder is below 1e-21 for s <= 4), generated from
 * a = sum (-1)^k s^k / (4^k (2k)!), b = sum (-1)^k s^k / (2 4^k (2k+1)!). */
static const double fq_series[6][13] = {
    {1, -0.125, 0.0026041666666666665, -2.170138888888889e-05, 9.6881200396825397e-08,
     -2.6911444554673719e-10, 5.0968644989912354e-13, -7.0011874986143338e-16,
     7.2929036443899311e-19, -5.9582546114296819e-22, 3.919904349624791e-25,
     -2.1211603623510776e-28, 9.6067045396335029e-32},
    {-0.125, 0.005208333333333333, -6.5104166666666666e-05, 3.8752480158730159e-07,
     -1.3455722277336862e-09, 3.0581186993947412e-12, -4.9008312490300334e-15,
     5.8343229155119449e-18, -5.3624291502867138e-21, 3.9199043496247909e-24,
     -2.3332763985861853e-27, 1.1528045447560203e-30, -4.8033522698167515e-34},
    {0.005208333333333333, -0.00013020833333333333, 1.1625744047619049e-06,
     -5.3822889109347446e-09, 1.5290593496973705e-11, -2.9404987494180202e-14,
     4.0840260408583613e-17, -4.289943320229371e-20, 3.5279139146623119e-23,
     -2.3332763985861851e-26, 1.2680849992316224e-29, -5.7640227237801014e-33,
     2.2237741989892369e-36},
    {0.5, -0.020833333333333332, 0.00026041666666666666, -1.5500992063492063e-06,
     5.3822889109347446e-09, -1.2232474797578965e-11, 1.9603324996120133e-14,
     -2.333729166204778e-17, 2.1449716601146855e-20, -1.5679617398499164e-23,
     9.3331055943447412e-27, -4.6112181790240814e-30, 1.9213409079267006e-33},
    {-0.020833333333333332, 0.00052083333333333333, -4.6502976190476195e-06,
     2.1529155643738979e-08, -6.1162373987894818e-11, 1.1761994997672081e-13,
     -1.6336104163433445e-16, 1.7159773280917484e-19, -1.4111655658649248e-22,
     9.3331055943447406e-26, -5.0723399969264897e-29, 2.3056090895120406e-32,
     -8.8950967959569475e-36},
    {0.00052083333333333333, -9.3005952380952389e-06, 6.4587466931216936e-08,
     -2.4464949595157927e-10, 5.8809974988360406e-13, -9.8016624980600667e-16,
     1.2011841296642239e-18, -1.1289324526919398e-21, 8.3997950349102667e-25,
     -5.0723399969264892e-28, 2.5361699984632447e-31, -1.0674116155148335e-34,
     3.8340934465331669e-38}};

static inline void fq_rot_eval(const double w[3], int ord, fq_rot *R) {
  double s = w[0] * w[0] + w[1] * w[1] + w[2] * w[2], a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
  if (s <= 4.0) {
    for (int d = 0; d <= ord && d < 3; ++d) {
      double pa = 0.0, pb = 0.0;
      for (int k = 12; k >= 0; --k) {
        pa = pa * s + fq_series[d][k];
        pb = pb * s + fq_series[3 + d][k];
      }
      a[d] = pa;
      b[d] = pb;
    }
  } else {
    double r = sqrt(s), sh = sin(0.5 * r), ch = cos(0.5 * r), r3 = r * s;
    double u = 0.5 * r * ch - sh;
    a[0] = ch;
    a[1] = -sh / (4.0 * r);
    a[2] = -u / (8.0 * r3);
    b[0] = sh / r;
    b[1] = u / (2.0 * r3);
    b[2] = -sh / (16.0 * r3) - 3.0 * u / (4.0 * r3 * s);
  }
  R->P[0] = a[0];
  for (int k = 0; k < 3; ++k) R->P[1 + k] = b[0] * w[k];
  if (ord < 1) return;
  for (int i = 0; i < 3; ++i) {
    R->dP[i][0] = 2.0 * a[1] * w[i];
    for (int k = 0; k < 3; ++k)
      R->dP[i][1 + k] = (i == k ? b[0] : 0.0) + 2.0 * b[1] * w[i] * w[k];
  }
  if (ord < 2) return;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      R->d2P[i][j][0] = (i == j ? 2.0 * a[1] : 0.0) + 4.0 * a[2] * w[i] * w[j];
      for (int k = 0; k < 3; ++k)
        R->d2P[i][j][1 + k] =
            2.0 * b[1] *
                ((i == j ? w[k] : 0.0) + (i == k ? w[j] : 0.0) + (j == k ? w[i] : 0.0)) +
            4.0 * b[2] * w[i] * w[j] * w[k];
    }
}

#endif

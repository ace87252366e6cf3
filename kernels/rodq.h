/* rodq.h - closed-form bending and twisting of a vertex stencil from
 * quaternions of the material frames (internal to kernels/; docs/energy.md,
 * "Closed forms").
 *
 * Quaternions are double[4] = (w, x, y, z), a (x) b the Hamilton product, a*
 * the conjugate.  A frame (t, d1, d2) is the rotation taking the axes
 * (e_x, e_y, e_z) to it.  For edge j:
 *   g_j = fhat_j (x) x(theta_j)     stored reference frame (t_hat, a1_hat)
 *                                   turned by theta about its tangent,
 *                                   x(theta) = (cos theta/2, sin theta/2, 0, 0);
 *   q_j = (1 + t_hat . t, t_hat x t) the parallel transport from t_hat to t
 *                                   (the time-parallel transport of the
 *                                   reference director), LINEAR in t;
 *   h_j = q_j (x) g_j                the material frame (t, d1, d2).
 * None is normalised: every quantity below is homogeneous of degree 0 in each
 * h_j.  The relative rotation r = h_0* (x) h_1 = (w, x, y, z) is bilinear in
 * (t_0, t_1) and, with rho = w^2 + x^2 (proportional to 1 + t_0 . t_1),
 *   kappa_1 = 2 w z / rho,  kappa_2 = -2 w y / rho,
 *   d tau   = 2 (w dx - x dw) / rho,
 * exactly seed 000 (2.2) kappa = ((t1.d1_0 - t0.d1_1), (t1.d2_0 - t0.d2_1)) /
 * (1 + t0.t1) and the twist theta_1 - theta_0 + reference twist, whose value
 * is continued from the stored reference twist (wrapped difference).  With
 * z = w + i x, w / rho = Re(1/z) and tau/2 = arg z + const, so all second
 * derivatives in r come from powers of 1/z. */
#ifndef RODNET_RODQ_H
#define RODNET_RODQ_H

#include <math.h>

#include "rnk.h"
#include "rqmath.h"

/* Small fixed loops are unrolled completely, so that the loops over
 * stencils that contain them vectorise at -O2. */
#if defined(__GNUC__) && !defined(__clang__)
#define RQ_UNROLL _Pragma("GCC unroll 16")
#else
#define RQ_UNROLL
#endif
#if defined(__GNUC__)
#define RQ_INLINE static inline __attribute__((always_inline))
#else
#define RQ_INLINE static inline
#endif

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

RQ_INLINE double rq_dot3(const double a[3], const double b[3]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

RQ_INLINE void rq_cross3(const double a[3], const double b[3], double r[3]) {
  double t0 = a[1] * b[2] - a[2] * b[1], t1 = a[2] * b[0] - a[0] * b[2],
         t2 = a[0] * b[1] - a[1] * b[0];
  r[0] = t0;
  r[1] = t1;
  r[2] = t2;
}

RQ_INLINE double rq_qdot(const double a[4], const double b[4]) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3];
}

/* r = a (x) b; ca, cb: conjugate a or b first.  r may alias neither. */
RQ_INLINE void rq_qmul_c(const double a[4], int ca, const double b[4], int cb,
                         double r[4]) {
  double sa = ca ? -1.0 : 1.0, sb = cb ? -1.0 : 1.0;
  double aw = a[0], ax = sa * a[1], ay = sa * a[2], az = sa * a[3];
  double bw = b[0], bx = sb * b[1], by = sb * b[2], bz = sb * b[3];
  r[0] = aw * bw - ax * bx - ay * by - az * bz;
  r[1] = aw * bx + ax * bw + ay * bz - az * by;
  r[2] = aw * by - ax * bz + ay * bw + az * bx;
  r[3] = aw * bz + ax * by - ay * bx + az * bw;
}
RQ_INLINE void rq_qmul(const double a[4], const double b[4], double r[4]) {
  rq_qmul_c(a, 0, b, 0, r);
}

/* a (x) X and X (x) a with X = (0, 1, 0, 0) (the tangent axis). */
RQ_INLINE void rq_mulX(const double a[4], double r[4]) {
  double w = a[0], x = a[1], y = a[2], z = a[3];
  r[0] = -x;
  r[1] = w;
  r[2] = z;
  r[3] = -y;
}
RQ_INLINE void rq_Xmul(const double a[4], double r[4]) {
  double w = a[0], x = a[1], y = a[2], z = a[3];
  r[0] = -x;
  r[1] = w;
  r[2] = -z;
  r[3] = y;
}

/* Quaternion of the frame (t, a1, t x a1), scaled by 4 times its largest
 * component (Shepperd's choice, sqrt-free: scale does not matter here). */
RQ_INLINE void rq_frame_quat(const rnk_frame *f, double out[4]) {
  const double *t = f->t, *a = f->a1;
  double b[3];
  rq_cross3(t, a, b);
  double R00 = t[0], R10 = t[1], R20 = t[2], R01 = a[0], R11 = a[1], R21 = a[2];
  double R02 = b[0], R12 = b[1], R22 = b[2];
  double dw = 1.0 + R00 + R11 + R22, dx = 1.0 + R00 - R11 - R22;
  double dy = 1.0 - R00 + R11 - R22, dz = 1.0 - R00 - R11 + R22;
  double aw = R21 - R12, bw = R02 - R20, cw = R10 - R01;
  double sxy = R01 + R10, sxz = R02 + R20, syz = R12 + R21;
  /* selects on comparisons only (no integer values: the loops that call
   * this vectorise) */
  double mwx = dw >= dx ? dw : dx, myz = dy >= dz ? dy : dz, m = mwx >= myz ? mwx : myz;
  out[0] = dw == m ? dw : dx == m ? aw : dy == m ? bw : cw;
  out[1] = dw == m ? aw : dx == m ? dx : dy == m ? sxy : sxz;
  out[2] = dw == m ? bw : dx == m ? sxy : dy == m ? dy : syz;
  out[3] = dw == m ? cw : dx == m ? sxz : dy == m ? syz : dz;
}

/* One edge of a vertex stencil. */
typedef struct rq_edge {
  double t[3];   /* unit tangent */
  double l, il;  /* |e|, 1 / |e| */
  double th[3];  /* stored reference tangent t_hat */
  double g[4];   /* fhat (x) x(theta) */
  double q[4];   /* (1 + t_hat . t, t_hat x t) */
  double h[4];   /* q (x) g */
  double cs, sn; /* cos, sin of theta / 2 */
  double theta;
  double short_; /* 1: zero-length (or non-finite) edge, else 0 */
  double bad;    /* 1: short_, or t opposite to t_hat, else 0 */
} rq_edge;

RQ_INLINE void rq_edge_init(const double e[3], double theta, const rnk_frame *ref,
                            rq_edge *E) {
  double l2 = rq_dot3(e, e), f[4];
  E->short_ = l2 > 0.0 ? (l2 <= 1.79e308 ? 0.0 : 1.0) : 1.0;
  E->l = sqrt(l2);
  E->il = 1.0 / E->l;
  RQ_UNROLL for (int k = 0; k < 3; ++k) {
    E->t[k] = e[k] * E->il;
    E->th[k] = ref->t[k];
  }
  double c1 = 1.0 + rq_dot3(E->th, E->t);
  E->bad = c1 >= RNK_OPPOSITE_TOL ? E->short_ : 1.0;
  rq_frame_quat(ref, f);
  E->theta = theta;
  rq_sincos(0.5 * theta, &E->sn, &E->cs);
  E->g[0] = f[0] * E->cs - f[1] * E->sn;
  E->g[1] = f[0] * E->sn + f[1] * E->cs;
  E->g[2] = f[2] * E->cs + f[3] * E->sn;
  E->g[3] = f[3] * E->cs - f[2] * E->sn;
  E->q[0] = c1;
  rq_cross3(E->th, E->t, E->q + 1);
  rq_qmul(E->q, E->g, E->h);
}

/* Angles beyond RQ_TRIG_MAX: cos, sin of theta / 2 from libm (a branch:
 * the vectorised loops call this afterwards, in a loop of their own). */
RQ_INLINE void rq_edge_big_angle(const rnk_frame *ref, rq_edge *E) {
  if (!(fabs(0.5 * E->theta) > RQ_TRIG_MAX)) return;
  double f[4];
  rq_frame_quat(ref, f);
  E->cs = cos(0.5 * E->theta);
  E->sn = sin(0.5 * E->theta);
  E->g[0] = f[0] * E->cs - f[1] * E->sn;
  E->g[1] = f[0] * E->sn + f[1] * E->cs;
  E->g[2] = f[2] * E->cs + f[3] * E->sn;
  E->g[3] = f[3] * E->cs - f[2] * E->sn;
  rq_qmul(E->q, E->g, E->h);
}

/* Strains, energy and the gradient in r of one vertex. */
typedef struct rq_vert {
  double r[4];
  double u1[2], u2[2], u3[2]; /* 1/z, 1/z^2, 1/z^3 (re, im), z = w + i x */
  double phi;                 /* w / rho */
  double kappa[2], tau;
  double ref_twist;  /* reference twist, continued from the stored value */
  double B[3], beta; /* stiffnesses divided by the Voronoi length */
  double m1, m2, mt; /* dE/dkappa_1, dE/dkappa_2, dE/dtau */
  double mu[4];      /* dE/dr */
  double Eb, Et;
  double bad; /* 1: 1 + t0 . t1 too small, else 0 */
} rq_vert;

/* Value part (energy), first-order part (mu) when ord >= 1. */
RQ_INLINE void rq_vert_eval(const rq_edge *E0, const rq_edge *E1,
                            const rnk_bend_param *bp, const rnk_twist_param *tp,
                            double m_prev, int ord, rq_vert *V) {
  double *r = V->r;
  rq_qmul_c(E0->h, 1, E1->h, 0, r);
  V->bad = 1.0 + rq_dot3(E0->t, E1->t) >= RNK_OPPOSITE_TOL ? 0.0 : 1.0;
  double w = r[0], x = r[1], y = r[2], z = r[3];
  double irho = 1.0 / (w * w + x * x);
  double a = w * irho, b = -x * irho;
  V->u1[0] = a;
  V->u1[1] = b;
  V->phi = a;
  V->kappa[0] = 2.0 * z * a;
  V->kappa[1] = -2.0 * y * a;
  /* reference part of the twist: (w, x) turned back by (theta1 - theta0)/2 */
  double ca = E1->cs * E0->cs + E1->sn * E0->sn, sa = E1->sn * E0->cs - E1->cs * E0->sn;
  double W = ca * w + sa * x, X = ca * x - sa * w;
  double d = 2.0 * rq_atan2(X, W) - m_prev;
  d -= 2.0 * M_PI * rq_rint(d * (0.5 / M_PI));
  V->ref_twist = m_prev + d;
  V->tau = E1->theta - E0->theta + V->ref_twist;
  /* 1 / vlen of bending and twisting (equal in practice) with one division */
  double ivv = 1.0 / (bp->vlen * tp->vlen), iv = tp->vlen * ivv;
  V->B[0] = bp->B[0] * iv;
  V->B[1] = bp->B[1] * iv;
  V->B[2] = bp->B[2] * iv;
  V->beta = tp->beta * (bp->vlen * ivv);
  double d1 = V->kappa[0] - bp->kbar[0], d2 = V->kappa[1] - bp->kbar[1];
  double dt = V->tau - tp->taubar;
  V->m1 = V->B[0] * d1 + V->B[1] * d2;
  V->m2 = V->B[1] * d1 + V->B[2] * d2;
  V->mt = V->beta * dt;
  V->Eb = 0.5 * (V->m1 * d1 + V->m2 * d2);
  V->Et = 0.5 * V->mt * dt;
  if (ord < 1) return;
  V->u2[0] = a * a - b * b;
  V->u2[1] = 2.0 * a * b;
  V->u3[0] = V->u2[0] * a - V->u2[1] * b;
  V->u3[1] = V->u2[0] * b + V->u2[1] * a;
  double phw = -V->u2[0], phx = V->u2[1], s = V->m1 * z - V->m2 * y;
  V->mu[0] = 2.0 * (phw * s + V->mt * b);
  V->mu[1] = 2.0 * (phx * s + V->mt * a);
  V->mu[2] = -2.0 * V->m2 * a;
  V->mu[3] = 2.0 * V->m1 * a;
}

/* dE/dt = eta_w t_hat + eta_v x t_hat for eta = dE/dq. */
RQ_INLINE void rq_dq_to_dt(const double eta[4], const double th[3], double gt[3]) {
  double c[3];
  rq_cross3(eta + 1, th, c);
  RQ_UNROLL for (int k = 0; k < 3; ++k) gt[k] = eta[0] * th[k] + c[k];
}

/* Gradient in y = (t0, theta0, t1, theta1) for a given dE/dr = mu. */
RQ_INLINE void rq_grad_y(const rq_edge *E0, const rq_edge *E1, const double r[4],
                         const double mu[4], double gy[8]) {
  double gam[4], eta[4], mX[4];
  rq_qmul_c(E1->h, 0, mu, 1, gam); /* dE/dh0 = h1 (x) mu* */
  rq_qmul_c(gam, 0, E0->g, 1, eta);
  rq_dq_to_dt(eta, E0->th, gy);
  rq_qmul(E0->h, mu, gam); /* dE/dh1 = h0 (x) mu */
  rq_qmul_c(gam, 0, E1->g, 1, eta);
  rq_dq_to_dt(eta, E1->th, gy + 4);
  rq_Xmul(mu, mX);
  gy[3] = 0.5 * rq_qdot(mX, r);
  rq_mulX(mu, mX);
  gy[7] = -0.5 * rq_qdot(mX, r);
}

/* Derivative of mu along dr (mu as a function of r). */
RQ_INLINE void rq_mu_dot(const rq_vert *V, const double dr[4], double dmu[4]) {
  const double *r = V->r;
  double y = r[2], z = r[3];
  double dw = dr[0], dx = dr[1], dy = dr[2], dz = dr[3];
  double a = V->u1[0], b = V->u1[1];
  double phw = -V->u2[0], phx = V->u2[1];
  double phww = 2.0 * V->u3[0], phwx = -2.0 * V->u3[1], phxx = -phww;
  double aww = -V->u2[1], awx = -V->u2[0], axx = V->u2[1];
  double dphi = phw * dw + phx * dx;
  double dk1 = 2.0 * (z * dphi + a * dz), dk2 = -2.0 * (y * dphi + a * dy);
  double dtau = 2.0 * (b * dw + a * dx);
  double dm1 = V->B[0] * dk1 + V->B[1] * dk2, dm2 = V->B[1] * dk1 + V->B[2] * dk2;
  double dmt = V->beta * dtau;
  double s = V->m1 * z - V->m2 * y, ds = dm1 * z - dm2 * y;
  double sm = V->m1 * dz - V->m2 * dy;
  double P1 = phww * dw + phwx * dx, P2 = phwx * dw + phxx * dx;
  dmu[0] = 2.0 * (phw * ds + dmt * b + s * P1 + phw * sm + V->mt * (aww * dw + awx * dx));
  dmu[1] = 2.0 * (phx * ds + dmt * a + s * P2 + phx * sm + V->mt * (awx * dw + axx * dx));
  dmu[2] = -2.0 * (dm2 * a + V->m2 * dphi);
  dmu[3] = 2.0 * (dm1 * a + V->m1 * dphi);
}

/* Hessian (in y) times a direction dy = (dt0, dtheta0, dt1, dtheta1). */
RQ_INLINE void rq_hvp_y(const rq_edge *E0, const rq_edge *E1, const rq_vert *V,
                        const double dyv[8], double hy[8]) {
  const double *r = V->r, *mu = V->mu;
  double dq[4], dh0[4], dh1[4], t4[4], dr[4], dmu[4];
  /* dh_j = dq_j (x) g_j + dtheta_j / 2 h_j (x) X */
  dq[0] = rq_dot3(E0->th, dyv);
  rq_cross3(E0->th, dyv, dq + 1);
  rq_qmul(dq, E0->g, dh0);
  rq_mulX(E0->h, t4);
  RQ_UNROLL for (int k = 0; k < 4; ++k) dh0[k] += 0.5 * dyv[3] * t4[k];
  dq[0] = rq_dot3(E1->th, dyv + 4);
  rq_cross3(E1->th, dyv + 4, dq + 1);
  rq_qmul(dq, E1->g, dh1);
  rq_mulX(E1->h, t4);
  RQ_UNROLL for (int k = 0; k < 4; ++k) dh1[k] += 0.5 * dyv[7] * t4[k];
  rq_qmul_c(dh0, 1, E1->h, 0, dr);
  rq_qmul_c(E0->h, 1, dh1, 0, t4);
  RQ_UNROLL for (int k = 0; k < 4; ++k) dr[k] += t4[k];
  rq_mu_dot(V, dr, dmu);
  /* d(dE/dh0) = dh1 (x) mu* + h1 (x) dmu*; d(dE/dh1) = dh0 (x) mu + h0 (x) dmu */
  double gam[4], dgam[4], eta[4];
  rq_qmul_c(dh1, 0, mu, 1, dgam);
  rq_qmul_c(E1->h, 0, dmu, 1, t4);
  rq_qmul_c(E1->h, 0, mu, 1, gam);
  rq_mulX(gam, dq);
  RQ_UNROLL for (int k = 0; k < 4; ++k) dgam[k] += t4[k] - 0.5 * dyv[3] * dq[k];
  rq_qmul_c(dgam, 0, E0->g, 1, eta);
  rq_dq_to_dt(eta, E0->th, hy);
  rq_qmul(dh0, mu, dgam);
  rq_qmul(E0->h, dmu, t4);
  rq_qmul(E0->h, mu, gam);
  rq_mulX(gam, dq);
  RQ_UNROLL for (int k = 0; k < 4; ++k) dgam[k] += t4[k] - 0.5 * dyv[7] * dq[k];
  rq_qmul_c(dgam, 0, E1->g, 1, eta);
  rq_dq_to_dt(eta, E1->th, hy + 4);
  double a1[4], a2[4];
  rq_Xmul(dmu, a1);
  rq_Xmul(mu, a2);
  hy[3] = 0.5 * (rq_qdot(a1, r) + rq_qdot(a2, dr));
  rq_mulX(dmu, a1);
  rq_mulX(mu, a2);
  hy[7] = -0.5 * (rq_qdot(a1, r) + rq_qdot(a2, dr));
}

/* y -> e: projected gradient P g / l of one edge. */
RQ_INLINE void rq_project(const rq_edge *E, const double gt[3], double ge[3]) {
  double s = rq_dot3(E->t, gt);
  RQ_UNROLL for (int k = 0; k < 3; ++k) ge[k] = (gt[k] - s * E->t[k]) * E->il;
}

/* Second-order term of t(e) along de: -(1/l^2)[(t.g) P de + t (P g . de) +
 * (P g)(t . de)], g = dE/dt (unprojected), added to out. */
RQ_INLINE void rq_curv_add(const rq_edge *E, const double gt[3], const double de[3],
                           double out[3]) {
  double tg = rq_dot3(E->t, gt), td = rq_dot3(E->t, de), pg[3], pd[3];
  RQ_UNROLL for (int k = 0; k < 3; ++k) {
    pg[k] = gt[k] - tg * E->t[k];
    pd[k] = de[k] - td * E->t[k];
  }
  double pgd = rq_dot3(pg, de), il2 = E->il * E->il;
  RQ_UNROLL for (int k = 0; k < 3; ++k) out[k] -=
      il2 * (tg * pd[k] + E->t[k] * pgd + pg[k] * td);
}

/* G = d2E/dr2 (4 x 4, symmetric) of a vertex evaluated with ord >= 1. */
RQ_INLINE void rq_vert_G(const rq_vert *V, double G[4][4]) {
  const double *r = V->r;
  /* G: gradients of kappa1, kappa2, tau in r, and the second-derivative part */
  double y = r[2], z = r[3], a = V->u1[0], b = V->u1[1];
  double phw = -V->u2[0], phx = V->u2[1];
  double phww = 2.0 * V->u3[0], phwx = -2.0 * V->u3[1];
  double aww = -V->u2[1], awx = -V->u2[0];
  double s = V->m1 * z - V->m2 * y, mt = V->mt;
  double k1[4] = {2.0 * z * phw, 2.0 * z * phx, 0.0, 2.0 * a};
  double k2[4] = {-2.0 * y * phw, -2.0 * y * phx, -2.0 * a, 0.0};
  double tw[4] = {2.0 * b, 2.0 * a, 0.0, 0.0};
  RQ_UNROLL for (int i = 0; i < 4; ++i) RQ_UNROLL for (int j = i; j < 4; ++j) G[i][j] =
      V->B[0] * k1[i] * k1[j] + V->B[1] * (k1[i] * k2[j] + k2[i] * k1[j]) +
      V->B[2] * k2[i] * k2[j] + V->beta * tw[i] * tw[j];
  G[0][0] += 2.0 * (s * phww + mt * aww);
  G[0][1] += 2.0 * (s * phwx + mt * awx);
  G[1][1] += 2.0 * (-s * phww - mt * aww); /* phi and arg are harmonic */
  G[0][2] += -2.0 * V->m2 * phw;
  G[1][2] += -2.0 * V->m2 * phx;
  G[0][3] += 2.0 * V->m1 * phw;
  G[1][3] += 2.0 * V->m1 * phx;
  RQ_UNROLL for (int i = 0; i < 4; ++i) RQ_UNROLL for (int j = 0; j < i; ++j) G[i][j] =
      G[j][i];
}

/* Hessian in y = (t0, theta0, t1, theta1), explicitly: J^T G J + S with J =
 * dr/dy (columns D0k* (x) h1, -X (x) r / 2, h0* (x) D1k, r (x) X / 2 where
 * D_jk = dq_j/dt_k (x) g_j), G = d2E/dr2 and S = mu . d2r/dy2 (nonzero only in
 * the theta rows and columns and the t0-t1 block). */
RQ_INLINE void rq_hess_y(const rq_edge *E0, const rq_edge *E1, const rq_vert *V,
                         double Hy[8][8]) {
  const double *r = V->r, *mu = V->mu;
  double J[8][4], D0[3][4], D1[3][4], GJ[8][4];
  RQ_UNROLL for (int k = 0; k < 3; ++k) {
    const rq_edge *Es[2] = {E0, E1};
    RQ_UNROLL for (int s = 0; s < 2; ++s) {
      const double *th = Es[s]->th;
      double kq[4] = {th[k], 0.0, 0.0, 0.0};
      /* t_hat x e_k */
      kq[1 + (k + 1) % 3] = th[(k + 2) % 3];
      kq[1 + (k + 2) % 3] = -th[(k + 1) % 3];
      rq_qmul(kq, Es[s]->g, s ? D1[k] : D0[k]);
    }
    rq_qmul_c(D0[k], 1, E1->h, 0, J[k]);
    rq_qmul_c(E0->h, 1, D1[k], 0, J[4 + k]);
  }
  rq_Xmul(r, J[3]);
  rq_mulX(r, J[7]);
  RQ_UNROLL for (int k = 0; k < 4; ++k) {
    J[3][k] *= -0.5;
    J[7][k] *= 0.5;
  }
  double G[4][4];
  rq_vert_G(V, G);
  RQ_UNROLL for (int c = 0; c < 8; ++c) RQ_UNROLL for (int i = 0; i < 4; ++i) GJ[c][i] =
      G[i][0] * J[c][0] + G[i][1] * J[c][1] + G[i][2] * J[c][2] + G[i][3] * J[c][3];
  RQ_UNROLL for (int c = 0; c < 8; ++c) RQ_UNROLL for (int d = c; d < 8; ++d) Hy[c][d] =
      Hy[d][c] = rq_qdot(J[c], GJ[d]);
  /* S: theta rows, then the t0-t1 block */
  double muL[4], muR[4], S3[8], S7[8];
  rq_Xmul(mu, muL);
  rq_mulX(mu, muR);
  RQ_UNROLL for (int d = 0; d < 8; ++d) {
    S3[d] = 0.5 * rq_qdot(muL, J[d]);
    S7[d] = -0.5 * rq_qdot(muR, J[d]);
  }
  RQ_UNROLL for (int d = 0; d < 8; ++d) {
    Hy[3][d] += S3[d];
    Hy[7][d] += S7[d];
    if (d != 3 && d != 7) {
      Hy[d][3] += S3[d];
      Hy[d][7] += S7[d];
    }
  }
  RQ_UNROLL for (int k = 0; k < 3; ++k) {
    double nu[4];
    rq_qmul(D0[k], mu, nu);
    RQ_UNROLL for (int l = 0; l < 3; ++l) {
      double v = rq_qdot(nu, D1[l]);
      Hy[k][4 + l] += v;
      Hy[4 + l][k] += v;
    }
  }
}

/* Hessian in the edge variables (e0, theta0, e1, theta1) from the one in y:
 * t blocks times P/l on both sides, plus the curvature of t(e) on the
 * diagonal t blocks (gy: the gradient in y). */
RQ_INLINE void rq_hess_e(const rq_edge *E0, const rq_edge *E1, const double gy[8],
                         double H[8][8]) {
  const rq_edge *Es[2] = {E0, E1};
  RQ_UNROLL for (int sr = 0; sr < 2; ++sr) {
    const double *tr = Es[sr]->t;
    double ilr = Es[sr]->il;
    /* rows of block sr: P_r applied to every column (all 8) */
    RQ_UNROLL for (int c = 0; c < 8; ++c) {
      double *h0 = &H[4 * sr][c], *h1 = &H[4 * sr + 1][c], *h2 = &H[4 * sr + 2][c];
      double d = tr[0] * *h0 + tr[1] * *h1 + tr[2] * *h2;
      *h0 = (*h0 - d * tr[0]) * ilr;
      *h1 = (*h1 - d * tr[1]) * ilr;
      *h2 = (*h2 - d * tr[2]) * ilr;
    }
  }
  RQ_UNROLL for (int sc = 0; sc < 2; ++sc) {
    const double *tc = Es[sc]->t;
    double ilc = Es[sc]->il;
    RQ_UNROLL for (int rr = 0; rr < 8; ++rr) {
      double *h = &H[rr][4 * sc];
      double d = h[0] * tc[0] + h[1] * tc[1] + h[2] * tc[2];
      RQ_UNROLL for (int k = 0; k < 3; ++k) h[k] = (h[k] - d * tc[k]) * ilc;
    }
  }
  RQ_UNROLL for (int s = 0; s < 2; ++s) {
    const double *t = Es[s]->t, *g = gy + 4 * s;
    double tg = rq_dot3(t, g), il2 = Es[s]->il * Es[s]->il, pg[3];
    RQ_UNROLL for (int k = 0; k < 3; ++k) pg[k] = g[k] - tg * t[k];
    RQ_UNROLL for (int i = 0; i < 3; ++i) RQ_UNROLL for (int k = 0; k < 3; ++k)
        H[4 * s + i][4 * s + k] -=
        il2 * (tg * ((i == k ? 1.0 : 0.0) - t[i] * t[k]) + t[i] * pg[k] + pg[i] * t[k]);
  }
}

#endif

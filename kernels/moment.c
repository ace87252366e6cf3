/* moment.c - a couple M acting on the material frame of one edge.
 * E = -|M| (angle0 + alpha), alpha = rotation about n = M / |M| of a vector
 * f fixed in the material frame since the last update (value f0): with u0
 * the projection of f0 onto the plane normal to n,
 * alpha = atan2((n x u0) . f, u0 . f).
 * Closed forms: f = R(h) b for the edge's frame quaternion h (rodq.h), so
 * both arguments of atan2 are Davenport quadratic forms h^T K h (the common
 * 1 / |h|^2 cancels), differentiated in h and taken to the stencil through
 * frameq.h.  The jets (rnk_jet_moment_*) are the test oracle. */
#include <math.h>

#include "frameq.h"
#include "rnk.h"
#include "stencil.h"

/* alpha for the frame vector f (jets) against the constant f0 about n. */
int rnk_projected_angle(const jvec *f, const double f0[3], const double n[3],
                        jet *alpha) {
  double fn = f0[0] * n[0] + f0[1] * n[1] + f0[2] * n[2], u0[3], c[3];
  for (int k = 0; k < 3; ++k) u0[k] = f0[k] - fn * n[k];
  double uu = u0[0] * u0[0] + u0[1] * u0[1] + u0[2] * u0[2];
  if (!(uu > 1e-12)) return RNK_DEGENERATE;
  c[0] = n[1] * u0[2] - n[2] * u0[1];
  c[1] = n[2] * u0[0] - n[0] * u0[2];
  c[2] = n[0] * u0[1] - n[1] * u0[0];
  jet num, den;
  jvec_dot_const(&num, f, c);
  jvec_dot_const(&den, f, u0);
  if (!(num.v * num.v + den.v * den.v > 1e-12 * uu)) return RNK_DEGENERATE;
  jet_atan2(alpha, &num, &den);
  return RNK_OK;
}

static int moment_eval(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                       int ord, jet *alpha, double *mag) {
  double e[3] = {q[4] - q[0], q[5] - q[1], q[6] - q[2]};
  rnk_edge_jet f;
  int st = rnk_edge_jet_eval(e, q[3], ref, ord, &f);
  if (st) return st;
  double m = sqrt(p->M[0] * p->M[0] + p->M[1] * p->M[1] + p->M[2] * p->M[2]);
  *mag = m;
  if (!(m > 0.0)) {
    jet_const(alpha, 4, ord, 0.0);
    return RNK_OK;
  }
  double n[3] = {p->M[0] / m, p->M[1] / m, p->M[2] / m};
  /* f = b1 t + b2 d1 + b3 d2, and its value at the last update */
  jvec fv;
  double f0[3];
  for (int a = 0; a < 3; ++a) {
    jet t1;
    jet_lin(&t1, p->b[0], &f.t.c[a], p->b[1], &f.d1.c[a]);
    jet_lin(&fv.c[a], 1.0, &t1, p->b[2], &f.d2.c[a]);
    f0[a] = p->b[0] * p->f0[a] + p->b[1] * p->f0[3 + a] + p->b[2] * p->f0[6 + a];
  }
  return rnk_projected_angle(&fv, f0, n, alpha);
}

static int moment_energy_jet(const double q[7], const rnk_frame *ref,
                             const rnk_moment_param *p, int ord, jet *E) {
  double m;
  int st = moment_eval(q, ref, p, ord, E, &m);
  if (st) return st;
  jet_add_const(E, E, p->angle0);
  jet_scale(E, -m, E);
  return RNK_OK;
}

int rnk_jet_moment_angle(const double q[7], const rnk_frame *ref,
                         const rnk_moment_param *p, double *alpha) {
  jet a;
  double m;
  int st = moment_eval(q, ref, p, 0, &a, &m);
  if (st) return st;
  *alpha = a.v;
  return RNK_OK;
}

int rnk_jet_moment_energy(const double q[7], const rnk_frame *ref,
                          const rnk_moment_param *p, double *E) {
  jet e;
  int st = moment_energy_jet(q, ref, p, 0, &e);
  if (st) return st;
  *E = e.v;
  return RNK_OK;
}

int rnk_jet_moment_grad(const double q[7], const rnk_frame *ref,
                        const rnk_moment_param *p, double *E, double g[7]) {
  jet e;
  int st = moment_energy_jet(q, ref, p, 1, &e);
  if (st) return st;
  if (E) *E = e.v;
  rnk_scatter_edge(&e, g, NULL);
  return RNK_OK;
}

int rnk_jet_moment_hess(const double q[7], const rnk_frame *ref,
                        const rnk_moment_param *p, double H[49]) {
  jet e;
  int st = moment_energy_jet(q, ref, p, 2, &e);
  if (st) return st;
  rnk_scatter_edge(&e, NULL, H);
  return RNK_OK;
}

int rnk_jet_moment_hvp(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                       const double v[7], double Hv[7]) {
  double H[49];
  int st = rnk_jet_moment_hess(q, ref, p, H);
  if (st) return st;
  rnk_block_mv(7, H, v, Hv);
  return RNK_OK;
}

/* ---- closed forms ------------------------------------------------------------ */
typedef struct mq_eval {
  rq_edge E;
  double m, alpha;
  double gam[4], Gam[4][4]; /* dE/dh, d2E/dh2 */
} mq_eval;

static int mq_eval_at(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                      int ord, mq_eval *X) {
  double e[3] = {q[4] - q[0], q[5] - q[1], q[6] - q[2]};
  rq_edge_init(e, q[3], ref, &X->E);
  rq_edge_big_angle(ref, &X->E);
  if (X->E.bad != 0.0) return RNK_DEGENERATE;
  double m = sqrt(p->M[0] * p->M[0] + p->M[1] * p->M[1] + p->M[2] * p->M[2]);
  X->m = m;
  X->alpha = 0.0;
  for (int i = 0; i < 4; ++i) {
    X->gam[i] = 0.0;
    for (int k = 0; k < 4; ++k) X->Gam[i][k] = 0.0;
  }
  if (!(m > 0.0)) return RNK_OK;
  double n[3] = {p->M[0] / m, p->M[1] / m, p->M[2] / m}, f0[3], u0[3], c[3];
  for (int a = 0; a < 3; ++a)
    f0[a] = p->b[0] * p->f0[a] + p->b[1] * p->f0[3 + a] + p->b[2] * p->f0[6 + a];
  double fn = rq_dot3(f0, n);
  for (int k = 0; k < 3; ++k) u0[k] = f0[k] - fn * n[k];
  double uu = rq_dot3(u0, u0);
  if (!(uu > 1e-12)) return RNK_DEGENERATE;
  rq_cross3(n, u0, c);
  double B1[9], B2[9], K1[4][4], K2[4][4], K1h[4], K2h[4];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      B1[3 * a + b] = c[a] * p->b[b];
      B2[3 * a + b] = u0[a] * p->b[b];
    }
  fq_davenport(B1, K1);
  fq_davenport(B2, K2);
  const double *h = X->E.h;
  for (int i = 0; i < 4; ++i) {
    K1h[i] = rq_qdot(K1[i], h);
    K2h[i] = rq_qdot(K2[i], h);
  }
  double Y = rq_qdot(h, K1h), Xv = rq_qdot(h, K2h), hh = rq_qdot(h, h);
  double r2 = Xv * Xv + Y * Y;
  if (!(r2 > 1e-12 * uu * hh * hh)) return RNK_DEGENERATE;
  X->alpha = rq_atan2(Y, Xv);
  if (ord < 1) return RNK_OK;
  double fx = -Y / r2, fy = Xv / r2, dY[4], dX[4];
  for (int i = 0; i < 4; ++i) {
    dY[i] = 2.0 * K1h[i];
    dX[i] = 2.0 * K2h[i];
    X->gam[i] = -m * (fx * dX[i] + fy * dY[i]);
  }
  if (ord < 2) return RNK_OK;
  double r4 = r2 * r2, fxx = 2.0 * Xv * Y / r4, fyy = -fxx, fxy = (Y * Y - Xv * Xv) / r4;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k)
      X->Gam[i][k] = -m * (2.0 * (fx * K2[i][k] + fy * K1[i][k]) + fxx * dX[i] * dX[k] +
                           fyy * dY[i] * dY[k] + fxy * (dX[i] * dY[k] + dY[i] * dX[k]));
  return RNK_OK;
}

int rnk_moment_angle(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                     double *alpha) {
  mq_eval X;
  int st = mq_eval_at(q, ref, p, 0, &X);
  if (st) return st;
  *alpha = X.alpha;
  return RNK_OK;
}

int rnk_moment_energy(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                      double *E) {
  mq_eval X;
  int st = mq_eval_at(q, ref, p, 0, &X);
  if (st) return st;
  *E = -X.m * (p->angle0 + X.alpha);
  return RNK_OK;
}

/* e-gradient (e, theta) of a prepared evaluation; gy its y-gradient. */
static void mq_grad_e(const mq_eval *X, double J[4][4], double gy[4], double ge[4]) {
  fq_grad_y(J, X->gam, gy);
  rq_project(&X->E, gy, ge);
  ge[3] = gy[3];
}

int rnk_moment_grad(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                    double *E, double g[7]) {
  mq_eval X;
  double J[4][4], gy[4], ge[4];
  int st = mq_eval_at(q, ref, p, 1, &X);
  if (st) return st;
  if (E) *E = -X.m * (p->angle0 + X.alpha);
  fq_dh_dy(&X.E, J);
  mq_grad_e(&X, J, gy, ge);
  for (int k = 0; k < 3; ++k) {
    g[k] = -ge[k];
    g[4 + k] = ge[k];
  }
  g[3] = ge[3];
  return RNK_OK;
}

int rnk_moment_hess(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                    double H[49]) {
  mq_eval X;
  double J[4][4], gy[4], ge[4], Hy[4][4];
  int st = mq_eval_at(q, ref, p, 2, &X);
  if (st) return st;
  fq_dh_dy(&X.E, J);
  mq_grad_e(&X, J, gy, ge);
  fq_hess_y(&X.E, J, X.gam, X.Gam, Hy);
  /* y -> e: P / l on the t rows and columns, curvature of t(e) */
  const rq_edge *E = &X.E;
  for (int c = 0; c < 4; ++c) {
    double d = E->t[0] * Hy[0][c] + E->t[1] * Hy[1][c] + E->t[2] * Hy[2][c];
    for (int i = 0; i < 3; ++i) Hy[i][c] = (Hy[i][c] - d * E->t[i]) * E->il;
  }
  for (int a = 0; a < 4; ++a) {
    double d = rq_dot3(Hy[a], E->t);
    for (int i = 0; i < 3; ++i) Hy[a][i] = (Hy[a][i] - d * E->t[i]) * E->il;
  }
  for (int k = 0; k < 3; ++k) {
    double de[3] = {0, 0, 0}, out[3] = {0, 0, 0};
    de[k] = 1.0;
    rq_curv_add(E, gy, de, out);
    for (int i = 0; i < 3; ++i) Hy[i][k] += out[i];
  }
  /* e = x1 - x0: stencil (x0, theta, x1) */
  static const int idx[4][2] = {{0, 4}, {1, 5}, {2, 6}, {3, 3}};
  for (int i = 0; i < 49; ++i) H[i] = 0.0;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      for (int x = 0; x < (a < 3 ? 2 : 1); ++x)
        for (int y = 0; y < (b < 3 ? 2 : 1); ++y) {
          double sa = a < 3 ? (x ? 1.0 : -1.0) : 1.0, sb = b < 3 ? (y ? 1.0 : -1.0) : 1.0;
          H[7 * idx[a][x] + idx[b][y]] += sa * sb * Hy[a][b];
        }
  for (int a = 0; a < 7; ++a) /* exactly symmetric (projections: rounding) */
    for (int b = a + 1; b < 7; ++b)
      H[7 * a + b] = H[7 * b + a] = 0.5 * (H[7 * a + b] + H[7 * b + a]);
  return RNK_OK;
}

int rnk_moment_hvp(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                   const double v[7], double Hv[7]) {
  mq_eval X;
  double J[4][4], gy[4], ge[4], Hy[4][4], de[3], dy[4], hy[4], he[3];
  int st = mq_eval_at(q, ref, p, 2, &X);
  if (st) return st;
  const rq_edge *E = &X.E;
  fq_dh_dy(&X.E, J);
  mq_grad_e(&X, J, gy, ge);
  fq_hess_y(&X.E, J, X.gam, X.Gam, Hy);
  for (int k = 0; k < 3; ++k) de[k] = v[4 + k] - v[k];
  double td = rq_dot3(E->t, de);
  for (int k = 0; k < 3; ++k) dy[k] = (de[k] - td * E->t[k]) * E->il;
  dy[3] = v[3];
  for (int a = 0; a < 4; ++a)
    hy[a] = Hy[a][0] * dy[0] + Hy[a][1] * dy[1] + Hy[a][2] * dy[2] + Hy[a][3] * dy[3];
  rq_project(E, hy, he);
  rq_curv_add(E, gy, de, he);
  for (int k = 0; k < 3; ++k) {
    Hv[k] = -he[k];
    Hv[4 + k] = he[k];
  }
  Hv[3] = hy[3];
  return RNK_OK;
}

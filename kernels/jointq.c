/* jointq.c - closed-form joint kernels (both models, any valence): energy,
 * gradient, Hessian block and a Hessian-vector product that never forms the
 * block; the connection-edge end stencil as a rigid joint of valence 1.
 * Same functions as the jet implementations (joint.c, joint_net.c: the test
 * oracle); docs/energy.md "Closed forms of the joints".
 *
 * Each end k is the rod vertex kernel (rodq.h) between the terminal edge's
 * material frame h_T = q(t) (x) g(theta) and the connection frame
 * h_C = P(w) (x) c_k, c_k the quaternion of Q_ref applied to the rest frame:
 * r = h_T* (x) h_C (side 0) or h_C* (x) h_T (side 1).  Its derivatives are
 * formed in (h_T, w) (r is bilinear), then taken to y = (t, theta) (frameq.h)
 * and to the stencil.
 *   Rigid:   P(w) = exp of the rotation DOFs, Q_ref = Qhat.
 *   Elastic: Q = exp([phi]) Q0, Q0 = polar(M) at the evaluation point, so
 *            w = phi(Y) = 0 there and P's derivatives are those at w = 0.
 *            With U = Q0^T M, K = tr(U) I - U, the rotation vector's
 *            derivatives are (implicit differentiation of M = exp([phi]) Q0 S)
 *              dphi = L(dM) = Q0 K^-1 axial(Q0^T dM - dM^T Q0),
 *              d2phi[1,2] = L(d2M[1,2] - B12),
 *              B12 = sym([dphi1][dphi2]) Q0 U + [dphi1] Q0 dS2 + [dphi2] Q0 dS1,
 *              dS = Q0^T dM - [Q0^T dphi] U,
 *            and G . L(B) = <Lambda, B> with Lambda = [mu] Q0,
 *            mu = Q0 K^-1 Q0^T G.  So the chain-rule terms G . dphi and
 *            G . d2phi are the derivatives of sum_k <Lambda Fbar_k, F_k>
 *            (Davenport quadratic forms in h_T) minus a quadratic form W in
 *            (dphi, dS); the Hessian couples the ends only through the
 *            rank-18 factors L_k R_l (no d2phi/dM2 tensor is formed). */
#include <string.h>

#include "frameq.h"
#include "rnk.h"
#include "rnk_couple.h"

/* ---- 3x3 helpers (row-major) ---- */
static void m3_mul(const double A[9], const double B[9], double C[9]) {
  double T[9];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      T[3 * i + k] = A[3 * i] * B[k] + A[3 * i + 1] * B[3 + k] + A[3 * i + 2] * B[6 + k];
  memcpy(C, T, sizeof T);
}
/* C = A^T B */
static void m3_tmul(const double A[9], const double B[9], double C[9]) {
  double T[9];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      T[3 * i + k] = A[i] * B[k] + A[3 + i] * B[3 + k] + A[6 + i] * B[6 + k];
  memcpy(C, T, sizeof T);
}
static void m3_vec(const double A[9], const double v[3], double r[3]) {
  double t[3];
  for (int i = 0; i < 3; ++i)
    t[i] = A[3 * i] * v[0] + A[3 * i + 1] * v[1] + A[3 * i + 2] * v[2];
  memcpy(r, t, sizeof t);
}
static void m3_tvec(const double A[9], const double v[3], double r[3]) {
  double t[3];
  for (int i = 0; i < 3; ++i) t[i] = A[i] * v[0] + A[3 + i] * v[1] + A[6 + i] * v[2];
  memcpy(r, t, sizeof t);
}
/* [a] B */
static void m3_skew_mul(const double a[3], const double B[9], double C[9]) {
  for (int k = 0; k < 3; ++k) {
    double b0 = B[k], b1 = B[3 + k], b2 = B[6 + k];
    C[k] = a[1] * b2 - a[2] * b1;
    C[3 + k] = a[2] * b0 - a[0] * b2;
    C[6 + k] = a[0] * b1 - a[1] * b0;
  }
}

/* ---- one end --------------------------------------------------------------- */
typedef struct jq_end {
  rq_edge T; /* terminal edge */
  rq_vert V; /* vertex between terminal and connection edge */
  double hC[4];
  double dhC[3][4];
  double s;      /* e = s (x_J - x_n) */
  double gam[4]; /* dE/dh_T */
  double gw[3];  /* dE/dw */
  double Gam[4][4], Gw[4][3], Hww[3][3];
} jq_end;

/* Terminal edge of end k from the joint stencil. */
static void end_edge(const double *q, const rnk_joint *j, int k, rq_edge *T, double *s) {
  int base = 3 + (j->rigid ? 3 : 0) + 4 * k;
  double e[3], sg = j->ends[k].side == 0 ? 1.0 : -1.0;
  for (int c = 0; c < 3; ++c) e[c] = sg * (q[c] - q[base + c]);
  rq_edge_init(e, q[base + 3], &j->refs[k], T);
  rq_edge_big_angle(&j->refs[k], T);
  *s = sg;
}

/* Quaternion of the connection frame at w = 0: Qref applied to cbar. */
static void connection_quat(const double Qref[9], const double cbar[9], double c[4]) {
  rnk_frame f;
  m3_vec(Qref, cbar, f.t);
  m3_vec(Qref, cbar + 3, f.a1);
  rq_frame_quat(&f, c);
}

/* Energy of end k and (ord >= 1) its derivatives in (h_T, w). */
static int end_eval(const rnk_joint_end *en, const fq_rot *R, const double cq[4], int ord,
                    jq_end *X) {
  rq_edge Z[2];
  const rq_edge *T = &X->T;
  int side = en->side;
  if (T->bad != 0.0) return RNK_DEGENERATE;
  rq_qmul(R->P, cq, X->hC);
  /* the vertex kernel on the two frames, angles already in the quaternions */
  double *hC = X->hC, in = 1.0 / rq_qdot(hC, hC);
  double tC[3] = {(hC[0] * hC[0] + hC[1] * hC[1] - hC[2] * hC[2] - hC[3] * hC[3]) * in,
                  2.0 * (hC[1] * hC[2] + hC[0] * hC[3]) * in,
                  2.0 * (hC[1] * hC[3] - hC[0] * hC[2]) * in};
  for (int s = 0; s < 2; ++s) {
    int term = (s == 0) == (side == 0);
    memcpy(Z[s].h, term ? T->h : hC, sizeof Z[s].h);
    memcpy(Z[s].t, term ? T->t : tC, sizeof Z[s].t);
    Z[s].cs = 1.0;
    Z[s].sn = 0.0;
    Z[s].theta = 0.0;
  }
  rq_vert_eval(&Z[0], &Z[1], &en->bend, &en->twist, en->twist.ref_twist, ord, &X->V);
  if (X->V.bad != 0.0) return RNK_DEGENERATE;
  if (ord < 1) return RNK_OK;
  const double *mu = X->V.mu, *hT = T->h;
  double zeta[4];
  rq_qmul_c(hC, 0, mu, side == 0, X->gam); /* dE/dh_T */
  rq_qmul_c(hT, 0, mu, side != 0, zeta);   /* dE/dh_C */
  for (int i = 0; i < 3; ++i) {
    rq_qmul(R->dP[i], cq, X->dhC[i]);
    X->gw[i] = rq_qdot(zeta, X->dhC[i]);
  }
  if (ord < 2) return RNK_OK;
  double G[4][4], Jt[4][4], Jw[3][4], GJt[4][4], GJw[3][4];
  rq_vert_G(&X->V, G);
  for (int i = 0; i < 4; ++i) {
    double ei[4] = {0, 0, 0, 0};
    ei[i] = 1.0;
    if (side == 0)
      rq_qmul_c(ei, 1, hC, 0, Jt[i]);
    else
      rq_qmul_c(hC, 1, ei, 0, Jt[i]);
  }
  for (int i = 0; i < 3; ++i) {
    if (side == 0)
      rq_qmul_c(hT, 1, X->dhC[i], 0, Jw[i]);
    else
      rq_qmul_c(X->dhC[i], 1, hT, 0, Jw[i]);
  }
  for (int c = 0; c < 4; ++c)
    for (int i = 0; i < 4; ++i) GJt[c][i] = rq_qdot(G[i], Jt[c]);
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < 4; ++i) GJw[c][i] = rq_qdot(G[i], Jw[c]);
  for (int a = 0; a < 4; ++a)
    for (int b = a; b < 4; ++b) X->Gam[a][b] = X->Gam[b][a] = rq_qdot(Jt[a], GJt[b]);
  for (int b = 0; b < 3; ++b) {
    double S[4];
    rq_qmul_c(X->dhC[b], 0, mu, side == 0, S);
    for (int a = 0; a < 4; ++a) X->Gw[a][b] = rq_qdot(Jt[a], GJw[b]) + S[a];
  }
  for (int a = 0; a < 3; ++a)
    for (int b = a; b < 3; ++b) {
      double d2[4];
      rq_qmul(R->d2P[a][b], cq, d2);
      X->Hww[a][b] = X->Hww[b][a] = rq_qdot(Jw[a], GJw[b]) + rq_qdot(zeta, d2);
    }
  return RNK_OK;
}

/* ---- the couple on the joint rotation ---------------------------------------- */
/* E = -|M| (angle0 + alpha), alpha = atan2(c . f, u0 . f), f = R(P (x) p0) cp:
 * both arguments are Davenport forms in p = P (x) p0 (the common 1/|p|^2
 * cancels in atan2).  Adds to *E, gw, Hww (ord >= 1, 2); alpha on request. */
static int couple_eval(const rnk_joint *j, const double Qref[9], const fq_rot *R, int ord,
                       double *E, double gw[3], double Hww[3][3], double *alpha_out) {
  double m = sqrt(j->M[0] * j->M[0] + j->M[1] * j->M[1] + j->M[2] * j->M[2]);
  if (alpha_out) *alpha_out = 0.0;
  if (!(m > 0.0)) return RNK_OK;
  double n[3] = {j->M[0] / m, j->M[1] / m, j->M[2] / m}, f0c[3], u0[3], c[3];
  const double *cp = j->couple_p;
  m3_vec(j->f0, cp, f0c);
  double fn = rq_dot3(f0c, n);
  for (int k = 0; k < 3; ++k) u0[k] = f0c[k] - fn * n[k];
  double uu = rq_dot3(u0, u0);
  if (!(uu > 1e-12)) return RNK_DEGENERATE;
  rq_cross3(n, u0, c);
  double B1[9], B2[9], K1[4][4], K2[4][4], p0[4], p[4];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      B1[3 * a + b] = c[a] * cp[b];
      B2[3 * a + b] = u0[a] * cp[b];
    }
  fq_davenport(B1, K1);
  fq_davenport(B2, K2);
  fq_matrix_quat(Qref, p0);
  rq_qmul(R->P, p0, p);
  double K1p[4], K2p[4];
  for (int i = 0; i < 4; ++i) {
    K1p[i] = rq_qdot(K1[i], p);
    K2p[i] = rq_qdot(K2[i], p);
  }
  double Y = rq_qdot(p, K1p), Xv = rq_qdot(p, K2p), pp = rq_qdot(p, p);
  double r2 = Xv * Xv + Y * Y;
  if (!(r2 > 1e-12 * uu * pp * pp)) return RNK_DEGENERATE;
  double alpha = rq_atan2(Y, Xv);
  if (alpha_out) *alpha_out = alpha;
  *E += -m * (j->angle0 + alpha);
  if (ord < 1) return RNK_OK;
  double dp[3][4], dY[3], dX[3], fx = -Y / r2, fy = Xv / r2;
  for (int a = 0; a < 3; ++a) {
    rq_qmul(R->dP[a], p0, dp[a]);
    dY[a] = 2.0 * rq_qdot(dp[a], K1p);
    dX[a] = 2.0 * rq_qdot(dp[a], K2p);
    gw[a] += -m * (fx * dX[a] + fy * dY[a]);
  }
  if (ord < 2) return RNK_OK;
  double r4 = r2 * r2, fxx = 2.0 * Xv * Y / r4, fyy = -fxx, fxy = (Y * Y - Xv * Xv) / r4;
  for (int a = 0; a < 3; ++a) {
    double K1d[4], K2d[4];
    for (int i = 0; i < 4; ++i) {
      K1d[i] = rq_qdot(K1[i], dp[a]);
      K2d[i] = rq_qdot(K2[i], dp[a]);
    }
    for (int b = a; b < 3; ++b) {
      double d2p[4];
      rq_qmul(R->d2P[a][b], p0, d2p);
      double d2Y = 2.0 * (rq_qdot(dp[b], K1d) + rq_qdot(d2p, K1p));
      double d2X = 2.0 * (rq_qdot(dp[b], K2d) + rq_qdot(d2p, K2p));
      double h = fx * d2X + fy * d2Y + fxx * dX[a] * dX[b] + fyy * dY[a] * dY[b] +
                 fxy * (dX[a] * dY[b] + dY[a] * dX[b]);
      Hww[a][b] += -m * h;
      if (b != a) Hww[b][a] += -m * h;
    }
  }
  return RNK_OK;
}

/* ---- a couple fixed in space on the joint rotation ------------------------------ */
/* The couple M does the virtual work M . omega, omega the angular velocity of
 * Q = R(P(w)) Qref: [omega] = dQ Q^T, omega = 2 Im(dP (x) P*) (P is a unit
 * quaternion for every w).  In the sign of an energy gradient (the residual
 * gets -M . omega_a): Gw[a] -= M . omega_a and Hww[a][b] -= M . d omega_a /
 * d w_b = 2 M . Im(d2P_ab (x) P* + dP_a (x) dP_b*) (nonsymmetric). */
static void fixed_eval(const double M[3], const fq_rot *R, int ord, double Gw[3],
                       double Hww[3][3]) {
  double t[4], u[4];
  for (int a = 0; a < 3 && ord >= 1; ++a) {
    rq_qmul_c(R->dP[a], 0, R->P, 1, t);
    Gw[a] -= 2.0 * (M[0] * t[1] + M[1] * t[2] + M[2] * t[3]);
    for (int b = 0; b < 3 && ord >= 2; ++b) {
      rq_qmul_c(R->d2P[a][b], 0, R->P, 1, t);
      rq_qmul_c(R->dP[a], 0, R->dP[b], 1, u);
      for (int c = 0; c < 3; ++c) t[1 + c] += u[1 + c];
      Hww[a][b] -= 2.0 * (M[0] * t[1] + M[1] * t[2] + M[2] * t[3]);
    }
  }
}

/* ---- maps y -> e -> stencil ----------------------------------------------------- */
/* Rows 0..2 of a 4 x m row-major block (the t rows) times P / l. */
static void project_rows(const rq_edge *T, double *B, int m) {
  for (int c = 0; c < m; ++c) {
    double d = T->t[0] * B[c] + T->t[1] * B[m + c] + T->t[2] * B[2 * m + c];
    for (int i = 0; i < 3; ++i) B[i * m + c] = (B[i * m + c] - d * T->t[i]) * T->il;
  }
}
/* Columns 0..2 of an r x 4 row-major block. */
static void project_cols(const rq_edge *T, double *B, int r) {
  for (int a = 0; a < r; ++a) {
    double *h = B + 4 * a, d = rq_dot3(h, T->t);
    for (int i = 0; i < 3; ++i) h[i] = (h[i] - d * T->t[i]) * T->il;
  }
}
/* Curvature of t(e) on the t-t block of a 4 x 4 e-block, gt = dE/dt. */
static void add_curvature(const rq_edge *T, const double gt[3], double H[4][4]) {
  double tg = rq_dot3(T->t, gt), il2 = T->il * T->il, pg[3];
  for (int k = 0; k < 3; ++k) pg[k] = gt[k] - tg * T->t[k];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      H[i][k] -= il2 * (tg * ((i == k ? 1.0 : 0.0) - T->t[i] * T->t[k]) +
                        T->t[i] * pg[k] + pg[i] * T->t[k]);
}

/* Stencil index of end k's e-variable c (0..2: x_J with +s and x_n with -s;
 * 3: theta). */
static int end_base(const rnk_joint *j, int k) { return 3 + (j->rigid ? 3 : 0) + 4 * k; }

static void scatter_grad_e(int base, double s, const double ge[4], double *g) {
  for (int c = 0; c < 3; ++c) {
    g[c] += s * ge[c];
    g[base + c] -= s * ge[c];
  }
  g[base + 3] += ge[3];
}

/* H[rows of end (bk, sk)][cols of end (bl, sl)] += B (4 x 4 in e). */
static void scatter_ee(double *H, int n, int bk, double sk, int bl, double sl,
                       double B[4][4]) {
  for (int a = 0; a < 4; ++a) {
    int ra[2] = {a < 3 ? a : bk + 3, bk + a};
    double ca[2] = {a < 3 ? sk : 1.0, -sk};
    int na = a < 3 ? 2 : 1;
    for (int b = 0; b < 4; ++b) {
      int rb[2] = {b < 3 ? b : bl + 3, bl + b};
      double cb[2] = {b < 3 ? sl : 1.0, -sl};
      int nb = b < 3 ? 2 : 1;
      for (int x = 0; x < na; ++x)
        for (int y = 0; y < nb; ++y) H[ra[x] * n + rb[y]] += ca[x] * cb[y] * B[a][b];
    }
  }
}

/* H[end rows][w cols] += B (4 x 3) and the transpose (rigid joints). */
static void scatter_ew(double *H, int n, int bk, double sk, double B[4][3]) {
  for (int a = 0; a < 4; ++a) {
    int ra[2] = {a < 3 ? a : bk + 3, bk + a};
    double ca[2] = {a < 3 ? sk : 1.0, -sk};
    int na = a < 3 ? 2 : 1;
    for (int x = 0; x < na; ++x)
      for (int b = 0; b < 3; ++b) {
        H[ra[x] * n + 3 + b] += ca[x] * B[a][b];
        H[(3 + b) * n + ra[x]] += ca[x] * B[a][b];
      }
  }
}

/* e-direction of end k from a stencil direction v, and its y image. */
static void end_dir(const double *v, int base, double s, const rq_edge *T, double de[4],
                    double dy[4]) {
  for (int c = 0; c < 3; ++c) de[c] = s * (v[c] - v[base + c]);
  de[3] = dy[3] = v[base + 3];
  double td = rq_dot3(T->t, de);
  for (int c = 0; c < 3; ++c) dy[c] = (de[c] - td * T->t[c]) * T->il;
}

/* y-space results of one end -> gradient, Hessian or HVP in the stencil.
 * hy (HVP): y-space product already formed; gy: y gradient. */
static void end_out_grad(int base, double s, const rq_edge *T, const double gy[4],
                         double *g) {
  double ge[4];
  rq_project(T, gy, ge);
  ge[3] = gy[3];
  scatter_grad_e(base, s, ge, g);
}

static void end_out_hvp(int base, double s, const rq_edge *T, const double gy[4],
                        const double hy[4], const double de[4], int curv, double *Hv) {
  double he[4];
  rq_project(T, hy, he);
  if (curv) rq_curv_add(T, gy, de, he);
  he[3] = hy[3];
  scatter_grad_e(base, s, he, Hv);
}

/* e-space diagonal block of an end from its y-space block. */
static void end_block_e(const rq_edge *T, const double gy[4], double Hy[4][4]) {
  project_rows(T, Hy[0], 4);
  project_cols(T, Hy[0], 4);
  add_curvature(T, gy, Hy);
}

/* ---- the elastic fit ------------------------------------------------------------- */
typedef struct jq_fit {
  double Q0[9], U[9], Ki[9]; /* polar factor, stretch, (tr U I - U)^-1 */
  double Lam[9];             /* [mu] Q0 */
  double Wpp[9], Wps[3][9];  /* quadratic form in (dphi, dS) */
} jq_fit;

/* dphi = Q0 K^-1 axial(Q0^T B - B^T Q0) */
static void fit_L(const jq_fit *F, const double B[9], double dphi[3]) {
  double X[9], ax[3], psi[3];
  m3_tmul(F->Q0, B, X);
  ax[0] = X[7] - X[5];
  ax[1] = X[2] - X[6];
  ax[2] = X[3] - X[1];
  m3_vec(F->Ki, ax, psi);
  m3_vec(F->Q0, psi, dphi);
}

static void inv3_sym(const double A[9], double Ai[9]) {
  double c0 = A[4] * A[8] - A[5] * A[7], c1 = A[5] * A[6] - A[3] * A[8],
         c2 = A[3] * A[7] - A[4] * A[6];
  double id = 1.0 / (A[0] * c0 + A[1] * c1 + A[2] * c2);
  Ai[0] = c0 * id;
  Ai[3] = c1 * id;
  Ai[6] = c2 * id;
  Ai[1] = (A[2] * A[7] - A[1] * A[8]) * id;
  Ai[4] = (A[0] * A[8] - A[2] * A[6]) * id;
  Ai[7] = (A[1] * A[6] - A[0] * A[7]) * id;
  Ai[2] = (A[1] * A[5] - A[2] * A[4]) * id;
  Ai[5] = (A[2] * A[3] - A[0] * A[5]) * id;
  Ai[8] = (A[0] * A[4] - A[1] * A[3]) * id;
}

/* Rotation of the material frame of h (columns t, d1, d2) times Fbar^T
 * (cbar rows: rest t, d1, d2). */
static void frame_times_rest(const double h[4], const double cbar[9], double A[9]) {
  double F[9];
  fq_quat_matrix(h, F);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      A[3 * a + b] =
          F[3 * a] * cbar[b] + F[3 * a + 1] * cbar[3 + b] + F[3 * a + 2] * cbar[6 + b];
}

/* Q0 = polar(M) over the terminal frames; U, K^-1. */
static int fit_init(const double *q, const rnk_joint *j, jq_fit *F) {
  double M[9] = {0}, A[9], s;
  rq_edge T;
  for (int k = 0; k < j->valence; ++k) {
    end_edge(q, j, k, &T, &s);
    if (T.short_ != 0.0 || T.bad != 0.0) return RNK_DEGENERATE;
    frame_times_rest(T.h, j->ends[k].cbar, A);
    for (int i = 0; i < 9; ++i) M[i] += A[i];
  }
  int st = rnk_polar(M, F->Q0);
  if (st) return st;
  double U[9], K[9];
  m3_tmul(F->Q0, M, U);
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) F->U[3 * a + b] = 0.5 * (U[3 * a + b] + U[3 * b + a]);
  double tr = F->U[0] + F->U[4] + F->U[8];
  for (int i = 0; i < 9; ++i) K[i] = (i % 4 == 0 ? tr : 0.0) - F->U[i];
  inv3_sym(K, F->Ki);
  return RNK_OK;
}

/* Lambda and W from the total dE/dw = G at w = 0. */
static void fit_lambda(jq_fit *F, const double G[3], int ord) {
  double a[3], mu[3];
  m3_tvec(F->Q0, G, a);
  m3_vec(F->Ki, a, a);
  m3_vec(F->Q0, a, mu);
  m3_skew_mul(mu, F->Q0, F->Lam);
  if (ord < 2) return;
  /* N = Q0 U Lambda^T; Wpp = sym(N) - tr(N) I */
  double QU[9], N[9];
  m3_mul(F->Q0, F->U, QU);
  for (int a2 = 0; a2 < 3; ++a2)
    for (int b = 0; b < 3; ++b)
      N[3 * a2 + b] = QU[3 * a2] * F->Lam[3 * b] + QU[3 * a2 + 1] * F->Lam[3 * b + 1] +
                      QU[3 * a2 + 2] * F->Lam[3 * b + 2];
  double tr = N[0] + N[4] + N[8];
  for (int a2 = 0; a2 < 3; ++a2)
    for (int b = 0; b < 3; ++b)
      F->Wpp[3 * a2 + b] = 0.5 * (N[3 * a2 + b] + N[3 * b + a2]) - (a2 == b ? tr : 0.0);
  /* Z(e_j) = -Q0^T [e_j] Lambda */
  for (int jj = 0; jj < 3; ++jj) {
    double e[3] = {0, 0, 0}, S[9];
    e[jj] = 1.0;
    m3_skew_mul(e, F->Lam, S);
    m3_tmul(F->Q0, S, F->Wps[jj]);
    for (int i = 0; i < 9; ++i) F->Wps[jj][i] = -F->Wps[jj][i];
  }
}

/* Per-end storage of elastic joints in the caller's work array. */
enum {
  JQ_P1 = 4 + 16 + 12, /* gam, Gam, Gw */
  JQ_LR = 4 * 18,      /* L_k (4 x 18) or R_k (18 x 4) */
  JQ_STORE = JQ_P1 + 2 * JQ_LR
};

size_t rnk_joint_work_size(const rnk_joint *j) {
  return (size_t)JQ_STORE * (size_t)j->valence + 8;
}

/* Low-rank factors of end k (pass 2 of elastic joints): Lk = [Gw | Phi^T |
 * Xi^T] (4 x 18) and Rk = [Phi; Gw^T + Hww Phi; -W Xi] (18 x 4), in y. */
static void end_factors(const jq_fit *F, const rq_edge *T, double J[4][4],
                        const double cbar[9], double Gw[4][3], double Hww[3][3],
                        double *Lk, double *Rk) {
  double A[9], n = rq_qdot(T->h, T->h), Xi[12][4];
  frame_times_rest(T->h, cbar, A);
  for (int i = 0; i < 4; ++i) {
    double t4[4], Om[3], dM[9], dphi[3], psi[3], QdM[9], PU[9];
    rq_qmul_c(J[i], 0, T->h, 1, t4);
    for (int c = 0; c < 3; ++c) Om[c] = 2.0 * t4[1 + c] / n;
    m3_skew_mul(Om, A, dM);
    fit_L(F, dM, dphi);
    m3_tvec(F->Q0, dphi, psi);
    m3_tmul(F->Q0, dM, QdM);
    m3_skew_mul(psi, F->U, PU);
    for (int c = 0; c < 3; ++c) Xi[c][i] = dphi[c];
    for (int c = 0; c < 9; ++c) Xi[3 + c][i] = QdM[c] - PU[c];
  }
  for (int a = 0; a < 4; ++a) {
    double *row = Lk + 18 * a;
    for (int c = 0; c < 3; ++c) {
      row[c] = Gw[a][c];
      row[3 + c] = Xi[c][a];
    }
    for (int c = 0; c < 12; ++c) row[6 + c] = Xi[c][a];
  }
  for (int i = 0; i < 4; ++i) {
    for (int c = 0; c < 3; ++c) {
      Rk[4 * c + i] = Xi[c][i];
      Rk[4 * (3 + c) + i] =
          Gw[i][c] + Hww[c][0] * Xi[0][i] + Hww[c][1] * Xi[1][i] + Hww[c][2] * Xi[2][i];
    }
    /* W xi = (Wpp dphi + Wps dS ; Wps^T dphi) */
    for (int c = 0; c < 3; ++c) {
      double v = 0.0;
      for (int d = 0; d < 3; ++d) v += F->Wpp[3 * c + d] * Xi[d][i];
      for (int d = 0; d < 9; ++d) v += F->Wps[c][d] * Xi[3 + d][i];
      Rk[4 * (6 + c) + i] = -v;
    }
    for (int d = 0; d < 9; ++d) {
      double v = 0.0;
      for (int c = 0; c < 3; ++c) v += F->Wps[c][d] * Xi[c][i];
      Rk[4 * (9 + d) + i] = -v;
    }
  }
}

/* ---- the whole joint ------------------------------------------------------------ */
enum { OP_E = 0, OP_G = 1, OP_H = 2, OP_HV = 3 };

/* The connection frames' reference rotation Qref (rigid: Qhat; elastic: the
 * fit Q0, then F is set) and P(w) with its derivatives to order ord (w the
 * rotation DOFs, or 0 for elastic joints). */
static int joint_setup(const double *q, const rnk_joint *j, int ord, jq_fit *F, fq_rot *R,
                       const double **Qref) {
  double w[3] = {0, 0, 0};
  int st;
  *Qref = j->Qhat;
  if (j->rigid) {
    memcpy(w, q + 3, sizeof w);
  } else {
    if ((st = fit_init(q, j, F))) return st;
    *Qref = F->Q0;
  }
  fq_rot_eval(w, ord, R);
  return RNK_OK;
}

/* One evaluation of a whole joint: the operation, the derivative order, the
 * stencil size, the rotation P(w) and reference Qref (joint_setup), the direction
 * (v; dw its rotation part, rigid joints) and the outputs. */
typedef struct jq_eval {
  int op, ord, n;
  const fq_rot *R;
  const double *Qref, *v, *dw;
  double *g, *H, *Hv;
} jq_eval;

/* Pass 1 for end k: its energy and derivatives in (h_T, w), added to *Etot, Gw and
 * Hww.  Elastic joints keep gamma (and Gamma, G_w) in the end's work for pass 2;
 * rigid joints put the end's gradient, Hessian block or HVP in the outputs. */
static int end_pass1(const double *q, const rnk_joint *j, int k, const jq_eval *c,
                     double *work, double *Etot, double Gw[3], double Hww[3][3]) {
  jq_end X;
  double cq[4];
  int st, base = end_base(j, k), ord = c->ord;
  end_edge(q, j, k, &X.T, &X.s);
  connection_quat(c->Qref, j->ends[k].cbar, cq);
  if ((st = end_eval(&j->ends[k], c->R, cq, ord, &X))) return st;
  *Etot += X.V.Eb + X.V.Et;
  if (ord < 1) return RNK_OK;
  for (int a = 0; a < 3; ++a) Gw[a] += X.gw[a];
  if (ord >= 2)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) Hww[a][b] += X.Hww[a][b];
  if (!j->rigid) { /* finished in pass 2, once Lambda is known */
    double *st1 = work + (size_t)JQ_STORE * k;
    memcpy(st1, X.gam, 4 * sizeof(double));
    if (ord >= 2) {
      memcpy(st1 + 4, X.Gam, 16 * sizeof(double));
      memcpy(st1 + 20, X.Gw, 12 * sizeof(double));
    }
    return RNK_OK;
  }
  double J[4][4], gy[4], Hy[4][4], Hyw[4][3];
  fq_dh_dy(&X.T, J);
  fq_grad_y(J, X.gam, gy);
  if (c->op == OP_G) end_out_grad(base, X.s, &X.T, gy, c->g);
  if (ord < 2) return RNK_OK;
  fq_hess_y(&X.T, J, X.gam, X.Gam, Hy);
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 3; ++b)
      Hyw[a][b] = J[a][0] * X.Gw[0][b] + J[a][1] * X.Gw[1][b] + J[a][2] * X.Gw[2][b] +
                  J[a][3] * X.Gw[3][b];
  if (c->op == OP_H) {
    end_block_e(&X.T, gy, Hy);
    scatter_ee(c->H, c->n, base, X.s, base, X.s, Hy);
    project_rows(&X.T, Hyw[0], 3);
    scatter_ew(c->H, c->n, base, X.s, Hyw);
  } else { /* HVP */
    const double *dw = c->dw;
    double de[4], dy[4], hy[4];
    end_dir(c->v, base, X.s, &X.T, de, dy);
    for (int a = 0; a < 4; ++a)
      hy[a] = Hy[a][0] * dy[0] + Hy[a][1] * dy[1] + Hy[a][2] * dy[2] + Hy[a][3] * dy[3] +
              Hyw[a][0] * dw[0] + Hyw[a][1] * dw[1] + Hyw[a][2] * dw[2];
    for (int b = 0; b < 3; ++b)
      c->Hv[3 + b] +=
          Hyw[0][b] * dy[0] + Hyw[1][b] * dy[1] + Hyw[2][b] * dy[2] + Hyw[3][b] * dy[3];
    end_out_hvp(base, X.s, &X.T, gy, hy, de, 1, c->Hv);
  }
  return RNK_OK;
}

/* Rigid joints: the rotation DOFs' gradient, Hessian block or HVP (Gw, Hww). */
static void rigid_rotation_out(const jq_eval *c, const double Gw[3], double Hww[3][3]) {
  int n = c->n;
  const double *dw = c->dw;
  if (c->op == OP_G)
    for (int a = 0; a < 3; ++a) c->g[3 + a] += Gw[a];
  if (c->op == OP_H)
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) c->H[(3 + a) * n + 3 + b] += Hww[a][b];
  if (c->op == OP_HV)
    for (int a = 0; a < 3; ++a)
      c->Hv[3 + a] += Hww[a][0] * dw[0] + Hww[a][1] * dw[1] + Hww[a][2] * dw[2];
}

/* Elastic joints, pass 2 for end k: the chain rule through phi (F's Lambda known):
 * the end's gradient, or its Hessian block or HVP and its factors L_k, R_k of the
 * coupling through phi (in the end's work; the HVP adds R_k de to rho). */
static void end_pass2(const double *q, const rnk_joint *j, int k, const jq_eval *c,
                      const jq_fit *F, double Hww[3][3], double *work, double rho[18]) {
  double *st1 = work + (size_t)JQ_STORE * k, *Lk = st1 + JQ_P1, *Rk = Lk + JQ_LR;
  double B[9], Kd[4][4], J[4][4], gam[4], Gam[4][4], Gwk[4][3], gy[4], Hy[4][4];
  int base = end_base(j, k);
  const double *cbar = j->ends[k].cbar;
  rq_edge T;
  double s;
  end_edge(q, j, k, &T, &s);
  memcpy(gam, st1, sizeof gam);
  /* <Lambda, F_k Fbar_k^T> = <Lambda Fbar_k, F_k> */
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      B[3 * a + b] = F->Lam[3 * a] * cbar[3 * b] + F->Lam[3 * a + 1] * cbar[3 * b + 1] +
                     F->Lam[3 * a + 2] * cbar[3 * b + 2];
  fq_davenport(B, Kd);
  fq_dh_dy(&T, J);
  if (c->ord < 2) {
    fq_rayleigh_add(Kd, T.h, gam, NULL);
    fq_grad_y(J, gam, gy);
    end_out_grad(base, s, &T, gy, c->g);
    return;
  }
  memcpy(Gam, st1 + 4, sizeof Gam);
  memcpy(Gwk, st1 + 20, sizeof Gwk);
  fq_rayleigh_add(Kd, T.h, gam, Gam);
  fq_grad_y(J, gam, gy);
  fq_hess_y(&T, J, gam, Gam, Hy);
  double Hyw[4][3];
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 3; ++b)
      Hyw[a][b] = J[a][0] * Gwk[0][b] + J[a][1] * Gwk[1][b] + J[a][2] * Gwk[2][b] +
                  J[a][3] * Gwk[3][b];
  end_factors(F, &T, J, cbar, Hyw, Hww, Lk, Rk);
  project_rows(&T, Lk, 18);
  project_cols(&T, Rk, 18);
  if (c->op == OP_H) {
    end_block_e(&T, gy, Hy);
    scatter_ee(c->H, c->n, base, s, base, s, Hy);
  } else {
    double de[4], dy[4], hy[4];
    end_dir(c->v, base, s, &T, de, dy);
    for (int a = 0; a < 4; ++a)
      hy[a] = Hy[a][0] * dy[0] + Hy[a][1] * dy[1] + Hy[a][2] * dy[2] + Hy[a][3] * dy[3];
    end_out_hvp(base, s, &T, gy, hy, de, 1, c->Hv);
    for (int m = 0; m < 18; ++m)
      rho[m] += Rk[4 * m] * de[0] + Rk[4 * m + 1] * de[1] + Rk[4 * m + 2] * de[2] +
                Rk[4 * m + 3] * de[3];
  }
}

/* Elastic joints, pass 3: the coupling of the ends through phi, in e: the blocks
 * L_k R_l of the Hessian, or L_k rho of the HVP. */
static void ends_coupling(const rnk_joint *j, const jq_eval *c, const double *work,
                          const double rho[18]) {
  int nv = j->valence;
  for (int k = 0; k < nv; ++k) {
    const double *Lk = work + (size_t)JQ_STORE * k + JQ_P1;
    double sk = j->ends[k].side == 0 ? 1.0 : -1.0;
    int bk = end_base(j, k);
    if (c->op == OP_HV) {
      double he[4];
      for (int a = 0; a < 4; ++a) {
        double s = 0.0;
        for (int m = 0; m < 18; ++m) s += Lk[18 * a + m] * rho[m];
        he[a] = s;
      }
      scatter_grad_e(bk, sk, he, c->Hv);
      continue;
    }
    for (int l = 0; l < nv; ++l) {
      const double *Rl = work + (size_t)JQ_STORE * l + JQ_P1 + JQ_LR;
      double sl = j->ends[l].side == 0 ? 1.0 : -1.0, B[4][4];
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b) {
          double s = 0.0;
          for (int m = 0; m < 18; ++m) s += Lk[18 * a + m] * Rl[4 * m + b];
          B[a][b] = s;
        }
      scatter_ee(c->H, c->n, bk, sk, end_base(j, l), sl, B);
    }
  }
}

static int joint_eval(const double *q, const rnk_joint *j, int op, double *work,
                      double *E, double *g, double *H, const double *v, double *Hv,
                      const double *Mfix) {
  int n = (int)rnk_joint_stencil_size(j), nv = j->valence, st;
  int ord = op == OP_HV ? 2 : op;
  double Gw[3] = {0, 0, 0}, Hww[3][3] = {{0}}, Etot = 0.0;
  const double *Qref;
  jq_fit F;
  fq_rot R;
  if ((st = joint_setup(q, j, ord, &F, &R, &Qref))) return st;
  if (g) memset(g, 0, sizeof(double) * (size_t)n);
  if (H) memset(H, 0, sizeof(double) * (size_t)n * (size_t)n);
  if (Hv) memset(Hv, 0, sizeof(double) * (size_t)n);
  const jq_eval c = {op, ord, n, &R, Qref, v, j->rigid && v ? v + 3 : NULL, g, H, Hv};
  /* pass 1: every end's energy and derivatives in (h_T, w) */
  for (int k = 0; k < nv; ++k) {
    if (Mfix) { /* the fixed couple alone: the ends carry no energy */
      if (!j->rigid) memset(work + (size_t)JQ_STORE * k, 0, JQ_P1 * sizeof(double));
      continue;
    }
    if ((st = end_pass1(q, j, k, &c, work, &Etot, Gw, Hww))) return st;
  }
  if (Mfix)
    fixed_eval(Mfix, &R, ord, Gw, Hww);
  else if ((st = couple_eval(j, Qref, &R, ord, &Etot, Gw, Hww, NULL)))
    return st;
  if (E) *E = Etot;
  if (ord < 1) return RNK_OK;
  if (j->rigid) {
    rigid_rotation_out(&c, Gw, Hww);
    return RNK_OK;
  }
  /* elastic, pass 2: the chain rule through phi */
  fit_lambda(&F, Gw, ord);
  double rho[18] = {0};
  for (int k = 0; k < nv; ++k) end_pass2(q, j, k, &c, &F, Hww, work, rho);
  if (ord < 2) return RNK_OK;
  /* pass 3: the coupling of the ends through phi, in e */
  ends_coupling(j, &c, work, rho);
  return RNK_OK;
}

int rnk_joint_energy(const double *q, const rnk_joint *j, double *work, double *E) {
  if (j->smooth) {
    double Et = 0.0;
    int st = rnk_smooth_joint_energy(q, j, E, &Et);
    *E += Et;
    return st;
  }
  return joint_eval(q, j, OP_E, work, E, NULL, NULL, NULL, NULL, NULL);
}

int rnk_joint_grad(const double *q, const rnk_joint *j, double *work, double *E,
                   double *g) {
  if (j->smooth) return rnk_smooth_joint_grad(q, j, E, g);
  return joint_eval(q, j, OP_G, work, E, g, NULL, NULL, NULL, NULL);
}

/* The blocks above are symmetric up to rounding (projections applied to
 * rows, then columns; the elastic end-end blocks L_k R_l); the mean of H and
 * H^T makes them exactly so, as the assembled Hessian and its Cholesky
 * factor assume (the jets' rigid blocks were exactly symmetric). */
static void symmetrize(double *H, int n) {
  for (int a = 0; a < n; ++a)
    for (int b = a + 1; b < n; ++b)
      H[a * n + b] = H[b * n + a] = 0.5 * (H[a * n + b] + H[b * n + a]);
}

int rnk_joint_hess(const double *q, const rnk_joint *j, double *work, double *H) {
  if (j->smooth) return rnk_smooth_joint_hess(q, j, H);
  int st = joint_eval(q, j, OP_H, work, NULL, NULL, H, NULL, NULL, NULL);
  if (st == RNK_OK) symmetrize(H, (int)rnk_joint_stencil_size(j));
  return st;
}

int rnk_joint_hvp(const double *q, const rnk_joint *j, double *work, const double *v,
                  double *Hv) {
  if (j->smooth) return rnk_smooth_joint_hvp(q, j, v, Hv);
  return joint_eval(q, j, OP_HV, work, NULL, NULL, NULL, v, Hv, NULL);
}

/* Twists of every end and the couple's angle at the current state. */
int rnk_joint_couple_fixed_force(const double *q, const rnk_joint *j, const double M[3],
                                 double *work, double *Q, double *J) {
  int n = (int)rnk_joint_stencil_size(j), st;
  if (j->smooth) return RNK_DEGENERATE; /* no rotation to turn */
  if ((st = joint_eval(q, j, OP_G, work, NULL, Q, NULL, NULL, NULL, M))) return st;
  for (int i = 0; i < n; ++i) Q[i] = -Q[i];
  if (!J) return RNK_OK;
  if ((st = joint_eval(q, j, OP_H, work, NULL, NULL, J, NULL, NULL, M))) return st;
  for (int i = 0; i < n * n; ++i) J[i] = -J[i];
  return RNK_OK;
}

int rnk_joint_twists(const double *q, const rnk_joint *j, double *twist) {
  const double *Qref;
  jq_fit F;
  fq_rot R;
  jq_end X;
  int st;
  if (j->smooth) return rnk_smooth_joint_twists(q, j, twist);
  if ((st = joint_setup(q, j, 0, &F, &R, &Qref))) return st;
  for (int k = 0; k < j->valence; ++k) {
    double cq[4];
    end_edge(q, j, k, &X.T, &X.s);
    connection_quat(Qref, j->ends[k].cbar, cq);
    if ((st = end_eval(&j->ends[k], &R, cq, 0, &X))) return st;
    twist[k] = X.V.tau;
  }
  return RNK_OK;
}

int rnk_joint_couple_angle(const double *q, const rnk_joint *j, double *alpha) {
  double E = 0.0;
  const double *Qref;
  jq_fit F;
  fq_rot R;
  int st;
  if (j->smooth) { /* no couple on a smooth joint */
    *alpha = 0.0;
    return RNK_OK;
  }
  if ((st = joint_setup(q, j, 0, &F, &R, &Qref))) return st;
  return couple_eval(j, Qref, &R, 0, &E, NULL, NULL, alpha);
}

/* ---- the end stencil q[10] = (x_n, theta, x_J, w) as a rigid joint of valence
 * 1 with Qhat = I and rest frame p->c: joint stencil (x_J, w, x_n, theta) ---- */
static const int end_perm[10] = {4, 5, 6, 7, 8, 9, 0, 1, 2, 3};

static void end_joint(const double q10[10], const rnk_frame *ref,
                      const rnk_joint_end_param *p, rnk_joint_end *en, rnk_joint *j,
                      double qj[10]) {
  memset(j, 0, sizeof *j);
  memset(en, 0, sizeof *en);
  en->side = p->side;
  memcpy(en->cbar, p->c, sizeof en->cbar);
  en->bend = p->bend;
  en->twist = p->twist;
  j->rigid = 1;
  j->valence = 1;
  j->ends = en;
  j->refs = ref;
  for (int i = 0; i < 9; ++i) j->Qhat[i] = j->f0[i] = (i % 4 == 0);
  for (int i = 0; i < 10; ++i) qj[i] = q10[end_perm[i]];
}

int rnk_joint_end_energy(const double q[10], const rnk_frame *ref,
                         const rnk_joint_end_param *p, double *E) {
  rnk_joint j;
  rnk_joint_end en;
  double qj[10];
  end_joint(q, ref, p, &en, &j, qj);
  return joint_eval(qj, &j, OP_E, NULL, E, NULL, NULL, NULL, NULL, NULL);
}

int rnk_joint_end_grad(const double q[10], const rnk_frame *ref,
                       const rnk_joint_end_param *p, double *E, double g[10]) {
  rnk_joint j;
  rnk_joint_end en;
  double qj[10], gj[10];
  end_joint(q, ref, p, &en, &j, qj);
  int st = joint_eval(qj, &j, OP_G, NULL, E, gj, NULL, NULL, NULL, NULL);
  for (int i = 0; i < 10; ++i) g[end_perm[i]] = gj[i];
  return st;
}

int rnk_joint_end_hess(const double q[10], const rnk_frame *ref,
                       const rnk_joint_end_param *p, double H[100]) {
  rnk_joint j;
  rnk_joint_end en;
  double qj[10], Hj[100];
  end_joint(q, ref, p, &en, &j, qj);
  int st = joint_eval(qj, &j, OP_H, NULL, NULL, NULL, Hj, NULL, NULL, NULL);
  if (st == RNK_OK) symmetrize(Hj, 10);
  for (int a = 0; a < 10; ++a)
    for (int b = 0; b < 10; ++b) H[10 * end_perm[a] + end_perm[b]] = Hj[10 * a + b];
  return st;
}

int rnk_joint_end_hvp(const double q[10], const rnk_frame *ref,
                      const rnk_joint_end_param *p, const double v[10], double Hv[10]) {
  rnk_joint j;
  rnk_joint_end en;
  double qj[10], vj[10], Hj[10];
  end_joint(q, ref, p, &en, &j, qj);
  for (int i = 0; i < 10; ++i) vj[i] = v[end_perm[i]];
  int st = joint_eval(qj, &j, OP_HV, NULL, NULL, NULL, NULL, vj, Hj, NULL);
  for (int i = 0; i < 10; ++i) Hv[end_perm[i]] = Hj[i];
  return st;
}

int rnk_joint_end_strains(const double q[10], const rnk_frame *ref,
                          const rnk_joint_end_param *p, double kappa[2], double *twist) {
  rnk_joint j;
  rnk_joint_end en;
  double qj[10], w[3] = {q[7], q[8], q[9]}, cq[4];
  fq_rot R;
  jq_end X;
  end_joint(q, ref, p, &en, &j, qj);
  fq_rot_eval(w, 0, &R);
  end_edge(qj, &j, 0, &X.T, &X.s);
  connection_quat(j.Qhat, en.cbar, cq);
  int st = end_eval(&en, &R, cq, 0, &X);
  if (st) return st;
  if (kappa) kappa[0] = X.V.kappa[0], kappa[1] = X.V.kappa[1];
  if (twist) *twist = X.V.tau;
  return RNK_OK;
}

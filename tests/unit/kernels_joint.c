/* kernels_joint.c - the joint stencil (rod end meeting a rotating joint
 * through a connection edge) and the rotation exponential: central-difference
 * gradient and HVP with an h-sweep showing second order (both sides, small
 * and large rotation vectors, across the series/closed-form switch of the
 * Rodrigues coefficients), symmetry, zero energy at rest, invariance under
 * rigid motions, and agreement with the interior bend-twist stencil when the
 * connection edge coincides with the next edge of a rod. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "rnk.h"
#include "testutil.h"

static uint64_t rng = 777;
static double rnd(void) { return rn_test_rand(&rng); }

static void mat_vec(const double R[9], const double v[3], double out[3]) {
  for (int i = 0; i < 3; ++i)
    out[i] = R[3 * i] * v[0] + R[3 * i + 1] * v[1] + R[3 * i + 2] * v[2];
}
static double norm(int n, const double *v) {
  double s = 0;
  for (int i = 0; i < n; ++i) s += v[i] * v[i];
  return sqrt(s);
}

/* random frame (t, d1, d2) near direction t0 */
static void frame_near(const double t0[3], double spread, double f[9]) {
  double t[3], a[3];
  for (int k = 0; k < 3; ++k) t[k] = t0[k] + spread * rnd();
  rn_test_normalize3(t);
  for (int k = 0; k < 3; ++k) a[k] = rnd();
  double d = a[0] * t[0] + a[1] * t[1] + a[2] * t[2];
  for (int k = 0; k < 3; ++k) a[k] -= d * t[k];
  rn_test_normalize3(a);
  memcpy(f, t, sizeof t);
  memcpy(f + 3, a, sizeof a);
  rn_test_cross3(t, a, f + 6);
}

static void random_joint(int side, double wmag, double q[10], rnk_frame *ref,
                         rnk_joint_end_param *p) {
  double xn[3] = {0.1 * rnd(), 0.1 * rnd(), 0.1 * rnd()};
  double xj[3] = {1 + 0.2 * rnd(), 0.3 * rnd(), 0.3 * rnd()};
  if (side == 1) /* terminal edge from x_J to x_n: put x_n after x_J */
    for (int k = 0; k < 3; ++k) xn[k] = 2 * xj[k] - xn[k];
  double w[3] = {rnd(), rnd(), rnd()};
  rn_test_normalize3(w);
  for (int k = 0; k < 3; ++k) {
    q[k] = xn[k];
    q[4 + k] = xj[k];
    q[7 + k] = wmag * w[k];
  }
  q[3] = 0.6 * rnd();
  double e[3];
  for (int k = 0; k < 3; ++k) e[k] = side == 0 ? xj[k] - xn[k] : xn[k] - xj[k];
  double f[9];
  frame_near(e, 0.3, f);
  memcpy(ref->t, f, 3 * sizeof(double));
  memcpy(ref->a1, f + 3, 3 * sizeof(double));
  /* connection frame near the terminal tangent, pre-rotated by exp(-[w]) so
   * the current connection edge stays near the terminal edge */
  double cf[9], Rm[9], mw[3] = {-q[7], -q[8], -q[9]};
  frame_near(e, 0.3, cf);
  rnk_rotation_exp(mw, Rm);
  for (int v = 0; v < 3; ++v) mat_vec(Rm, cf + 3 * v, p->c + 3 * v);
  p->side = side;
  p->bend = (rnk_bend_param){.B = {2.0, 0.4, 0.9}, .kbar = {0.05, -0.1}, .vlen = 0.8};
  p->twist =
      (rnk_twist_param){.beta = 1.1, .taubar = 0.07, .vlen = 0.8, .ref_twist = 0.2};
}

static void check_fd(const double q[10], const rnk_frame *ref,
                     const rnk_joint_end_param *p) {
  double E, g[10], H[100], Hv[10], v[10];
  CHECK_STATUS(rnk_joint_end_grad(q, ref, p, &E, g), RNK_OK);
  CHECK_STATUS(rnk_joint_end_hess(q, ref, p, H), RNK_OK);
  double hmax = 0, asym = 0;
  for (int i = 0; i < 100; ++i) hmax = fmax(hmax, fabs(H[i]));
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) asym = fmax(asym, fabs(H[10 * i + j] - H[10 * j + i]));
  CHECK(asym <= 1e-13 * hmax);
  for (int dir = 0; dir < 3; ++dir) {
    for (int i = 0; i < 10; ++i) v[i] = rnd();
    double nv = norm(10, v);
    for (int i = 0; i < 10; ++i) v[i] /= nv;
    CHECK_STATUS(rnk_joint_end_hvp(q, ref, p, v, Hv), RNK_OK);
    double gv = 0;
    for (int i = 0; i < 10; ++i) gv += g[i] * v[i];
    double hs[5], eg[5], eh[5];
    double sg = norm(10, g) + norm(10, Hv), sh = norm(10, Hv) + 1e-300;
    for (int s = 0; s < 5; ++s) {
      double h = 1e-2 / pow(2.0, s), qp[10], qm[10], Ep, Em, gp[10], gm[10];
      for (int i = 0; i < 10; ++i) {
        qp[i] = q[i] + h * v[i];
        qm[i] = q[i] - h * v[i];
      }
      CHECK_STATUS(rnk_joint_end_grad(qp, ref, p, &Ep, gp), RNK_OK);
      CHECK_STATUS(rnk_joint_end_grad(qm, ref, p, &Em, gm), RNK_OK);
      hs[s] = h;
      eg[s] = fabs((Ep - Em) / (2 * h) - gv) / sg;
      double err = 0;
      for (int i = 0; i < 10; ++i) err += pow((gp[i] - gm[i]) / (2 * h) - Hv[i], 2);
      eh[s] = sqrt(err) / sh;
    }
    double og = rn_test_loglog_slope(5, hs, eg), oh = rn_test_loglog_slope(5, hs, eh);
    if (eg[0] > 1e-9 && !(og > 1.8 && og < 2.3))
      rn_test_fail(__FILE__, __LINE__, "joint gradient FD order %.3f", og);
    if (eh[0] > 1e-9 && !(oh > 1.8 && oh < 2.3))
      rn_test_fail(__FILE__, __LINE__, "joint HVP FD order %.3f", oh);
    rn_test_checks += 2;
    CHECK(eg[4] < 1e-5);
    CHECK(eh[4] < 1e-5);
  }
}

static void test_rotation_exp(void) {
  double mags[6] = {0.0, 1e-8, 0.3, 1.99999, 2.00001, 3.0};
  for (int m = 0; m < 6; ++m) {
    double w[3] = {0.3, -0.5, 0.8}, R[9];
    rn_test_normalize3(w);
    for (int k = 0; k < 3; ++k) w[k] *= mags[m];
    rnk_rotation_exp(w, R);
    /* orthogonal, det 1, axis fixed, rotation angle |w| */
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        double s = 0;
        for (int k = 0; k < 3; ++k) s += R[3 * k + i] * R[3 * k + j];
        CHECK_NEAR(s, i == j ? 1.0 : 0.0, 1e-15);
      }
    double Rw[3];
    mat_vec(R, w, Rw);
    for (int k = 0; k < 3; ++k) CHECK_NEAR(Rw[k], w[k], 1e-15);
    CHECK_NEAR(R[0] + R[4] + R[8], 1 + 2 * cos(mags[m]), 1e-14);
  }
}

static void test_fd(void) {
  double mags[4] = {0.0, 0.4, 1.9999, 2.3}; /* |w|^2 = 4 switches the coefficients */
  for (int side = 0; side < 2; ++side)
    for (int m = 0; m < 4; ++m)
      for (int trial = 0; trial < 10; ++trial) {
        double q[10];
        rnk_frame ref;
        rnk_joint_end_param p;
        random_joint(side, mags[m], q, &ref, &p);
        check_fd(q, &ref, &p);
      }
}

static void test_rest_and_invariance(void) {
  for (int side = 0; side < 2; ++side)
    for (int trial = 0; trial < 10; ++trial) {
      double q[10], E, g[10];
      rnk_frame ref;
      rnk_joint_end_param p;
      random_joint(side, 0.0, q, &ref, &p);
      /* rest: straight continuation with the same material frame */
      double e[3], t[3], d1[3], d2[3];
      for (int k = 0; k < 3; ++k) e[k] = side == 0 ? q[4 + k] - q[k] : q[k] - q[4 + k];
      CHECK_STATUS(rnk_material_frame(e, &ref, q[3], t, d1, d2), RNK_OK);
      memcpy(p.c, t, sizeof t);
      memcpy(p.c + 3, d1, sizeof d1);
      memcpy(p.c + 6, d2, sizeof d2);
      p.bend.kbar[0] = p.bend.kbar[1] = 0;
      p.twist.taubar = p.twist.ref_twist = 0;
      CHECK_STATUS(rnk_joint_end_grad(q, &ref, &p, &E, g), RNK_OK);
      CHECK_NEAR(E, 0.0, 1e-20);
      CHECK_NEAR(norm(10, g), 0.0, 1e-13);
      /* rigid motion: rotate points, frames and w; translate */
      random_joint(side, 0.7, q, &ref, &p);
      double R[9], wv[3] = {rnd(), rnd(), rnd()}, c[3] = {rnd(), rnd(), rnd()}, q2[10];
      rnk_rotation_exp(wv, R);
      rnk_frame ref2;
      rnk_joint_end_param p2 = p;
      mat_vec(R, ref.t, ref2.t);
      mat_vec(R, ref.a1, ref2.a1);
      for (int v = 0; v < 3; ++v) mat_vec(R, p.c + 3 * v, p2.c + 3 * v);
      memcpy(q2, q, sizeof q2);
      mat_vec(R, q, q2);
      mat_vec(R, q + 4, q2 + 4);
      mat_vec(R, q + 7, q2 + 7);
      for (int k = 0; k < 3; ++k) q2[k] += c[k], q2[4 + k] += c[k];
      double E1, E2;
      CHECK_STATUS(rnk_joint_end_energy(q, &ref, &p, &E1), RNK_OK);
      CHECK_STATUS(rnk_joint_end_energy(q2, &ref2, &p2, &E2), RNK_OK);
      CHECK_NEAR(E2, E1, 1e-12 * E1);
    }
}

/* A joint whose connection edge is the next edge of a rod gives the interior
 * bend + twist energy, and the same gradient for the terminal edge's DOFs. */
static void test_matches_rod_vertex(void) {
  for (int trial = 0; trial < 10; ++trial) {
    double q11[11] = {0, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0};
    for (int i = 0; i < 11; ++i) q11[i] += 0.3 * rnd();
    rnk_frame ref[2];
    double e0[3], e1[3], f[9];
    for (int k = 0; k < 3; ++k)
      e0[k] = q11[4 + k] - q11[k], e1[k] = q11[8 + k] - q11[4 + k];
    frame_near(e0, 0.2, f);
    memcpy(ref[0].t, f, 24), memcpy(ref[0].a1, f + 3, 24);
    frame_near(e1, 0.2, f);
    memcpy(ref[1].t, f, 24), memcpy(ref[1].a1, f + 3, 24);
    rnk_bend_param bp = {.B = {1.5, 0.2, 0.8}, .kbar = {0.1, 0.05}, .vlen = 0.9};
    rnk_twist_param tp = {.beta = 0.7, .taubar = -0.1, .vlen = 0.9, .ref_twist = 0.3};
    double Eb, Et, g11[11], kap[2], tau;
    CHECK_STATUS(rnk_bendtwist_energy(q11, ref, &bp, &tp, &Eb, &Et), RNK_OK);
    CHECK_STATUS(rnk_bendtwist_grad(q11, ref, &bp, &tp, NULL, g11), RNK_OK);
    CHECK_STATUS(rnk_strains(q11, ref, tp.ref_twist, kap, &tau), RNK_OK);
    rnk_joint_end_param p = {.side = 0, .bend = bp, .twist = tp};
    p.twist.ref_twist = tau;
    CHECK_STATUS(rnk_material_frame(e1, &ref[1], q11[7], p.c, p.c + 3, p.c + 6), RNK_OK);
    double q10[10] = {q11[0], q11[1], q11[2], q11[3], q11[4], q11[5], q11[6], 0, 0, 0};
    double E, g10[10], kj[2], tj;
    CHECK_STATUS(rnk_joint_end_grad(q10, &ref[0], &p, &E, g10), RNK_OK);
    CHECK_STATUS(rnk_joint_end_strains(q10, &ref[0], &p, kj, &tj), RNK_OK);
    CHECK_NEAR(kj[0], kap[0], 1e-14);
    CHECK_NEAR(kj[1], kap[1], 1e-14);
    CHECK_NEAR(tj, tau, 1e-14);
    CHECK_NEAR(E, Eb + Et, 1e-13 * (Eb + Et));
    for (int i = 0; i < 4; ++i) CHECK_NEAR(g10[i], g11[i], 1e-12 * (1 + fabs(g11[i])));
  }
}

int main(void) {
  test_rotation_exp();
  test_fd();
  test_rest_and_invariance();
  test_matches_rod_vertex();
  return rn_test_finish("kernels_joint");
}

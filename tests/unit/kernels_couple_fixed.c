/* kernels_couple_fixed.c - the couple fixed in space (rnk_couple_fixed_force)
 * and the spatial moment of the conservative couple (rnk_moment_spatial):
 *  - Q against the virtual work M . omega with omega from central
 *    differences of the material frame (log of the relative rotation),
 *    h-sweep of order 2;
 *  - J against central differences of Q, h-sweep of order 2, and J is
 *    nonsymmetric at a general state;
 *  - the conservative couple's gradient is -Q of the fixed couple
 *    m = f x (M x f) / |n x f|^2 (the formula of docs/model.md) at general
 *    3D states, and m differs from M once f leaves the plane normal to M;
 *  - in a plane (couple normal to it, frame turning in it) both models give
 *    the same force and the same in-plane Jacobian. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "rnk.h"
#include "rnk_couple.h"
#include "testutil.h"

static uint64_t seed = 12345;
static double rnd(void) { return rn_test_rand(&seed); }

static void frame_of(const double q[7], const rnk_frame *ref, double F[9]) {
  double e[3] = {q[4] - q[0], q[5] - q[1], q[6] - q[2]};
  CHECK_STATUS(rnk_material_frame(e, ref, q[3], F, F + 3, F + 6), RNK_OK);
}

/* axial vector of log(Fp Fm^T) (frames as columns): the rotation from Fm to Fp */
static void rotation_between(const double Fm[9], const double Fp[9], double w[3]) {
  double R[3][3];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      R[a][b] = Fp[a] * Fm[b] + Fp[3 + a] * Fm[3 + b] + Fp[6 + a] * Fm[6 + b];
  double c = 0.5 * (R[0][0] + R[1][1] + R[2][2] - 1.0);
  double v[3] = {0.5 * (R[2][1] - R[1][2]), 0.5 * (R[0][2] - R[2][0]),
                 0.5 * (R[1][0] - R[0][1])};
  double s = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  double phi = atan2(s, c), k = s > 1e-300 ? phi / s : 1.0;
  for (int a = 0; a < 3; ++a) w[a] = k * v[a];
}

static void random_state(double q[7], rnk_frame *ref) {
  for (int k = 0; k < 7; ++k) q[k] = rnd();
  q[4] += 1.5; /* a well-shaped edge */
  double e[3] = {q[4] - q[0], q[5] - q[1], q[6] - q[2]};
  double t[3] = {e[0] + 0.3 * rnd(), e[1] + 0.3 * rnd(), e[2] + 0.3 * rnd()};
  rn_test_normalize3(t);
  double a[3] = {rnd(), rnd(), rnd()}, ta = t[0] * a[0] + t[1] * a[1] + t[2] * a[2];
  for (int k = 0; k < 3; ++k) a[k] -= ta * t[k];
  rn_test_normalize3(a);
  memcpy(ref->t, t, sizeof t);
  memcpy(ref->a1, a, sizeof a);
}

static void test_force_is_virtual_work(void) {
  for (int trial = 0; trial < 20; ++trial) {
    double q[7], Q[7], M[3] = {rnd(), rnd(), rnd()};
    rnk_frame ref;
    random_state(q, &ref);
    CHECK_STATUS(rnk_couple_fixed_force(q, &ref, M, Q, NULL), RNK_OK);
    double hs[4] = {1e-2, 5e-3, 2.5e-3, 1.25e-3}, err[4];
    for (int ih = 0; ih < 4; ++ih) {
      err[ih] = 0.0;
      for (int i = 0; i < 7; ++i) {
        double qp[7], qm[7], Fp[9], Fm[9], w[3];
        memcpy(qp, q, sizeof qp);
        memcpy(qm, q, sizeof qm);
        qp[i] += hs[ih];
        qm[i] -= hs[ih];
        frame_of(qp, &ref, Fp);
        frame_of(qm, &ref, Fm);
        rotation_between(Fm, Fp, w);
        double fd = (M[0] * w[0] + M[1] * w[1] + M[2] * w[2]) / (2.0 * hs[ih]);
        err[ih] = fmax(err[ih], fabs(fd - Q[i]));
      }
    }
    double slope = rn_test_loglog_slope(4, hs, err);
    if (err[0] > 1e-13) CHECK(slope > 1.8 && slope < 2.2);
    CHECK(err[3] < 1e-4);
  }
}

static void test_jacobian(void) {
  double worst_asym = 0.0;
  for (int trial = 0; trial < 20; ++trial) {
    double q[7], Q[7], J[49], M[3] = {rnd(), rnd(), rnd()};
    rnk_frame ref;
    random_state(q, &ref);
    CHECK_STATUS(rnk_couple_fixed_force(q, &ref, M, Q, J), RNK_OK);
    double Q2[7];
    CHECK_STATUS(rnk_couple_fixed_force(q, &ref, M, Q2, NULL), RNK_OK);
    for (int i = 0; i < 7; ++i) CHECK(Q2[i] == Q[i]);
    double hs[4] = {1e-2, 5e-3, 2.5e-3, 1.25e-3}, err[4], jmax = 0.0;
    for (int i = 0; i < 49; ++i) jmax = fmax(jmax, fabs(J[i]));
    for (int ih = 0; ih < 4; ++ih) {
      err[ih] = 0.0;
      for (int j = 0; j < 7; ++j) {
        double qp[7], qm[7], Qp[7], Qm[7];
        memcpy(qp, q, sizeof qp);
        memcpy(qm, q, sizeof qm);
        qp[j] += hs[ih];
        qm[j] -= hs[ih];
        CHECK_STATUS(rnk_couple_fixed_force(qp, &ref, M, Qp, NULL), RNK_OK);
        CHECK_STATUS(rnk_couple_fixed_force(qm, &ref, M, Qm, NULL), RNK_OK);
        for (int i = 0; i < 7; ++i)
          err[ih] = fmax(err[ih], fabs((Qp[i] - Qm[i]) / (2.0 * hs[ih]) - J[7 * i + j]));
      }
    }
    double slope = rn_test_loglog_slope(4, hs, err);
    CHECK(slope > 1.8 && slope < 2.2);
    CHECK(err[3] < 1e-4 * jmax);
    double asym = 0.0;
    for (int i = 0; i < 7; ++i)
      for (int j = 0; j < 7; ++j) asym = fmax(asym, fabs(J[7 * i + j] - J[7 * j + i]));
    worst_asym = fmax(worst_asym, asym / jmax);
  }
  CHECK(worst_asym > 1e-2); /* a couple fixed in space is not conservative */
}

/* body vector b picked perpendicular to M at the frame Fb (as rn_couple_vector) */
static void body_vector(const double Fb[9], const double M[3], double b[3]) {
  double n[3] = {M[0], M[1], M[2]}, u[3];
  rn_test_normalize3(n);
  double fn = Fb[3] * n[0] + Fb[4] * n[1] + Fb[5] * n[2];
  for (int a = 0; a < 3; ++a) u[a] = Fb[3 + a] - fn * n[a];
  rn_test_normalize3(u);
  for (int k = 0; k < 3; ++k)
    b[k] = Fb[3 * k] * u[0] + Fb[3 * k + 1] * u[1] + Fb[3 * k + 2] * u[2];
}

static void test_conservative_spatial_moment(void) {
  double worst_dev = 0.0;
  for (int trial = 0; trial < 20; ++trial) {
    double q[7], M[3] = {rnd(), rnd(), rnd()}, F[9], F0[9], q0[7];
    rnk_frame ref;
    random_state(q, &ref);
    /* the couple starts at a nearby state q0 (the body vector is chosen there) */
    for (int k = 0; k < 7; ++k) q0[k] = q[k] + 0.2 * rnd();
    frame_of(q0, &ref, F0);
    frame_of(q, &ref, F);
    rnk_moment_param p;
    memcpy(p.M, M, sizeof p.M);
    memcpy(p.f0, F0, sizeof p.f0);
    p.angle0 = 0.1;
    body_vector(F0, M, p.b);
    double g[7], E, m[3], Q[7];
    CHECK_STATUS(rnk_moment_grad(q, &ref, &p, &E, g), RNK_OK);
    CHECK_STATUS(rnk_moment_spatial(F, p.b, M, m), RNK_OK);
    CHECK_STATUS(rnk_couple_fixed_force(q, &ref, m, Q, NULL), RNK_OK);
    double gmax = 0.0;
    for (int i = 0; i < 7; ++i) gmax = fmax(gmax, fabs(g[i]));
    for (int i = 0; i < 7; ++i) CHECK_NEAR(-g[i], Q[i], 1e-12 * gmax);
    /* m . n = |M| always; m departs from M off the plane */
    double mm = sqrt(M[0] * M[0] + M[1] * M[1] + M[2] * M[2]);
    CHECK_NEAR((m[0] * M[0] + m[1] * M[1] + m[2] * M[2]) / mm, mm, 1e-13 * mm);
    double dev = sqrt((m[0] - M[0]) * (m[0] - M[0]) + (m[1] - M[1]) * (m[1] - M[1]) +
                      (m[2] - M[2]) * (m[2] - M[2]));
    worst_dev = fmax(worst_dev, dev / mm);
    /* at the start (f perpendicular to n) m = M */
    double m0[3];
    CHECK_STATUS(rnk_moment_spatial(F0, p.b, M, m0), RNK_OK);
    for (int a = 0; a < 3; ++a) CHECK_NEAR(m0[a], M[a], 1e-14 * mm);
  }
  CHECK(worst_dev > 1e-2);
}

/* Edge in the xy-plane, couple along z, the frame turned about z only. */
static void test_planar_coincide(void) {
  for (int trial = 0; trial < 10; ++trial) {
    double phi = 3.0 * rnd(), phi0 = phi + 0.7 * rnd(), L = 1.0 + 0.5 * rnd();
    double q[7] = {rnd(), rnd(), 0.0, 0.0, 0.0, 0.0, 0.0};
    q[4] = q[0] + L * cos(phi);
    q[5] = q[1] + L * sin(phi);
    rnk_frame ref = {{cos(phi0), sin(phi0), 0.0}, {0.0, 0.0, 1.0}};
    double M[3] = {0.0, 0.0, 2.0 * rnd()}, F[9], F0[9];
    frame_of(q, &ref, F);
    double q0[7];
    memcpy(q0, q, sizeof q0);
    q0[4] = q0[0] + L * cos(phi0);
    q0[5] = q0[1] + L * sin(phi0);
    frame_of(q0, &ref, F0);
    rnk_moment_param p;
    memcpy(p.M, M, sizeof p.M);
    memcpy(p.f0, F0, sizeof p.f0);
    p.angle0 = 0.0;
    p.b[0] = 1.0, p.b[1] = 0.0, p.b[2] = 0.0; /* f = t, in the plane */
    double g[7], E, H[49], Q[7], J[49], m[3];
    CHECK_STATUS(rnk_moment_grad(q, &ref, &p, &E, g), RNK_OK);
    CHECK_STATUS(rnk_moment_hess(q, &ref, &p, H), RNK_OK);
    CHECK_STATUS(rnk_couple_fixed_force(q, &ref, M, Q, J), RNK_OK);
    CHECK_STATUS(rnk_moment_spatial(F, p.b, M, m), RNK_OK);
    for (int a = 0; a < 3; ++a) CHECK_NEAR(m[a], M[a], 1e-14);
    CHECK_NEAR(E, -M[2] * (phi - phi0), 1e-13);
    double s = fabs(M[2]) + 1e-300;
    for (int i = 0; i < 7; ++i) CHECK_NEAR(-g[i], Q[i], 1e-13 * s);
    static const int in[4] = {0, 1, 4, 5}; /* in-plane position DOFs */
    for (int a = 0; a < 4; ++a)
      for (int b = 0; b < 4; ++b)
        CHECK_NEAR(J[7 * in[a] + in[b]], -H[7 * in[a] + in[b]], 1e-12 * s);
  }
}

int main(void) {
  test_force_is_virtual_work();
  test_jacobian();
  test_conservative_spatial_moment();
  test_planar_coincide();
  return rn_test_finish("kernels_couple_fixed");
}

/* kernels_joint_net.c - whole-joint kernels (rnk_joint_*) for both models at
 * valence 1..8: central-difference gradient and Hessian-vector product (the
 * matrix-free rnk_joint_hvp, which must equal the block rnk_joint_hess times
 * the direction; h-sweep, second order), symmetry, zero energy and gradient at rest,
 * invariance under rigid motions; the polar factor on its own (recovery of R from R S)
 * and the first and second derivatives of the elastic fit through the joint energy (the
 * FD checks of elastic joints exercise them). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rnk.h"
#include "testutil.h"

static uint64_t rng = 4242;
static double rnd(void) { return rn_test_rand(&rng); }

static void mat_vec(const double R[9], const double v[3], double out[3]) {
  double t[3];
  for (int i = 0; i < 3; ++i)
    t[i] = R[3 * i] * v[0] + R[3 * i + 1] * v[1] + R[3 * i + 2] * v[2];
  memcpy(out, t, sizeof t);
}

typedef struct star {
  rnk_joint j;
  rnk_joint_end ends[8];
  rnk_frame refs[8];
  double q[6 + 32];
  int n;
} star;

/* A joint of valence v at the origin with rods along random directions; the
 * current state is the rest state perturbed by `amp`. */
static void make_star(star *s, int v, int rigid, double amp) {
  memset(s, 0, sizeof *s);
  s->j.rigid = rigid;
  s->j.valence = v;
  s->j.ends = s->ends;
  s->j.refs = s->refs;
  for (int i = 0; i < 9; ++i) s->j.Qhat[i] = s->j.f0[i] = (i % 4 == 0);
  int off = rigid ? 6 : 3;
  for (int k = 0; k < v; ++k) {
    double dir[3] = {rnd(), rnd(), rnd()}, a[3] = {rnd(), rnd(), rnd()};
    rn_test_normalize3(dir);
    int side = k % 2;
    double len = 0.5 + 0.3 * fabs(rnd());
    /* rest: x_n = -side-dependent along dir; t points from x_n to x_J (side 0)
     * or from x_J to x_n (side 1) */
    double xn[3];
    for (int c = 0; c < 3; ++c) xn[c] = len * dir[c];
    double t[3];
    for (int c = 0; c < 3; ++c) t[c] = side == 0 ? -dir[c] : dir[c];
    double d = a[0] * t[0] + a[1] * t[1] + a[2] * t[2];
    for (int c = 0; c < 3; ++c) a[c] -= d * t[c];
    rn_test_normalize3(a);
    rnk_joint_end *e = &s->ends[k];
    e->side = side;
    memcpy(e->cbar, t, sizeof t);
    memcpy(e->cbar + 3, a, sizeof a);
    rn_test_cross3(t, a, e->cbar + 6);
    double B11 = 1 + fabs(rnd()), B22 = 1 + fabs(rnd()), B12 = 0.3 * rnd();
    e->bend = (rnk_bend_param){.B = {B11, B12, B22}, .kbar = {0, 0}, .vlen = 0.5 * len};
    e->twist =
        (rnk_twist_param){.beta = 0.8, .taubar = 0, .vlen = 0.5 * len, .ref_twist = 0};
    memcpy(s->refs[k].t, t, sizeof t);
    memcpy(s->refs[k].a1, a, sizeof a);
    for (int c = 0; c < 3; ++c) s->q[off + 4 * k + c] = xn[c];
    s->q[off + 4 * k + 3] = 0.0;
  }
  s->n = (int)rnk_joint_stencil_size(&s->j);
  /* perturb everything; move the reference frames a little off too */
  for (int i = 0; i < s->n; ++i) s->q[i] += amp * rnd();
  for (int k = 0; k < v && amp > 0; ++k) {
    for (int c = 0; c < 3; ++c) s->refs[k].t[c] += 0.1 * amp * rnd();
    rn_test_normalize3(s->refs[k].t);
    double *a = s->refs[k].a1, *t = s->refs[k].t;
    double d = a[0] * t[0] + a[1] * t[1] + a[2] * t[2];
    for (int c = 0; c < 3; ++c) a[c] -= d * t[c];
    rn_test_normalize3(a);
  }
}

static double norm(int n, const double *v) {
  double s = 0;
  for (int i = 0; i < n; ++i) s += v[i] * v[i];
  return sqrt(s);
}

/* worst FD errors over a few directions; returns observed orders */
static void fd_check(const star *s, double *worst_g, double *worst_h, double *og_min,
                     double *oh_min) {
  int n = s->n;
  double *work = malloc(sizeof(double) * rnk_joint_work_size(&s->j));
  double *g = malloc(sizeof(double) * (size_t)n),
         *H = malloc(sizeof(double) * (size_t)n * n);
  double *gp = malloc(sizeof(double) * (size_t)n),
         *gm = malloc(sizeof(double) * (size_t)n);
  double *Hv = malloc(sizeof(double) * (size_t)n),
         *vv = malloc(sizeof(double) * (size_t)n);
  double *qp = malloc(sizeof(double) * (size_t)n),
         *qm = malloc(sizeof(double) * (size_t)n);
  double E;
  CHECK_STATUS(rnk_joint_grad(s->q, &s->j, work, &E, g), RNK_OK);
  CHECK_STATUS(rnk_joint_hess(s->q, &s->j, work, H), RNK_OK);
  double hmax = 0, asym = 0;
  for (int i = 0; i < n * n; ++i) hmax = fmax(hmax, fabs(H[i]));
  if (!s->j.rigid && s->j.valence == 1 && s->j.M[0] == 0.0) {
    /* the fit of a single end reproduces its frame: no energy at all */
    CHECK_NEAR(E, 0.0, 1e-28);
    CHECK(norm(n, g) < 1e-14);
    CHECK(hmax < 1e-12);
    free(work), free(g), free(H), free(gp), free(gm), free(Hv), free(vv), free(qp),
        free(qm);
    *og_min = *oh_min = 2.0;
    return;
  }
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) asym = fmax(asym, fabs(H[i * n + k] - H[k * n + i]));
  CHECK(asym <= 1e-12 * hmax);
  for (int dir = 0; dir < 3; ++dir) {
    for (int i = 0; i < n; ++i) vv[i] = rnd();
    double nv = norm(n, vv);
    for (int i = 0; i < n; ++i) vv[i] /= nv;
    /* the matrix-free HVP is the block times the direction */
    CHECK_STATUS(rnk_joint_hvp(s->q, &s->j, work, vv, Hv), RNK_OK);
    rnk_block_mv(n, H, vv, qp);
    for (int i = 0; i < n; ++i) CHECK_NEAR(Hv[i], qp[i], 1e-13 * hmax * sqrt(n));
    double gv = 0;
    for (int i = 0; i < n; ++i) gv += g[i] * vv[i];
    double hs[5], eg[5], eh[5], sg = norm(n, g) + norm(n, Hv), sh = norm(n, Hv) + 1e-300;
    for (int st = 0; st < 5; ++st) {
      double h = 1e-3 / pow(2.0, st), Ep, Em;
      for (int i = 0; i < n; ++i)
        qp[i] = s->q[i] + h * vv[i], qm[i] = s->q[i] - h * vv[i];
      CHECK_STATUS(rnk_joint_grad(qp, &s->j, work, &Ep, gp), RNK_OK);
      CHECK_STATUS(rnk_joint_grad(qm, &s->j, work, &Em, gm), RNK_OK);
      hs[st] = h;
      eg[st] = fabs((Ep - Em) / (2 * h) - gv) / sg;
      double err = 0;
      for (int i = 0; i < n; ++i) err += pow((gp[i] - gm[i]) / (2 * h) - Hv[i], 2);
      eh[st] = sqrt(err) / sh;
    }
    double og = rn_test_loglog_slope(4, hs, eg), oh = rn_test_loglog_slope(4, hs, eh);
    *worst_g = fmax(*worst_g, eg[3]);
    *worst_h = fmax(*worst_h, eh[3]);
    if (eg[0] > 1e-9) *og_min = fmin(*og_min, og);
    if (eh[0] > 1e-9) *oh_min = fmin(*oh_min, oh);
  }
  free(work), free(g), free(H), free(gp), free(gm), free(Hv), free(vv), free(qp),
      free(qm);
}

static void test_polar(void) {
  for (int trial = 0; trial < 20; ++trial) {
    double w[3] = {2 * rnd(), 2 * rnd(), 2 * rnd()}, R[9], S[9], M[9], P[9];
    rnk_rotation_exp(w, R);
    double A[9];
    for (int i = 0; i < 9; ++i) A[i] = rnd();
    for (int i = 0; i < 3; ++i) /* S = A A^T + I (SPD) */
      for (int k = 0; k < 3; ++k) {
        double s = (i == k) ? 1.0 : 0.0;
        for (int l = 0; l < 3; ++l) s += A[3 * i + l] * A[3 * k + l];
        S[3 * i + k] = s;
      }
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) {
        double s = 0;
        for (int l = 0; l < 3; ++l) s += R[3 * i + l] * S[3 * l + k];
        M[3 * i + k] = s;
      }
    CHECK_STATUS(rnk_polar(M, P), RNK_OK);
    for (int i = 0; i < 9; ++i) CHECK_NEAR(P[i], R[i], 1e-13);
  }
  double Z[9] = {1, 0, 0, 0, 1, 0, 0, 0, 0}, P[9];
  CHECK_STATUS(rnk_polar(Z, P), RNK_DEGENERATE);
  double Ref[9] = {1, 0, 0, 0, 1, 0, 0, 0, -1};
  CHECK_STATUS(rnk_polar(Ref, P), RNK_DEGENERATE);
}

/* rotation vector of a rotation matrix near the identity (numeric log) */
static void rotvec(const double P[9], double w[3]) {
  double c = 0.5 * (P[0] + P[4] + P[8] - 1.0);
  double ax[3] = {0.5 * (P[7] - P[5]), 0.5 * (P[2] - P[6]), 0.5 * (P[3] - P[1])};
  double s = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
  double th = atan2(s, c), f = s > 1e-300 ? th / s : 1.0;
  for (int k = 0; k < 3; ++k) w[k] = f * ax[k];
}

/* phi(M + h E) relative to R0: exp([phi]) R0 = polar(M + h E) */
static void phi_num(const double M[9], const double E[9], double h, const double R0[9],
                    double phi[3]) {
  double Mh[9], R[9], P[9];
  for (int i = 0; i < 9; ++i) Mh[i] = M[i] + h * E[i];
  CHECK_STATUS(rnk_polar(Mh, R), RNK_OK);
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      double sum = 0;
      for (int l = 0; l < 3; ++l) sum += R[3 * i + l] * R0[3 * k + l];
      P[3 * i + k] = sum;
    }
  rotvec(P, phi);
}

/* The polar factor's first and second derivatives on their own: central
 * differences of phi(M + h E) against dphi . E and of the second difference
 * against E^T d2phi E, over an h-sweep (second order). */
static void test_polar_derivatives(void) {
  for (int trial = 0; trial < 10; ++trial) {
    double w[3] = {rnd(), rnd(), rnd()}, R[9], A[9], S[9], M[9];
    rnk_rotation_exp(w, R);
    for (int i = 0; i < 9; ++i) A[i] = 0.5 * rnd();
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) {
        double s = (i == k) ? 1.0 : 0.0;
        for (int l = 0; l < 3; ++l) s += A[3 * i + l] * A[3 * k + l];
        S[3 * i + k] = s;
      }
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k) {
        double s = 0;
        for (int l = 0; l < 3; ++l) s += R[3 * i + l] * S[3 * l + k];
        M[3 * i + k] = s;
      }
    double R0[9], d1[27], d2[243], E[9];
    CHECK_STATUS(rnk_polar_rotvec_derivs(M, R0, d1, d2), RNK_OK);
    for (int i = 0; i < 9; ++i) CHECK_NEAR(R0[i], R[i], 1e-13);
    for (int i = 0; i < 9; ++i) E[i] = rnd();
    double hs[4], e1[4], e2[4], lin[3], quad[3];
    for (int a = 0; a < 3; ++a) {
      lin[a] = quad[a] = 0;
      for (int m = 0; m < 9; ++m) {
        lin[a] += d1[9 * a + m] * E[m];
        for (int n = 0; n < 9; ++n) quad[a] += E[m] * d2[81 * a + 9 * m + n] * E[n];
      }
    }
    for (int st = 0; st < 4; ++st) {
      double h = 1e-2 / pow(2.0, st), pp[3], pm[3], err1 = 0, err2 = 0;
      phi_num(M, E, h, R0, pp);
      phi_num(M, E, -h, R0, pm);
      for (int a = 0; a < 3; ++a) {
        err1 += pow((pp[a] - pm[a]) / (2 * h) - lin[a], 2);
        err2 += pow((pp[a] + pm[a]) / (h * h) - quad[a], 2);
      }
      hs[st] = h;
      e1[st] = sqrt(err1) / (norm(3, lin) + 1e-300);
      e2[st] = sqrt(err2) / (norm(3, quad) + 1e-300);
    }
    double o1 = rn_test_loglog_slope(4, hs, e1), o2 = rn_test_loglog_slope(4, hs, e2);
    if (trial == 0)
      printf("polar: first-derivative FD error %.2e (order %.2f), second %.2e (order "
             "%.2f)\n",
             e1[3], o1, e2[3], o2);
    CHECK(e1[3] < 1e-5 && e2[3] < 1e-4);
    CHECK(o1 > 1.8 && o1 < 2.3);
    CHECK(o2 > 1.8 && o2 < 2.3);
  }
}

static void test_rest_and_invariance(void) {
  for (int rigid = 0; rigid < 2; ++rigid)
    for (int v = 1; v <= 8; ++v) {
      star s;
      make_star(&s, v, rigid, 0.0);
      double *work = malloc(sizeof(double) * rnk_joint_work_size(&s.j)), g[38], E;
      CHECK_STATUS(rnk_joint_grad(s.q, &s.j, work, &E, g), RNK_OK);
      CHECK_NEAR(E, 0.0, 1e-24);
      CHECK_NEAR(norm(s.n, g), 0.0, 1e-12);
      double R[9];
      CHECK_STATUS(rnk_joint_rotation(s.q, &s.j, R), RNK_OK);
      for (int i = 0; i < 9; ++i) CHECK_NEAR(R[i], (double)(i % 4 == 0), 1e-14);
      /* rigid motion of a deformed star */
      make_star(&s, v, rigid, 0.2);
      star t = s;
      double w[3] = {rnd(), rnd(), rnd()}, Rm[9], c[3] = {rnd(), rnd(), rnd()};
      rnk_rotation_exp(w, Rm);
      int off = rigid ? 6 : 3;
      mat_vec(Rm, s.q, t.q);
      for (int k = 0; k < 3; ++k) t.q[k] += c[k];
      if (rigid) {
        mat_vec(Rm, s.q + 3, t.q + 3);
        double Q[9];
        for (int i = 0; i < 3; ++i)
          for (int k = 0; k < 3; ++k) {
            double sum = 0;
            for (int l = 0; l < 3; ++l) sum += Rm[3 * i + l] * s.j.Qhat[3 * l + k];
            Q[3 * i + k] = sum;
          }
        memcpy(t.j.Qhat, Q, sizeof Q);
      }
      for (int k = 0; k < v; ++k) {
        mat_vec(Rm, s.q + off + 4 * k, t.q + off + 4 * k);
        for (int cc = 0; cc < 3; ++cc) t.q[off + 4 * k + cc] += c[cc];
        mat_vec(Rm, s.refs[k].t, t.refs[k].t);
        mat_vec(Rm, s.refs[k].a1, t.refs[k].a1);
        /* rest frames are not rotated (only the current configuration is) */
      }
      t.j.ends = t.ends;
      t.j.refs = t.refs;
      double E1, E2;
      CHECK_STATUS(rnk_joint_energy(s.q, &s.j, work, &E1), RNK_OK);
      /* rest frames stay: the energy of a rigidly moved elastic star equals the
       * original only if the fit rotates along, which it does */
      CHECK_STATUS(rnk_joint_energy(t.q, &t.j, work, &E2), RNK_OK);
      CHECK_NEAR(E2, E1, 1e-11 * E1 + 1e-25);
      free(work);
    }
}

int main(void) {
  test_polar();
  test_polar_derivatives();
  test_rest_and_invariance();
  printf("model    valence  worst grad err  order   worst HVP err  order\n");
  for (int rigid = 0; rigid < 2; ++rigid)
    for (int v = 1; v <= 8; ++v) {
      double wg = 0, wh = 0, og = 9, oh = 9;
      for (int trial = 0; trial < 4; ++trial) {
        star s;
        make_star(&s, v, rigid, 0.15);
        if (trial == 3) { /* with a couple on the rotation */
          s.j.M[0] = 0.3, s.j.M[1] = -0.2, s.j.M[2] = 0.5;
          s.j.couple_p[0] = 0.8, s.j.couple_p[1] = 0.6, s.j.couple_p[2] = -0.24;
          s.j.angle0 = 0.1;
        }
        fd_check(&s, &wg, &wh, &og, &oh);
      }
      printf("%-8s %7d  %14.2e  %5.2f   %13.2e  %5.2f\n", rigid ? "rigid" : "elastic", v,
             wg, og, wh, oh);
      CHECK(wg < 1e-6);
      CHECK(wh < 1e-6);
      CHECK(og > 1.8 && og < 2.4);
      CHECK(oh > 1.8 && oh < 2.4);
    }
  return rn_test_finish("kernels_joint_net");
}

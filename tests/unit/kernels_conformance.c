/* kernels_conformance.c - one conformance checker run over every energy
 * kernel: central-difference gradient and HVP with an h-sweep showing second
 * order, Hessian symmetry, HVP == Hessian block times v, zero energy and
 * gradient at rest, invariance under rigid motions, and invariance of the
 * energy under a reference-frame update.  Random deformed stencils with
 * reference frames that are NOT up to date, so the derivatives are checked
 * as exact derivatives of E(q; reference), not at a frozen frame. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "rnk.h"
#include "testutil.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

typedef struct term {
  const char *name;
  int n; /* 7 or 11 */
  int (*energy)(const struct term *, const double *q, double *E);
  int (*grad)(const struct term *, const double *q, double *E, double *g);
  int (*hess)(const struct term *, const double *q, double *H);
  int (*hvp)(const struct term *, const double *q, const double *v, double *Hv);
  rnk_frame ref[2];
  rnk_stretch_param sp;
  rnk_bend_param bp;
  rnk_twist_param tp;
  rnk_moment_param mp;
} term;

/* adapters */
static int st_e(const term *t, const double *q, double *E) {
  return rnk_stretch_energy(q, &t->sp, E);
}
static int st_g(const term *t, const double *q, double *E, double *g) {
  return rnk_stretch_grad(q, &t->sp, E, g);
}
static int st_h(const term *t, const double *q, double *H) {
  return rnk_stretch_hess(q, &t->sp, H);
}
static int st_v(const term *t, const double *q, const double *v, double *Hv) {
  return rnk_stretch_hvp(q, &t->sp, v, Hv);
}
static int be_e(const term *t, const double *q, double *E) {
  return rnk_bend_energy(q, t->ref, &t->bp, E);
}
static int be_g(const term *t, const double *q, double *E, double *g) {
  return rnk_bend_grad(q, t->ref, &t->bp, E, g);
}
static int be_h(const term *t, const double *q, double *H) {
  return rnk_bend_hess(q, t->ref, &t->bp, H);
}
static int be_v(const term *t, const double *q, const double *v, double *Hv) {
  return rnk_bend_hvp(q, t->ref, &t->bp, v, Hv);
}
static int tw_e(const term *t, const double *q, double *E) {
  return rnk_twist_energy(q, t->ref, &t->tp, E);
}
static int tw_g(const term *t, const double *q, double *E, double *g) {
  return rnk_twist_grad(q, t->ref, &t->tp, E, g);
}
static int tw_h(const term *t, const double *q, double *H) {
  return rnk_twist_hess(q, t->ref, &t->tp, H);
}
static int tw_v(const term *t, const double *q, const double *v, double *Hv) {
  return rnk_twist_hvp(q, t->ref, &t->tp, v, Hv);
}
static int mo_e(const term *t, const double *q, double *E) {
  return rnk_moment_energy(q, t->ref, &t->mp, E);
}
static int mo_g(const term *t, const double *q, double *E, double *g) {
  return rnk_moment_grad(q, t->ref, &t->mp, E, g);
}
static int mo_h(const term *t, const double *q, double *H) {
  return rnk_moment_hess(q, t->ref, &t->mp, H);
}
static int mo_v(const term *t, const double *q, const double *v, double *Hv) {
  return rnk_moment_hvp(q, t->ref, &t->mp, v, Hv);
}

static int bt_e(const term *t, const double *q, double *E) {
  double eb, et;
  int st = rnk_bendtwist_energy(q, t->ref, &t->bp, &t->tp, &eb, &et);
  *E = eb + et;
  return st;
}
static int bt_g(const term *t, const double *q, double *E, double *g) {
  return rnk_bendtwist_grad(q, t->ref, &t->bp, &t->tp, E, g);
}
static int bt_h(const term *t, const double *q, double *H) {
  return rnk_bendtwist_hess(q, t->ref, &t->bp, &t->tp, H);
}
static int bt_v(const term *t, const double *q, const double *v, double *Hv) {
  return rnk_bendtwist_hvp(q, t->ref, &t->bp, &t->tp, v, Hv);
}

static uint64_t rng = 12345;
static double rnd(void) { return rn_test_rand(&rng); }

/* A reference frame near (not at) the tangent of edge vector e. */
static void near_frame(const double e[3], double spread, rnk_frame *f) {
  double t[3], a[3];
  for (int k = 0; k < 3; ++k)
    t[k] = e[k] + spread * rnd() * sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
  rn_test_normalize3(t);
  for (int k = 0; k < 3; ++k) a[k] = rnd();
  double d = a[0] * t[0] + a[1] * t[1] + a[2] * t[2];
  for (int k = 0; k < 3; ++k) a[k] -= d * t[k];
  rn_test_normalize3(a);
  memcpy(f->t, t, sizeof t);
  memcpy(f->a1, a, sizeof a);
}

/* Random curved, stretched, twisted stencil. */
static void random_stencil(int n, double *q) {
  double x[3][3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  for (int v = 0; v < 3; ++v)
    for (int k = 0; k < 3; ++k) x[v][k] += 0.35 * rnd();
  for (int k = 0; k < 3; ++k) {
    q[k] = x[0][k];
    q[4 + k] = x[1][k];
    if (n == 11) q[8 + k] = x[2][k];
  }
  q[3] = 0.7 * rnd();
  if (n == 11) q[7] = 0.7 * rnd();
}

static void setup_frames(term *t, const double *q, double spread) {
  double e0[3] = {q[4] - q[0], q[5] - q[1], q[6] - q[2]};
  near_frame(e0, spread, &t->ref[0]);
  if (t->n == 11) {
    double e1[3] = {q[8] - q[4], q[9] - q[5], q[10] - q[6]};
    near_frame(e1, spread, &t->ref[1]);
  }
}

static double norm(int n, const double *v) {
  double s = 0;
  for (int i = 0; i < n; ++i) s += v[i] * v[i];
  return sqrt(s);
}

/* FD sweep: returns worst relative error at the best h and the fitted slope. */
static void check_derivatives(const term *t, const double *q) {
  int n = t->n;
  double g[11], H[121], v[11], Hv[11], E;
  CHECK_STATUS(t->grad(t, q, &E, g), RNK_OK);
  CHECK_STATUS(t->hess(t, q, H), RNK_OK);
  /* symmetry */
  double hmax = 0, asym = 0;
  for (int i = 0; i < n * n; ++i) hmax = fmax(hmax, fabs(H[i]));
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) asym = fmax(asym, fabs(H[i * n + j] - H[j * n + i]));
  CHECK(asym <= 1e-13 * hmax + 1e-300);
  for (int dir = 0; dir < 3; ++dir) {
    for (int i = 0; i < n; ++i) v[i] = rnd();
    double nv = norm(n, v);
    for (int i = 0; i < n; ++i) v[i] /= nv;
    CHECK_STATUS(t->hvp(t, q, v, Hv), RNK_OK);
    double Hv2[11];
    rnk_block_mv(n, H, v, Hv2);
    for (int i = 0; i < n; ++i) CHECK_NEAR(Hv[i], Hv2[i], 1e-14 * hmax);
    double gv = 0;
    for (int i = 0; i < n; ++i) gv += g[i] * v[i];
    double hs[5], eg[5], eh[5];
    double scale_g = norm(n, g) + norm(n, Hv) + 1e-300, scale_h = norm(n, Hv) + 1e-300;
    for (int s = 0; s < 5; ++s) {
      double h = 1e-2 / pow(2.0, s), qp[11], qm[11], Ep, Em, gp[11], gm[11];
      for (int i = 0; i < n; ++i) {
        qp[i] = q[i] + h * v[i];
        qm[i] = q[i] - h * v[i];
      }
      CHECK_STATUS(t->grad(t, qp, &Ep, gp), RNK_OK);
      CHECK_STATUS(t->grad(t, qm, &Em, gm), RNK_OK);
      hs[s] = h;
      eg[s] = fabs((Ep - Em) / (2 * h) - gv) / scale_g;
      double err = 0;
      for (int i = 0; i < n; ++i) {
        double d = (gp[i] - gm[i]) / (2 * h) - Hv[i];
        err += d * d;
      }
      eh[s] = sqrt(err) / scale_h;
    }
    double sg = rn_test_loglog_slope(5, hs, eg), sh = rn_test_loglog_slope(5, hs, eh);
    /* Second order, unless already at round-off over the whole sweep. */
    if (eg[0] > 1e-9) {
      if (!(sg > 1.8 && sg < 2.3))
        rn_test_fail(__FILE__, __LINE__,
                     "%s gradient FD order %.3f (errors %.3g .. %.3g)", t->name, sg,
                     eg[0], eg[4]);
      rn_test_checks++;
    }
    if (!(eg[4] < 1e-5))
      rn_test_fail(__FILE__, __LINE__,
                   "%s gradient FD error %.3g (scale %.3g) errs %.3g %.3g %.3g", t->name,
                   eg[4], scale_g, eg[0], eg[1], eg[2]);
    if (eh[0] > 1e-9) {
      if (!(sh > 1.8 && sh < 2.3))
        rn_test_fail(__FILE__, __LINE__, "%s HVP FD order %.3f (errors %.3g .. %.3g)",
                     t->name, sh, eh[0], eh[4]);
      rn_test_checks++;
    }
    CHECK(eh[4] < 1e-5);
  }
}

/* rotate points and frames of a stencil by rotation matrix R, translate by c */
static void rigid(const term *t, const double *q, const double R[9], const double c[3],
                  term *t2, double *q2) {
  *t2 = *t;
  memcpy(q2, q, sizeof(double) * (size_t)t->n);
  int nv = t->n == 11 ? 3 : 2;
  for (int v = 0; v < nv; ++v)
    for (int a = 0; a < 3; ++a) {
      double s = c[a];
      for (int b = 0; b < 3; ++b) s += R[3 * a + b] * q[4 * v + b];
      q2[4 * v + a] = s;
    }
  for (int f = 0; f < 2; ++f)
    for (int a = 0; a < 3; ++a) {
      double s1 = 0, s2 = 0;
      for (int b = 0; b < 3; ++b) {
        s1 += R[3 * a + b] * t->ref[f].t[b];
        s2 += R[3 * a + b] * t->ref[f].a1[b];
      }
      t2->ref[f].t[a] = s1;
      t2->ref[f].a1[a] = s2;
    }
}

static void random_rotation(double R[9]) {
  double a[3] = {rnd(), rnd(), rnd()}, b[3] = {rnd(), rnd(), rnd()}, c[3];
  rn_test_normalize3(a);
  double d = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  for (int k = 0; k < 3; ++k) b[k] -= d * a[k];
  rn_test_normalize3(b);
  rn_test_cross3(a, b, c);
  for (int k = 0; k < 3; ++k) {
    R[k] = a[k];
    R[3 + k] = b[k];
    R[6 + k] = c[k];
  }
}

#define NTERMS 5
static void make_terms(term *T) {
  memset(T, 0, NTERMS * sizeof *T);
  T[0] = (term){
      .name = "stretch", .n = 7, .energy = st_e, .grad = st_g, .hess = st_h, .hvp = st_v};
  T[0].sp = (rnk_stretch_param){.k = 3.0, .lbar = 0.8};
  T[1] = (term){
      .name = "bend", .n = 11, .energy = be_e, .grad = be_g, .hess = be_h, .hvp = be_v};
  T[1].bp = (rnk_bend_param){.B = {2.0, 0.3, 0.7}, .kbar = {0.2, -0.15}, .vlen = 0.9};
  T[2] = (term){
      .name = "twist", .n = 11, .energy = tw_e, .grad = tw_g, .hess = tw_h, .hvp = tw_v};
  T[2].tp = (rnk_twist_param){.beta = 1.3, .taubar = 0.1, .vlen = 0.9, .ref_twist = 0.4};
  T[3] = (term){
      .name = "moment", .n = 7, .energy = mo_e, .grad = mo_g, .hess = mo_h, .hvp = mo_v};
  T[3].mp =
      (rnk_moment_param){.M = {0.3, -0.5, 0.8}, .angle0 = 0.25, .b = {0.6, 0.0, 0.8}};
  T[4] = (term){.name = "bendtwist",
                .n = 11,
                .energy = bt_e,
                .grad = bt_g,
                .hess = bt_h,
                .hvp = bt_v};
  T[4].bp = T[1].bp;
  T[4].tp = T[2].tp;
}

/* The combined kernel equals bend + twist (value, gradient, Hessian). */
static void test_bendtwist_sum(void) {
  term T[NTERMS];
  make_terms(T);
  for (int trial = 0; trial < 10; ++trial) {
    double q[11], E1, E2, E3, g1[11], g2[11], g3[11], H1[121], H2[121], H3[121];
    random_stencil(11, q);
    setup_frames(&T[4], q, 0.3);
    T[1].ref[0] = T[2].ref[0] = T[4].ref[0];
    T[1].ref[1] = T[2].ref[1] = T[4].ref[1];
    CHECK_STATUS(T[1].grad(&T[1], q, &E1, g1), RNK_OK);
    CHECK_STATUS(T[2].grad(&T[2], q, &E2, g2), RNK_OK);
    CHECK_STATUS(T[4].grad(&T[4], q, &E3, g3), RNK_OK);
    CHECK_NEAR(E3, E1 + E2, 1e-14 * (E1 + E2));
    T[1].hess(&T[1], q, H1);
    T[2].hess(&T[2], q, H2);
    T[4].hess(&T[4], q, H3);
    for (int i = 0; i < 11; ++i)
      CHECK_NEAR(g3[i], g1[i] + g2[i], 1e-13 * (fabs(g1[i]) + fabs(g2[i]) + 1e-12));
    for (int i = 0; i < 121; ++i)
      CHECK_NEAR(H3[i], H1[i] + H2[i], 1e-13 * (fabs(H1[i]) + fabs(H2[i]) + 1e-12));
  }
}

/* moment reference frame f0 near the current material frame */
static void moment_f0(term *t, const double *q) {
  double e[3] = {q[4] - q[0], q[5] - q[1], q[6] - q[2]}, tt[3], d1[3], d2[3];
  CHECK_STATUS(rnk_material_frame(e, &t->ref[0], q[3] + 0.3, tt, d1, d2), RNK_OK);
  double R[9];
  (void)R;
  memcpy(t->mp.f0, tt, sizeof tt);
  memcpy(t->mp.f0 + 3, d1, sizeof d1);
  memcpy(t->mp.f0 + 6, d2, sizeof d2);
}

static void test_terms(void) {
  term T[NTERMS];
  make_terms(T);
  for (int trial = 0; trial < 40; ++trial) {
    for (int k = 0; k < NTERMS; ++k) {
      term t = T[k];
      double q[11];
      random_stencil(t.n, q);
      setup_frames(&t, q, 0.3);
      if (k == 3) moment_f0(&t, q);
      check_derivatives(&t, q);
      /* rigid motion invariance (not for the external couple) */
      if (k != 3) {
        double R[9], c[3] = {rnd(), rnd(), rnd()}, q2[11], E1, E2;
        term t2;
        random_rotation(R);
        rigid(&t, q, R, c, &t2, q2);
        CHECK_STATUS(t.energy(&t, q, &E1), RNK_OK);
        CHECK_STATUS(t2.energy(&t2, q2, &E2), RNK_OK);
        CHECK_NEAR(E2, E1, 1e-12 * (fabs(E1) + 1e-3));
      }
    }
  }
}

/* Zero energy and gradient at rest: rest values taken from the current state. */
static void test_rest(void) {
  term T[NTERMS];
  make_terms(T);
  for (int trial = 0; trial < 10; ++trial) {
    double q[11], g[11], E, kappa[2], tw;
    /* stretch */
    term t = T[0];
    random_stencil(7, q);
    t.sp.lbar = sqrt(pow(q[4] - q[0], 2) + pow(q[5] - q[1], 2) + pow(q[6] - q[2], 2));
    CHECK_STATUS(t.grad(&t, q, &E, g), RNK_OK);
    CHECK_NEAR(E, 0.0, 1e-15);
    CHECK_NEAR(norm(7, g), 0.0, 1e-13);
    /* bend and twist */
    random_stencil(11, q);
    t = T[1];
    setup_frames(&t, q, 0.2);
    CHECK_STATUS(rnk_strains(q, t.ref, 0.4, kappa, &tw), RNK_OK);
    t.bp.kbar[0] = kappa[0];
    t.bp.kbar[1] = kappa[1];
    CHECK_STATUS(t.grad(&t, q, &E, g), RNK_OK);
    CHECK_NEAR(E, 0.0, 1e-15);
    CHECK_NEAR(norm(11, g), 0.0, 1e-12);
    term u = T[2];
    u.ref[0] = t.ref[0];
    u.ref[1] = t.ref[1];
    u.tp.taubar = tw;
    CHECK_STATUS(u.grad(&u, q, &E, g), RNK_OK);
    CHECK_NEAR(E, 0.0, 1e-15);
    CHECK_NEAR(norm(11, g), 0.0, 1e-12);
  }
}

/* Parallel transport: exact for equal tangents, accurate for nearly parallel
 * ones (norm and orthogonality preserved), rejects opposite tangents. */
static void test_transport(void) {
  double t[3] = {0.3, -0.4, 0.866}, v[3] = {0.8, 0.6, 0.0}, out[3];
  rn_test_normalize3(t);
  double d = v[0] * t[0] + v[1] * t[1] + v[2] * t[2];
  for (int k = 0; k < 3; ++k) v[k] -= d * t[k];
  rn_test_normalize3(v);
  CHECK_STATUS(rnk_transport(t, t, v, out), RNK_OK);
  for (int k = 0; k < 3; ++k) CHECK_NEAR(out[k], v[k], 4e-16);
  for (int p = 4; p <= 15; ++p) {
    double tb[3] = {t[0] + pow(10.0, -p), t[1] - pow(10.0, -p), t[2]};
    rn_test_normalize3(tb);
    CHECK_STATUS(rnk_transport(t, tb, v, out), RNK_OK);
    CHECK_NEAR(out[0] * out[0] + out[1] * out[1] + out[2] * out[2], 1.0, 1e-15);
    CHECK_NEAR(out[0] * tb[0] + out[1] * tb[1] + out[2] * tb[2], 0.0, 1e-15);
    CHECK_NEAR(out[0], v[0], 10 * pow(10.0, -p));
  }
  double mt[3] = {-t[0], -t[1], -t[2]};
  CHECK_STATUS(rnk_transport(t, mt, v, out), RNK_DEGENERATE);
  /* 90 degrees: transport of a vector along the rotation axis stays put */
  double a[3] = {1, 0, 0}, b[3] = {0, 1, 0}, z[3] = {0, 0, 1};
  CHECK_STATUS(rnk_transport(a, b, z, out), RNK_OK);
  CHECK_NEAR(out[2], 1.0, 1e-16);
  CHECK_STATUS(rnk_transport(a, b, b, out), RNK_OK);
  CHECK_NEAR(out[0], -1.0, 1e-16);
  /* a zero-length edge is degenerate for every kernel */
  double q[11] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0}, E;
  term T[NTERMS];
  make_terms(T);
  rnk_frame_update((double[3]){1, 0, 0}, &T[1].ref[0]);
  CHECK_STATUS(rnk_bend_energy(q, T[1].ref, &T[1].bp, &E), RNK_DEGENERATE);
  CHECK_STATUS(rnk_stretch_energy(q, &T[0].sp, &E), RNK_DEGENERATE);
  /* a full fold-back (opposite consecutive tangents) is degenerate for bending */
  double fold[11] = {0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 1e-300};
  rnk_frame r2[2] = {{{1, 0, 0}, {0, 1, 0}}, {{-1, 0, 0}, {0, 1, 0}}};
  CHECK_STATUS(rnk_bend_energy(fold, r2, &T[1].bp, &E), RNK_DEGENERATE);
}

/* The reference update leaves the energy unchanged, and the reference twist
 * is continued across many updates without aliasing modulo 2 pi. */
static void test_update_and_twist_continuation(void) {
  term T[NTERMS];
  make_terms(T);
  for (int trial = 0; trial < 10; ++trial) {
    double q[11], E1, E2, m;
    random_stencil(11, q);
    term t = T[2];
    setup_frames(&t, q, 0.3);
    term b = T[1];
    b.ref[0] = t.ref[0];
    b.ref[1] = t.ref[1];
    double Eb1, Eb2;
    CHECK_STATUS(t.energy(&t, q, &E1), RNK_OK);
    CHECK_STATUS(b.energy(&b, q, &Eb1), RNK_OK);
    CHECK_STATUS(rnk_reference_twist(q, t.ref, t.tp.ref_twist, &m), RNK_OK);
    double e0[3] = {q[4] - q[0], q[5] - q[1], q[6] - q[2]},
           e1[3] = {q[8] - q[4], q[9] - q[5], q[10] - q[6]};
    CHECK_STATUS(rnk_frame_update(e0, &t.ref[0]), RNK_OK);
    CHECK_STATUS(rnk_frame_update(e1, &t.ref[1]), RNK_OK);
    t.tp.ref_twist = m;
    b.ref[0] = t.ref[0];
    b.ref[1] = t.ref[1];
    CHECK_STATUS(t.energy(&t, q, &E2), RNK_OK);
    CHECK_STATUS(b.energy(&b, q, &Eb2), RNK_OK);
    CHECK_NEAR(E2, E1, 1e-13 * (E1 + 1e-3));
    CHECK_NEAR(Eb2, Eb1, 1e-13 * (Eb1 + 1e-3));
  }
  /* Twist a straight rod's second edge frame by 5 full turns in steps of
   * 0.9 rad: the continued reference twist must reach -10 pi (reference
   * director of edge 1 rotated by +phi means the reference twist grows). */
  double q[11] = {0, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0};
  rnk_frame ref[2] = {{{1, 0, 0}, {0, 1, 0}}, {{1, 0, 0}, {0, 1, 0}}};
  double m = 0, phi = 0;
  while (phi < 10 * M_PI) {
    phi = fmin(phi + 0.9, 10 * M_PI);
    ref[1].a1[0] = 0;
    ref[1].a1[1] = cos(phi);
    ref[1].a1[2] = sin(phi);
    CHECK_STATUS(rnk_reference_twist(q, ref, m, &m), RNK_OK);
  }
  CHECK_NEAR(m, 10 * M_PI, 1e-12);
}

int main(void) {
  test_transport();
  test_terms();
  test_rest();
  test_update_and_twist_continuation();
  test_bendtwist_sum();
  return rn_test_finish("kernels_conformance");
}

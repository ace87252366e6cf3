/* kernels_closed_form.c - the closed-form bending + twisting kernels (rod.c)
 * against the jet oracle (rnk_jet_bendtwist_*, generic second-order forward
 * differentiation of the same composition) at many random configurations:
 * strongly bent and stretched stencils, stale reference frames (tangents up
 * to ~70 degrees off), reference twists continued over several turns, large
 * material angles, rest curvature and twist, anisotropic bending stiffness,
 * and the bending-only / twisting-only special cases.  Energy, gradient,
 * Hessian block and HVP must agree to round-off (1e-12 relative), and both
 * must flag the same degenerate configurations. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rnk.h"
#include "rqmath.h"
#include "testutil.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

static uint64_t rng = 0x5eed5eedULL;
static double rnd(void) { return rn_test_rand(&rng); }

static double norm(int n, const double *v) {
  double s = 0;
  for (int i = 0; i < n; ++i) s += v[i] * v[i];
  return sqrt(s);
}

/* Reference frame with tangent near e (relative spread) and a random
 * director. */
static void stale_frame(const double e[3], double spread, rnk_frame *f) {
  double t[3], a[3], le = norm(3, e);
  for (int k = 0; k < 3; ++k) t[k] = e[k] / le + spread * rnd();
  rn_test_normalize3(t);
  for (int k = 0; k < 3; ++k) a[k] = rnd();
  double d = a[0] * t[0] + a[1] * t[1] + a[2] * t[2];
  for (int k = 0; k < 3; ++k) a[k] -= d * t[k];
  rn_test_normalize3(a);
  memcpy(f->t, t, sizeof t);
  memcpy(f->a1, a, sizeof a);
}

typedef struct config {
  double q[11];
  rnk_frame ref[2];
  rnk_bend_param bp;
  rnk_twist_param tp;
} config;

/* The reference twist of the stored frames themselves (the value a
 * reference update would have stored), plus whole turns. */
static double stored_twist(const rnk_frame ref[2], int turns) {
  double q[11] = {0}, m = 0.0;
  for (int k = 0; k < 3; ++k) {
    q[4 + k] = ref[0].t[k];
    q[8 + k] = ref[0].t[k] + ref[1].t[k];
  }
  CHECK_STATUS(rnk_reference_twist(q, ref, 0.0, &m), RNK_OK);
  return m + 2.0 * M_PI * turns;
}

static void random_config(config *c, double bend, double spread) {
  double x[3][3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  for (int v = 0; v < 3; ++v)
    for (int k = 0; k < 3; ++k) x[v][k] += bend * rnd();
  for (int k = 0; k < 3; ++k) {
    c->q[k] = x[0][k];
    c->q[4 + k] = x[1][k];
    c->q[8 + k] = x[2][k];
  }
  c->q[3] = 4.0 * rnd();
  c->q[7] = c->q[3] + 0.8 * rnd();
  double e0[3] = {x[1][0] - x[0][0], x[1][1] - x[0][1], x[1][2] - x[0][2]};
  double e1[3] = {x[2][0] - x[1][0], x[2][1] - x[1][1], x[2][2] - x[1][2]};
  stale_frame(e0, spread, &c->ref[0]);
  stale_frame(e1, spread, &c->ref[1]);
  double B11 = 1.0 + rnd(), B22 = 3.0 + 2.0 * rnd(), B12 = 0.4 * rnd();
  c->bp =
      (rnk_bend_param){{B11, B12, B22}, {0.3 * rnd(), 0.3 * rnd()}, 0.7 + 0.2 * rnd()};
  c->tp = (rnk_twist_param){1.0 + 0.5 * rnd(), 0.2 * rnd(), c->bp.vlen,
                            stored_twist(c->ref, (int)lround(3.0 * rnd()))};
}

static double max_abs(int n, const double *v) {
  double m = 0;
  for (int i = 0; i < n; ++i) m = fmax(m, fabs(v[i]));
  return m;
}

static double worst_e, worst_g, worst_h, worst_v; /* scaled to dm = 0 */
/* Angles of size |theta| are known to |theta| eps: the tolerance grows by
 * 1 + |theta| eps / 1e-12 (test_big_angles). */
static double tol_scale = 1.0;
static int near_wrap; /* configurations with |dm| > 2.94 */

/* Compares the closed forms with the jets at one configuration.  The jets
 * take the twist increment dm as 2 atan2(4 W X, 4 W^2) (their reference
 * frames' swing-twist form): its derivatives lose accuracy like
 * 1 / cos^2(dm / 2) as dm nears the wrap at +-pi (a discontinuity of the
 * continued twist where no solver step ends: the stored twist is updated at
 * every accepted step), so the tolerance grows by that factor there. */
static void compare(const config *c) {
  double Eb1, Et1, Eb2, Et2, E1, E2, g1[11], g2[11], H1[121], H2[121], v[11], Hv1[11],
      Hv2[11], m;
  int s1 = rnk_bendtwist_energy(c->q, c->ref, &c->bp, &c->tp, &Eb1, &Et1);
  int s2 = rnk_jet_bendtwist_energy(c->q, c->ref, &c->bp, &c->tp, &Eb2, &Et2);
  CHECK_STATUS(s1, s2);
  if (s1 || s2) return;
  CHECK_STATUS(rnk_reference_twist(c->q, c->ref, c->tp.ref_twist, &m), RNK_OK);
  double cw = cos(0.5 * (m - c->tp.ref_twist)), tol = 1e-12 * tol_scale / (cw * cw);
  double se = fabs(Eb2) + fabs(Et2) + 1e-300;
  worst_e = fmax(worst_e, (fabs(Eb1 - Eb2) + fabs(Et1 - Et2)) / se);
  CHECK_NEAR(Eb1, Eb2, 1e-12 * tol_scale * se);
  CHECK_NEAR(Et1, Et2, 1e-12 * tol_scale * se);
  if (cw * cw < 0.01) ++near_wrap;
  CHECK_STATUS(rnk_bendtwist_grad(c->q, c->ref, &c->bp, &c->tp, &E1, g1), RNK_OK);
  CHECK_STATUS(rnk_jet_bendtwist_grad(c->q, c->ref, &c->bp, &c->tp, &E2, g2), RNK_OK);
  CHECK_NEAR(E1, Eb1 + Et1, 1e-14 * se);
  double sg = max_abs(11, g2);
  for (int i = 0; i < 11; ++i) {
    worst_g = fmax(worst_g, fabs(g1[i] - g2[i]) / sg * 1e-12 / tol);
    CHECK_NEAR(g1[i], g2[i], tol * sg);
  }
  CHECK_STATUS(rnk_bendtwist_hess(c->q, c->ref, &c->bp, &c->tp, H1), RNK_OK);
  CHECK_STATUS(rnk_jet_bendtwist_hess(c->q, c->ref, &c->bp, &c->tp, H2), RNK_OK);
  double sh = max_abs(121, H2);
  for (int i = 0; i < 121; ++i) {
    worst_h = fmax(worst_h, fabs(H1[i] - H2[i]) / sh * 1e-12 / tol);
    CHECK_NEAR(H1[i], H2[i], tol * sh);
  }
  for (int i = 0; i < 11; ++i) v[i] = rnd();
  CHECK_STATUS(rnk_bendtwist_hvp(c->q, c->ref, &c->bp, &c->tp, v, Hv1), RNK_OK);
  rnk_block_mv(11, H2, v, Hv2);
  double sv = sh * norm(11, v);
  for (int i = 0; i < 11; ++i) {
    worst_v = fmax(worst_v, fabs(Hv1[i] - Hv2[i]) / sv * 1e-12 / tol);
    CHECK_NEAR(Hv1[i], Hv2[i], tol * sv);
  }
}

static void test_random(void) {
  config c;
  for (int trial = 0; trial < 3000; ++trial) {
    double bend = trial < 1000 ? 0.1 : (trial < 2000 ? 0.4 : 0.7);
    double spread = trial % 3 == 0 ? 0.0 : (trial % 3 == 1 ? 0.3 : 1.0);
    random_config(&c, bend, spread);
    if (trial % 7 == 3) { /* bending only */
      c.tp.beta = 0.0;
    }
    if (trial % 7 == 5) { /* twisting only */
      c.bp.B[0] = c.bp.B[1] = c.bp.B[2] = 0.0;
    }
    if (trial % 11 == 4) { /* a stored twist inconsistent with the frames */
      c.tp.ref_twist += 2.0 * rnd();
    }
    compare(&c);
  }
  printf("closed form vs jets, worst relative differences (scaled by cos^2(dm/2)): E "
         "%.2e, g %.2e, H %.2e, Hv %.2e; %d configurations near the twist wrap\n",
         worst_e, worst_g, worst_h, worst_v, near_wrap);
}

/* Nearly straight, up-to-date stencils (the common case in a solve) and exact
 * rest states. */
static void test_straight(void) {
  config c;
  for (int trial = 0; trial < 200; ++trial) {
    random_config(&c, 1e-6, 0.0);
    c.bp.kbar[0] = c.bp.kbar[1] = 0.0;
    compare(&c);
  }
}

/* Material angles beyond the polynomial sine/cosine range (|theta/2| >
 * RQ_TRIG_MAX) take libm's: still the jets' values, in the stencil kernels
 * and in the whole-rod kernels. */
static void test_big_angles(void) {
  config c;
  for (int trial = 0; trial < 20; ++trial) {
    random_config(&c, 0.3, 0.3);
    c.q[3] = (trial % 2 ? -1.0 : 1.0) * (2.0 * RQ_TRIG_MAX + 1e4 * rnd());
    c.q[7] = c.q[3] + 0.5 * rnd();
    tol_scale = 1.0 + fabs(c.q[3]) * 0x1p-52 / 1e-12;
    compare(&c);
  }
  tol_scale = 1.0;
  /* a rod segment of 3 edges with one big angle: same as its stencils */
  double x[15], g1[15] = {0}, g2[15] = {0}, E[3], Eb, Et;
  rnk_frame ref[3];
  rnk_stretch_param sp[3] = {{1.0, 1.0}, {1.0, 1.0}, {1.0, 1.0}};
  rnk_bend_param bp[2];
  rnk_twist_param tp[2];
  double m[2];
  random_config(&c, 0.3, 0.3);
  memcpy(x, c.q, sizeof c.q);
  for (int k = 0; k < 4; ++k) x[11 + k] = c.q[8 + k % 3] + (k < 3 ? 1.0 : 0.0);
  x[11] = 5.0 * RQ_TRIG_MAX; /* theta^2 (x[12..14] = x_3) */
  x[12] = c.q[8] + 1.0;
  x[13] = c.q[9] + 0.1;
  x[14] = c.q[10];
  ref[0] = c.ref[0];
  ref[1] = c.ref[1];
  ref[2] = c.ref[1];
  bp[0] = bp[1] = c.bp;
  tp[0] = tp[1] = c.tp;
  m[0] = m[1] = c.tp.ref_twist;
  rnk_rod_seg s = {3, x, ref, sp, 0, 0, bp, tp, m};
  int bad[2];
  CHECK_STATUS(rnk_rod_grad(&s, E, g1, bad), RNK_OK);
  for (int k = 1; k < 3; ++k) {
    double g[11];
    rnk_twist_param t = tp[k - 1];
    t.ref_twist = m[k - 1];
    CHECK_STATUS(
        rnk_bendtwist_grad(x + 4 * (k - 1), &ref[k - 1], &bp[k - 1], &t, NULL, g),
        RNK_OK);
    CHECK_STATUS(
        rnk_jet_bendtwist_energy(x + 4 * (k - 1), &ref[k - 1], &bp[k - 1], &t, &Eb, &Et),
        RNK_OK);
    for (int i = 0; i < 11; ++i) g2[4 * (k - 1) + i] += g[i];
  }
  for (int i = 0; i < 15; ++i) CHECK_NEAR(g1[i], g2[i], 1e-13 * (fabs(g2[i]) + 1.0));
}

/* Both implementations flag the same degenerate configurations. */
static void test_degenerate(void) {
  config c;
  random_config(&c, 0.1, 0.0);
  /* zero-length first edge */
  memcpy(c.q + 4, c.q, 3 * sizeof(double));
  compare(&c);
  double Eb, Et;
  CHECK_STATUS(rnk_bendtwist_energy(c.q, c.ref, &c.bp, &c.tp, &Eb, &Et), RNK_DEGENERATE);
  /* fold-back: opposite consecutive tangents */
  double fold[11] = {0, 0, 0, 0.3, 1, 0, 0, -0.2, 0, 0, 1e-300};
  rnk_frame r2[2] = {{{1, 0, 0}, {0, 1, 0}}, {{-1, 0, 0}, {0, 1, 0}}};
  memcpy(c.q, fold, sizeof fold);
  memcpy(c.ref, r2, sizeof r2);
  CHECK_STATUS(rnk_bendtwist_energy(c.q, c.ref, &c.bp, &c.tp, &Eb, &Et), RNK_DEGENERATE);
  compare(&c);
  /* current tangent opposite to the stored one */
  double q[11] = {0, 0, 0, 0, -1, 0, 0, 0, -2, 0.1, 0};
  rnk_frame r3[2] = {{{1, 0, 0}, {0, 1, 0}}, {{1, 0, 0}, {0, 1, 0}}};
  memcpy(c.q, q, sizeof q);
  memcpy(c.ref, r3, sizeof r3);
  CHECK_STATUS(rnk_bendtwist_energy(c.q, c.ref, &c.bp, &c.tp, &Eb, &Et), RNK_DEGENERATE);
  compare(&c);
}

/* ---- whole-rod segments: the sums of the stencil kernels ------------------ */
enum { NE = 150 }; /* crosses the kernels' chunks of 64 edges */

typedef struct rod_case {
  double x[4 * NE + 3];
  rnk_frame ref[NE];
  rnk_stretch_param sp[NE];
  rnk_bend_param bp[NE - 1];
  rnk_twist_param tp[NE - 1];
  double m[NE - 1];
} rod_case;

static void random_rod(rod_case *c) {
  for (int i = 0; i <= NE; ++i) {
    double s = 0.1 * i;
    c->x[4 * i] = cos(s) + 0.02 * rnd();
    c->x[4 * i + 1] = sin(s) + 0.02 * rnd();
    c->x[4 * i + 2] = 0.05 * s + 0.02 * rnd();
    if (i < NE) c->x[4 * i + 3] = 2.0 * rnd();
  }
  for (int j = 0; j < NE; ++j) {
    double *xa = c->x + 4 * j;
    double e[3] = {xa[4] - xa[0], xa[5] - xa[1], xa[6] - xa[2]};
    stale_frame(e, 0.2, &c->ref[j]);
    c->sp[j] = (rnk_stretch_param){100.0 + rnd(), 0.1 * (1.0 + 0.1 * rnd())};
  }
  for (int k = 0; k < NE - 1; ++k) {
    c->bp[k] = (rnk_bend_param){{1.0 + 0.1 * rnd(), 0.1 * rnd(), 2.0 + 0.1 * rnd()},
                                {0.1 * rnd(), 0.1 * rnd()},
                                0.1};
    c->m[k] = stored_twist(&c->ref[k], (int)lround(2.0 * rnd()));
    c->tp[k] = (rnk_twist_param){0.7 + 0.1 * rnd(), 0.05 * rnd(), 0.1, 1e9};
  }
}

static rnk_rod_seg rod_seg(const rod_case *c, int lo, int hi) {
  rnk_rod_seg s = {NE, c->x, c->ref, c->sp, lo, hi, c->bp, c->tp, c->m};
  return s;
}

static void test_rod(void) {
  static rod_case c;
  enum { N = 4 * NE + 3 };
  static double g1[N], g2[N], v[N], hv1[N], hv2[N], band[N * RNK_BAND], dense[N * N];
  for (int trial = 0; trial < 4; ++trial) {
    random_rod(&c);
    int lo = trial == 1 ? 1 : 0, hi = trial == 2 ? NE - 1 : NE;
    rnk_rod_seg s = rod_seg(&c, lo, hi);
    double E1[3], E2[3] = {0, 0, 0}, Eg[3];
    int bad[2];
    memset(g1, 0, sizeof g1);
    memset(g2, 0, sizeof g2);
    memset(hv1, 0, sizeof hv1);
    memset(hv2, 0, sizeof hv2);
    memset(band, 0, sizeof band);
    memset(dense, 0, sizeof dense);
    for (int i = 0; i < N; ++i) v[i] = rnd();
    CHECK_STATUS(rnk_rod_energy(&s, E1, bad), RNK_OK);
    CHECK_STATUS(rnk_rod_grad(&s, Eg, g1, bad), RNK_OK);
    CHECK_STATUS(rnk_rod_hvp(&s, v, hv1, bad), RNK_OK);
    CHECK_STATUS(rnk_rod_hess(&s, band, bad), RNK_OK);
    /* stencil by stencil */
    for (int j = lo; j < hi; ++j) {
      double E, g[7], H[49];
      CHECK_STATUS(rnk_stretch_grad(c.x + 4 * j, &c.sp[j], &E, g), RNK_OK);
      CHECK_STATUS(rnk_stretch_hess(c.x + 4 * j, &c.sp[j], H), RNK_OK);
      E2[0] += E;
      for (int a = 0; a < 7; ++a) {
        g2[4 * j + a] += g[a];
        for (int b = 0; b < 7; ++b) dense[(4 * j + a) * N + 4 * j + b] += H[a * 7 + b];
      }
    }
    for (int k = 1; k < NE; ++k) {
      double Eb, Et, g[11], H[121];
      const double *q = c.x + 4 * (k - 1);
      rnk_twist_param tp = c.tp[k - 1];
      tp.ref_twist = c.m[k - 1];
      CHECK_STATUS(rnk_bendtwist_energy(q, &c.ref[k - 1], &c.bp[k - 1], &tp, &Eb, &Et),
                   RNK_OK);
      CHECK_STATUS(rnk_bendtwist_grad(q, &c.ref[k - 1], &c.bp[k - 1], &tp, NULL, g),
                   RNK_OK);
      CHECK_STATUS(rnk_bendtwist_hess(q, &c.ref[k - 1], &c.bp[k - 1], &tp, H), RNK_OK);
      E2[1] += Eb;
      E2[2] += Et;
      for (int a = 0; a < 11; ++a) {
        g2[4 * (k - 1) + a] += g[a];
        for (int b = 0; b < 11; ++b)
          dense[(4 * (k - 1) + a) * N + 4 * (k - 1) + b] += H[a * 11 + b];
      }
    }
    for (int t = 0; t < 3; ++t) {
      CHECK_NEAR(E1[t], E2[t], 1e-13 * fabs(E2[t]));
      CHECK_NEAR(Eg[t], E2[t], 1e-13 * fabs(E2[t]));
    }
    double sg = max_abs(N, g2), sh = max_abs(N * N, dense);
    rnk_block_mv(N, dense, v, hv2);
    for (int a = 0; a < N; ++a) {
      CHECK_NEAR(g1[a], g2[a], 1e-13 * sg);
      CHECK_NEAR(hv1[a], hv2[a], 1e-12 * sh * norm(N, v) / sqrt((double)N));
      for (int b = 0; b < N; ++b) {
        double hb = abs(a - b) <= RNK_BAND_HALF
                        ? band[a * RNK_BAND + b - a + RNK_BAND_HALF]
                        : 0.0;
        CHECK_NEAR(hb, dense[a * N + b], 1e-13 * sh);
      }
    }
  }
  /* degenerate stencils are reported, the first of each kind */
  random_rod(&c);
  memcpy(c.x + 4 * 100, c.x + 4 * 99, 3 * sizeof(double)); /* edge 99 of zero length */
  rnk_rod_seg s = rod_seg(&c, 0, NE);
  double E[3];
  int bad[2];
  CHECK_STATUS(rnk_rod_energy(&s, E, bad), RNK_DEGENERATE);
  CHECK(bad[0] == 99 && bad[1] == 99);
  memset(g1, 0, sizeof g1);
  CHECK_STATUS(rnk_rod_grad(&s, E, g1, bad), RNK_DEGENERATE);
  CHECK(bad[0] == 99 && bad[1] == 99);
  random_rod(&c);
  for (int k = 0; k < 3; ++k) /* edge 120 against its stored tangent */
    c.x[4 * 121 + k] = c.x[4 * 120 + k] - (c.ref[120].t[k]);
  s = rod_seg(&c, 0, NE);
  CHECK_STATUS(rnk_rod_hvp(&s, v, hv1, bad), RNK_DEGENERATE);
  CHECK(bad[0] == -1 && bad[1] == 120);
}

/* The branch-free sine, cosine and arctangent of the vectorised loops
 * against libm: a few units in the last place over the whole range used
 * (|x| <= RQ_TRIG_MAX for the sine and cosine), signs and quadrants of atan2
 * included. */
static void test_math(void) {
  double worst_sc = 0.0, worst_at = 0.0;
  for (int i = 0; i < 200000; ++i) {
    double u = rnd(), x;
    if (i % 4 == 0)
      x = 4.0 * u; /* |x| < 4 */
    else if (i % 4 == 1)
      x = 40.0 * u;
    else if (i % 4 == 2)
      x = RQ_TRIG_MAX * u;
    else
      x = (i % 8 - 4) * (M_PI / 4) * (1.0 + 1e-15 * u); /* near quadrant edges */
    double s, c;
    rq_sincos(x, &s, &c);
    /* error relative to 1 (the functions' scale) in units of 2^-52 */
    worst_sc = fmax(worst_sc, fmax(fabs(s - sin(x)), fabs(c - cos(x))) / 0x1p-52);
    double y = rnd() * pow(10.0, 6.0 * rnd()), z = rnd() * pow(10.0, 6.0 * rnd());
    double a = rq_atan2(y, z), b = atan2(y, z);
    worst_at = fmax(worst_at, fabs(a - b) / (fabs(b) * 0x1p-52 + 1e-300));
  }
  CHECK(worst_sc <= 4.0);
  CHECK(worst_at <= 4.0);
  CHECK(rq_atan2(0.0, 1.0) == 0.0);
  CHECK_NEAR(rq_atan2(1.0, 0.0), M_PI / 2, 4e-16);
  CHECK_NEAR(rq_atan2(0.0, -1.0), M_PI, 8e-16);
  CHECK_NEAR(rq_atan2(-1.0, -1.0), -0.75 * M_PI, 8e-16);
  printf("rq_sincos: worst error %.2f ulp(1); rq_atan2: %.2f ulp\n", worst_sc, worst_at);
}

/* Signed area of the spherical triangle (a, b, c). */
static double tri_area(const double a[3], const double b[3], const double c[3]) {
  double bc[3];
  rn_test_cross3(b, c, bc);
  double ab = a[0] * b[0] + a[1] * b[1] + a[2] * b[2],
         bcd = b[0] * c[0] + b[1] * c[1] + b[2] * c[2],
         ca = c[0] * a[0] + c[1] * a[1] + c[2] * a[2];
  return 2.0 * atan2(a[0] * bc[0] + a[1] * bc[1] + a[2] * bc[2], 1.0 + ab + bcd + ca);
}

/* The continued reference twist by an independent formula: with the stored
 * twist equal to the stored frames' own, the holonomy of parallel transport
 * gives m - m_stored = -(signed area of the spherical quadrilateral
 * (t_hat0, t0, t1, t_hat1)). */
static void test_holonomy(void) {
  config c;
  double worst = 0.0;
  for (int trial = 0; trial < 500; ++trial) {
    random_config(&c, 0.5, 0.4);
    double m, t[2][3];
    for (int s = 0; s < 2; ++s) {
      for (int k = 0; k < 3; ++k) t[s][k] = c.q[4 * s + 4 + k] - c.q[4 * s + k];
      rn_test_normalize3(t[s]);
    }
    CHECK_STATUS(rnk_reference_twist(c.q, c.ref, c.tp.ref_twist, &m), RNK_OK);
    double area =
        tri_area(c.ref[0].t, t[0], t[1]) + tri_area(c.ref[0].t, t[1], c.ref[1].t);
    double d = remainder(m - c.tp.ref_twist + area, 2.0 * M_PI);
    worst = fmax(worst, fabs(d));
    CHECK_NEAR(d, 0.0, 1e-13);
  }
  printf("reference twist vs holonomy: worst difference %.2e\n", worst);
}

int main(void) {
  test_math();
  test_random();
  test_straight();
  test_degenerate();
  test_big_angles();
  test_holonomy();
  test_rod();
  return rn_test_finish("kernels_closed_form");
}

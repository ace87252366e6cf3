/* kernels_joint_closed.c - the closed-form joint kernels (jointq.c) against
 * the jet oracle (rnk_jet_joint_*, generic second-order forward
 * differentiation of the same composition) at many random configurations:
 * valence 1 to 8 and 12, rigid and elastic joints, reference rotations and
 * rotation DOFs up to |w| ~ 3.5 (across the series/closed-form switch at
 * |w| = 2), stale reference frames, stored twists continued over several
 * turns, rest curvature and twist, anisotropic bending, couples on the
 * joint rotation.  Energy, gradient, Hessian block, HVP (never forming the
 * block), twists and couple angle must agree to 1e-12 relative; both must
 * flag the same degenerate configurations.  Also the single end stencil
 * (rnk_joint_end_*) against rnk_jet_joint_end_*, and the couple on an edge
 * (rnk_moment_*) against rnk_jet_moment_*.  The couple fixed in space on the
 * joint rotation (rnk_joint_couple_fixed_force) against central differences:
 * its force against M . omega (omega from the rotation rnk_joint_rotation),
 * its Jacobian against the force, h-sweeps of order 2. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rnk.h"
#include "rnk_couple.h"
#include "testutil.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

enum { VMAX = 12, NMAX = 6 + 4 * VMAX };

static uint64_t rng = 0x10147ULL;
static double rnd(void) { return rn_test_rand(&rng); }

static double max_abs(int n, const double *v) {
  double m = 0;
  for (int i = 0; i < n; ++i) m = fmax(m, fabs(v[i]));
  return m;
}

static void mat_vec(const double R[9], const double v[3], double out[3]) {
  double t[3];
  for (int i = 0; i < 3; ++i)
    t[i] = R[3 * i] * v[0] + R[3 * i + 1] * v[1] + R[3 * i + 2] * v[2];
  memcpy(out, t, sizeof t);
}

static void random_unit(double v[3]) {
  for (int k = 0; k < 3; ++k) v[k] = rnd();
  rn_test_normalize3(v);
}

typedef struct star {
  rnk_joint j;
  rnk_joint_end ends[VMAX];
  rnk_frame refs[VMAX];
  double q[NMAX];
  int n;
} star;

/* A joint of valence v with rods along random directions, perturbed by amp;
 * rigid joints get a reference rotation Qhat = exp(u), |u| <= umax, and the
 * rotation DOFs near -u (so the connection edges stay near the terminal
 * edges); reference frames off by `spread`; a couple when `couple`. */
static void make_star(star *s, int v, int rigid, double amp, double umax, double spread,
                      int couple) {
  memset(s, 0, sizeof *s);
  s->j.rigid = rigid;
  s->j.valence = v;
  s->j.ends = s->ends;
  s->j.refs = s->refs;
  double u[3];
  random_unit(u);
  for (int k = 0; k < 3; ++k) u[k] *= umax * (0.5 + 0.5 * fabs(rnd()));
  rnk_rotation_exp(u, s->j.Qhat);
  int off = rigid ? 6 : 3;
  for (int k = 0; k < v; ++k) {
    double dir[3], a[3], t[3], xn[3];
    random_unit(dir);
    random_unit(a);
    int side = (k + v) % 2;
    double len = 0.5 + 0.3 * fabs(rnd());
    for (int c = 0; c < 3; ++c) {
      xn[c] = len * dir[c];
      t[c] = side == 0 ? -dir[c] : dir[c];
    }
    double d = a[0] * t[0] + a[1] * t[1] + a[2] * t[2];
    for (int c = 0; c < 3; ++c) a[c] -= d * t[c];
    rn_test_normalize3(a);
    rnk_joint_end *e = &s->ends[k];
    e->side = side;
    memcpy(e->cbar, t, sizeof t);
    memcpy(e->cbar + 3, a, sizeof a);
    rn_test_cross3(t, a, e->cbar + 6);
    double B11 = 1 + fabs(rnd()), B22 = 1 + 2 * fabs(rnd()), B12 = 0.3 * rnd();
    e->bend = (rnk_bend_param){
        .B = {B11, B12, B22}, .kbar = {0.1 * rnd(), 0.1 * rnd()}, .vlen = 0.5 * len};
    e->twist = (rnk_twist_param){
        .beta = 0.8 + 0.2 * rnd(), .taubar = 0.1 * rnd(), .vlen = 0.5 * len};
    memcpy(s->refs[k].t, t, sizeof t);
    memcpy(s->refs[k].a1, a, sizeof a);
    for (int c = 0; c < 3; ++c) s->q[off + 4 * k + c] = xn[c];
    s->q[off + 4 * k + 3] = 3.0 * rnd(); /* material angles */
  }
  s->n = (int)rnk_joint_stencil_size(&s->j);
  for (int i = 0; i < s->n; ++i) s->q[i] += amp * rnd();
  if (rigid)
    for (int c = 0; c < 3; ++c) s->q[3 + c] += -u[c];
  for (int k = 0; k < v; ++k) { /* stale reference frames */
    double *a = s->refs[k].a1, *t = s->refs[k].t;
    for (int c = 0; c < 3; ++c) t[c] += spread * rnd();
    rn_test_normalize3(t);
    for (int c = 0; c < 3; ++c) a[c] += 0.3 * rnd();
    double d = a[0] * t[0] + a[1] * t[1] + a[2] * t[2];
    for (int c = 0; c < 3; ++c) a[c] -= d * t[c];
    rn_test_normalize3(a);
  }
  for (int i = 0; i < 9; ++i) s->j.f0[i] = (i % 4 == 0);
  if (couple) {
    double m[3], p[3], w[3];
    random_unit(m);
    random_unit(p);
    double d = m[0] * p[0] + m[1] * p[1] + m[2] * p[2];
    for (int c = 0; c < 3; ++c) p[c] -= d * m[c];
    rn_test_normalize3(p);
    for (int c = 0; c < 3; ++c) {
      s->j.M[c] = (0.5 + fabs(rnd())) * m[c];
      s->j.couple_p[c] = p[c];
      w[c] = 0.3 * rnd();
    }
    rnk_rotation_exp(w, s->j.f0); /* the rotation at the last update */
    s->j.angle0 = 2.0 * rnd();
  }
  /* stored twists: the current ones plus whole turns plus a little */
  double tw[VMAX];
  if (rnk_jet_joint_twists(s->q, &s->j, tw) == RNK_OK)
    for (int k = 0; k < v; ++k)
      s->ends[k].twist.ref_twist = tw[k] + 2.0 * M_PI * (k % 3 - 1) + 0.3 * rnd();
}

/* Condition number of the elastic fit's M = R U (largest over smallest
 * eigenvalue of U): the oracle's Newton iteration for the polar factor
 * inverts M, so its round-off grows with it (near the singular fits that
 * both refuse); the closed forms divide only by K = tr(U) I - U.  At one
 * configuration with cond(M) = 731 where they differed by 1.3e-11, sixth-
 * order central differences of the closed-form gradient agreed with the
 * closed-form Hessian to 3e-13 and with the jets' to 1.3e-11. */
static double fit_condition(const star *s) {
  double M[9] = {0}, R[9], U[9];
  for (int k = 0; k < s->j.valence; ++k) {
    int base = 3 + 4 * k;
    double e[3], F[9], sg = s->ends[k].side == 0 ? 1.0 : -1.0;
    for (int c = 0; c < 3; ++c) e[c] = sg * (s->q[c] - s->q[base + c]);
    if (rnk_material_frame(e, &s->refs[k], s->q[base + 3], F, F + 3, F + 6))
      return INFINITY;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int c = 0; c < 3; ++c)
          M[3 * a + b] += F[3 * c + a] * s->ends[k].cbar[3 * c + b];
  }
  if (rnk_polar(M, R)) return INFINITY;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      U[3 * a + b] = R[a] * M[b] + R[3 + a] * M[3 + b] + R[6 + a] * M[6 + b];
  /* eigenvalues of the symmetric U by Jacobi sweeps */
  double A[3][3];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) A[a][b] = 0.5 * (U[3 * a + b] + U[3 * b + a]);
  for (int sweep = 0; sweep < 30; ++sweep)
    for (int p = 0; p < 2; ++p)
      for (int r = p + 1; r < 3; ++r) {
        if (fabs(A[p][r]) < 1e-300) continue;
        double th = 0.5 * atan2(2 * A[p][r], A[r][r] - A[p][p]), c = cos(th),
               sn = sin(th);
        for (int k = 0; k < 3; ++k) {
          double x = A[k][p], y = A[k][r];
          A[k][p] = c * x - sn * y;
          A[k][r] = sn * x + c * y;
        }
        for (int k = 0; k < 3; ++k) {
          double x = A[p][k], y = A[r][k];
          A[p][k] = c * x - sn * y;
          A[r][k] = sn * x + c * y;
        }
      }
  double u0 = A[0][0], u1 = A[1][1], u2 = A[2][2];
  return fmax(u0, fmax(u1, u2)) / fmin(u0, fmin(u1, u2));
}

static double worst_e, worst_g, worst_h, worst_v, worst_t;
static int ncompared, ndegenerate, nscaled, nfold;

static void compare(const star *s) {
  int n = s->n;
  double *wj = malloc(sizeof(double) * rnk_jet_joint_work_size(&s->j));
  double *wc = malloc(sizeof(double) * rnk_joint_work_size(&s->j));
  double E1, E2, E3, g1[NMAX], g2[NMAX], v[NMAX], Hv1[NMAX], Hv2[NMAX];
  double *H1 = malloc(sizeof(double) * n * n), *H2 = malloc(sizeof(double) * n * n);
  int s1 = rnk_joint_energy(s->q, &s->j, wc, &E1);
  int s2 = rnk_jet_joint_energy(s->q, &s->j, wj, &E2);
  CHECK_STATUS(s1, s2);
  if (s1 || s2) {
    ++ndegenerate;
    goto done;
  }
  ++ncompared;
  /* tolerance: 1e-12 relative, times cond(M) / 10 beyond 10 (elastic) */
  double tol = 1e-12;
  if (!s->j.rigid) {
    double cm = fit_condition(s);
    if (cm > 10.0) {
      tol *= cm / 10.0;
      ++nscaled;
    }
  }
  /* near a fold (rigid: connection tangent R cbar_t almost opposite the
   * terminal tangent, chi = 1 + t_T . t_C -> 0) the jets form chi from unit
   * tangents, absolute error ~ eps, so relative eps / chi, while the closed
   * forms take cos(phi / 2) from a quaternion product (relative error ~ eps /
   * sqrt(chi), the conditioning of the energy itself): the tolerance is the
   * oracle's, 1e-12 or 32 eps / chi.  (Measured at bending angle pi - eps
   * on a valence-1 rigid joint, the spread of the energy over 64 rigid
   * rotations of the whole configuration, relative: eps = 1e-2: closed forms
   * 4e-13, jets 2.7e-11; 1e-3: 2.6e-12, 3.1e-9; 1e-4: 2.3e-11, 2.2e-7.) */
  if (s->j.rigid) {
    double R[9], Q[9], chi = 2.0;
    rnk_rotation_exp(s->q + 3, R);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        Q[3 * a + b] = R[3 * a] * s->j.Qhat[b] + R[3 * a + 1] * s->j.Qhat[3 + b] +
                       R[3 * a + 2] * s->j.Qhat[6 + b];
    for (int k = 0; k < s->j.valence; ++k) {
      double tc[3], tt[3], sg = s->ends[k].side == 0 ? 1.0 : -1.0;
      mat_vec(Q, s->ends[k].cbar, tc);
      for (int c = 0; c < 3; ++c) tt[c] = sg * (s->q[c] - s->q[6 + 4 * k + c]);
      rn_test_normalize3(tt);
      chi = fmin(chi, 1.0 + tt[0] * tc[0] + tt[1] * tc[1] + tt[2] * tc[2]);
    }
    if (32.0 * DBL_EPSILON / chi > tol) {
      tol = 32.0 * DBL_EPSILON / chi;
      ++nfold;
    }
  }
  double se = fabs(E2) + 1e-300;
  worst_e = fmax(worst_e, fabs(E1 - E2) / se * 1e-12 / tol);
  CHECK_NEAR(E1, E2, tol * se);
  CHECK_STATUS(rnk_joint_grad(s->q, &s->j, wc, &E3, g1), RNK_OK);
  CHECK_NEAR(E3, E1, 1e-14 * se);
  CHECK_STATUS(rnk_jet_joint_grad(s->q, &s->j, wj, &E2, g2), RNK_OK);
  /* scales: the values, at least the stiffness (a valence-1 elastic joint
   * follows its rod end: constant energy, zero derivatives) */
  double s0 = 0.0;
  for (int k = 0; k < s->j.valence; ++k) {
    const rnk_joint_end *e = &s->j.ends[k];
    s0 = fmax(s0, (e->bend.B[0] + e->bend.B[2] + e->twist.beta) / e->bend.vlen);
  }
  double sg = fmax(max_abs(n, g2), s0);
  for (int i = 0; i < n; ++i) {
    worst_g = fmax(worst_g, fabs(g1[i] - g2[i]) / sg * 1e-12 / tol);
    CHECK_NEAR(g1[i], g2[i], tol * sg);
  }
  CHECK_STATUS(rnk_joint_hess(s->q, &s->j, wc, H1), RNK_OK);
  CHECK_STATUS(rnk_jet_joint_hess(s->q, &s->j, wj, H2), RNK_OK);
  double sh = fmax(max_abs(n * n, H2), s0);
  for (int i = 0; i < n * n; ++i) {
    worst_h = fmax(worst_h, fabs(H1[i] - H2[i]) / sh * 1e-12 / tol);
    CHECK_NEAR(H1[i], H2[i], tol * sh);
  }
  for (int i = 0; i < n; ++i) v[i] = rnd();
  CHECK_STATUS(rnk_joint_hvp(s->q, &s->j, wc, v, Hv1), RNK_OK);
  rnk_block_mv(n, H2, v, Hv2);
  double sv = sh * max_abs(n, v) * n;
  for (int i = 0; i < n; ++i) {
    worst_v = fmax(worst_v, fabs(Hv1[i] - Hv2[i]) / sv * 1e-12 / tol);
    CHECK_NEAR(Hv1[i], Hv2[i], tol * sv);
  }
  double t1[VMAX], t2[VMAX], a1, a2;
  CHECK_STATUS(rnk_joint_twists(s->q, &s->j, t1), RNK_OK);
  CHECK_STATUS(rnk_jet_joint_twists(s->q, &s->j, t2), RNK_OK);
  for (int k = 0; k < s->j.valence; ++k) {
    worst_t = fmax(worst_t, fabs(t1[k] - t2[k]) / (1.0 + fabs(t2[k])));
    CHECK_NEAR(t1[k], t2[k], tol * (1.0 + fabs(t2[k])));
  }
  CHECK_STATUS(rnk_joint_couple_angle(s->q, &s->j, &a1), RNK_OK);
  CHECK_STATUS(rnk_jet_joint_couple_angle(s->q, &s->j, &a2), RNK_OK);
  CHECK_NEAR(a1, a2, tol * (1.0 + fabs(a2)));
done:
  free(wj);
  free(wc);
  free(H1);
  free(H2);
}

static void test_random(void) {
  static const int valences[9] = {1, 2, 3, 4, 5, 6, 7, 8, 12};
  star s;
  printf("model    valence  worst relative difference: E, grad, Hess, HVP\n");
  for (int rigid = 0; rigid <= 1; ++rigid)
    for (int iv = 0; iv < 9; ++iv) {
      worst_e = worst_g = worst_h = worst_v = 0.0;
      int v = valences[iv];
      for (int trial = 0; trial < 60; ++trial) {
        double amp = trial % 3 == 0 ? 0.05 : 0.2;
        double umax = rigid ? (trial % 4) * 1.2 : 0.0;
        double spread = trial % 2 ? 0.4 : 0.0;
        make_star(&s, v, rigid, amp, umax, spread, trial % 3 != 1);
        compare(&s);
      }
      printf("%-8s %5d    %.2e    %.2e    %.2e    %.2e\n", rigid ? "rigid" : "elastic", v,
             worst_e, worst_g, worst_h, worst_v);
    }
  printf("(errors scaled to the 1e-12 tolerance; %d elastic fits with cond(M) > 10 had\n"
         " the tolerance times cond(M) / 10)\n",
         nscaled);
  printf("twists: worst %.2e; %d configurations compared, %d degenerate in both\n",
         worst_t, ncompared, ndegenerate);
  CHECK(ncompared > 900);
}

/* Near-degenerate configurations (the degenerate ones are refused by both):
 * a rigid joint turned until end 0's connection edge almost folds back onto
 * its terminal edge (bending angle pi - eps), terminal edges much shorter
 * than the others, rotation vectors on either side of the series/closed-form
 * switch at |w| = 2 and near a whole turn |w| = 2 pi.  Same 1e-12 relative
 * tolerance (compare() scales by the largest entry). */
static void test_near_degenerate(void) {
  star s;
  int before = ncompared, refused = ndegenerate;
  worst_e = worst_g = worst_h = worst_v = 0.0;
  for (int trial = 0; trial < 24; ++trial) {
    /* fold: the rotation DOFs exp(w) Qhat turn end 0's connection tangent
     * by pi - eps about an axis normal to it */
    double eps = pow(10.0, -1.0 - (trial % 4));
    make_star(&s, 1 + trial % 4, 1, 0.0, 0.0, 0.0, trial % 2);
    double ax[3], *t = s.ends[0].cbar;
    random_unit(ax);
    double d = ax[0] * t[0] + ax[1] * t[1] + ax[2] * t[2];
    for (int c = 0; c < 3; ++c) ax[c] -= d * t[c];
    rn_test_normalize3(ax);
    for (int c = 0; c < 3; ++c) s.q[3 + c] = (M_PI - eps) * ax[c];
    compare(&s);
  }
  printf("near fold (pi - 1e-1 .. 1e-4): %.2e %.2e %.2e %.2e\n", worst_e, worst_g,
         worst_h, worst_v);
  worst_e = worst_g = worst_h = worst_v = 0.0;
  for (int trial = 0; trial < 48; ++trial) {
    /* short terminal edge of end 0: |x_n - x_J| down to 1e-6 */
    int rigid = trial % 2;
    double len = pow(10.0, -2.0 - (trial / 2) % 5);
    make_star(&s, 2 + trial % 5, rigid, 0.01, rigid ? 1.0 : 0.0, 0.2, trial % 3 == 0);
    int off = rigid ? 6 : 3;
    double dir[3];
    for (int c = 0; c < 3; ++c) dir[c] = s.q[off + c] - s.q[c];
    rn_test_normalize3(dir);
    for (int c = 0; c < 3; ++c) s.q[off + c] = s.q[c] + len * dir[c];
    compare(&s);
  }
  printf("short terminal edge (1e-2 .. 1e-6): %.2e %.2e %.2e %.2e\n", worst_e, worst_g,
         worst_h, worst_v);
  worst_e = worst_g = worst_h = worst_v = 0.0;
  for (int trial = 0; trial < 40; ++trial) {
    /* |w| = 2 (1 +- 1e-9 .. 1e-3) and |w| = 2 pi (1 +- 1e-3) */
    static const double rel[5] = {1e-9, 1e-7, 1e-5, 1e-3, 0.0};
    double r = trial < 30 ? 2.0 * (1.0 + (trial % 2 ? 1.0 : -1.0) * rel[(trial / 2) % 5])
                          : 2.0 * M_PI * (1.0 + (trial % 2 ? 1e-3 : -1e-3));
    make_star(&s, 1 + trial % 6, 1, 0.05, 0.0, 0.3, trial % 3 != 0);
    double u[3];
    random_unit(u);
    for (int c = 0; c < 3; ++c) s.q[3 + c] = r * u[c];
    /* the reference rotation undoes most of it */
    double mu[3] = {-r * u[0], -r * u[1], -r * u[2]};
    rnk_rotation_exp(mu, s.j.Qhat);
    compare(&s);
  }
  printf("|w| near 2 and 2 pi: %.2e %.2e %.2e %.2e\n", worst_e, worst_g, worst_h,
         worst_v);
  printf("near-degenerate: %d compared, %d refused by both, %d with the tolerance\n"
         " 32 eps / chi of the oracle near the fold\n",
         ncompared - before, ndegenerate - refused, nfold);
  CHECK(ncompared - before > 100);
}

/* Degenerate configurations: both implementations must refuse them. */
static void test_degenerate(void) {
  star s;
  make_star(&s, 3, 1, 0.0, 0.0, 0.0, 0);
  int off = 6;
  /* x_n of end 0 at the joint: zero-length terminal edge */
  star z = s;
  for (int c = 0; c < 3; ++c) z.q[off + c] = z.q[c];
  double E, *w = malloc(sizeof(double) * rnk_jet_joint_work_size(&z.j));
  CHECK_STATUS(rnk_joint_energy(z.q, &z.j, w, &E), RNK_DEGENERATE);
  CHECK_STATUS(rnk_jet_joint_energy(z.q, &z.j, w, &E), RNK_DEGENERATE);
  /* a half turn of the joint about an axis normal to end 0's tangent folds
   * its connection edge back onto the terminal edge */
  star f = s;
  double ax[3], *t = f.ends[0].cbar;
  random_unit(ax);
  double d = ax[0] * t[0] + ax[1] * t[1] + ax[2] * t[2];
  for (int c = 0; c < 3; ++c) ax[c] -= d * t[c];
  rn_test_normalize3(ax);
  for (int c = 0; c < 3; ++c) f.q[3 + c] = M_PI * ax[c];
  CHECK_STATUS(rnk_joint_energy(f.q, &f.j, w, &E), RNK_DEGENERATE);
  CHECK_STATUS(rnk_jet_joint_energy(f.q, &f.j, w, &E), RNK_DEGENERATE);
  /* elastic: all ends on one line with parallel frames is fine, but a fit
   * of frames that cancel (M singular) is not */
  star e;
  make_star(&e, 2, 0, 0.0, 0.0, 0.0, 0);
  /* end 1's rest frame turned by pi about its tangent's normal: M = F0 Fb0^T
   * + F1 Fb1^T with F1 Fb1^T = -F0 Fb0^T on a plane */
  e.ends[1] = e.ends[0];
  e.refs[1] = e.refs[0];
  for (int c = 0; c < 4; ++c) e.q[3 + 4 + c] = e.q[3 + c];
  for (int c = 3; c < 9; ++c) e.ends[1].cbar[c] = -e.ends[0].cbar[c];
  int s1 = rnk_joint_energy(e.q, &e.j, w, &E),
      s2 = rnk_jet_joint_energy(e.q, &e.j, w, &E);
  CHECK_STATUS(s1, RNK_DEGENERATE);
  CHECK_STATUS(s2, RNK_DEGENERATE);
  free(w);
}

/* The single end stencil q[10] = (x_n, theta, x_J, w). */
static void test_end_stencil(void) {
  double worst = 0.0;
  for (int trial = 0; trial < 400; ++trial) {
    star s;
    make_star(&s, 1, 1, 0.2, (trial % 4) * 1.2, trial % 2 ? 0.4 : 0.0, 0);
    rnk_joint_end_param p;
    double q[10];
    memset(&p, 0, sizeof p);
    for (int vv = 0; vv < 3; ++vv)
      mat_vec(s.j.Qhat, s.ends[0].cbar + 3 * vv, p.c + 3 * vv);
    p.side = s.ends[0].side;
    p.bend = s.ends[0].bend;
    p.twist = s.ends[0].twist;
    for (int c = 0; c < 3; ++c) {
      q[c] = s.q[6 + c];
      q[4 + c] = s.q[c];
      q[7 + c] = s.q[3 + c];
    }
    q[3] = s.q[9];
    double E1, E2, g1[10], g2[10], H1[100], H2[100], v[10], Hv1[10], Hv2[10];
    double k1[2], k2[2], tw1, tw2;
    int st1 = rnk_joint_end_energy(q, &s.refs[0], &p, &E1);
    int st2 = rnk_jet_joint_end_energy(q, &s.refs[0], &p, &E2);
    CHECK_STATUS(st1, st2);
    if (st1) continue;
    CHECK_NEAR(E1, E2, 1e-12 * fabs(E2));
    CHECK_STATUS(rnk_joint_end_grad(q, &s.refs[0], &p, &E1, g1), RNK_OK);
    CHECK_STATUS(rnk_jet_joint_end_grad(q, &s.refs[0], &p, &E2, g2), RNK_OK);
    CHECK_STATUS(rnk_joint_end_hess(q, &s.refs[0], &p, H1), RNK_OK);
    CHECK_STATUS(rnk_jet_joint_end_hess(q, &s.refs[0], &p, H2), RNK_OK);
    for (int i = 0; i < 10; ++i) v[i] = rnd();
    CHECK_STATUS(rnk_joint_end_hvp(q, &s.refs[0], &p, v, Hv1), RNK_OK);
    CHECK_STATUS(rnk_jet_joint_end_hvp(q, &s.refs[0], &p, v, Hv2), RNK_OK);
    double sg = max_abs(10, g2), sh = max_abs(100, H2), sv = max_abs(10, Hv2);
    for (int i = 0; i < 10; ++i) {
      CHECK_NEAR(g1[i], g2[i], 1e-12 * sg);
      CHECK_NEAR(Hv1[i], Hv2[i], 1e-11 * sv);
      worst = fmax(worst, fabs(g1[i] - g2[i]) / sg);
    }
    for (int i = 0; i < 100; ++i) {
      CHECK_NEAR(H1[i], H2[i], 1e-12 * sh);
      worst = fmax(worst, fabs(H1[i] - H2[i]) / sh);
    }
    CHECK_STATUS(rnk_joint_end_strains(q, &s.refs[0], &p, k1, &tw1), RNK_OK);
    CHECK_STATUS(rnk_jet_joint_end_strains(q, &s.refs[0], &p, k2, &tw2), RNK_OK);
    CHECK_NEAR(k1[0], k2[0], 1e-12 * (1 + fabs(k2[0])));
    CHECK_NEAR(k1[1], k2[1], 1e-12 * (1 + fabs(k2[1])));
    CHECK_NEAR(tw1, tw2, 1e-12 * (1 + fabs(tw2)));
  }
  printf("end stencil: worst relative gradient/Hessian difference %.2e\n", worst);
}

/* The couple on an edge's material frame, edge stencil q[7]. */
static void test_moment(void) {
  double worst = 0.0;
  int compared = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    double q[7], e[3], t[3], a[3];
    rnk_frame ref;
    rnk_moment_param p;
    memset(&p, 0, sizeof p);
    random_unit(e);
    for (int k = 0; k < 3; ++k) {
      q[k] = rnd();
      q[4 + k] = q[k] + (0.5 + 0.5 * fabs(rnd())) * e[k];
    }
    q[3] = trial % 5 == 0 ? 40.0 * rnd() : 3.0 * rnd();
    for (int k = 0; k < 3; ++k) t[k] = e[k] + (trial % 2 ? 0.5 : 0.0) * rnd();
    rn_test_normalize3(t);
    random_unit(a);
    double d = a[0] * t[0] + a[1] * t[1] + a[2] * t[2];
    for (int k = 0; k < 3; ++k) a[k] -= d * t[k];
    rn_test_normalize3(a);
    memcpy(ref.t, t, sizeof t);
    memcpy(ref.a1, a, sizeof a);
    /* the frame at the last update: the current one turned a little */
    double th0 = q[3] + 0.4 * rnd();
    CHECK_STATUS(rnk_material_frame(e, &ref, th0, p.f0, p.f0 + 3, p.f0 + 6), RNK_OK);
    for (int k = 0; k < 3; ++k) {
      p.M[k] = trial % 17 == 0 ? 0.0 : 2.0 * rnd();
      p.b[k] = rnd();
    }
    p.angle0 = 3.0 * rnd();
    double E1, E2, g1[7], g2[7], H1[49], H2[49], v[7], Hv1[7], Hv2[7], a1, a2;
    int s1 = rnk_moment_energy(q, &ref, &p, &E1),
        s2 = rnk_jet_moment_energy(q, &ref, &p, &E2);
    CHECK_STATUS(s1, s2);
    if (s1) continue;
    ++compared;
    double m = sqrt(p.M[0] * p.M[0] + p.M[1] * p.M[1] + p.M[2] * p.M[2]) + 1e-300;
    CHECK_NEAR(E1, E2, 1e-12 * (fabs(E2) + m));
    CHECK_STATUS(rnk_moment_angle(q, &ref, &p, &a1), RNK_OK);
    CHECK_STATUS(rnk_jet_moment_angle(q, &ref, &p, &a2), RNK_OK);
    CHECK_NEAR(a1, a2, 1e-12 * (1.0 + fabs(a2)));
    CHECK_STATUS(rnk_moment_grad(q, &ref, &p, &E1, g1), RNK_OK);
    CHECK_STATUS(rnk_jet_moment_grad(q, &ref, &p, &E2, g2), RNK_OK);
    CHECK_STATUS(rnk_moment_hess(q, &ref, &p, H1), RNK_OK);
    CHECK_STATUS(rnk_jet_moment_hess(q, &ref, &p, H2), RNK_OK);
    for (int i = 0; i < 7; ++i) v[i] = rnd();
    CHECK_STATUS(rnk_moment_hvp(q, &ref, &p, v, Hv1), RNK_OK);
    rnk_block_mv(7, H2, v, Hv2);
    double sg = fmax(max_abs(7, g2), m), sh = fmax(max_abs(49, H2), m);
    for (int i = 0; i < 7; ++i) {
      CHECK_NEAR(g1[i], g2[i], 1e-12 * sg);
      CHECK_NEAR(Hv1[i], Hv2[i], 1e-12 * 7 * sh);
      worst = fmax(worst, fabs(g1[i] - g2[i]) / sg);
      worst = fmax(worst, fabs(Hv1[i] - Hv2[i]) / (7 * sh));
    }
    for (int i = 0; i < 49; ++i) {
      CHECK_NEAR(H1[i], H2[i], 1e-12 * sh);
      worst = fmax(worst, fabs(H1[i] - H2[i]) / sh);
    }
  }
  printf("edge couple: %d configurations, worst relative difference %.2e\n", compared,
         worst);
  CHECK(compared > 1800);
}

/* axial vector of log(Rp Rm^T) (row-major rotations): the rotation from Rm
 * to Rp in the spatial frame */
static void rotation_from_to(const double Rm[9], const double Rp[9], double w[3]) {
  double R[9];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      R[3 * a + b] = Rp[3 * a] * Rm[3 * b] + Rp[3 * a + 1] * Rm[3 * b + 1] +
                     Rp[3 * a + 2] * Rm[3 * b + 2];
  double c = 0.5 * (R[0] + R[4] + R[8] - 1.0);
  double v[3] = {0.5 * (R[7] - R[5]), 0.5 * (R[2] - R[6]), 0.5 * (R[3] - R[1])};
  double sn = sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  double k = sn > 1e-300 ? atan2(sn, c) / sn : 1.0;
  for (int a = 0; a < 3; ++a) w[a] = k * v[a];
}

/* The couple fixed in space on the joint rotation, rigid and elastic joints
 * of valence 1 to 5: Q_i = M . omega_i with omega_i from central differences
 * of the joint rotation, and J = dQ/dq against central differences of Q,
 * both with h-sweeps of order 2 (the errors of the finest step below 1e-4
 * relative); J is nonsymmetric; on a rigid joint at w = 0 the force on w is
 * M itself and the ends get none. */
static void test_couple_fixed(void) {
  enum { NH = 4 };
  static const double hs[NH] = {1e-2, 5e-3, 2.5e-3, 1.25e-3};
  double worst_asym = 1.0, worst_q = 0.0, worst_j = 0.0;
  int ntested = 0;
  for (int rigid = 0; rigid < 2; ++rigid)
    for (int v = 1; v <= 5; ++v)
      for (int trial = 0; trial < 4; ++trial) {
        star s, t;
        double M[3], Q[NMAX], J[NMAX * NMAX], R0[9], eq[NH], ej[NH], jmax = 0.0;
        make_star(&s, v, rigid, 0.1, rigid ? 0.4 + 0.6 * trial : 0.0, 0.2, 0);
        for (int c = 0; c < 3; ++c) M[c] = 2.0 * rnd();
        double *w = malloc(sizeof(double) * rnk_joint_work_size(&s.j));
        int n = s.n;
        if (rnk_joint_rotation(s.q, &s.j, R0) != RNK_OK ||
            rnk_joint_couple_fixed_force(s.q, &s.j, M, w, Q, J) != RNK_OK) {
          free(w);
          continue;
        }
        ++ntested;
        for (int i = 0; i < n * n; ++i) jmax = fmax(jmax, fabs(J[i]));
        double qmax = max_abs(n, Q);
        for (int ih = 0; ih < NH; ++ih) {
          eq[ih] = ej[ih] = 0.0;
          for (int i = 0; i < n; ++i) {
            double Rp[9], Rm[9], om[3], Qp[NMAX], Qm[NMAX], h = hs[ih];
            t = s;
            t.q[i] += h;
            CHECK_STATUS(rnk_joint_rotation(t.q, &t.j, Rp), RNK_OK);
            CHECK_STATUS(rnk_joint_couple_fixed_force(t.q, &t.j, M, w, Qp, NULL), RNK_OK);
            t.q[i] -= 2.0 * h;
            CHECK_STATUS(rnk_joint_rotation(t.q, &t.j, Rm), RNK_OK);
            CHECK_STATUS(rnk_joint_couple_fixed_force(t.q, &t.j, M, w, Qm, NULL), RNK_OK);
            rotation_from_to(Rm, Rp, om);
            double fd = (M[0] * om[0] + M[1] * om[1] + M[2] * om[2]) / (2.0 * h);
            eq[ih] = fmax(eq[ih], fabs(fd - Q[i]) / qmax);
            for (int a = 0; a < n; ++a) /* column i of J */
              ej[ih] =
                  fmax(ej[ih], fabs((Qp[a] - Qm[a]) / (2.0 * h) - J[n * a + i]) / jmax);
          }
        }
        double sq = rn_test_loglog_slope(NH, hs, eq),
               sj = rn_test_loglog_slope(NH, hs, ej);
        if (eq[0] > 1e-11) CHECK(sq > 1.8 && sq < 2.2);
        if (ej[0] > 1e-11) CHECK(sj > 1.8 && sj < 2.2);
        CHECK(eq[NH - 1] < 1e-4);
        CHECK(ej[NH - 1] < 1e-4);
        worst_q = fmax(worst_q, eq[NH - 1]);
        worst_j = fmax(worst_j, ej[NH - 1]);
        double asym = 0.0;
        for (int a = 0; a < n; ++a)
          for (int b = 0; b < n; ++b)
            asym = fmax(asym, fabs(J[n * a + b] - J[n * b + a]));
        worst_asym = fmin(worst_asym, asym / jmax);
        if (rigid) { /* at w = 0 the force on w is M, the ends get none */
          t = s;
          for (int c = 0; c < 3; ++c) t.q[3 + c] = 0.0;
          CHECK_STATUS(rnk_joint_couple_fixed_force(t.q, &t.j, M, w, Q, NULL), RNK_OK);
          for (int i = 0; i < n; ++i)
            CHECK(fabs(Q[i] - (i >= 3 && i < 6 ? M[i - 3] : 0.0)) < 1e-15);
        }
        free(w);
      }
  printf("fixed couple on the joint rotation: %d states, force and Jacobian against\n"
         " central differences (h = 1.25e-3): %.1e, %.1e relative; least asymmetry "
         "%.2f\n",
         ntested, worst_q, worst_j, worst_asym);
  CHECK(ntested >= 36);
  CHECK(worst_asym > 1e-2); /* a couple fixed in space is not conservative */
}

int main(void) {
  test_moment();
  test_random();
  test_near_degenerate();
  test_degenerate();
  test_end_stencil();
  test_couple_fixed();
  return rn_test_finish("kernels_joint_closed");
}

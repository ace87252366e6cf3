/* api_conformance.c - network-level conformance of the assembled energy:
 * random deformed rods (anisotropic sections with I12 != 0, rest curvature,
 * twist and lengths, every BC type, forces, moments, line loads, gravity, a
 * load factor < 1) checked with central differences over an h-sweep (second
 * order for the gradient and the HVP), Hessian symmetry, CSR == HVP, zero
 * energy and gradient at rest, invariance under rigid motions of a free rod,
 * the energy unchanged by update_reference, load lumping, the motion of
 * clamped ends under the load factor, and the built-in self-test. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "testutil.h"

enum { MAXN = 512, N_H = 5 };

static uint64_t rng = 12345;

static double urand(void) { return rn_test_rand(&rng); }

static double dot(size_t n, const double *a, const double *b) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) s += a[i] * b[i];
  return s;
}

static double norm(size_t n, const double *a) { return sqrt(dot(n, a, a)); }

/* Rodrigues rotation of v by the rotation vector w. */
static void rotate(const double w[3], const double v[3], double out[3]) {
  double th = sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]), k[3], kv, c, s, kxv[3];
  if (th == 0.0) {
    memcpy(out, v, 3 * sizeof(double));
    return;
  }
  for (int i = 0; i < 3; ++i) k[i] = w[i] / th;
  kv = k[0] * v[0] + k[1] * v[1] + k[2] * v[2];
  kxv[0] = k[1] * v[2] - k[2] * v[1];
  kxv[1] = k[2] * v[0] - k[0] * v[2];
  kxv[2] = k[0] * v[1] - k[1] * v[0];
  c = cos(th);
  s = sin(th);
  for (int i = 0; i < 3; ++i) out[i] = v[i] * c + kxv[i] * s + k[i] * kv * (1.0 - c);
}

/* Random polyline: edges of length 0.08..0.12 turning by up to ~35 deg. */
static void polyline(int nv, double *xyz) {
  double dir[3] = {1.0, 0.2, -0.1};
  double n0 = norm(3, dir);
  for (int k = 0; k < 3; ++k) dir[k] /= n0;
  xyz[0] = 0.1 * urand();
  xyz[1] = 0.1 * urand();
  xyz[2] = 0.1 * urand();
  for (int i = 1; i < nv; ++i) {
    double w[3] = {0.35 * urand(), 0.35 * urand(), 0.35 * urand()}, nd[3];
    double len = 0.1 + 0.02 * urand();
    rotate(w, dir, nd);
    memcpy(dir, nd, sizeof(nd));
    for (int k = 0; k < 3; ++k) xyz[3 * i + k] = xyz[3 * (i - 1) + k] + len * dir[k];
  }
}

/* Anisotropic section with I12 != 0, varying along the rod. */
static rn_section aniso(int j) {
  rn_section s;
  s.A = 1e-2 * (1.0 + 0.1 * j);
  s.I11 = 3e-4 * (1.0 + 0.05 * j);
  s.I22 = 1e-4;
  s.I12 = 5e-5;
  s.J = 2e-4;
  return s;
}

/* Rod 0: clamp start with motion, pin with displacement, fixed angle, end
 * force and moments, rest overrides.  Rod 1: both ends clamped, the end one
 * rotated; line load, gravity, a force.  Rod 2: one free edge. */
static rn_network *build_full(rn_context *ctx, double lambda) {
  rn_network *net = NULL;
  double xa[3 * 9], xb[3 * 7], xc[6] = {1, 1, 1, 1.05, 1.1, 0.95};
  double d1[3] = {0.3, 0.1, 1.0};
  double kap[14], tau[7], len[8];
  double disp[3] = {0.02, -0.01, 0.03}, rot[3] = {0.1, -0.2, 0.15},
         pd[3] = {0.01, 0.0, -0.02};
  double rot_b[3] = {0.0, 0.3, 0.2}, f[3] = {0.01, -0.02, 0.03},
         M[3] = {0.01, 0.02, -0.015};
  double M2[3] = {-0.02, 0.005, 0.01}, w[3] = {0.0, 0.05, -0.1}, g[3] = {0.0, 0.0, -0.98};
  rn_material m = {1.0, 0.4, 0.0}, mb;
  rn_section s;
  int rod;
  polyline(9, xa);
  polyline(7, xb);
  for (int i = 0; i < 7; ++i) {
    kap[2 * i] = 0.2 * urand();
    kap[2 * i + 1] = 0.2 * urand();
    tau[i] = 0.2 * urand();
  }
  for (int j = 0; j < 8; ++j) len[j] = 0.1 * (1.0 + 0.2 * urand());
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "a", 9, xa, d1, &rod), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, 0, -1, &m), RN_OK);
  for (int j = 0; j < 8; ++j) {
    s = aniso(j);
    CHECK_STATUS(rn_network_set_section(net, 0, j, &s), RN_OK);
  }
  CHECK_STATUS(rn_network_set_rest_curvature(net, 0, kap), RN_OK);
  CHECK_STATUS(rn_network_set_rest_twist(net, 0, tau), RN_OK);
  CHECK_STATUS(rn_network_set_rest_lengths(net, 0, len), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, 0, RN_START), RN_OK);
  CHECK_STATUS(rn_network_displace_end(net, 0, RN_START, disp, rot), RN_OK);
  CHECK_STATUS(rn_network_pin(net, 0, 5), RN_OK);
  CHECK_STATUS(rn_network_displace_vertex(net, 0, 5, pd), RN_OK);
  CHECK_STATUS(rn_network_fix_theta(net, 0, 6), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, 0, -1, f), RN_OK);
  CHECK_STATUS(rn_network_add_moment(net, 0, -1, M), RN_OK);
  CHECK_STATUS(rn_network_add_moment(net, 0, 3, M2), RN_OK);

  CHECK_STATUS(rn_network_add_rod(net, "b", 7, xb, NULL, &rod), RN_OK);
  CHECK_STATUS(rn_material_from_E_nu(2.0, 0.3, 0.5, &mb), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, 1, -1, &mb), RN_OK);
  CHECK_STATUS(rn_section_rectangle(0.2, 0.08, &s), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, 1, -1, &s), RN_OK);
  CHECK_STATUS(rn_section_ellipse(0.1, 0.15, &s), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, 1, 2, &s), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, 1, RN_START), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, 1, RN_END), RN_OK);
  CHECK_STATUS(rn_network_displace_end(net, 1, RN_END, NULL, rot_b), RN_OK);
  CHECK_STATUS(rn_network_add_line_load(net, 1, w), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, 1, 3, f), RN_OK);

  CHECK_STATUS(rn_network_add_rod(net, "c", 2, xc, NULL, &rod), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, 2, -1, &mb), RN_OK);
  s = aniso(3);
  CHECK_STATUS(rn_network_set_section(net, 2, -1, &s), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, 2, 1, f), RN_OK);
  CHECK_STATUS(rn_network_add_moment(net, 2, 0, M), RN_OK);

  CHECK_STATUS(rn_network_add_gravity(net, g), RN_OK);
  CHECK_STATUS(rn_network_set_load_factor(net, lambda), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

/* Random direction on the scale of an edge length (0.1). */
static void direction(const rn_network *net, double *d) {
  size_t n = rn_network_num_dofs(net);
  for (size_t i = 0; i < n; ++i) d[i] = 0.1 * urand();
}

static void deform(const rn_network *net, double *x, double pos, double ang) {
  /* perturbation of every DOF; positions and angles are told apart by
   * comparing with the current state's scale (angles start at 0) */
  size_t n = rn_network_num_dofs(net);
  for (size_t i = 0; i < n; ++i) x[i] += (x[i] == 0.0 ? ang : pos) * urand();
}

/* Gradient and HVP against central differences over h = 10^-2 .. 10^-4:
 * second order (fitted slope), small error at the smallest h. */
static void fd_sweep(const rn_network *net, const double *x, const char *label) {
  size_t n = rn_network_num_dofs(net);
  double d[MAXN], g[MAXN], hv[MAXN], xp[MAXN], xm[MAXN], gp[MAXN], gm[MAXN];
  double h[N_H], eg[N_H], eh[N_H], E0, gd, hvn, den;
  CHECK(n <= MAXN);
  direction(net, d);
  CHECK_STATUS(rn_network_gradient(net, x, &E0, g), RN_OK);
  CHECK_STATUS(rn_network_hvp(net, x, d, hv), RN_OK);
  gd = dot(n, g, d);
  hvn = norm(n, hv);
  /* relative to g.d, or to its typical size if d is nearly orthogonal to g */
  den = fmax(fabs(gd), norm(n, g) * norm(n, d) / sqrt((double)n));
  for (int k = 0; k < N_H; ++k) {
    double Ep, Em, r2 = 0.0;
    h[k] = pow(10.0, -2.0 - 0.5 * k);
    for (size_t i = 0; i < n; ++i) {
      xp[i] = x[i] + h[k] * d[i];
      xm[i] = x[i] - h[k] * d[i];
    }
    CHECK_STATUS(rn_network_gradient(net, xp, &Ep, gp), RN_OK);
    CHECK_STATUS(rn_network_gradient(net, xm, &Em, gm), RN_OK);
    eg[k] = fabs((Ep - Em) / (2.0 * h[k]) - gd) / den;
    for (size_t i = 0; i < n; ++i) {
      double r = (gp[i] - gm[i]) / (2.0 * h[k]) - hv[i];
      r2 += r * r;
    }
    eh[k] = sqrt(r2) / hvn;
  }
  {
    double sg = rn_test_loglog_slope(N_H, h, eg), sh = rn_test_loglog_slope(N_H, h, eh);
    if (!(sg > 1.8 && sg < 2.2) || !(sh > 1.8 && sh < 2.2))
      rn_test_fail(__FILE__, __LINE__, "%s: FD slopes gradient %.3f HVP %.3f", label, sg,
                   sh);
    CHECK(sg > 1.8 && sg < 2.2);
    CHECK(sh > 1.8 && sh < 2.2);
  }
  if (getenv("RN_VERBOSE"))
    for (int k = 0; k < N_H; ++k)
      fprintf(stderr, "%s h %.2e eg %.3e eh %.3e\n", label, h[k], eg[k], eh[k]);
  CHECK(eg[N_H - 1] < 1e-7);
  CHECK(eh[N_H - 1] < 1e-7);
}

/* CSR values: symmetric and equal to the HVP for random vectors. */
static void csr_checks(const rn_network *net, const double *x) {
  size_t n = rn_network_num_dofs(net), nnz;
  const int64_t *rp;
  const int32_t *cl;
  double *vals, v[MAXN], hv[MAXN], y[MAXN], asym = 0.0, amax = 0.0, diff = 0.0;
  CHECK_STATUS(rn_network_hessian_pattern(net, &nnz, &rp, &cl), RN_OK);
  vals = malloc(nnz * sizeof(double));
  CHECK_STATUS(rn_network_hessian_values(net, x, vals), RN_OK);
  for (size_t r = 0; r < n; ++r)
    for (int64_t p = rp[r]; p < rp[r + 1]; ++p) {
      int64_t q = rp[cl[p]];
      while (q < rp[cl[p] + 1] && (size_t)cl[q] != r) q++;
      CHECK(q < rp[cl[p] + 1]);
      if (q < rp[cl[p] + 1]) asym = fmax(asym, fabs(vals[p] - vals[q]));
      amax = fmax(amax, fabs(vals[p]));
    }
  CHECK(asym <= 1e-13 * amax);
  for (int trial = 0; trial < 3; ++trial) {
    for (size_t i = 0; i < n; ++i) v[i] = urand();
    CHECK_STATUS(rn_network_hvp(net, x, v, hv), RN_OK);
    diff = 0.0;
    for (size_t r = 0; r < n; ++r) {
      y[r] = 0.0;
      for (int64_t p = rp[r]; p < rp[r + 1]; ++p) y[r] += vals[p] * v[cl[p]];
      diff += (y[r] - hv[r]) * (y[r] - hv[r]);
    }
    CHECK(sqrt(diff) <= 1e-13 * norm(n, hv));
  }
  free(vals);
}

static void test_full(rn_context *ctx) {
  rn_network *net = build_full(ctx, 0.7);
  size_t n = rn_network_num_dofs(net);
  double x[MAXN], terms[RN_TERM_COUNT], E, Eg, g[MAXN];
  /* full: 9+7+2 vertices -> 35 + 27 + 7 = 69; fixed: rod a 7 + 3 + 1,
   * rod b 14 */
  CHECK(rn_network_num_full_dofs(net) == 69);
  CHECK(n == 69 - 11 - 14);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  deform(net, x, 0.01, 0.3);
  CHECK_STATUS(rn_network_energy_terms(net, x, terms), RN_OK);
  CHECK_STATUS(rn_network_energy(net, x, &E), RN_OK);
  CHECK_STATUS(rn_network_gradient(net, x, &Eg, g), RN_OK);
  CHECK_NEAR(terms[0] + terms[1] + terms[2] + terms[3], E, 1e-15 * fabs(E));
  /* The gradient path sums the same stencil energies into other buckets (bending
   * and twisting of a vertex together): equal to a few units of round-off of the
   * terms' magnitudes, not bit for bit (it matched bit for bit only while the load
   * term, then -f . x with absolute positions, dwarfed the rest). */
  CHECK_NEAR(Eg, E,
             4 * DBL_EPSILON *
                 (fabs(terms[0]) + fabs(terms[1]) + fabs(terms[2]) + fabs(terms[3])));
  for (int t = 0; t < RN_TERM_COUNT; ++t) CHECK(terms[t] != 0.0);
  CHECK(terms[RN_TERM_STRETCH] > 0 && terms[RN_TERM_BEND] > 0 &&
        terms[RN_TERM_TWIST] > 0);
  fd_sweep(net, x, "full network, deformed");
  fd_sweep(net, x, "full network, deformed, 2nd direction");
  csr_checks(net, x);
  rn_network_destroy(&net);
}

/* The energy at x is unchanged by update_reference(x), and so are the
 * strains; derivatives stay exact with the new reference. */
static void test_update_reference(rn_context *ctx) {
  rn_network *net = build_full(ctx, 0.7);
  size_t n = rn_network_num_dofs(net);
  double x[MAXN], x2[MAXN], y[MAXN], E1, E2, t1[RN_TERM_COUNT], t2[RN_TERM_COUNT];
  double k1[14], k2[14], tau1[7], tau2[7];
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  deform(net, x, 0.02, 0.5);
  CHECK_STATUS(rn_network_energy_terms(net, x, t1), RN_OK);
  CHECK_STATUS(rn_network_energy(net, x, &E1), RN_OK);
  CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_rod_strains(net, 0, NULL, k1, tau1), RN_OK);
  CHECK_STATUS(rn_network_update_reference(net, x), RN_OK);
  CHECK_STATUS(rn_network_get_dofs(net, y), RN_OK);
  CHECK(memcmp(x, y, n * sizeof(double)) == 0);
  CHECK_STATUS(rn_network_energy(net, x, &E2), RN_OK);
  CHECK_STATUS(rn_network_energy_terms(net, x, t2), RN_OK);
  CHECK_REL(E2, E1, 1e-12);
  for (int t = 0; t < RN_TERM_COUNT; ++t) CHECK_NEAR(t2[t], t1[t], 1e-12 * fabs(E1));
  CHECK_STATUS(rn_network_rod_strains(net, 0, NULL, k2, tau2), RN_OK);
  for (int i = 0; i < 7; ++i) {
    CHECK_NEAR(k2[2 * i], k1[2 * i], 1e-13);
    CHECK_NEAR(k2[2 * i + 1], k1[2 * i + 1], 1e-13);
    CHECK_NEAR(tau2[i], tau1[i], 1e-13);
  }
  /* a second step: deform further, update twice; still equal */
  memcpy(x2, x, n * sizeof(double));
  deform(net, x2, 0.02, 0.5);
  CHECK_STATUS(rn_network_energy(net, x2, &E1), RN_OK);
  CHECK_STATUS(rn_network_update_reference(net, x2), RN_OK);
  CHECK_STATUS(rn_network_energy(net, x2, &E2), RN_OK);
  CHECK_REL(E2, E1, 1e-12);
  fd_sweep(net, x2, "after update_reference");
  csr_checks(net, x2);
  rn_network_destroy(&net);
}

/* Rods at rest with no loads and no prescribed motion: E = 0, g = 0. */
static void test_rest(rn_context *ctx) {
  rn_network *net = NULL;
  double xa[3 * 9], xb[3 * 5], x[MAXN], g[MAXN], E, terms[RN_TERM_COUNT];
  rn_material m = {1.0, 0.4, 2.0};
  size_t n;
  polyline(9, xa);
  polyline(5, xb);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "a", 9, xa, NULL, NULL), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "b", 5, xb, NULL, NULL), RN_OK);
  for (int r = 0; r < 2; ++r) {
    rn_section s = aniso(r);
    CHECK_STATUS(rn_network_set_material(net, r, -1, &m), RN_OK);
    CHECK_STATUS(rn_network_set_section(net, r, -1, &s), RN_OK);
  }
  CHECK_STATUS(rn_network_clamp(net, 0, RN_START), RN_OK);
  CHECK_STATUS(rn_network_pin(net, 1, 2), RN_OK);
  CHECK_STATUS(rn_network_fix_theta(net, 1, 3), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  n = rn_network_num_dofs(net);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_gradient(net, x, &E, g), RN_OK);
  CHECK_STATUS(rn_network_energy_terms(net, x, terms), RN_OK);
  CHECK(fabs(E) < 1e-28);
  for (int t = 0; t < RN_TERM_COUNT; ++t) CHECK(fabs(terms[t]) < 1e-28);
  CHECK(norm(n, g) < 1e-14);
  /* the Hessian at rest is positive semidefinite along random directions */
  for (int trial = 0; trial < 5; ++trial) {
    double d[MAXN], hv[MAXN];
    direction(net, d);
    CHECK_STATUS(rn_network_hvp(net, x, d, hv), RN_OK);
    CHECK(dot(n, d, hv) > 0.0);
  }
  {
    double strain[8], kap[14], tau[7];
    CHECK_STATUS(rn_network_rod_strains(net, 0, strain, kap, tau), RN_OK);
    for (int j = 0; j < 8; ++j) CHECK_NEAR(strain[j], 0.0, 1e-15);
  }
  rn_network_destroy(&net);
}

/* A free rod (no BCs, no loads) with anisotropic section and rest overrides. */
static rn_network *build_free(rn_context *ctx, const double *xyz, const double *d1,
                              const double *kap, const double *tau) {
  rn_network *net = NULL;
  rn_material m = {1.0, 0.4, 0.0};
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "free", 8, xyz, d1, NULL), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, 0, -1, &m), RN_OK);
  for (int j = 0; j < 7; ++j) {
    rn_section s = aniso(j);
    CHECK_STATUS(rn_network_set_section(net, 0, j, &s), RN_OK);
  }
  CHECK_STATUS(rn_network_set_rest_curvature(net, 0, kap), RN_OK);
  CHECK_STATUS(rn_network_set_rest_twist(net, 0, tau), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

/* Translation of a deformed state leaves energy and gradient unchanged; a
 * rotated copy of the rod (input shape, d1 and state rotated) has the same
 * energy and a rotated gradient. */
static void test_rigid_motion(rn_context *ctx) {
  double xyz[24], rxyz[24], d1[3] = {0.0, 0.0, 1.0}, rd1[3], kap[12], tau[6];
  double w[3] = {0.7, -1.1, 0.4}, c[3] = {3.0, -2.0, 0.5};
  double x[31], y[31], g[31], gy[31], E, Ey;
  rn_network *net, *rnet;
  polyline(8, xyz);
  for (int i = 0; i < 6; ++i) {
    kap[2 * i] = 0.3 * urand();
    kap[2 * i + 1] = 0.3 * urand();
    tau[i] = 0.3 * urand();
  }
  for (int i = 0; i < 8; ++i) rotate(w, xyz + 3 * i, rxyz + 3 * i);
  rotate(w, d1, rd1);
  net = build_free(ctx, xyz, d1, kap, tau);
  rnet = build_free(ctx, rxyz, rd1, kap, tau);
  CHECK(rn_network_num_dofs(net) == 31);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  deform(net, x, 0.02, 0.4);
  CHECK_STATUS(rn_network_gradient(net, x, &E, g), RN_OK);
  CHECK(E > 0.0);
  /* translation: vertices at 0, 4, 8, ... (full = reduced for a free rod) */
  memcpy(y, x, sizeof(x));
  for (int i = 0; i < 8; ++i)
    for (int k = 0; k < 3; ++k) y[4 * i + k] += c[k];
  CHECK_STATUS(rn_network_gradient(net, y, &Ey, gy), RN_OK);
  CHECK_REL(Ey, E, 1e-11);
  for (int i = 0; i < 31; ++i) CHECK_NEAR(gy[i], g[i], 1e-10 * norm(31, g));
  /* rotation */
  memcpy(y, x, sizeof(x));
  for (int i = 0; i < 8; ++i) rotate(w, x + 4 * i, y + 4 * i);
  CHECK_STATUS(rn_network_gradient(rnet, y, &Ey, gy), RN_OK);
  CHECK_REL(Ey, E, 1e-12);
  for (int i = 0; i < 8; ++i) {
    double rg[3];
    rotate(w, g + 4 * i, rg);
    for (int k = 0; k < 3; ++k) CHECK_NEAR(gy[4 * i + k], rg[k], 1e-12 * norm(31, g));
    if (i < 7) CHECK_NEAR(gy[4 * i + 3], g[4 * i + 3], 1e-12 * norm(31, g));
  }
  fd_sweep(net, x, "free rod");
  csr_checks(net, x);
  rn_network_destroy(&net);
  rn_network_destroy(&rnet);
}

/* Line load and gravity lumped with Voronoi rest lengths, scaled by lambda:
 * at the undeformed state the gradient is minus the lumped forces. */
static void test_lumping(rn_context *ctx) {
  rn_network *net = NULL;
  double xyz[15], x[19], g[19], w[3] = {0.0, 0.0, -2.0}, gr[3] = {0.0, -9.81, 0.0};
  double vor[5] = {0.125, 0.25, 0.25, 0.25, 0.125}, E;
  rn_material m = {1.0, 0.4, 3.0};
  rn_section s;
  for (int i = 0; i < 5; ++i) {
    xyz[3 * i] = 0.25 * i;
    xyz[3 * i + 1] = xyz[3 * i + 2] = 0.0;
  }
  CHECK_STATUS(rn_section_circle(0.1, &s), RN_OK);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "r", 5, xyz, NULL, NULL), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, 0, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, 0, -1, &s), RN_OK);
  CHECK_STATUS(rn_network_add_line_load(net, 0, w), RN_OK);
  CHECK_STATUS(rn_network_add_gravity(net, gr), RN_OK);
  CHECK_STATUS(rn_network_set_load_factor(net, 0.5), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_gradient(net, x, &E, g), RN_OK);
  for (int i = 0; i < 5; ++i) {
    CHECK_NEAR(g[4 * i], 0.0, 1e-15);
    CHECK_NEAR(g[4 * i + 1], 0.5 * 9.81 * 3.0 * s.A * vor[i], 1e-14);
    CHECK_NEAR(g[4 * i + 2], 0.5 * 2.0 * vor[i], 1e-14);
  }
  /* E = -lambda sum f . x: only the x coordinates are nonzero and f_x = 0 */
  CHECK_NEAR(E, 0.0, 1e-15);
  rn_network_destroy(&net);
}

/* The load factor moves a clamped end: x = c0 + l d + R(l w)(x0 - c0); the
 * clamped edge's director rotates with R (theta stays 0). */
static void test_load_factor(rn_context *ctx) {
  rn_network *net = build_full(ctx, 0.0);
  double x0[27], x[27], d10[24], d1[24], c0[3], rel[3], rd[3];
  double disp[3] = {0.02, -0.01, 0.03}, rot[3] = {0.1, -0.2, 0.15}, wl[3], E0, E1;
  double theta[8], xr[MAXN];
  const double lam = 0.7;
  CHECK_STATUS(rn_network_rod_initial_vertices(net, 0, x0), RN_OK);
  CHECK_STATUS(rn_network_rod_vertices(net, 0, x), RN_OK);
  for (int k = 0; k < 6; ++k) CHECK_NEAR(x[k], x0[k], 1e-16); /* lambda = 0: in place */
  CHECK_STATUS(rn_network_rod_frames(net, 0, d10, NULL), RN_OK);
  CHECK_STATUS(rn_network_get_dofs(net, xr), RN_OK);
  CHECK_STATUS(rn_network_energy(net, xr, &E0), RN_OK);
  CHECK_STATUS(rn_network_set_load_factor(net, lam), RN_OK);
  CHECK(rn_network_load_factor(net) == lam);
  CHECK_STATUS(rn_network_energy(net, xr, &E1), RN_OK);
  CHECK(E1 != E0);
  CHECK_STATUS(rn_network_rod_vertices(net, 0, x), RN_OK);
  CHECK_STATUS(rn_network_rod_frames(net, 0, d1, NULL), RN_OK);
  CHECK_STATUS(rn_network_rod_theta(net, 0, theta), RN_OK);
  CHECK(theta[0] == 0.0);
  for (int k = 0; k < 3; ++k) {
    c0[k] = 0.5 * (x0[k] + x0[3 + k]);
    wl[k] = lam * rot[k];
  }
  for (int v = 0; v < 2; ++v) {
    for (int k = 0; k < 3; ++k) rel[k] = x0[3 * v + k] - c0[k];
    rotate(wl, rel, rd);
    for (int k = 0; k < 3; ++k)
      CHECK_NEAR(x[3 * v + k], c0[k] + lam * disp[k] + rd[k], 1e-15);
  }
  rotate(wl, d10, rd);
  for (int k = 0; k < 3; ++k) CHECK_NEAR(d1[k], rd[k], 1e-15);
  /* the pinned vertex 5 moves by lambda times its displacement */
  CHECK_NEAR(x[15], x0[15] + lam * 0.01, 1e-15);
  CHECK_NEAR(x[17], x0[17] - lam * 0.02, 1e-15);
  /* back to 0: everything returns */
  CHECK_STATUS(rn_network_set_load_factor(net, 0.0), RN_OK);
  CHECK_STATUS(rn_network_energy(net, xr, &E1), RN_OK);
  CHECK_REL(E1, E0, 1e-14);
  rn_network_destroy(&net);
}

/* The built-in self-test: small errors, second order, deterministic. */
static void test_self_check(rn_context *ctx) {
  rn_network *net = build_full(ctx, 0.7);
  rn_check_report a, b;
  double x[MAXN];
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  deform(net, x, 0.01, 0.3);
  CHECK_STATUS(rn_network_check_derivatives(net, x, 2, 0.05, 7, &a), RN_OK);
  if (getenv("RN_VERBOSE"))
    fprintf(
        stderr,
        "self-check: grad %.2e (order %.2f) hvp %.2e (order %.2f) sym %.2e csr %.2e\n",
        a.grad_rel_err, a.grad_order, a.hvp_rel_err, a.hvp_order, a.hess_sym_err,
        a.hess_hvp_err);
  CHECK(a.n_points == 3);
  CHECK(a.grad_rel_err < 1e-7);
  CHECK(a.hvp_rel_err < 1e-7);
  CHECK(a.hess_sym_err < 1e-13);
  CHECK(a.hess_hvp_err < 1e-13);
  CHECK(a.grad_order > 1.9 && a.grad_order < 2.1);
  CHECK(a.hvp_order > 1.9 && a.hvp_order < 2.1);
  CHECK_STATUS(rn_network_check_derivatives(net, x, 2, 0.05, 7, &b), RN_OK);
  CHECK(memcmp(&a, &b, sizeof(a)) == 0);
  CHECK_STATUS(rn_network_check_derivatives(net, NULL, 0, 0.0, 1, &b), RN_OK);
  CHECK(b.n_points == 1);
  CHECK(b.grad_rel_err < 1e-7 && b.hvp_rel_err < 1e-7);
  rn_network_destroy(&net);
}

int main(void) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  test_full(ctx);
  test_update_reference(ctx);
  test_rest(ctx);
  test_rigid_motion(ctx);
  test_lumping(ctx);
  test_load_factor(ctx);
  test_self_check(ctx);
  if (rn_test_failures) fprintf(stderr, "last error: %s\n", rn_context_last_error(ctx));
  rn_context_destroy(&ctx);
  return rn_test_finish("api_conformance");
}

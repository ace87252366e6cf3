/* api_contact.c - contact in the network (c_api/contact/contact.c, rodnet_contact.h): two
 * crossing rods and a rod folded back on itself with contact on; the network
 * gradient and HVP against central differences (h-sweep, second order), the CSR
 * Hessian against the HVP (the pattern holds the contact blocks), the gap of
 * rn_network_contact_stats against the closed form, excluded neighbours, the
 * continuous check (a trial state on the far side of the other rod is
 * degenerate, the same state reached in small accepted steps is not), and the
 * errors (bad settings, an interpenetrating start). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "rodnet_contact.h"
#include "testutil.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

enum { NV = 9, MAXN = 256 };
static uint64_t rng = 777;

/* Rod a along x at z = 0 (clamped at both ends), rod b along y at height zb,
 * crossing a's edge 4 in its middle (clamped at its start only); contact radius
 * r, or rb for rod b if rb >= 0. */
static rn_network *crossing2(rn_context *ctx, double zb, double r, double rb, double dhat,
                             double kappa, rn_status want) {
  rn_network *net = NULL;
  double xa[3 * NV], xb[3 * NV];
  rn_material m = {10.0, 4.0, 0.0};
  rn_section s;
  int rod;
  for (int i = 0; i < NV; ++i) {
    xa[3 * i] = -1.0 + 0.25 * i;
    xa[3 * i + 1] = 0.0;
    xa[3 * i + 2] = 0.0;
    xb[3 * i] = 0.125;
    xb[3 * i + 1] = -0.875 + 0.25 * i;
    xb[3 * i + 2] = zb;
  }
  CHECK_STATUS(rn_section_circle(r, &s), RN_OK);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "a", NV, xa, NULL, &rod), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "b", NV, xb, NULL, &rod), RN_OK);
  for (int k = 0; k < 2; ++k) {
    CHECK_STATUS(rn_network_set_material(net, k, -1, &m), RN_OK);
    CHECK_STATUS(rn_network_set_section(net, k, -1, &s), RN_OK);
  }
  CHECK_STATUS(rn_network_clamp(net, 0, RN_START), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, 0, RN_END), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, 1, RN_START), RN_OK);
  CHECK_STATUS(rn_network_set_contact(net, dhat, kappa, r), RN_OK);
  if (rb >= 0.0) CHECK_STATUS(rn_network_set_rod_contact_radius(net, 1, rb), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), want);
  if (want != RN_OK) rn_network_destroy(&net);
  return net;
}

static rn_network *crossing(rn_context *ctx, double zb, double r, double dhat,
                            double kappa, rn_status want) {
  return crossing2(ctx, zb, r, -1.0, dhat, kappa, want);
}

static double dot(size_t n, const double *a, const double *b) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) s += a[i] * b[i];
  return s;
}

/* Gradient and HVP against central differences along d; CSR Hessian = HVP. */
static void fd_sweep(rn_network *net, const double *x, const double *d,
                     const char *label) {
  enum { NH = 5 };
  size_t n = rn_network_num_dofs(net), nnz;
  double g[MAXN], hv[MAXN], gp[MAXN], gm[MAXN], xp[MAXN], xm[MAXN], y[MAXN];
  double h[NH], eg[NH], eh[NH], E0;
  const int64_t *rp;
  const int32_t *cl;
  CHECK(n <= MAXN);
  CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK); /* the accepted state */
  CHECK_STATUS(rn_network_gradient(net, x, &E0, g), RN_OK);
  CHECK_STATUS(rn_network_hvp(net, x, d, hv), RN_OK);
  for (int k = 0; k < NH; ++k) {
    double Ep, Em, r2 = 0.0;
    h[k] = 2e-5 / pow(2.0, k);
    for (size_t i = 0; i < n; ++i) {
      xp[i] = x[i] + h[k] * d[i];
      xm[i] = x[i] - h[k] * d[i];
    }
    CHECK_STATUS(rn_network_gradient(net, xp, &Ep, gp), RN_OK);
    CHECK_STATUS(rn_network_gradient(net, xm, &Em, gm), RN_OK);
    eg[k] = fabs((Ep - Em) / (2.0 * h[k]) - dot(n, g, d)) / sqrt(dot(n, g, g));
    for (size_t i = 0; i < n; ++i) {
      double r = (gp[i] - gm[i]) / (2.0 * h[k]) - hv[i];
      r2 += r * r;
    }
    eh[k] = sqrt(r2 / dot(n, hv, hv));
  }
  double sg = rn_test_loglog_slope(NH, h, eg), sh = rn_test_loglog_slope(NH, h, eh);
  if (!(eg[0] < 1e-8 || (sg > 1.8 && sg < 2.3)) ||
      !(eh[0] < 1e-8 || (sh > 1.8 && sh < 2.3)))
    rn_test_fail(__FILE__, __LINE__, "%s: FD orders gradient %.3f HVP %.3f (%.3g %.3g)",
                 label, sg, sh, eg[0], eh[0]);
  if (!(eg[NH - 1] < 1e-7 && eh[NH - 1] < 1e-6))
    rn_test_fail(__FILE__, __LINE__,
                 "%s: FD errors gradient %.3g HVP %.3g (orders %.3f %.3f)", label,
                 eg[NH - 1], eh[NH - 1], sg, sh);
  rn_test_checks++;
  /* the CSR Hessian in its pattern equals the HVP */
  CHECK_STATUS(rn_network_hessian_pattern(net, &nnz, &rp, &cl), RN_OK);
  double *vals = malloc(nnz * sizeof(double)), diff = 0.0;
  CHECK_STATUS(rn_network_hessian_values(net, x, vals), RN_OK);
  for (size_t r = 0; r < n; ++r) {
    y[r] = 0.0;
    for (int64_t p = rp[r]; p < rp[r + 1]; ++p) y[r] += vals[p] * d[cl[p]];
    diff += (y[r] - hv[r]) * (y[r] - hv[r]);
  }
  CHECK(sqrt(diff) <= 1e-12 * sqrt(dot(n, hv, hv)));
  free(vals);
}

static void test_crossing(rn_context *ctx) {
  const double r = 0.02, dhat = 0.05, kappa = 3.0, zb = 2 * r + 0.03;
  rn_network *net = crossing(ctx, zb, r, dhat, kappa, RN_OK);
  size_t n = rn_network_num_dofs(net);
  double x[MAXN], d[MAXN], E[RN_TERM_COUNT];
  rn_contact_stats cs;
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  /* the closed form at the start: one pair (a's edge 4, b's edge 3) at gap 0.03 */
  CHECK_STATUS(rn_network_contact_stats(net, x, &cs), RN_OK);
  CHECK_NEAR(cs.min_gap, 0.03, 1e-15);
  CHECK(cs.active == 1);
  CHECK_NEAR(cs.energy, -kappa * 0.02 * 0.02 * log(0.6), 1e-15);
  CHECK_STATUS(rn_network_energy_terms(net, x, E), RN_OK);
  CHECK_NEAR(E[RN_TERM_LOAD], cs.energy, 1e-15); /* no loads: the barrier alone */
  /* deformed states: every DOF perturbed (the pairs stay in their regimes) */
  for (int trial = 0; trial < 3; ++trial) {
    for (size_t i = 0; i < n; ++i) {
      x[i] += 0.002 * rn_test_rand(&rng);
      d[i] = rn_test_rand(&rng);
    }
    CHECK_STATUS(rn_network_contact_stats(net, x, &cs), RN_OK);
    CHECK(cs.active >= 1 && cs.min_gap > 0.0 && cs.min_gap < dhat);
    fd_sweep(net, x, d, "crossing rods");
  }
  /* continuous check: b's free end dropped to the far side of a in one trial
   * step is rejected, though that state itself does not interpenetrate */
  double y[MAXN], Ey;
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  memcpy(y, x, n * sizeof(double));
  for (size_t i = 0; i < n; ++i) y[i] = x[i];
  {
    /* every free z of rod b (its vertices after the clamped edge) to -zb */
    rn_network_destroy(&net);
    net = crossing(ctx, zb, r, dhat, kappa, RN_OK);
    CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
    memcpy(y, x, n * sizeof(double));
    for (size_t i = 0; i < n; ++i)
      if (fabs(x[i] - zb) < 1e-15) y[i] = -zb;
    CHECK_STATUS(rn_network_energy(net, y, &Ey), RN_DEGENERATE);
    CHECK(strstr(rn_context_last_error(ctx), "contact") != NULL);
  }
  rn_network_destroy(&net);
  /* errors */
  crossing(ctx, 2 * r - 0.001, r, dhat, kappa, RN_ERR_GEOMETRY);
  CHECK(strstr(rn_context_last_error(ctx), "interpenetrates") != NULL);
  {
    rn_network *bad = NULL;
    CHECK_STATUS(rn_network_create(ctx, &bad), RN_OK);
    CHECK_STATUS(rn_network_set_contact(bad, 0.0, 1.0, 0.1), RN_ERR_ARG);
    CHECK_STATUS(rn_network_set_contact(bad, 0.1, -1.0, 0.1), RN_ERR_ARG);
    CHECK_STATUS(rn_network_set_contact(bad, 0.1, 1.0, NAN), RN_ERR_ARG);
    CHECK(rn_network_get_contact(bad, NULL, NULL, NULL) == 0);
    rn_network_destroy(&bad);
  }
}

/* A rod bent into a hairpin: its two legs at gap 0.01 (self contact); the
 * edges around the fold are excluded (rest arc length within reach). */
static void test_hairpin(rn_context *ctx) {
  enum { N = 21 };
  const double r = 0.02, dhat = 0.05, kappa = 2.0, w = 2 * r + 0.01;
  double xyz[3 * N], x[MAXN], d[MAXN];
  rn_material m = {10.0, 4.0, 0.0};
  rn_section s;
  rn_network *net = NULL;
  rn_contact_stats cs;
  int rod;
  /* legs along x at y = 0 and y = w, joined by a half circle of radius w/2 */
  for (int i = 0; i < N; ++i) {
    double t;
    if (i <= 8) {
      xyz[3 * i] = -1.0 + 0.125 * i;
      xyz[3 * i + 1] = 0.0;
    } else if (i < 12) {
      t = M_PI * (i - 8) / 4.0;
      xyz[3 * i] = 0.5 * w * sin(t);
      xyz[3 * i + 1] = 0.5 * w * (1.0 - cos(t));
    } else {
      xyz[3 * i] = -0.125 * (i - 12);
      xyz[3 * i + 1] = w;
    }
    xyz[3 * i + 2] = 0.0;
  }
  CHECK_STATUS(rn_section_circle(r, &s), RN_OK);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "hairpin", N, xyz, NULL, &rod), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, 0, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, 0, -1, &s), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, 0, RN_START), RN_OK);
  CHECK_STATUS(rn_network_set_contact(net, dhat, kappa, r), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  size_t n = rn_network_num_dofs(net);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_contact_stats(net, x, &cs), RN_OK);
  CHECK_NEAR(cs.min_gap, 0.01, 1e-12);
  CHECK(cs.active >= 8); /* the legs face each other over 8 edges */
  for (size_t i = 0; i < n; ++i) {
    x[i] += 0.001 * rn_test_rand(&rng);
    d[i] = rn_test_rand(&rng);
  }
  fd_sweep(net, x, d, "hairpin");
  rn_network_destroy(&net);
}

/* The Hessian pattern follows the accepted state: rod b starts far above a
 * (its pair outside the pattern); a trial state that lowers b to within dhat
 * of a is degenerate (a pair outside the pattern comes within reach); once
 * accepted (rn_network_set_dofs) the pattern holds the pair (a new version,
 * more entries), and the CSR Hessian equals the HVP there. */
/* Interface DOFs of rn_network_dof_blocks (no joints here: contact makes them):
 * each a vertex position; hit[] counts the components of a's vertices 4, 5 and
 * b's vertices 3, 4 among them. */
static int count_contact_interface(const rn_network *net, int hit[4]) {
  int32_t blk[MAXN];
  rn_dof_info info[MAXN];
  const size_t n = rn_network_num_dofs(net);
  int count = 0;
  CHECK_STATUS(rn_network_dof_blocks(net, blk, NULL, NULL), RN_OK);
  CHECK_STATUS(rn_network_dof_info(net, info), RN_OK);
  for (size_t i = 0; i < n; ++i) {
    if (blk[i] != RN_DOF_INTERFACE) {
      CHECK(blk[i] == info[i].rod);
      continue;
    }
    ++count;
    CHECK(info[i].kind == RN_DOF_POSITION);
    if (!hit) continue;
    const int a = info[i].rod == 0, v = info[i].index;
    if (a && (v == 4 || v == 5)) hit[v - 4]++;
    if (!a && (v == 3 || v == 4)) hit[2 + v - 3]++;
  }
  return count;
}

static void test_pattern_change(rn_context *ctx) {
  const double r = 0.02, dhat = 0.05, kappa = 3.0, far = 2 * r + 0.5;
  const double near = 2 * r + 0.6 * dhat;
  rn_network *net = crossing(ctx, far, r, dhat, kappa, RN_OK);
  size_t n = rn_network_num_dofs(net), nnz0, nnz1;
  const int64_t *rp;
  const int32_t *cl;
  double x[MAXN], y[MAXN], d[MAXN], E;
  rn_contact_stats cs;
  CHECK_STATUS(rn_network_hessian_pattern(net, &nnz0, &rp, &cl), RN_OK);
  const unsigned long v0 = rn_network_pattern_version(net);
  CHECK(count_contact_interface(net, NULL) == 0); /* no pair: two rod interiors */
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  for (size_t i = 0; i < n; ++i) y[i] = fabs(x[i] - far) < 1e-15 ? near : x[i];
  CHECK_STATUS(rn_network_contact_stats(net, y, &cs), RN_OK);
  CHECK(cs.active == 1);
  CHECK_NEAR(cs.min_gap, 0.6 * dhat, 1e-14);
  CHECK_STATUS(rn_network_energy(net, y, &E), RN_DEGENERATE);
  CHECK(strstr(rn_context_last_error(ctx), "outside the Hessian pattern") != NULL);
  CHECK_STATUS(rn_network_set_dofs(net, y), RN_OK); /* accepted: the pattern follows */
  CHECK(rn_network_pattern_version(net) != v0);
  {
    /* the pair's vertices (a's 4 and 5, b's 3 and 4) join the interface */
    int hit[4] = {0, 0, 0, 0};
    CHECK(count_contact_interface(net, hit) > 0);
    CHECK(hit[0] == 3 && hit[1] == 3 && hit[2] == 3 && hit[3] == 3);
  }
  CHECK_STATUS(rn_network_hessian_pattern(net, &nnz1, &rp, &cl), RN_OK);
  CHECK(nnz1 > nnz0);
  CHECK_STATUS(rn_network_energy(net, y, &E), RN_OK);
  for (size_t i = 0; i < n; ++i) {
    y[i] += 0.001 * rn_test_rand(&rng);
    d[i] = rn_test_rand(&rng);
  }
  fd_sweep(net, y, d, "pattern changed");
  /* back up (accepted): the pair stays in the pattern, no new version */
  const unsigned long v1 = rn_network_pattern_version(net);
  CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK);
  CHECK(rn_network_pattern_version(net) == v1);
  rn_network_destroy(&net);
}

/* Per-rod contact radius: the gap of the crossing is zb - (ra + rb). */
static void test_rod_radius(rn_context *ctx) {
  const double ra = 0.01, rb = 0.03, dhat = 0.05, kappa = 3.0, zb = ra + rb + 0.02;
  rn_network *net = crossing2(ctx, zb, ra, rb, dhat, kappa, RN_OK);
  double x[MAXN], d[MAXN];
  size_t n = rn_network_num_dofs(net);
  rn_contact_stats cs;
  CHECK_NEAR(rn_network_rod_contact_radius(net, 0), ra, 0.0);
  CHECK_NEAR(rn_network_rod_contact_radius(net, 1), rb, 0.0);
  CHECK(isnan(rn_network_rod_contact_radius(net, 2)));
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_contact_stats(net, x, &cs), RN_OK);
  CHECK_NEAR(cs.min_gap, 0.02, 1e-15);
  CHECK(cs.active == 1);
  CHECK_NEAR(cs.energy, -kappa * 0.03 * 0.03 * log(0.4), 1e-15);
  for (size_t i = 0; i < n; ++i) {
    x[i] += 0.002 * rn_test_rand(&rng);
    d[i] = rn_test_rand(&rng);
  }
  fd_sweep(net, x, d, "per-rod radius");
  CHECK_STATUS(rn_network_set_rod_contact_radius(net, 0, 0.1), RN_ERR_STATE);
  rn_network_destroy(&net);
  /* with rb the start interpenetrates */
  crossing2(ctx, ra + 0.02 + 0.01, ra, 0.021 + 0.01, dhat, kappa, RN_ERR_GEOMETRY);
  {
    rn_network *bad = NULL;
    double xyz[6] = {0, 0, 0, 1, 0, 0};
    int rod;
    CHECK_STATUS(rn_network_create(ctx, &bad), RN_OK);
    CHECK_STATUS(rn_network_add_rod(bad, "a", 2, xyz, NULL, &rod), RN_OK);
    CHECK_STATUS(rn_network_set_rod_contact_radius(bad, 0, 0.1), RN_ERR_STATE);
    CHECK_STATUS(rn_network_set_contact(bad, 0.1, 1.0, 0.1), RN_OK);
    CHECK_STATUS(rn_network_set_rod_contact_radius(bad, 1, 0.1), RN_ERR_ARG);
    CHECK_STATUS(rn_network_set_rod_contact_radius(bad, 0, -0.1), RN_ERR_ARG);
    CHECK_STATUS(rn_network_set_rod_contact_radius(bad, 0, INFINITY), RN_ERR_ARG);
    CHECK_STATUS(rn_network_set_rod_contact_radius(bad, 0, 0.2), RN_OK);
    CHECK_NEAR(rn_network_rod_contact_radius(bad, 0), 0.2, 0.0);
    rn_network_destroy(&bad);
  }
}

/* A k x k grid of crossings (rods of 4 (k + 2) edges of length 0.25 at spacing
 * 1, crossing at edge midpoints away from the clamped starts, the layers at
 * half dhat): the contact entries of
 * the Hessian pattern (nnz with contact minus without) grow like the number
 * of crossings, k^2, not like the square of the contact vertices. */
static size_t grid_nnz(rn_context *ctx, int k, int contact) {
  enum { MAXV = 41 };
  const double r = 0.01, dhat = 0.02, z = 2 * r + 0.5 * dhat;
  rn_material m = {1e3, 4e2, 0.0};
  rn_section s;
  rn_network *net = NULL;
  double xyz[3 * MAXV];
  const int nv = 4 * (k + 2) + 1;
  int rod;
  size_t nnz;
  const int64_t *rp;
  const int32_t *cl;
  CHECK(nv <= MAXV);
  CHECK_STATUS(rn_section_circle(r, &s), RN_OK);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  for (int layer = 0; layer < 2; ++layer)
    for (int j = 0; j < k; ++j) {
      const double c = 1.625 + j; /* the middle of an edge of the other layer */
      for (int i = 0; i < nv; ++i) {
        const double t = 0.25 * i;
        xyz[3 * i] = layer ? c : t;
        xyz[3 * i + 1] = layer ? t : c;
        xyz[3 * i + 2] = layer ? z : 0.0;
      }
      const int id = layer * k + j;
      CHECK_STATUS(rn_network_add_rod(net, NULL, nv, xyz, NULL, &rod), RN_OK);
      CHECK_STATUS(rn_network_set_material(net, id, -1, &m), RN_OK);
      CHECK_STATUS(rn_network_set_section(net, id, -1, &s), RN_OK);
      CHECK_STATUS(rn_network_clamp(net, id, RN_START), RN_OK);
    }
  if (contact) CHECK_STATUS(rn_network_set_contact(net, dhat, 1.0, r), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK_STATUS(rn_network_hessian_pattern(net, &nnz, &rp, &cl), RN_OK);
  if (contact) {
    double *x = malloc(rn_network_num_dofs(net) * sizeof(double));
    rn_contact_stats cs;
    CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
    CHECK_STATUS(rn_network_contact_stats(net, x, &cs), RN_OK);
    CHECK(cs.active == (size_t)(k * k)); /* every crossing one active pair */
    free(x);
  }
  rn_network_destroy(&net);
  return nnz;
}

static void test_pattern_linear(rn_context *ctx) {
  const int ks[3] = {2, 4, 8};
  size_t extra[3];
  for (int i = 0; i < 3; ++i) {
    size_t on = grid_nnz(ctx, ks[i], 1), off = grid_nnz(ctx, ks[i], 0);
    CHECK(on > off);
    extra[i] = on - off;
    printf("  grid %d x %d: Hessian entries %zu with contact, %zu without (%zu per "
           "crossing)\n",
           ks[i], ks[i], on, off, extra[i] / (size_t)(ks[i] * ks[i]));
  }
  for (int i = 1; i < 3; ++i)
    CHECK(extra[i] * (size_t)(ks[0] * ks[0]) == extra[0] * (size_t)(ks[i] * ks[i]));
}

int main(void) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  test_crossing(ctx);
  test_hairpin(ctx);
  test_pattern_change(ctx);
  test_rod_radius(ctx);
  test_pattern_linear(ctx);
  rn_context_destroy(&ctx);
  return rn_test_finish("api_contact");
}

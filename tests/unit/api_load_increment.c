/* api_load_increment.c - rn_network_load_increment against finite differences
 * of the gradient in the load factor at a random deformed state:
 *   e(h) = || g(x; t0 + h) - g(x; t0) - dg(t0, t0 + h) ||
 * falls as h^2 (fitted order in [1.9, 2.1]) for h = 1e-2 ... 1.56e-4 (halving) on
 *  (a) a rod with a pinned displaced end, dead forces and a couple;
 *  (b) a rod with a clamped end with prescribed translation and rotation;
 *  (c) three rods and three joints, both joint models: a pinned joint with a
 *      displacement, a clamped joint with prescribed rotation and translation,
 *      a free joint with a force and a couple, a dead force on a rod.
 * Also: dg = 0 for t == t_prev, the load factor and the state unchanged by the
 * call, and the error paths (NULL, non-finite or out-of-range load factor). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "testutil.h"

enum { N_H = 7, NV = 6 };

static uint64_t rng = 20261122;

static double urand(void) { return rn_test_rand(&rng); }

static void rod_xyz(double x0, double y0, double dx, double dy, int nv, double *xyz) {
  for (int i = 0; i < nv; ++i) {
    xyz[3 * i] = x0 + dx * i / (nv - 1);
    xyz[3 * i + 1] = y0 + dy * i / (nv - 1);
    xyz[3 * i + 2] = 0.03 * sin(1.3 * i);
  }
}

static void set_props(rn_network *net, int rod) {
  rn_material m;
  rn_section s;
  CHECK_STATUS(rn_material_from_E_nu(1e4, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_ellipse(0.04, 0.025, &s), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
}

static int add_rod(rn_network *net, double x0, double y0, double dx, double dy) {
  double xyz[3 * NV];
  int rod = -1;
  rod_xyz(x0, y0, dx, dy, NV, xyz);
  CHECK_STATUS(rn_network_add_rod(net, NULL, NV, xyz, NULL, &rod), RN_OK);
  set_props(net, rod);
  return rod;
}

/* (a) pinned displaced end, forces, a couple. */
static void build_pinned(rn_network *net) {
  const double d[3] = {0.1, -0.05, 0.08}, f[3] = {0.3, 0.7, -0.4},
               m[3] = {0.2, -0.1, 0.3};
  int r = add_rod(net, 0.0, 0.0, 1.0, 0.2);
  CHECK_STATUS(rn_network_pin(net, r, 0), RN_OK);
  CHECK_STATUS(rn_network_displace_vertex(net, r, 0, d), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, r, -1, f), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, r, 2, m), RN_OK);
  CHECK_STATUS(rn_network_add_moment(net, r, 3, m), RN_OK);
}

/* (b) clamped end with prescribed translation and rotation. */
static void build_clamped(rn_network *net) {
  const double d[3] = {0.05, 0.1, -0.07}, w[3] = {0.4, -0.3, 0.6}, f[3] = {0, 0, -0.5};
  int r = add_rod(net, 0.0, 0.0, 1.0, -0.1);
  CHECK_STATUS(rn_network_clamp(net, r, RN_START), RN_OK);
  CHECK_STATUS(rn_network_displace_end(net, r, RN_START, d, w), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, r, -1, f), RN_OK);
}

/* (c) joints: J0 pinned and displaced where three rods meet, J1 clamped with
 * prescribed motion, J2 free with a force and a couple. */
static void build_joints(rn_network *net, rn_joint_model model) {
  const double d0[3] = {0.05, -0.04, 0.06}, d1[3] = {-0.03, 0.05, 0.02};
  const double w1[3] = {0.3, 0.5, -0.2}, f2[3] = {0.2, -0.3, 0.4},
               m2[3] = {0.1, 0.2, -0.15};
  const double fr[3] = {0.0, 0.1, 0.3};
  int r0 = add_rod(net, 0.0, 0.0, 1.0, 0.1), r1 = add_rod(net, 0.0, 0.0, -0.1, 1.0);
  int r2 = add_rod(net, 0.0, 0.0, -0.7, -0.7), j0 = -1, j1 = -1, j2 = -1;
  int rods0[3] = {r0, r1, r2}, ends0[3] = {RN_START, RN_START, RN_START};
  CHECK_STATUS(rn_network_add_joint(net, "J0", model, 3, rods0, ends0, &j0), RN_OK);
  CHECK_STATUS(rn_network_add_joint(net, "J1", model, 1, &r0, (int[]){RN_END}, &j1),
               RN_OK);
  CHECK_STATUS(rn_network_add_joint(net, "J2", model, 1, &r1, (int[]){RN_END}, &j2),
               RN_OK);
  CHECK_STATUS(rn_network_pin_joint(net, j0), RN_OK);
  CHECK_STATUS(rn_network_displace_joint(net, j0, d0, NULL), RN_OK);
  CHECK_STATUS(rn_network_clamp_joint(net, j1), RN_OK);
  CHECK_STATUS(rn_network_displace_joint(net, j1, d1, w1), RN_OK);
  CHECK_STATUS(rn_network_add_joint_force(net, j2, f2), RN_OK);
  CHECK_STATUS(rn_network_add_joint_moment(net, j2, m2), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, r2, -2, fr), RN_OK);
  CHECK_STATUS(rn_network_pin(net, r2, -1), RN_OK);
}

static double diff_norm(size_t n, const double *g1, const double *g0, const double *dg) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) {
    double d = g1[i] - g0[i] - dg[i];
    s += d * d;
  }
  return sqrt(s);
}

static void sweep(rn_network *net, const char *name) {
  const double t0 = 0.4;
  size_t n = rn_network_num_dofs(net);
  double *x = malloc(n * sizeof(double)), *g0 = malloc(n * sizeof(double));
  double *g1 = malloc(n * sizeof(double)), *dg = malloc(n * sizeof(double));
  double h[N_H], e[N_H], E0, E1, order;
  CHECK_STATUS(rn_network_set_load_factor(net, t0), RN_OK);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  for (size_t i = 0; i < n; ++i) x[i] += 0.02 * urand();
  CHECK_STATUS(rn_network_gradient(net, x, &E0, g0), RN_OK);
  for (int k = 0; k < N_H; ++k) {
    h[k] = 1e-2 / pow(2.0, k);
    CHECK_STATUS(rn_network_load_increment(net, x, t0, t0 + h[k], dg), RN_OK);
    CHECK(rn_network_load_factor(net) == t0);
    CHECK_STATUS(rn_network_set_load_factor(net, t0 + h[k]), RN_OK);
    CHECK_STATUS(rn_network_gradient(net, x, NULL, g1), RN_OK);
    CHECK_STATUS(rn_network_set_load_factor(net, t0), RN_OK);
    e[k] = diff_norm(n, g1, g0, dg);
  }
  order = rn_test_loglog_slope(N_H, h, e);
  printf("%-16s h = %.3g: e = %.3e ... h = %.3g: e = %.3e, order %.3f\n", name, h[0],
         e[0], h[N_H - 1], e[N_H - 1], order);
  CHECK(order >= 1.9 && order <= 2.1);
  /* no increment: dg = 0; state and load factor untouched (bitwise) */
  CHECK_STATUS(rn_network_energy(net, x, &E0), RN_OK);
  CHECK_STATUS(rn_network_load_increment(net, x, t0, t0, dg), RN_OK);
  for (size_t i = 0; i < n; ++i) CHECK(dg[i] == 0.0);
  CHECK_STATUS(rn_network_energy(net, x, &E1), RN_OK);
  CHECK(E1 == E0);
  CHECK_STATUS(rn_network_load_increment(net, x, 0.0, 1.0, dg), RN_OK);
  CHECK_STATUS(rn_network_energy(net, x, &E1), RN_OK);
  CHECK(E1 == E0);
  CHECK(rn_network_load_factor(net) == t0);
  free(x);
  free(g0);
  free(g1);
  free(dg);
}

static void errors(rn_network *net) {
  size_t n = rn_network_num_dofs(net);
  double *x = calloc(n, sizeof(double)), *dg = calloc(n, sizeof(double));
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_load_increment(NULL, x, 0.0, 1.0, dg), RN_ERR_ARG);
  CHECK_STATUS(rn_network_load_increment(net, NULL, 0.0, 1.0, dg), RN_ERR_ARG);
  CHECK_STATUS(rn_network_load_increment(net, x, 0.0, 1.0, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_load_increment(net, x, NAN, 1.0, dg), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_load_increment(net, x, 0.0, INFINITY, dg), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_load_increment(net, x, -0.1, 1.0, dg), RN_ERR_ARG);
  CHECK_STATUS(rn_network_load_increment(net, x, 0.0, 1.5, dg), RN_ERR_ARG);
  x[0] = NAN;
  CHECK_STATUS(rn_network_load_increment(net, x, 0.0, 1.0, dg), RN_ERR_NOT_FINITE);
  free(x);
  free(dg);
}

typedef void (*builder)(rn_network *net);

static void build_rigid(rn_network *net) { build_joints(net, RN_JOINT_RIGID); }
static void build_elastic(rn_network *net) { build_joints(net, RN_JOINT_ELASTIC); }

int main(void) {
  const builder builders[] = {build_pinned, build_clamped, build_rigid, build_elastic};
  const char *names[] = {"pinned+loads", "clamped+motion", "joints rigid",
                         "joints elastic"};
  for (int b = 0; b < 4; ++b) {
    rn_context *ctx = NULL;
    rn_network *net = NULL;
    CHECK_STATUS(rn_context_create(&ctx), RN_OK);
    CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
    builders[b](net);
    CHECK_STATUS(rn_network_finalize(net), RN_OK);
    sweep(net, names[b]);
    if (b == 0) errors(net);
    rn_network_destroy(&net);
    rn_context_destroy(&ctx);
  }
  {
    rn_context *ctx = NULL;
    rn_network *net = NULL;
    double x[1] = {0.0}, dg[1];
    CHECK_STATUS(rn_context_create(&ctx), RN_OK);
    CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
    CHECK_STATUS(rn_network_load_increment(net, x, 0.0, 1.0, dg), RN_ERR_STATE);
    rn_network_destroy(&net);
    rn_context_destroy(&ctx);
  }
  return rn_test_finish("api_load_increment");
}

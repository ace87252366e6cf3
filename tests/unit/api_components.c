/* api_components.c - component pins (rn_network_pin_components,
 * rn_network_pin_joint_components):
 *  - the reduced DOF count drops by exactly the fixed components, and the
 *    fixed ones are those named: moving every reduced DOF moves the free
 *    components of a component-pinned joint / vertex and not the fixed ones;
 *  - repeated pins and pin + component pin + clamp add up (union), and a
 *    full component pin gives the same DOFs, energy and gradient as a pin;
 *  - a prescribed displacement acts on the fixed components, under the load
 *    factor; a non-zero displacement on a free component is RN_ERR_BC at
 *    finalize with a message naming the component; bad bitmasks RN_ERR_ARG;
 *  - the CSR pattern stays valid (sorted, in range, bandwidth) and the
 *    derivative self-test (gradient and HVP vs central differences, Hessian
 *    symmetry, CSR vs HVP) passes on a network with component pins, both
 *    joint models. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "testutil.h"

enum { NV = 5 }; /* vertices per rod */

static rn_context *ctx;

static int contains(const char *s, const char *sub) { return strstr(s, sub) != NULL; }

/* A straight rod of NV vertices from a to b with d1 = +z. */
static int add_rod(rn_network *net, const double a[3], const double b[3]) {
  double xyz[3 * NV], d1[3] = {0, 0, 1};
  rn_material m;
  rn_section s;
  int rod = -1;
  for (int i = 0; i < NV; ++i)
    for (int k = 0; k < 3; ++k)
      xyz[3 * i + k] = a[k] + (b[k] - a[k]) * (double)i / (NV - 1);
  CHECK_STATUS(rn_network_add_rod(net, NULL, NV, xyz, d1, &rod), RN_OK);
  CHECK_STATUS(rn_material_from_E_nu(1e3, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_ellipse(0.03, 0.02, &s), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
  return rod;
}

/* An L of two rods, a: (0,0,0)-(1,0,0) and b: (1,0,0)-(1,1,0.2), joined at
 * joint 0 (model); the start of a is free for the caller's BCs. */
static rn_network *make_l(rn_joint_model model) {
  rn_network *net = NULL;
  double p[3] = {0, 0, 0}, q[3] = {1, 0, 0}, r[3] = {1, 1, 0.2};
  int rods[2], ends[2] = {RN_END, RN_START}, j = -1;
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  rods[0] = add_rod(net, p, q);
  rods[1] = add_rod(net, q, r);
  CHECK_STATUS(rn_network_add_joint(net, "J", model, 2, rods, ends, &j), RN_OK);
  CHECK(j == 0);
  return net;
}

/* Moves every reduced DOF by delta; returns the joint position and the first
 * vertex of rod 0 after the move. */
static void shift_all(rn_network *net, double delta, double xj[3], double x0[3]) {
  size_t n = rn_network_num_dofs(net);
  double *x = malloc(n * sizeof(double)), xyz[3 * NV];
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  for (size_t i = 0; i < n; ++i) x[i] += delta;
  CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_joint_position(net, 0, xj), RN_OK);
  CHECK_STATUS(rn_network_rod_vertices(net, 0, xyz), RN_OK);
  memcpy(x0, xyz, 3 * sizeof(double));
  free(x);
}

/* DOF counts and which components are fixed. */
static void test_counts_and_fixed(void) {
  rn_network *net = make_l(RN_JOINT_ELASTIC);
  size_t nfree;
  double xj[3], x0[3];
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  nfree = rn_network_num_dofs(net); /* nothing fixed */
  rn_network_destroy(&net);

  net = make_l(RN_JOINT_ELASTIC);
  CHECK_STATUS(rn_network_pin_joint_components(net, 0, RN_FIX_X), RN_OK);
  CHECK_STATUS(rn_network_pin_components(net, 0, 0, RN_FIX_Y | RN_FIX_Z), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK(rn_network_num_dofs(net) == nfree - 3);
  shift_all(net, 0.01, xj, x0);
  CHECK(xj[0] == 1.0);            /* x fixed */
  CHECK_NEAR(xj[1], 0.01, 1e-15); /* y, z free */
  CHECK_NEAR(xj[2], 0.01, 1e-15);
  CHECK_NEAR(x0[0], 0.01, 1e-15);      /* x free */
  CHECK(x0[1] == 0.0 && x0[2] == 0.0); /* y, z fixed */
  /* the rod end at the joint aliases it: all three coordinates agree */
  {
    double xyz[3 * NV];
    CHECK_STATUS(rn_network_rod_vertices(net, 0, xyz), RN_OK);
    for (int k = 0; k < 3; ++k) CHECK(xyz[3 * (NV - 1) + k] == xj[k]);
  }
  rn_network_destroy(&net);

  /* union: y then z then x again, and a clamp over a component pin */
  net = make_l(RN_JOINT_ELASTIC);
  CHECK_STATUS(rn_network_pin_joint_components(net, 0, RN_FIX_Y), RN_OK);
  CHECK_STATUS(rn_network_pin_joint_components(net, 0, RN_FIX_Z | RN_FIX_Y), RN_OK);
  CHECK_STATUS(rn_network_pin_components(net, 0, 1, RN_FIX_Z), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, 0, RN_START), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  /* joint: y, z; start clamp: 2 vertices and 1 angle (vertex 1's z pin is inside) */
  CHECK(rn_network_num_dofs(net) == nfree - 2 - 7);
  shift_all(net, 0.01, xj, x0);
  CHECK_NEAR(xj[0], 1.01, 1e-15);
  CHECK(xj[1] == 0.0 && xj[2] == 0.0);
  rn_network_destroy(&net);

  /* pin + component pin = pin */
  net = make_l(RN_JOINT_RIGID);
  CHECK_STATUS(rn_network_pin_joint(net, 0), RN_OK);
  CHECK_STATUS(rn_network_pin_joint_components(net, 0, RN_FIX_X), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  {
    rn_network *ref = make_l(RN_JOINT_RIGID);
    CHECK_STATUS(rn_network_pin_joint(ref, 0), RN_OK);
    CHECK_STATUS(rn_network_finalize(ref), RN_OK);
    CHECK(rn_network_num_dofs(net) == rn_network_num_dofs(ref));
    rn_network_destroy(&ref);
  }
  rn_network_destroy(&net);
}

/* A full component pin (in two steps) is exactly a pin: same reduced vector,
 * energy and gradient, bit for bit, also with a prescribed displacement. */
static void test_full_equals_pin(void) {
  rn_network *a = make_l(RN_JOINT_RIGID), *b = make_l(RN_JOINT_RIGID);
  double d[3] = {0.05, -0.02, 0.01};
  CHECK_STATUS(rn_network_pin_joint(a, 0), RN_OK);
  CHECK_STATUS(rn_network_pin(a, 0, 0), RN_OK);
  CHECK_STATUS(rn_network_displace_joint(a, 0, d, NULL), RN_OK);
  CHECK_STATUS(rn_network_pin_joint_components(b, 0, RN_FIX_X | RN_FIX_Z), RN_OK);
  CHECK_STATUS(rn_network_pin_joint_components(b, 0, RN_FIX_Y), RN_OK);
  CHECK_STATUS(rn_network_pin_components(b, 0, 0, RN_FIX_XYZ), RN_OK);
  CHECK_STATUS(rn_network_displace_joint(b, 0, d, NULL), RN_OK);
  CHECK_STATUS(rn_network_finalize(a), RN_OK);
  CHECK_STATUS(rn_network_finalize(b), RN_OK);
  size_t n = rn_network_num_dofs(a);
  CHECK(n == rn_network_num_dofs(b));
  if (n == rn_network_num_dofs(b)) {
    double *x = malloc(n * sizeof(double)), *y = malloc(n * sizeof(double));
    double *ga = malloc(n * sizeof(double)), *gb = malloc(n * sizeof(double));
    double Ea, Eb;
    uint64_t seed = 7;
    CHECK_STATUS(rn_network_get_dofs(a, x), RN_OK);
    CHECK_STATUS(rn_network_get_dofs(b, y), RN_OK);
    CHECK(memcmp(x, y, n * sizeof(double)) == 0);
    for (size_t i = 0; i < n; ++i) x[i] += 0.01 * rn_test_rand(&seed);
    CHECK_STATUS(rn_network_gradient(a, x, &Ea, ga), RN_OK);
    CHECK_STATUS(rn_network_gradient(b, x, &Eb, gb), RN_OK);
    CHECK(Ea == Eb && Ea > 0.0);
    CHECK(memcmp(ga, gb, n * sizeof(double)) == 0);
    CHECK(rn_network_hessian_bandwidth(a) == rn_network_hessian_bandwidth(b));
    free(x), free(y), free(ga), free(gb);
  }
  rn_network_destroy(&a);
  rn_network_destroy(&b);
}

/* Prescribed displacement of a component-pinned joint and vertex. */
static void test_displacement(void) {
  rn_network *net = make_l(RN_JOINT_ELASTIC);
  double d[3] = {0.1, 0.0, 0.0}, dv[3] = {0.0, 0.0, -0.03}, xj[3], xyz[3 * NV];
  CHECK_STATUS(rn_network_pin_joint_components(net, 0, RN_FIX_X), RN_OK);
  CHECK_STATUS(rn_network_displace_joint(net, 0, d, NULL), RN_OK);
  CHECK_STATUS(rn_network_pin_components(net, 0, 0, RN_FIX_Z), RN_OK);
  CHECK_STATUS(rn_network_displace_vertex(net, 0, 0, dv), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK_STATUS(rn_network_joint_position(net, 0, xj), RN_OK);
  CHECK(xj[0] == 1.1 && xj[1] == 0.0 && xj[2] == 0.0);
  CHECK_STATUS(rn_network_rod_vertices(net, 0, xyz), RN_OK);
  CHECK(xyz[0] == 0.0 && xyz[1] == 0.0 && xyz[2] == -0.03);
  CHECK_STATUS(rn_network_set_load_factor(net, 0.5), RN_OK);
  CHECK_STATUS(rn_network_joint_position(net, 0, xj), RN_OK);
  CHECK_NEAR(xj[0], 1.05, 1e-15);
  CHECK_STATUS(rn_network_rod_vertices(net, 0, xyz), RN_OK);
  CHECK_NEAR(xyz[2], -0.015, 1e-15);
  /* the free components keep the state through a load factor change */
  {
    double a[3], b[3];
    shift_all(net, 0.02, a, b);
    CHECK_STATUS(rn_network_set_load_factor(net, 1.0), RN_OK);
    CHECK_STATUS(rn_network_joint_position(net, 0, xj), RN_OK);
    CHECK_NEAR(xj[0], 1.1, 1e-15);
    CHECK(xj[1] == a[1] && xj[2] == a[2]);
  }
  rn_network_destroy(&net);
}

/* One BC case at finalize: a component pin (mask) of joint 0 (on_joint) or of
 * vertex 0 of rod 0, a displacement value along axis (for joints a rotation
 * about x instead if rotate), the expected status and a substring of its
 * message (NULL: not checked). */
typedef struct bc_case {
  int model, on_joint, mask, axis;
  double value;
  int rotate;
  rn_status expect;
  const char *msg;
} bc_case;

static void check_bc_case(const bc_case *c) {
  rn_network *net = make_l((rn_joint_model)c->model);
  double d[3] = {0, 0, 0}, zero[3] = {0, 0, 0};
  d[c->axis] = c->value;
  if (c->on_joint) {
    CHECK_STATUS(rn_network_pin_joint_components(net, 0, c->mask), RN_OK);
    CHECK_STATUS(
        rn_network_displace_joint(net, 0, c->rotate ? zero : d, c->rotate ? d : zero),
        RN_OK);
  } else {
    CHECK_STATUS(rn_network_pin_components(net, 0, 0, c->mask), RN_OK);
    CHECK_STATUS(rn_network_displace_vertex(net, 0, 0, d), RN_OK);
  }
  CHECK_STATUS(rn_network_finalize(net), c->expect);
  if (c->msg) CHECK(contains(rn_context_last_error(ctx), c->msg));
  rn_network_destroy(&net);
}

/* Errors: displacement on a free component, bad bitmasks. */
static void test_errors(void) {
  static const bc_case cases[] = {
      {RN_JOINT_ELASTIC, 1, RN_FIX_X | RN_FIX_Z, 1, 0.1, 0, RN_ERR_BC,
       "joint 0 ('J'): prescribed displacement 0.1 along y, which is free (the joint "
       "is pinned in xz only)"},
      {RN_JOINT_ELASTIC, 0, RN_FIX_Y, 0, 0.2, 0, RN_ERR_BC,
       "vertex 0: prescribed displacement 0.2 along x, which is free (the vertex is "
       "pinned in y only)"},
      /* displacements on the fixed components only are fine */
      {RN_JOINT_ELASTIC, 0, RN_FIX_X, 0, 0.2, 0, RN_OK, NULL},
      {RN_JOINT_RIGID, 1, RN_FIX_Y, 1, -0.2, 0, RN_OK, NULL},
      /* a rotation still needs a clamp */
      {RN_JOINT_RIGID, 1, RN_FIX_XYZ, 0, 0.2, 1, RN_ERR_BC, "not clamped"},
  };
  rn_network *net;
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i) check_bc_case(&cases[i]);

  net = make_l(RN_JOINT_ELASTIC);
  CHECK_STATUS(rn_network_pin_joint_components(net, 0, 0), RN_ERR_ARG);
  CHECK(contains(rn_context_last_error(ctx), "got 0"));
  CHECK_STATUS(rn_network_pin_joint_components(net, 0, 8), RN_ERR_ARG);
  CHECK_STATUS(rn_network_pin_joint_components(net, 0, -1), RN_ERR_ARG);
  CHECK_STATUS(rn_network_pin_joint_components(net, 1, RN_FIX_X), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_pin_components(net, 0, 0, 0), RN_ERR_ARG);
  CHECK_STATUS(rn_network_pin_components(net, 0, NV, RN_FIX_X), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_pin_components(net, 2, 0, RN_FIX_X), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_pin_components(NULL, 0, 0, RN_FIX_X), RN_ERR_ARG);
  CHECK_STATUS(rn_network_pin_joint_components(NULL, 0, RN_FIX_X), RN_ERR_ARG);
  /* a component pin of a rod end at a joint is rejected like a pin */
  CHECK_STATUS(rn_network_pin_components(net, 0, -1, RN_FIX_X), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_ERR_BC);
  CHECK(contains(rn_context_last_error(ctx), "belongs to joint 0"));
  rn_network_destroy(&net);

  /* frozen after finalize */
  net = make_l(RN_JOINT_ELASTIC);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK_STATUS(rn_network_pin_joint_components(net, 0, RN_FIX_X), RN_ERR_STATE);
  CHECK_STATUS(rn_network_pin_components(net, 0, 0, RN_FIX_X), RN_ERR_STATE);
  rn_network_destroy(&net);
}

/* The CSR pattern is sorted, in range, symmetric in size; bandwidth matches. */
static void check_pattern(const rn_network *net) {
  size_t nnz = 0, n = rn_network_num_dofs(net), bw = 0;
  const int64_t *rowptr = NULL;
  const int32_t *col = NULL;
  int ok = 1;
  CHECK_STATUS(rn_network_hessian_pattern(net, &nnz, &rowptr, &col), RN_OK);
  CHECK(rowptr[0] == 0 && (size_t)rowptr[n] == nnz);
  for (size_t i = 0; i < n; ++i)
    for (int64_t p = rowptr[i]; p < rowptr[i + 1]; ++p) {
      ok &= col[p] >= 0 && (size_t)col[p] < n;
      ok &= p == rowptr[i] || col[p] > col[p - 1];
      size_t d = (size_t)col[p] > i ? (size_t)col[p] - i : i - (size_t)col[p];
      if (d > bw) bw = d;
    }
  CHECK(ok);
  CHECK(bw == rn_network_hessian_bandwidth(net));
}

/* Derivative self-test on a network with component pins and a prescribed
 * component displacement, both joint models. */
static void test_self_check(void) {
  for (int model = RN_JOINT_ELASTIC; model <= RN_JOINT_RIGID; ++model) {
    rn_network *net = make_l((rn_joint_model)model);
    double d[3] = {0.0, 0.0, 0.05}, f[3] = {0.3, -0.2, 0.1};
    rn_check_report rep;
    CHECK_STATUS(rn_network_pin_joint_components(net, 0, RN_FIX_Z), RN_OK);
    CHECK_STATUS(rn_network_displace_joint(net, 0, d, NULL), RN_OK);
    CHECK_STATUS(rn_network_pin_components(net, 0, 0, RN_FIX_X | RN_FIX_Y), RN_OK);
    CHECK_STATUS(rn_network_pin_components(net, 0, 1, RN_FIX_Y), RN_OK);
    CHECK_STATUS(rn_network_pin_components(net, 1, -1, RN_FIX_X | RN_FIX_Z), RN_OK);
    CHECK_STATUS(rn_network_add_force(net, 1, 2, f), RN_OK);
    CHECK_STATUS(rn_network_finalize(net), RN_OK);
    check_pattern(net);
    CHECK_STATUS(rn_network_check_derivatives(net, NULL, 3, 0.05, 11, &rep), RN_OK);
    printf(
        "model %d: grad %.2e (order %.2f), hvp %.2e (order %.2f), sym %.1e, csr %.1e\n",
        model, rep.grad_rel_err, rep.grad_order, rep.hvp_rel_err, rep.hvp_order,
        rep.hess_sym_err, rep.hess_hvp_err);
    CHECK(rep.grad_rel_err < 1e-6);
    CHECK(rep.hvp_rel_err < 1e-6);
    CHECK(rep.hess_sym_err < 1e-12);
    CHECK(rep.hess_hvp_err < 1e-12);
    CHECK(rep.grad_order > 1.5 && rep.hvp_order > 1.5);
    rn_network_destroy(&net);
  }
}

int main(void) {
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  test_counts_and_fixed();
  test_full_equals_pin();
  test_displacement();
  test_errors();
  test_self_check();
  rn_context_destroy(&ctx);
  return rn_test_finish("api_components");
}

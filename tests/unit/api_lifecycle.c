/* api_lifecycle.c - lifecycle of context and network, sizes, DOF map,
 * Hessian pattern, frames, and every error path of the C API. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "testutil.h"

static rn_material steel(void) {
  rn_material m = {1.0e7, 4.0e6, 1.0};
  return m;
}

static rn_section wire(void) {
  rn_section s;
  rn_section_circle(0.01, &s);
  return s;
}

/* Straight rod along x, nv vertices, spacing h. */
static void straight(int nv, double h, double *xyz) {
  for (int i = 0; i < nv; ++i) {
    xyz[3 * i] = h * i;
    xyz[3 * i + 1] = 0.0;
    xyz[3 * i + 2] = 0.0;
  }
}

/* A network with one straight rod, material and section set. */
static rn_network *simple(rn_context *ctx, int nv) {
  rn_network *net = NULL;
  double xyz[3 * 64];
  rn_material m = steel();
  rn_section s = wire();
  int rod = -1;
  straight(nv, 0.1, xyz);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "beam", nv, xyz, NULL, &rod), RN_OK);
  CHECK(rod == 0);
  CHECK_STATUS(rn_network_set_material(net, 0, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, 0, -1, &s), RN_OK);
  return net;
}

static int contains(const char *hay, const char *needle) {
  return strstr(hay, needle) != NULL;
}

static void test_status_and_version(void) {
  int a = -1, b = -1, c = -1;
  CHECK(strcmp(rn_status_name(RN_ERR_ARG), "RN_ERR_ARG") == 0);
  CHECK(strcmp(rn_status_name(RN_DEGENERATE), "RN_DEGENERATE") == 0);
  CHECK(strcmp(rn_status_message(RN_ERR_ALLOC), "out of memory") == 0);
  CHECK(rn_status_name((rn_status)99) != NULL);
  CHECK(rn_status_message((rn_status)-99) != NULL);
  CHECK(strcmp(rn_version_string(), RODNET_VERSION_STRING) == 0);
  rn_version(&a, &b, &c);
  CHECK(a == RODNET_VERSION_MAJOR && b == RODNET_VERSION_MINOR &&
        c == RODNET_VERSION_PATCH);
  rn_version(NULL, NULL, NULL);
}

static void test_context(void) {
  rn_context *ctx = NULL;
  rn_context_destroy(NULL);
  rn_context_destroy(&ctx);
  CHECK_STATUS(rn_context_create(NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  CHECK(ctx != NULL);
  CHECK(strcmp(rn_context_last_error(ctx), "") == 0);
  CHECK_STATUS(rn_context_set_error(ctx, RN_ERR_PARSE, "scene.json: %s at %d", "bad", 7),
               RN_ERR_PARSE);
  CHECK(strcmp(rn_context_last_error(ctx), "scene.json: bad at 7") == 0);
  rn_context_clear_error(ctx);
  CHECK(strcmp(rn_context_last_error(ctx), "") == 0);
  CHECK_STATUS(rn_context_set_error(NULL, RN_ERR_IO, "x"), RN_ERR_IO);
  CHECK(strcmp(rn_context_last_error(NULL), "") == 0);
  rn_context_clear_error(NULL);
  rn_context_destroy(&ctx);
  CHECK(ctx == NULL);
}

/* Every function given a NULL network handle. */
static void test_null_handles(void) {
  double v[3] = {0, 0, 0}, E = 0.0;
  size_t nnz;
  const int64_t *rp;
  const int32_t *cl;
  rn_material m = steel();
  rn_section s = wire();
  rn_check_report rep;
  rn_network *net = NULL;
  rn_network_destroy(NULL);
  rn_network_destroy(&net);
  CHECK_STATUS(rn_network_create(NULL, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_add_rod(NULL, "a", 2, v, NULL, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_set_material(NULL, 0, -1, &m), RN_ERR_ARG);
  CHECK_STATUS(rn_network_set_section(NULL, 0, -1, &s), RN_ERR_ARG);
  CHECK_STATUS(rn_network_set_rest_curvature(NULL, 0, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_set_rest_twist(NULL, 0, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_set_rest_lengths(NULL, 0, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_clamp(NULL, 0, RN_START), RN_ERR_ARG);
  CHECK_STATUS(rn_network_pin(NULL, 0, 0), RN_ERR_ARG);
  CHECK_STATUS(rn_network_fix_theta(NULL, 0, 0), RN_ERR_ARG);
  CHECK_STATUS(rn_network_displace_end(NULL, 0, RN_END, v, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_displace_vertex(NULL, 0, 0, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_add_force(NULL, 0, 0, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_add_moment(NULL, 0, 0, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_add_line_load(NULL, 0, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_add_gravity(NULL, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_finalize(NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_set_load_factor(NULL, 0.5), RN_ERR_ARG);
  CHECK(rn_network_load_factor(NULL) == 0.0);
  CHECK(rn_network_num_dofs(NULL) == 0);
  CHECK(rn_network_num_full_dofs(NULL) == 0);
  CHECK(rn_network_num_rods(NULL) == 0);
  CHECK(rn_network_rod_num_vertices(NULL, 0) == 0);
  CHECK(rn_network_rod_name(NULL, 0) != NULL);
  CHECK(rn_network_context(NULL) == NULL);
  CHECK_STATUS(rn_network_get_dofs(NULL, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_set_dofs(NULL, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_energy(NULL, v, &E), RN_ERR_ARG);
  CHECK_STATUS(rn_network_gradient(NULL, v, &E, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_hvp(NULL, v, v, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_energy_terms(NULL, v, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_hessian_pattern(NULL, &nnz, &rp, &cl), RN_ERR_ARG);
  CHECK_STATUS(rn_network_hessian_values(NULL, v, v), RN_ERR_ARG);
  CHECK(rn_network_hessian_bandwidth(NULL) == 0);
  CHECK_STATUS(rn_network_update_reference(NULL, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_rod_vertices(NULL, 0, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_rod_theta(NULL, 0, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_rod_initial_vertices(NULL, 0, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_rod_frames(NULL, 0, v, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_rod_strains(NULL, 0, v, v, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_check_derivatives(NULL, NULL, 0, 0.0, 1, &rep), RN_ERR_ARG);
}

static void test_add_rod_errors(rn_context *ctx) {
  rn_network *net = NULL;
  double xyz[3 * 8], d1[3] = {1, 0, 0}, zero[3] = {0, 0, 0}, nan3[3] = {NAN, 0, 0};
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  straight(4, 0.5, xyz);
  CHECK_STATUS(rn_network_add_rod(net, "a", 1, xyz, NULL, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_add_rod(net, "a", 4, NULL, NULL, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_add_rod(net, "a", 4, xyz, d1, NULL),
               RN_ERR_GEOMETRY); /* d1 || t */
  CHECK(contains(rn_context_last_error(ctx), "parallel"));
  CHECK_STATUS(rn_network_add_rod(net, "a", 4, xyz, zero, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_add_rod(net, "a", 4, xyz, nan3, NULL), RN_ERR_NOT_FINITE);
  xyz[4] = NAN;
  CHECK_STATUS(rn_network_add_rod(net, "a", 4, xyz, NULL, NULL), RN_ERR_NOT_FINITE);
  CHECK(contains(rn_context_last_error(ctx), "rn_network_add_rod: "));
  straight(4, 0.5, xyz);
  xyz[6] = xyz[3]; /* vertex 2 == vertex 1 */
  CHECK_STATUS(rn_network_add_rod(net, "a", 4, xyz, NULL, NULL), RN_ERR_GEOMETRY);
  CHECK(contains(rn_context_last_error(ctx), "edge 1"));
  CHECK(contains(rn_context_last_error(ctx), "zero-length"));
  straight(4, 0.5, xyz);
  xyz[6] = 0.0;   /* vertex 2 back at the origin: edges 0 and 1... */
  xyz[6] = -0.25; /* edge 1 points back along edge 0 */
  CHECK_STATUS(rn_network_add_rod(net, "a", 4, xyz, NULL, NULL), RN_ERR_GEOMETRY);
  CHECK(contains(rn_context_last_error(ctx), "opposite"));
  CHECK(rn_network_num_rods(net) == 0); /* nothing was added by the failures */
  CHECK_STATUS(rn_network_finalize(net), RN_ERR_ARG); /* no rods */
  rn_network_destroy(&net);
  CHECK(net == NULL);
}

static void test_property_errors(rn_context *ctx) {
  rn_network *net = simple(ctx, 5);
  rn_material m = steel();
  rn_section s = wire();
  double k[6] = {0}, len[4] = {0.1, 0.1, 0.1, 0.1};
  CHECK_STATUS(rn_network_set_material(net, 1, -1, &m), RN_ERR_RANGE);
  CHECK(contains(rn_context_last_error(ctx), "rod 1"));
  CHECK_STATUS(rn_network_set_material(net, -1, -1, &m), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_set_material(net, 0, 4, &m), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_set_material(net, 0, -2, &m), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_set_material(net, 0, 0, NULL), RN_ERR_ARG);
  m.E = -1.0;
  CHECK_STATUS(rn_network_set_material(net, 0, 0, &m), RN_ERR_ARG);
  CHECK(contains(rn_context_last_error(ctx), "E > 0"));
  m.E = 0.0;
  CHECK_STATUS(rn_network_set_material(net, 0, 0, &m), RN_ERR_ARG);
  m = steel();
  m.G = 0.0;
  CHECK_STATUS(rn_network_set_material(net, 0, 0, &m), RN_ERR_ARG);
  m = steel();
  m.density = -1.0;
  CHECK_STATUS(rn_network_set_material(net, 0, 0, &m), RN_ERR_ARG);
  m.density = NAN;
  CHECK_STATUS(rn_network_set_material(net, 0, 0, &m), RN_ERR_NOT_FINITE);
  s.I11 = -1.0;
  CHECK_STATUS(rn_network_set_section(net, 0, -1, &s), RN_ERR_ARG);
  s = wire();
  s.J = 0.0;
  CHECK_STATUS(rn_network_set_section(net, 0, 2, &s), RN_ERR_ARG);
  s.J = NAN;
  CHECK_STATUS(rn_network_set_section(net, 0, 2, &s), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_set_section(net, 0, 2, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_set_section(net, 3, 2, &s), RN_ERR_RANGE);
  /* rest overrides */
  CHECK_STATUS(rn_network_set_rest_curvature(net, 0, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_set_rest_curvature(net, 2, k), RN_ERR_RANGE);
  k[3] = NAN;
  CHECK_STATUS(rn_network_set_rest_curvature(net, 0, k), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_set_rest_twist(net, 0, k + 1), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_set_rest_twist(net, 0, NULL), RN_ERR_ARG);
  len[2] = 0.0;
  CHECK_STATUS(rn_network_set_rest_lengths(net, 0, len), RN_ERR_GEOMETRY);
  CHECK(contains(rn_context_last_error(ctx), "edge 2"));
  len[2] = -0.1;
  CHECK_STATUS(rn_network_set_rest_lengths(net, 0, len), RN_ERR_GEOMETRY);
  len[2] = INFINITY;
  CHECK_STATUS(rn_network_set_rest_lengths(net, 0, len), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_set_rest_lengths(net, 0, NULL), RN_ERR_ARG);
  rn_network_destroy(&net);
}

static void test_bc_load_errors(rn_context *ctx) {
  rn_network *net = simple(ctx, 5);
  double f[3] = {0, 0, 1}, bad[3] = {0, NAN, 0};
  CHECK_STATUS(rn_network_clamp(net, 1, RN_START), RN_ERR_RANGE); /* missing rod */
  CHECK(contains(rn_context_last_error(ctx), "rn_network_clamp: rod 1"));
  CHECK_STATUS(rn_network_clamp(net, -1, RN_START), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_clamp(net, 0, 2), RN_ERR_ARG);
  CHECK_STATUS(rn_network_pin(net, 0, 5), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_pin(net, 0, -6), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_pin(net, 3, 0), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_fix_theta(net, 0, 4), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_fix_theta(net, 0, -5), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_fix_theta(net, 2, 0), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_displace_end(net, 0, 5, f, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_displace_end(net, 1, RN_END, f, NULL), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_displace_end(net, 0, RN_END, bad, NULL), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_displace_end(net, 0, RN_END, NULL, bad), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_displace_vertex(net, 0, 9, f), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_displace_vertex(net, 0, 1, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_displace_vertex(net, 0, 1, bad), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_add_force(net, 0, 5, f), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_add_force(net, 1, 0, f), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_add_force(net, 0, 0, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_add_force(net, 0, -1, bad), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_add_moment(net, 0, -7, f), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_add_moment(net, 0, 0, bad), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_add_line_load(net, 4, f), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_add_line_load(net, 0, bad), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_add_line_load(net, 0, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_add_gravity(net, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_add_gravity(net, bad), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_set_load_factor(net, NAN), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_set_load_factor(net, -0.1), RN_ERR_ARG);
  CHECK_STATUS(rn_network_set_load_factor(net, 1.5), RN_ERR_ARG);
  CHECK(rn_network_load_factor(net) == 1.0);
  /* displace on an unclamped end: caught at finalize */
  CHECK_STATUS(rn_network_displace_end(net, 0, RN_END, f, NULL), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_ERR_BC);
  CHECK(contains(rn_context_last_error(ctx), "rod 0 ('beam')"));
  CHECK(contains(rn_context_last_error(ctx), "not clamped"));
  rn_network_destroy(&net);
  /* displacement of a free vertex */
  net = simple(ctx, 5);
  CHECK_STATUS(rn_network_displace_vertex(net, 0, 2, f), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_ERR_BC);
  CHECK(contains(rn_context_last_error(ctx), "vertex 2"));
  CHECK_STATUS(rn_network_pin(net, 0, 2), RN_OK); /* fixing it makes it valid */
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  rn_network_destroy(&net);
}

static void test_missing_properties(rn_context *ctx) {
  rn_network *net = NULL;
  double xyz[3 * 5];
  rn_material m = steel();
  rn_section s = wire();
  straight(5, 0.1, xyz);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "r", 5, xyz, NULL, NULL), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_ERR_ARG);
  CHECK(contains(rn_context_last_error(ctx), "rod 0 ('r') edge 0 has no material"));
  CHECK_STATUS(rn_network_set_section(net, 0, 0, &s), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, 0, 1, &s), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, 0, 2, &s), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, 0, 0, &m), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, 0, 1, &m), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_ERR_ARG);
  CHECK(contains(rn_context_last_error(ctx), "edge 2 has no material"));
  CHECK_STATUS(rn_network_set_material(net, 0, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_ERR_ARG);
  CHECK(contains(rn_context_last_error(ctx), "edge 3 has no section"));
  CHECK_STATUS(rn_network_set_section(net, 0, 3, &s), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  rn_network_destroy(&net);
}

/* Everything that needs finalize fails before it; everything that changes the
 * model fails after it. */
static void test_state_errors(rn_context *ctx) {
  rn_network *net = simple(ctx, 4);
  double x[64] = {0}, v[64] = {0}, E;
  size_t nnz;
  const int64_t *rp;
  const int32_t *cl;
  rn_material m = steel();
  rn_section s = wire();
  rn_check_report rep;
  CHECK(rn_network_num_dofs(net) == 0);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_ERR_STATE);
  CHECK_STATUS(rn_network_set_dofs(net, x), RN_ERR_STATE);
  CHECK_STATUS(rn_network_energy(net, x, &E), RN_ERR_STATE);
  CHECK(contains(rn_context_last_error(ctx), "not finalized"));
  CHECK_STATUS(rn_network_gradient(net, x, &E, v), RN_ERR_STATE);
  CHECK_STATUS(rn_network_hvp(net, x, v, v), RN_ERR_STATE);
  CHECK_STATUS(rn_network_energy_terms(net, x, v), RN_ERR_STATE);
  CHECK_STATUS(rn_network_hessian_pattern(net, &nnz, &rp, &cl), RN_ERR_STATE);
  CHECK_STATUS(rn_network_hessian_values(net, x, v), RN_ERR_STATE);
  CHECK_STATUS(rn_network_update_reference(net, x), RN_ERR_STATE);
  CHECK_STATUS(rn_network_rod_vertices(net, 0, x), RN_ERR_STATE);
  CHECK_STATUS(rn_network_check_derivatives(net, NULL, 0, 0.0, 1, &rep), RN_ERR_STATE);
  CHECK_STATUS(rn_network_set_load_factor(net, 0.5), RN_OK); /* allowed before */
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK(rn_network_load_factor(net) == 0.5);
  CHECK_STATUS(rn_network_finalize(net), RN_ERR_STATE);
  CHECK(contains(rn_context_last_error(ctx), "finalized"));
  CHECK_STATUS(rn_network_add_rod(net, "b", 4, x, NULL, NULL), RN_ERR_STATE);
  CHECK_STATUS(rn_network_set_material(net, 0, -1, &m), RN_ERR_STATE);
  CHECK_STATUS(rn_network_set_section(net, 0, -1, &s), RN_ERR_STATE);
  CHECK_STATUS(rn_network_set_rest_curvature(net, 0, v), RN_ERR_STATE);
  CHECK_STATUS(rn_network_set_rest_twist(net, 0, v), RN_ERR_STATE);
  CHECK_STATUS(rn_network_set_rest_lengths(net, 0, v), RN_ERR_STATE);
  CHECK_STATUS(rn_network_clamp(net, 0, RN_START), RN_ERR_STATE);
  CHECK_STATUS(rn_network_pin(net, 0, 0), RN_ERR_STATE);
  CHECK_STATUS(rn_network_fix_theta(net, 0, 0), RN_ERR_STATE);
  CHECK_STATUS(rn_network_displace_end(net, 0, RN_START, v, v), RN_ERR_STATE);
  CHECK_STATUS(rn_network_displace_vertex(net, 0, 0, v), RN_ERR_STATE);
  CHECK_STATUS(rn_network_add_force(net, 0, 0, v), RN_ERR_STATE);
  CHECK_STATUS(rn_network_add_moment(net, 0, 0, v), RN_ERR_STATE);
  CHECK_STATUS(rn_network_add_line_load(net, 0, v), RN_ERR_STATE);
  CHECK_STATUS(rn_network_add_gravity(net, v), RN_ERR_STATE);
  CHECK(rn_network_num_rods(net) == 1);
  /* bad arguments after finalize */
  CHECK_STATUS(rn_network_hessian_pattern(net, NULL, &rp, &cl), RN_ERR_ARG);
  CHECK_STATUS(rn_network_check_derivatives(net, NULL, 0, 0.0, 1, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_check_derivatives(net, NULL, -1, 0.0, 1, &rep), RN_ERR_ARG);
  CHECK_STATUS(rn_network_check_derivatives(net, NULL, 1, NAN, 1, &rep), RN_ERR_ARG);
  CHECK_STATUS(rn_network_rod_vertices(net, 1, x), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_rod_theta(net, -1, x), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_rod_frames(net, 2, x, NULL), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_rod_strains(net, 1, x, NULL, NULL), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_rod_initial_vertices(net, 1, x), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_rod_vertices(net, 0, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_energy(net, x, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_gradient(net, x, &E, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_network_hvp(net, x, NULL, v), RN_ERR_ARG);
  rn_network_destroy(&net);
}

/* NaN inputs to evaluations and set_dofs leave the state unchanged. */
static void test_not_finite(rn_context *ctx) {
  rn_network *net = simple(ctx, 4);
  double x[15], y[15], v[15] = {0}, g[15], E;
  size_t n;
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  n = rn_network_num_dofs(net);
  CHECK(n == 15);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  memcpy(y, x, sizeof(x));
  y[5] = NAN;
  CHECK_STATUS(rn_network_set_dofs(net, y), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_get_dofs(net, y), RN_OK);
  CHECK(memcmp(x, y, sizeof(x)) == 0);
  y[2] = INFINITY;
  CHECK_STATUS(rn_network_energy(net, y, &E), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_gradient(net, y, &E, g), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_update_reference(net, y), RN_ERR_NOT_FINITE);
  v[1] = NAN;
  CHECK_STATUS(rn_network_hvp(net, x, v, g), RN_ERR_NOT_FINITE);
  /* a degenerate trial point is recoverable (> 0) and names rod and edge */
  memcpy(y, x, sizeof(x));
  y[4] = y[0]; /* x_1 := x_0 */
  y[5] = y[1];
  y[6] = y[2];
  CHECK_STATUS(rn_network_energy(net, y, &E), RN_DEGENERATE);
  CHECK(contains(rn_context_last_error(ctx), "rod 0"));
  CHECK(contains(rn_context_last_error(ctx), "edge 0"));
  CHECK_STATUS(rn_network_gradient(net, y, &E, g), RN_DEGENERATE);
  CHECK_STATUS(rn_network_update_reference(net, y), RN_DEGENERATE);
  CHECK_STATUS(rn_network_get_dofs(net, y), RN_OK); /* unchanged */
  CHECK(memcmp(x, y, sizeof(x)) == 0);
  rn_network_destroy(&net);
}

/* Sizes, names, DOF map and the Hessian pattern of a clamped rod. */
static void test_sizes_and_pattern(rn_context *ctx) {
  rn_network *net = simple(ctx, 6);
  double xyz[3 * 6], x0[3 * 6];
  size_t nnz, n;
  const int64_t *rp;
  const int32_t *cl;
  int ok_sorted = 1, ok_sym = 1;
  straight(6, 0.1, xyz);
  CHECK(rn_network_num_rods(net) == 1);
  CHECK(rn_network_rod_num_vertices(net, 0) == 6);
  CHECK(rn_network_rod_num_vertices(net, 3) == 0);
  CHECK(strcmp(rn_network_rod_name(net, 0), "beam") == 0);
  CHECK(strcmp(rn_network_rod_name(net, 9), "") == 0);
  CHECK(rn_network_context(net) == ctx);
  CHECK(rn_network_num_full_dofs(net) == 23);
  CHECK_STATUS(rn_network_clamp(net, 0, RN_START), RN_OK); /* 7 DOFs */
  CHECK_STATUS(rn_network_pin(net, 0, -1), RN_OK);         /* 3 DOFs */
  CHECK_STATUS(rn_network_fix_theta(net, 0, -2), RN_OK);   /* theta^3 */
  CHECK_STATUS(rn_network_fix_theta(net, 0, 0), RN_OK);    /* already clamped */
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  n = rn_network_num_dofs(net);
  CHECK(n == 23 - 7 - 3 - 1);
  CHECK_STATUS(rn_network_rod_initial_vertices(net, 0, x0), RN_OK);
  CHECK(memcmp(x0, xyz, sizeof(xyz)) == 0);
  CHECK_STATUS(rn_network_rod_vertices(net, 0, x0), RN_OK);
  CHECK(memcmp(x0, xyz, sizeof(xyz)) == 0);
  CHECK_STATUS(rn_network_hessian_pattern(net, &nnz, &rp, &cl), RN_OK);
  CHECK(rp[0] == 0 && (size_t)rp[n] == nnz);
  for (size_t r = 0; r < n; ++r)
    for (int64_t p = rp[r]; p < rp[r + 1]; ++p) {
      int found = 0;
      if (p > rp[r] && cl[p] <= cl[p - 1]) ok_sorted = 0;
      for (int64_t q = rp[cl[p]]; q < rp[cl[p] + 1]; ++q) found |= (size_t)cl[q] == r;
      ok_sym &= found;
    }
  CHECK(ok_sorted);
  CHECK(ok_sym);
  /* free DOFs in order: th1 (0), x2 (1..3), th2 (4), x3 (5..7), x4 (8..10),
   * th4 (11); the widest coupling is the stencil of vertex 3 (x2 .. x4) */
  CHECK(rn_network_hessian_bandwidth(net) == 9);
  rn_network_destroy(&net);
  /* a free rod: the vertex stencil spans 11 DOFs => bandwidth 10 */
  net = simple(ctx, 6);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK(rn_network_hessian_bandwidth(net) == 10);
  CHECK_STATUS(rn_network_hessian_pattern(net, &nnz, &rp, &cl), RN_OK);
  CHECK(rp[1] == 11); /* row 0 couples to DOFs 0..10 */
  rn_network_destroy(&net);
}

/* d1 derivation rule and projection of a given d1. */
static void test_frames(rn_context *ctx) {
  rn_network *net = NULL;
  rn_material m = steel();
  rn_section s = wire();
  double diag[6] = {0, 0, 0, 1, 1, 1}, slanted[9] = {0, 0, 0, 1, 0, 0, 2, 0.5, 0};
  double d1in[3] = {1, 1, 0}, d1[6], d2[6];
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "diag", 2, diag, NULL, NULL), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "slanted", 3, slanted, d1in, NULL), RN_OK);
  for (int r = 0; r < 2; ++r) {
    CHECK_STATUS(rn_network_set_material(net, r, -1, &m), RN_OK);
    CHECK_STATUS(rn_network_set_section(net, r, -1, &s), RN_OK);
  }
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  /* t = (1,1,1)/sqrt3: all |t_k| tie -> x axis, projected: (2,-1,-1)/sqrt6 */
  CHECK_STATUS(rn_network_rod_frames(net, 0, d1, d2), RN_OK);
  CHECK_NEAR(d1[0], 2.0 / sqrt(6.0), 1e-15);
  CHECK_NEAR(d1[1], -1.0 / sqrt(6.0), 1e-15);
  CHECK_NEAR(d1[2], -1.0 / sqrt(6.0), 1e-15);
  CHECK_NEAR(d2[0], 0.0, 1e-15); /* d2 = t x d1 = (0, 1, -1)/sqrt2 */
  CHECK_NEAR(d2[1], 1.0 / sqrt(2.0), 1e-15);
  CHECK_NEAR(d2[2], -1.0 / sqrt(2.0), 1e-15);
  /* given d1 = (1,1,0) on t = x: projected to y; the second edge carries
   * its parallel transport, which stays in the xy plane (planar rod). */
  CHECK_STATUS(rn_network_rod_frames(net, 1, d1, d2), RN_OK);
  CHECK_NEAR(d1[0], 0.0, 1e-15);
  CHECK_NEAR(d1[1], 1.0, 1e-15);
  CHECK_NEAR(d1[2], 0.0, 1e-15);
  CHECK_NEAR(d1[3], -0.5 / sqrt(1.25), 1e-15);
  CHECK_NEAR(d1[4], 1.0 / sqrt(1.25), 1e-15);
  CHECK_NEAR(d1[5], 0.0, 1e-15);
  CHECK_NEAR(d2[5], 1.0, 1e-15);
  rn_network_destroy(&net);
}

int main(void) {
  rn_context *ctx = NULL;
  test_status_and_version();
  test_context();
  test_null_handles();
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  test_add_rod_errors(ctx);
  test_property_errors(ctx);
  test_bc_load_errors(ctx);
  test_missing_properties(ctx);
  test_state_errors(ctx);
  test_not_finite(ctx);
  test_sizes_and_pattern(ctx);
  test_frames(ctx);
  rn_context_destroy(&ctx);
  return rn_test_finish("api_lifecycle");
}

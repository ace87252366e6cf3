/* api_planar.c - the planar model at the C API (rodnet_model.h): the model
 * request and its errors, the free DOFs it leaves, the qualification report
 * and what finalize names when a network leaves its plane. */
#include <math.h>
#include <string.h>

#include "rodnet.h"
#include "rodnet_model.h"
#include "rodnet_ring.h"
#include "testutil.h"

enum { NV = 5 };

/* A straight rod along x at height z (vertex 2 lifted by lift), round section. */
static rn_network *rod_network(rn_context *ctx, double z, double lift, rn_model model) {
  rn_network *net = NULL;
  rn_material m;
  rn_section s;
  double xyz[3 * NV];
  int rod = -1;
  for (int v = 0; v < NV; ++v) {
    xyz[3 * v] = 0.25 * v;
    xyz[3 * v + 1] = 0.0;
    xyz[3 * v + 2] = z + (v == 2 ? lift : 0.0);
  }
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_set_model(net, model), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "r", NV, xyz, NULL, &rod), RN_OK);
  CHECK_STATUS(rn_material_from_E_nu(1.0, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_circle(0.01, &s), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
  return net;
}

static void test_request(rn_context *ctx) {
  rn_network *net = rod_network(ctx, 0.25, 0.0, RN_MODEL_PLANAR);
  CHECK(rn_network_is_planar(net) == -1);
  CHECK(rn_network_planar(net, NULL) == -1);
  CHECK_STATUS(rn_network_set_model(net, (rn_model)7), RN_ERR_ARG);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK(rn_network_is_planar(net) == 1);
  CHECK(rn_network_planar(net, NULL) == 1);
  CHECK(rn_network_num_dofs(net) == 2 * NV); /* x, y per vertex */
  CHECK_STATUS(rn_network_set_model(net, RN_MODEL_3D), RN_ERR_STATE);
  rn_network_destroy(&net);
  net = rod_network(ctx, 0.25, 0.0, RN_MODEL_AUTO);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK(rn_network_is_planar(net) == 0);
  CHECK(rn_network_planar(net, NULL) == 1);      /* qualifies, */
  CHECK(rn_network_num_dofs(net) == 4 * NV - 1); /* solved in 3D */
  rn_network_destroy(&net);
  CHECK(rn_network_is_planar(NULL) == -1);
  CHECK_STATUS(rn_network_set_model(NULL, RN_MODEL_PLANAR), RN_ERR_ARG);
}

static void test_not_planar(rn_context *ctx) {
  const char *why = NULL;
  rn_network *net = rod_network(ctx, 0.0, 1e-3, RN_MODEL_PLANAR);
  CHECK_STATUS(rn_network_finalize(net), RN_ERR_ARG);
  CHECK(strstr(rn_context_last_error(ctx), "rod 0 ('r') vertex 2 is at z = 0.001") !=
        NULL);
  rn_network_destroy(&net);
  /* a lift below 1e-12 of the extent is in the plane */
  net = rod_network(ctx, 0.0, 1e-14, RN_MODEL_PLANAR);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  rn_network_destroy(&net);
  /* detected, not asked for: a force out of the plane */
  const double f[3] = {0.0, 1.0, 1e-6};
  net = rod_network(ctx, 0.0, 0.0, RN_MODEL_AUTO);
  CHECK_STATUS(rn_network_add_force(net, 0, NV - 1, f), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK(rn_network_planar(net, &why) == 0);
  CHECK(why && strstr(why, "vertex 4: a point force out of the plane") != NULL);
  rn_network_destroy(&net);
  /* a couple about an in-plane axis at a clamped end */
  const double rot[3] = {0.1, 0.0, 0.0}, disp[3] = {0.0, 0.0, 0.0};
  net = rod_network(ctx, 0.0, 0.0, RN_MODEL_PLANAR);
  CHECK_STATUS(rn_network_clamp(net, 0, RN_START), RN_OK);
  CHECK_STATUS(rn_network_displace_end(net, 0, RN_START, disp, rot), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_ERR_ARG);
  CHECK(strstr(rn_context_last_error(ctx), "prescribed motion of its start end") != NULL);
  rn_network_destroy(&net);
}

/* A planar ring of N vertices (radius 1, round section) with link turns of twist
 * stored (total: a total twist instead, if has_total). */
static rn_network *ring_network(rn_context *ctx, rn_model model, int link, int has_total,
                                double total) {
  enum { N = 24 };
  rn_network *net = NULL;
  rn_material m;
  rn_section s;
  double xyz[3 * N];
  int rod = -1, joint = -1;
  for (int v = 0; v < N; ++v) {
    xyz[3 * v] = cos(2.0 * 3.141592653589793 * v / N);
    xyz[3 * v + 1] = sin(2.0 * 3.141592653589793 * v / N);
    xyz[3 * v + 2] = 0.0;
  }
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_set_model(net, model), RN_OK);
  CHECK_STATUS(rn_network_add_closed_rod(net, "ring", N, xyz, NULL, &rod, &joint), RN_OK);
  CHECK_STATUS(rn_material_from_E_nu(1.0, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_circle(0.01, &s), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
  if (has_total)
    CHECK_STATUS(rn_network_set_ring_total_twist(net, joint, total), RN_OK);
  else
    CHECK_STATUS(rn_network_set_joint_link(net, joint, link), RN_OK);
  return net;
}

/* Two straight rods along x meeting at a rigid or elastic joint at x = 1; the
 * second rod's d1 is d1b (the first's is +z). */
static rn_network *joint_network(rn_context *ctx, rn_model model, rn_joint_model jm,
                                 const double d1b[3], int *joint) {
  rn_network *net = NULL;
  rn_material m;
  rn_section s;
  double a[9], b[9], d1a[3] = {0.0, 0.0, 1.0};
  int r0 = -1, r1 = -1, ends[2] = {RN_END, RN_START};
  for (int v = 0; v < 3; ++v) {
    a[3 * v] = 0.5 * v;
    b[3 * v] = 1.0 + 0.5 * v;
    a[3 * v + 1] = b[3 * v + 1] = a[3 * v + 2] = b[3 * v + 2] = 0.0;
  }
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_set_model(net, model), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "a", 3, a, d1a, &r0), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "b", 3, b, d1b, &r1), RN_OK);
  CHECK_STATUS(rn_material_from_E_nu(1.0, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_circle(0.01, &s), RN_OK);
  for (int r = 0; r < 2; ++r) {
    CHECK_STATUS(rn_network_set_material(net, r, -1, &m), RN_OK);
    CHECK_STATUS(rn_network_set_section(net, r, -1, &s), RN_OK);
  }
  CHECK_STATUS(rn_network_add_joint(net, "J", jm, 2, (int[2]){r0, r1}, ends, joint),
               RN_OK);
  return net;
}

/* What the planar model cannot represent is refused, and the same predicate
 * reports the scene as not qualifying under the 3D model: twist stored in a
 * ring (link, total), a smooth joint's rest twist and out-of-plane rest
 * curvature, joint rest frames turned out of the plane. */
static void test_stored_state(rn_context *ctx) {
  const char *why = NULL;
  rn_network *net = ring_network(ctx, RN_MODEL_PLANAR, 1, 0, 0.0);
  CHECK_STATUS(rn_network_finalize(net), RN_ERR_ARG);
  CHECK(strstr(rn_context_last_error(ctx),
               "joint 0 ('ring'): the ring stores 1 full turn of twist (\"link\")") !=
        NULL);
  rn_network_destroy(&net);
  net = ring_network(ctx, RN_MODEL_AUTO, 1, 0, 0.0);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK(rn_network_planar(net, &why) == 0);
  CHECK(why && strstr(why, "1 full turn of twist") != NULL);
  rn_network_destroy(&net);
  net = ring_network(ctx, RN_MODEL_PLANAR, 0, 0, 0.0); /* no twist: planar */
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK(rn_network_is_planar(net) == 1);
  rn_network_destroy(&net);
  net = ring_network(ctx, RN_MODEL_PLANAR, 0, 1, 1.3); /* total twist 1.3 */
  CHECK_STATUS(rn_network_finalize(net), RN_ERR_ARG);
  CHECK(strstr(rn_context_last_error(ctx), "\"total\" 1.3") != NULL);
  rn_network_destroy(&net);
  net = ring_network(ctx, RN_MODEL_PLANAR, 0, 1, 2.0 * 3.141592653589793); /* = link 1 */
  CHECK_STATUS(rn_network_finalize(net), RN_ERR_ARG);
  rn_network_destroy(&net);
  net = ring_network(ctx, RN_MODEL_PLANAR, 0, 1, 0.0); /* total 0: planar */
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  rn_network_destroy(&net);
  /* smooth joint rest strains: twist, out-of-plane curvature (d1 = +z: kappa2
   * is the in-plane curvature, kappa1 out of plane) */
  net = ring_network(ctx, RN_MODEL_PLANAR, 0, 0, 0.0);
  CHECK_STATUS(rn_network_set_joint_rest_strains(net, 0, (double[2]){0.0, 0.0}, 0.2),
               RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_ERR_ARG);
  CHECK(strstr(rn_context_last_error(ctx), "joint 0 ('ring'): rest twist 0.2") != NULL);
  rn_network_destroy(&net);

  /* joint rest frames: "straight" between rods whose d1 differ (+z and +y) needs
   * a quarter turn of twist about x: refused; with equal d1 it is planar */
  int joint = -1;
  for (int jm = 0; jm < 2; ++jm) {
    rn_joint_model model = jm ? RN_JOINT_RIGID : RN_JOINT_ELASTIC;
    net = joint_network(ctx, RN_MODEL_PLANAR, model, (double[3]){0, 1, 0}, &joint);
    CHECK_STATUS(rn_network_finalize(net), RN_OK); /* input rest frames */
    rn_network_destroy(&net);
    net = joint_network(ctx, RN_MODEL_PLANAR, model, (double[3]){0, 1, 0}, &joint);
    CHECK_STATUS(rn_network_set_joint_rest_straight(net, joint), RN_OK);
    CHECK_STATUS(rn_network_finalize(net), RN_ERR_ARG);
    CHECK(strstr(rn_context_last_error(ctx),
                 "joint 0 ('J') end 1: its rest frame "
                 "(rest shape \"straight\") is turned out") != NULL);
    rn_network_destroy(&net);
    net = joint_network(ctx, RN_MODEL_AUTO, model, (double[3]){0, 1, 0}, &joint);
    CHECK_STATUS(rn_network_set_joint_rest_straight(net, joint), RN_OK);
    CHECK_STATUS(rn_network_finalize(net), RN_OK);
    CHECK(rn_network_planar(net, &why) == 0 && strstr(why, "end 1: its rest frame"));
    rn_network_destroy(&net);
    net = joint_network(ctx, RN_MODEL_PLANAR, model, (double[3]){0, 0, 1}, &joint);
    CHECK_STATUS(rn_network_set_joint_rest_straight(net, joint), RN_OK);
    CHECK_STATUS(rn_network_finalize(net), RN_OK);
    rn_network_destroy(&net);
  }
  /* given frames: both turned by 90 degrees about z (a kink in the plane) is
   * planar; both turned about x is planar for the elastic joint only (its fit
   * absorbs a common rotation, a rigid joint's rotation turns about z only) */
  const double kink[18] = {0, 1, 0, 0, 0, 1, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, 0, 1};
  const double about_x[18] = {1, 0, 0, 0, -1, 0, 0, 0, -1, 1, 0, 0, 0, 0, 1, 0, -1, 0};
  for (int jm = 0; jm < 2; ++jm) {
    rn_joint_model model = jm ? RN_JOINT_RIGID : RN_JOINT_ELASTIC;
    net = joint_network(ctx, RN_MODEL_PLANAR, model, (double[3]){0, 1, 0}, &joint);
    CHECK_STATUS(rn_network_set_joint_rest_frames(net, joint, kink), RN_OK);
    CHECK_STATUS(rn_network_finalize(net), RN_OK);
    rn_network_destroy(&net);
    net = joint_network(ctx, RN_MODEL_PLANAR, model, (double[3]){0, 1, 0}, &joint);
    CHECK_STATUS(rn_network_set_joint_rest_frames(net, joint, about_x), RN_OK);
    CHECK_STATUS(rn_network_finalize(net), jm ? RN_ERR_ARG : RN_OK);
    rn_network_destroy(&net);
  }
}

int main(void) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  test_request(ctx);
  test_not_planar(ctx);
  test_stored_state(ctx);
  rn_context_destroy(&ctx);
  return rn_test_finish("api_planar");
}

/* api_planar.c - the planar model at the C API (rodnet_model.h): the model
 * request and its errors, the free DOFs it leaves, the qualification report
 * and what finalize names when a network leaves its plane. */
#include <string.h>

#include "rodnet.h"
#include "rodnet_model.h"
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

int main(void) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  test_request(ctx);
  test_not_planar(ctx);
  rn_context_destroy(&ctx);
  return rn_test_finish("api_planar");
}

/* shim_system_nets.c - the networks of shim_system.cpp, built in C (the helpers of
 * shim_networks.h and shim_rods.h are C). */
#include "shim_networks.h"
#include "shim_rods.h"

rn_network *shim_system_portal(rn_context *ctx, int elastic);
rn_network *shim_system_column(rn_context *ctx);

/* Portal frame of shim_networks.h, both corner joints of one model. */
rn_network *shim_system_portal(rn_context *ctx, int elastic) {
  const int m = elastic ? RN_JOINT_ELASTIC : RN_JOINT_RIGID;
  return shimnet_portal(ctx, m, m, 4, 0.3, 1);
}

/* The column of shim_buckling.c under 3 times its Euler load, set to the straight
 * state shortened by P / EA: its Hessian is indefinite. */
rn_network *shim_system_column(rn_context *ctx) {
  rn_section s;
  CHECK_STATUS(rn_section_rectangle(0.02, 0.01, &s), RN_OK);
  const double P = 3.0 * SHIM_PI * SHIM_PI * 1e7 * fmin(s.I11, s.I22) / 4.0;
  const double f[3] = {0.0, 0.0, -P};
  rn_network *net = shim_clamped_rod(ctx, 21, 1.0, 2, &s, 1e7, f);
  const size_t n = rn_network_num_dofs(net);
  double *x = calloc(n, sizeof(double));
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  for (size_t i = 0; i < n; ++i) x[i] *= 1.0 - P / (1e7 * s.A);
  CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK);
  free(x);
  return net;
}

/* results.c - per-rod results at the current state: vertices, angles,
 * directors, strains. */
#include <math.h>
#include <string.h>

#include "network_internal.h"

static rn_status check_result(const rn_network *net, const char *where, int rod) {
  rn_status st;
  if ((st = rn_net_check_final(net, where))) return st;
  return rn_net_check_rod(net, where, rod);
}

rn_status rn_network_rod_vertices(const rn_network *net, int rod, double *xyz) {
  static const char *where = "rn_network_rod_vertices";
  const rn_rod *r;
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = check_result(net, where, rod))) return st;
  if (!xyz) return rn_fail(net->ctx, RN_ERR_ARG, where, "xyz is NULL");
  r = &net->rods[rod];
  for (int v = 0; v < r->nv; ++v)
    memcpy(xyz + 3 * v, net->xfull + rn_dof_vertex(r->off, v), 3 * sizeof(double));
  return RN_OK;
}

rn_status rn_network_rod_theta(const rn_network *net, int rod, double *theta) {
  static const char *where = "rn_network_rod_theta";
  const rn_rod *r;
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = check_result(net, where, rod))) return st;
  if (!theta) return rn_fail(net->ctx, RN_ERR_ARG, where, "theta is NULL");
  r = &net->rods[rod];
  for (int j = 0; j < r->ne; ++j) theta[j] = net->xfull[rn_dof_theta(r->off, j)];
  return RN_OK;
}

rn_status rn_network_rod_initial_vertices(const rn_network *net, int rod, double *xyz) {
  static const char *where = "rn_network_rod_initial_vertices";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_rod(net, where, rod))) return st;
  if (!xyz) return rn_fail(net->ctx, RN_ERR_ARG, where, "xyz is NULL");
  memcpy(xyz, net->rods[rod].x0, 3 * (size_t)net->rods[rod].nv * sizeof(double));
  return RN_OK;
}

rn_status rn_network_rod_frames(const rn_network *net, int rod, double *d1, double *d2) {
  static const char *where = "rn_network_rod_frames";
  const rn_rod *r;
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = check_result(net, where, rod))) return st;
  r = &net->rods[rod];
  for (int j = 0; j < r->ne; ++j) {
    const double *q = net->xfull + rn_dof_edge_stencil(r->off, j);
    double e[3];
    for (int k = 0; k < 3; ++k) e[k] = q[RN_EDGE_LOCAL_X1 + k] - q[RN_EDGE_LOCAL_X0 + k];
    if (rnk_material_frame(e, &r->ref[j], q[RN_EDGE_LOCAL_THETA], NULL,
                           d1 ? d1 + 3 * j : NULL, d2 ? d2 + 3 * j : NULL) != RNK_OK)
      return rn_fail(net->ctx, RN_DEGENERATE, where, "rod %d edge %d: degenerate edge",
                     rod, j);
  }
  return RN_OK;
}

rn_status rn_network_rod_strains(const rn_network *net, int rod, double *strain,
                                 double *kappa, double *tau) {
  static const char *where = "rn_network_rod_strains";
  const rn_rod *r;
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = check_result(net, where, rod))) return st;
  r = &net->rods[rod];
  for (int j = 0; strain && j < r->ne; ++j) {
    const double *q = net->xfull + rn_dof_edge_stencil(r->off, j);
    double l2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      double d = q[RN_EDGE_LOCAL_X1 + k] - q[RN_EDGE_LOCAL_X0 + k];
      l2 += d * d;
    }
    strain[j] = sqrt(l2) / r->lbar[j] - 1.0;
  }
  for (int i = 1; (kappa || tau) && i < r->nv - 1; ++i) {
    const double *q = net->xfull + rn_dof_vertex_stencil(r->off, i);
    double k2[2], t;
    if (rnk_strains(q, &r->ref[i - 1], r->ref_twist[i - 1], k2, &t) != RNK_OK)
      return rn_fail(net->ctx, RN_DEGENERATE, where,
                     "rod %d vertex %d: degenerate stencil", rod, i);
    if (kappa) {
      kappa[2 * (i - 1)] = k2[0];
      kappa[2 * (i - 1) + 1] = k2[1];
    }
    if (tau) tau[i - 1] = t;
  }
  return RN_OK;
}

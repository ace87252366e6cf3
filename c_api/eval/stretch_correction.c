/* stretch_correction.c - the force of the second-order stretching error of a
 * step (rn_network_stretch_correction): what a trust-region solver needs for a
 * second-order correction of the stiff stretching (docs/solvers.md).  Pure:
 * nothing in the network changes. */
#include <math.h>

#include "core/network_internal.h"

/* r = |e + d| - |e| - (e / |e|) . d, the length an edge e gets from the change
 * d beyond its linearisation, without cancellation:
 *   |e + d| - |e| = (2 e.d + |d|^2) / (L1 + L),
 *   r = (|d|^2 - (e.d) (2 e.d + |d|^2) / (L (L + L1))) / (L + L1). */
static double length_excess(const double e[3], const double d[3], double L, double L1) {
  double ed = e[0] * d[0] + e[1] * d[1] + e[2] * d[2];
  double dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  return (dd - ed * (2.0 * ed + dd) / (L * (L + L1))) / (L + L1);
}

rn_status rn_network_stretch_correction(const rn_network *net, const double *x,
                                        const double *s, double *f) {
  static const char *where = "rn_network_stretch_correction";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (net->nred && (!x || !s || !f))
    return rn_fail(net->ctx, RN_ERR_ARG, where, "NULL array");
  if (!rn_all_finite(net->nred, x) || !rn_all_finite(net->nred, s))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where,
                   "x or s has NaN or infinite entries");
  for (size_t i = 0; i < net->nred; ++i) f[i] = 0.0;
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    if (!rn_rod_evaluated(r)) continue;
    for (int j = 0; j < r->ne; ++j) {
      size_t at = rn_dof_edge_stencil(r->off, j);
      double q[RN_EDGE_STENCIL], v[RN_EDGE_STENCIL], fl[RN_EDGE_STENCIL] = {0.0};
      double e[3], d[3], e1[3];
      rn_gather(net, x, at, RN_EDGE_STENCIL, q);
      rn_gather_dir(net, s, at, RN_EDGE_STENCIL, v);
      for (int k = 0; k < 3; ++k) {
        e[k] = q[RN_EDGE_LOCAL_X1 + k] - q[RN_EDGE_LOCAL_X0 + k];
        d[k] = v[RN_EDGE_LOCAL_X1 + k] - v[RN_EDGE_LOCAL_X0 + k];
        e1[k] = e[k] + d[k];
      }
      double L = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
      double L1 = sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
      if (!(L > 0.0) || !(L1 > 0.0))
        return rn_fail(net->ctx, RN_DEGENERATE, where,
                       "rod %d ('%s') edge %d has zero length at x or x + s", r->gid,
                       r->name ? r->name : "", j);
      /* (E A / lbar) r times dL/dx = (-e/L at x_j, e/L at x_{j+1}) */
      double t = r->sp[j].k / r->sp[j].lbar * length_excess(e, d, L, L1) / L;
      for (int k = 0; k < 3; ++k) {
        fl[RN_EDGE_LOCAL_X0 + k] = -t * e[k];
        fl[RN_EDGE_LOCAL_X1 + k] = t * e[k];
      }
      rn_scatter_add(net, fl, at, RN_EDGE_STENCIL, f);
    }
  }
  if (!rn_all_finite(net->nred, f))
    return rn_fail(net->ctx, RN_OVERFLOW, where, "the correction force overflows");
  rn_cell_hold_zero(net, f);
  return RN_OK;
}

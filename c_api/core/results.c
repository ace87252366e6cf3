/* results.c - per-rod results at the current state: vertices, angles,
 * directors, strains, rest lengths, stress resultants and energies per
 * stencil. */
#include <math.h>
#include <string.h>

#include "core/network_internal.h"

/* The opening of every getter: net given, finalized (final: the getters of the
 * current state), rod a rod of this network (translated into the local index
 * *rod), out (named name) given if name is not NULL; *r its rod. */
static rn_status result_rod(const rn_network *net, const char *where, int final, int *rod,
                            const void *out, const char *name, const rn_rod **r) {
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if (final && (st = rn_net_check_final(net, where))) return st;
  if ((st = rn_net_check_rod(net, where, rod))) return st;
  if (name && !out) return rn_fail(net->ctx, RN_ERR_ARG, where, "%s is NULL", name);
  *r = &net->rods[*rod];
  return RN_OK;
}

rn_status rn_network_rod_vertices(const rn_network *net, int rod, double *xyz) {
  static const char *where = "rn_network_rod_vertices";
  const rn_rod *r = NULL;
  rn_status st = result_rod(net, where, 1, &rod, xyz, "xyz", &r);
  if (st) return st;
  for (int v = 0; v < r->nv; ++v)
    memcpy(xyz + 3 * v, net->xfull + rn_dof_vertex(r->off, v), 3 * sizeof(double));
  return RN_OK;
}

rn_status rn_network_rod_theta(const rn_network *net, int rod, double *theta) {
  static const char *where = "rn_network_rod_theta";
  const rn_rod *r = NULL;
  rn_status st = result_rod(net, where, 1, &rod, theta, "theta", &r);
  if (st) return st;
  for (int j = 0; j < r->ne; ++j) theta[j] = net->xfull[rn_dof_theta(r->off, j)];
  return RN_OK;
}

rn_status rn_network_rod_initial_vertices(const rn_network *net, int rod, double *xyz) {
  static const char *where = "rn_network_rod_initial_vertices";
  const rn_rod *r = NULL;
  rn_status st = result_rod(net, where, 0, &rod, xyz, "xyz", &r);
  if (st) return st;
  memcpy(xyz, r->x0, 3 * (size_t)r->nv * sizeof(double));
  return RN_OK;
}

rn_status rn_network_rod_frames(const rn_network *net, int rod, double *d1, double *d2) {
  static const char *where = "rn_network_rod_frames";
  const rn_rod *r = NULL;
  rn_status st = result_rod(net, where, 1, &rod, NULL, NULL, &r);
  if (st) return st;
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
  const rn_rod *r = NULL;
  rn_status st = result_rod(net, where, 1, &rod, NULL, NULL, &r);
  if (st) return st;
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

rn_status rn_network_rod_rest_lengths(const rn_network *net, int rod, double *len) {
  static const char *where = "rn_network_rod_rest_lengths";
  const rn_rod *r = NULL;
  rn_status st = result_rod(net, where, 0, &rod, len, "len", &r);
  if (st) return st;
  memcpy(len, r->lbar, (size_t)r->ne * sizeof(double));
  return RN_OK;
}

/* Bending moment B (kappa - kbar) / vlen and twisting moment of one stencil. */
static void vertex_moments(const rnk_bend_param *bp, const rnk_twist_param *tp,
                           const double kappa[2], double tau, double m[2], double *mt) {
  double dk0 = kappa[0] - bp->kbar[0], dk1 = kappa[1] - bp->kbar[1];
  m[0] = (bp->B[0] * dk0 + bp->B[1] * dk1) / bp->vlen;
  m[1] = (bp->B[1] * dk0 + bp->B[2] * dk1) / bp->vlen;
  *mt = tp->beta * (tau - tp->taubar) / tp->vlen;
}

rn_status rn_network_rod_vertex_fields(const rn_network *net, int rod, double *moment,
                                       double *twist_moment, double *bend_energy,
                                       double *twist_energy) {
  static const char *where = "rn_network_rod_vertex_fields";
  const rn_rod *r = NULL;
  rn_status st = result_rod(net, where, 1, &rod, NULL, NULL, &r);
  if (st) return st;
  for (int i = 1; i < r->nv - 1; ++i) {
    const double *q = net->xfull + rn_dof_vertex_stencil(r->off, i);
    const rnk_frame *ref = &r->ref[i - 1];
    rnk_twist_param tp = r->tp[i - 1];
    double kappa[2], tau, m[2], mt, eb, et;
    tp.ref_twist = r->ref_twist[i - 1];
    if (rnk_strains(q, ref, tp.ref_twist, kappa, &tau) != RNK_OK ||
        rnk_bendtwist_energy(q, ref, &r->bp[i - 1], &tp, &eb, &et) != RNK_OK)
      return rn_fail(net->ctx, RN_DEGENERATE, where,
                     "rod %d vertex %d: degenerate stencil", rod, i);
    vertex_moments(&r->bp[i - 1], &tp, kappa, tau, m, &mt);
    if (moment) {
      moment[2 * (i - 1)] = m[0];
      moment[2 * (i - 1) + 1] = m[1];
    }
    if (twist_moment) twist_moment[i - 1] = mt;
    if (bend_energy) bend_energy[i - 1] = eb;
    if (twist_energy) twist_energy[i - 1] = et;
  }
  return RN_OK;
}

rn_status rn_network_rod_edge_fields(const rn_network *net, int rod, double *axial_force,
                                     double *stretch_energy) {
  static const char *where = "rn_network_rod_edge_fields";
  const rn_rod *r = NULL;
  rn_status st = result_rod(net, where, 1, &rod, NULL, NULL, &r);
  if (st) return st;
  for (int j = 0; j < r->ne; ++j) {
    const double *q = net->xfull + rn_dof_edge_stencil(r->off, j);
    double l2 = 0.0, E = 0.0;
    for (int k = 0; k < 3; ++k) {
      double d = q[RN_EDGE_LOCAL_X1 + k] - q[RN_EDGE_LOCAL_X0 + k];
      l2 += d * d;
    }
    if (rnk_stretch_energy(q, &r->sp[j], &E) != RNK_OK)
      return rn_fail(net->ctx, RN_DEGENERATE, where, "rod %d edge %d: degenerate edge",
                     rod, j);
    if (axial_force) axial_force[j] = r->sp[j].k * (sqrt(l2) / r->sp[j].lbar - 1.0);
    if (stretch_energy) stretch_energy[j] = E;
  }
  return RN_OK;
}

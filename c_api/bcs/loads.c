/* loads.c - dead loads: point forces, couples, line loads, gravity, and
 * their lumping to vertex forces at finalize. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <math.h>

#include "bcs/bcs.h"
#include "rodnet_couple.h"

int rn_moment_edge(int nv, int vertex) { return vertex < nv - 1 ? vertex : nv - 2; }

/* Checks a load on vertex `vertex` of rod (whole-network index): the vertex
 * into *v, the local rod index into *lr; RN_NOT_HERE if another part holds
 * the rod (the load has no effect here). */
static rn_status check_load(const rn_network *net, const char *where, int rod, int vertex,
                            const double *value, int *v, int *lr) {
  rn_status st, here;
  int nv = rn_net_rod_nv(net, rod);
  *lr = rod;
  if ((st = rn_net_check_building(net, where))) return st;
  here = rn_net_rod(net, where, lr);
  if (here && here != RN_NOT_HERE) return here;
  *v = rn_wrap_index(vertex, nv);
  if (*v < 0)
    return rn_fail(net->ctx, RN_ERR_RANGE, where,
                   "rod %d: vertex %d out of range (%d vertices)", rod, vertex, nv);
  if (!value) return rn_fail(net->ctx, RN_ERR_ARG, where, "value is NULL");
  if (!rn_all_finite(3, value))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where,
                   "rod %d vertex %d: load is not finite", rod, *v);
  return here;
}

rn_status rn_network_add_force(rn_network *net, int rod, int vertex, const double f[3]) {
  rn_status st;
  int v, lr;
  if (!net) return RN_ERR_ARG;
  if ((st = check_load(net, "rn_network_add_force", rod, vertex, f, &v, &lr)))
    return rn_not_here_ok(st);
  for (int k = 0; k < 3; ++k) net->rods[lr].fpoint[3 * v + k] += f[k];
  return RN_OK;
}

rn_status rn_network_add_moment(rn_network *net, int rod, int vertex, const double m[3]) {
  return rn_network_add_moment_model(net, rod, vertex, m, RN_COUPLE_CONSERVATIVE);
}

rn_status rn_network_add_moment_model(rn_network *net, int rod, int vertex,
                                      const double m[3], rn_couple_model model) {
  static const char *where = "rn_network_add_moment";
  rn_status st;
  rn_moment *mo;
  int v, lr, gid;
  if (!net) return RN_ERR_ARG;
  if (model != RN_COUPLE_CONSERVATIVE && model != RN_COUPLE_FIXED)
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "rod %d vertex %d: unknown couple model %d", rod, vertex, (int)model);
  st = check_load(net, where, rod, vertex, m, &v, &lr);
  if (st && st != RN_NOT_HERE) return st;
  gid = rn_part_next_moment(net);
  if (model == RN_COUPLE_FIXED && net->nfixed_couples++ == 0) {
    net->fixed_on_joint = 0;
    net->fixed_rod = rod;
    net->fixed_vertex = v;
  }
  if (st == RN_NOT_HERE) return RN_OK;
  if (net->nmom == net->cap_mom) {
    int cap = net->cap_mom ? 2 * net->cap_mom : 8;
    rn_moment *p = realloc(net->moments, (size_t)cap * sizeof(*p));
    if (!p) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
    net->moments = p;
    net->cap_mom = cap;
  }
  mo = &net->moments[net->nmom++];
  memset(mo, 0, sizeof(*mo));
  mo->gid = gid;
  mo->rod = lr;
  mo->vertex = v;
  mo->edge = rn_moment_edge(net->rods[lr].nv, v);
  mo->model = (int)model;
  memcpy(mo->M, m, sizeof(mo->M));
  return RN_OK;
}

int rn_network_fixed_couples(const rn_network *net, int *rod, int *vertex) {
  if (!net) return 0;
  if (net->nfixed_couples > 0) {
    if (rod) *rod = net->fixed_rod;
    if (vertex) *vertex = net->fixed_vertex;
  }
  return net->nfixed_couples;
}

int rn_network_fixed_couple_joint(const rn_network *net, int *joint) {
  if (!net) return 0;
  if (net->nfixed_couples > 0 && joint)
    *joint = net->fixed_on_joint ? net->fixed_joint : -1;
  return net->nfixed_couples;
}

const char *rn_network_fixed_couple_where(const rn_network *net, char *buf, size_t n) {
  const char *name = NULL;
  if (!buf || n == 0) return buf;
  buf[0] = '\0';
  if (!net || net->nfixed_couples == 0) return buf;
  if (net->fixed_on_joint) {
    name = rn_network_joint_name(net, net->fixed_joint);
    if (name && name[0])
      snprintf(buf, n, "joint '%s'", name);
    else
      snprintf(buf, n, "joint %d", net->fixed_joint);
    return buf;
  }
  name = rn_network_rod_name(net, net->fixed_rod);
  if (name && name[0])
    snprintf(buf, n, "rod '%s' vertex %d", name, net->fixed_vertex);
  else
    snprintf(buf, n, "rod %d vertex %d", net->fixed_rod, net->fixed_vertex);
  return buf;
}

rn_status rn_network_add_line_load(rn_network *net, int rod, const double w[3]) {
  static const char *where = "rn_network_add_line_load";
  rn_status st;
  int v, lr;
  if (!net) return RN_ERR_ARG;
  if ((st = check_load(net, where, rod, 0, w, &v, &lr))) return rn_not_here_ok(st);
  for (int k = 0; k < 3; ++k) net->rods[lr].line_load[k] += w[k];
  return RN_OK;
}

rn_status rn_network_add_gravity(rn_network *net, const double g[3]) {
  static const char *where = "rn_network_add_gravity";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_building(net, where))) return st;
  if (!g) return rn_fail(net->ctx, RN_ERR_ARG, where, "g is NULL");
  if (!rn_all_finite(3, g))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "g is not finite");
  for (int k = 0; k < 3; ++k) net->gravity[k] += g[k];
  return RN_OK;
}

/* Vertex forces: point forces plus line load and gravity per unit rest
 * length, each edge giving half of its share to either end (Voronoi
 * lumping). */
void rn_rod_lump_forces(const rn_network *net, rn_rod *r) {
  memcpy(r->fvert, r->fpoint, 3 * (size_t)r->nv * sizeof(double));
  for (int j = 0; j < r->ne; ++j) {
    double half = 0.5 * r->lbar[j], rhoA = r->mat[j].density * r->sec[j].A;
    for (int k = 0; k < 3; ++k) {
      double f = half * (r->line_load[k] + rhoA * net->gravity[k]);
      r->fvert[3 * j + k] += f;
      r->fvert[3 * (j + 1) + k] += f;
    }
  }
}

/* partition.c - what every building call asks of a network that may be a part
 * of a partition or hold only the rod graph (docs/parallel.md): whole-network
 * counts and index translation, and the records of the rods and joints added
 * (the partition itself is made by parts/part.c). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/partition.h"

/* ---- counts and index translation ------------------------------------------ */
int rn_net_num_rods_g(const rn_network *net) {
  if (!net->part) return net->nrods;
  return net->part->mode == MODE_PART ? net->part->nrods_total : net->part->nrods;
}

int rn_net_num_joints_g(const rn_network *net) {
  if (!net->part) return net->njoints;
  return net->part->mode == MODE_PART ? net->part->njoints_total : net->part->njoints;
}

int rn_net_rods_added(const rn_network *net) {
  return net->part ? net->part->nrods : net->nrods;
}

int rn_net_joints_added(const rn_network *net) {
  return net->part ? net->part->njoints : net->njoints;
}

int rn_net_rod_nv(const rn_network *net, int gid) {
  if (gid < 0 || gid >= rn_net_num_rods_g(net)) return 0;
  if (!net->part) return net->rods[gid].nv;
  if (net->part->mode == MODE_PART && gid >= net->part->nrods) return 0; /* not yet */
  return net->part->rod_nv[gid];
}

rn_status rn_net_rod(const rn_network *net, const char *where, int *rod) {
  int n = net->part ? net->part->nrods : net->nrods; /* added so far */
  if (*rod < 0 || *rod >= n)
    return rn_fail(net->ctx, RN_ERR_RANGE, where, "rod %d does not exist (%d rods)", *rod,
                   n);
  if (!net->part) return RN_OK;
  if (net->part->mode == MODE_GRAPH || net->part->rod_local[*rod] < 0) return RN_NOT_HERE;
  *rod = net->part->rod_local[*rod];
  return RN_OK;
}

rn_status rn_net_joint(const rn_network *net, const char *where, int *joint) {
  int n = net->part ? net->part->njoints : net->njoints;
  if (*joint < 0 || *joint >= n)
    return rn_fail(net->ctx, RN_ERR_RANGE, where, "joint %d does not exist (%d joints)",
                   *joint, n);
  if (!net->part) return RN_OK;
  if (net->part->mode == MODE_GRAPH || net->part->joint_local[*joint] < 0)
    return RN_NOT_HERE;
  *joint = net->part->joint_local[*joint];
  return RN_OK;
}

/* Grows *a (elements of size bytes) to hold need elements; *cap in elements. */
static int grow(void **a, int *cap, int need, size_t size) {
  int c = *cap ? *cap : 16;
  void *p;
  if (need <= *cap) return 0;
  while (c < need) c *= 2;
  p = realloc(*a, (size_t)c * size);
  if (!p) return -1;
  *a = p;
  *cap = c;
  return 0;
}

static double dist3(const double *a, const double *b) {
  double d0 = a[0] - b[0], d1 = a[1] - b[1], d2 = a[2] - b[2];
  return sqrt(d0 * d0 + d1 * d1 + d2 * d2);
}

static rn_status graph_add_rod(rn_network *net, int nv, const double *xyz) {
  rn_part_data *p = net->part;
  int cap = p->cap_rods, cap2 = p->cap_rods;
  double *e;
  void *nvp = p->rod_nv, *ep = p->rod_ends, *jp = p->rod_endj;
  int fail = grow(&nvp, &cap, p->nrods + 1, sizeof(int));
  p->rod_nv = nvp;
  fail = fail || grow(&ep, &cap2, p->nrods + 1, 8 * sizeof(double));
  p->rod_ends = ep;
  fail = fail || grow(&jp, &p->cap_rods, p->nrods + 1, 2 * sizeof(int));
  p->rod_endj = jp;
  if (fail) return rn_fail(net->ctx, RN_ERR_ALLOC, "rn_network_add_rod", "out of memory");
  e = p->rod_ends + 8 * (size_t)p->nrods;
  memcpy(e, xyz, 3 * sizeof(double));
  memcpy(e + 3, xyz + 3 * (nv - 1), 3 * sizeof(double));
  e[6] = dist3(xyz, xyz + 3);
  e[7] = dist3(xyz + 3 * (nv - 2), xyz + 3 * (nv - 1));
  p->rod_nv[p->nrods] = nv;
  p->rod_endj[2 * p->nrods] = p->rod_endj[2 * p->nrods + 1] = -1;
  p->nrods++;
  return RN_NOT_HERE;
}

static rn_status graph_add_joint(rn_network *net, const char *name, int n,
                                 const int *rods, const int *ends, const int *images) {
  static const char *where = "rn_network_add_joint";
  rn_part_data *p = net->part;
  int cap = p->cap_ends, have = p->jptr[p->njoints];
  rn_joint_point *pt;
  for (int k = 0; k < n; ++k) {
    int o = p->rod_endj[2 * rods[k] + ends[k]];
    if (o >= 0)
      return rn_fail(net->ctx, RN_ERR_ARG, where,
                     "the %s of rod %d already belongs to joint %d; a rod end belongs "
                     "to at most one joint",
                     ends[k] == RN_START ? "start" : "end", rods[k], o);
  }
  void *rp = p->jrods, *ep = p->jends, *jp = p->jptr, *pp = p->points;
  int fail = grow(&rp, &cap, have + n, sizeof(int));
  p->jrods = rp;
  fail = fail || grow(&ep, &p->cap_ends, have + n, sizeof(int));
  p->jends = ep;
  fail = fail || grow(&jp, &p->cap_joints, p->njoints + 2, sizeof(int));
  p->jptr = jp;
  fail = fail || grow(&pp, &p->cap_points, p->njoints + 1, sizeof(rn_joint_point));
  p->points = pp;
  pp = p->names;
  fail = fail || grow(&pp, &p->cap_names, p->njoints + 1, sizeof(char *));
  p->names = pp;
  if (fail) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  pt = &p->points[p->njoints]; /* as rn_network_add_joint sets x0 and lmin */
  memcpy(pt->x0, p->rod_ends + 8 * (size_t)rods[0] + 3 * ends[0], sizeof(pt->x0));
  if (images && net->cell) { /* the first end at an image: shifted back */
    for (int c = 0; c < 3; ++c)
      for (int m = 0; m < net->cell->dim; ++m)
        pt->x0[c] -= images[m] * net->cell->a[m][c];
  }
  pt->lmin = INFINITY;
  for (int k = 0; k < n; ++k)
    pt->lmin = fmin(pt->lmin, p->rod_ends[8 * (size_t)rods[k] + 6 + ends[k]]);
  pt->gid = p->njoints;
  p->names[p->njoints] = name ? malloc(strlen(name) + 1) : NULL;
  if (p->names[p->njoints]) strcpy(p->names[p->njoints], name);
  pt->name = p->names[p->njoints];
  for (int k = 0; k < n; ++k) {
    p->jrods[have + k] = rods[k];
    p->jends[have + k] = ends[k];
    p->rod_endj[2 * rods[k] + ends[k]] = p->njoints;
  }
  p->jptr[++p->njoints] = have + n;
  return RN_NOT_HERE;
}

/* ---- building hooks --------------------------------------------------------- */
rn_status rn_part_add_rod(rn_network *net, int nv, const double *xyz, int *keep) {
  rn_part_data *p = net->part;
  int gid;
  *keep = 1;
  if (!p) return RN_OK;
  *keep = 0;
  if (p->mode == MODE_GRAPH) return graph_add_rod(net, nv, xyz);
  gid = p->nrods;
  if (gid >= p->nrods_total || p->rod_nv[gid] != nv)
    return rn_fail(net->ctx, RN_ERR_ARG, "rn_network_add_rod",
                   "rod %d (%d vertices) is not rod %d of the partition's graph", gid, nv,
                   gid);
  p->nrods++;
  if (p->rod_local[gid] >= 0) {
    p->rod_key[p->rod_local[gid]] = p->next_key;
    *keep = 1;
  }
  p->next_key += (int64_t)rn_dof_rod_count(nv);
  return *keep ? RN_OK : RN_NOT_HERE;
}

void rn_part_tag_rod(const rn_network *net, rn_rod *r) {
  const rn_part_data *p = net->part;
  r->gid = p ? p->nrods - 1 : net->nrods;
  r->owner = p ? p->rod_part[r->gid] : 0;
  r->ghost = p ? r->owner != p->part : 0;
}

rn_status rn_part_add_joint(rn_network *net, const char *name, int n, const int *rods,
                            const int *ends, const int *images, int *keep,
                            int *keep_end) {
  rn_part_data *p = net->part;
  int gid;
  *keep = 1;
  for (int k = 0; k < n; ++k) keep_end[k] = 1;
  if (!p) return RN_OK;
  *keep = 0;
  if (p->mode == MODE_GRAPH) return graph_add_joint(net, name, n, rods, ends, images);
  gid = p->njoints;
  if (gid >= p->njoints_total)
    return rn_fail(net->ctx, RN_ERR_ARG, "rn_network_add_joint",
                   "joint %d is not in the partition's graph (%d joints)", gid,
                   p->njoints_total);
  p->njoints++;
  if (p->joint_local[gid] < 0) return RN_NOT_HERE;
  for (int k = 0; k < n; ++k) keep_end[k] = p->rod_local[rods[k]] >= 0;
  if (!keep_end[0])
    return rn_fail(net->ctx, RN_ERR_INTERNAL, "rn_network_add_joint",
                   "joint %d: its first rod is not held by part %d", gid, p->part);
  *keep = 1;
  return RN_OK;
}

void rn_part_tag_joint(const rn_network *net, rn_joint *J) {
  const rn_part_data *p = net->part;
  J->gid = p ? p->njoints - 1 : net->njoints;
  J->owner = p ? p->joint_owner[J->gid] : 0;
  J->ghost = p ? J->owner != p->part : 0;
}

int rn_part_next_moment(rn_network *net) {
  return net->part ? net->part->nmom++ : net->nmom;
}

/* ---- queries -------------------------------------------------------------------- */
int rn_cell_owned_here(const rn_network *net) {
  return !net->part || (net->part->mode == MODE_PART && net->part->part == 0);
}

int rn_network_rod_is_local(const rn_network *net, int rod) {
  if (!net || rod < 0 || rod >= rn_net_num_rods_g(net)) return 0;
  if (!net->part) return 1;
  return net->part->mode == MODE_PART && net->part->rod_local[rod] >= 0;
}

int rn_network_is_part(const rn_network *net) {
  return net && net->part && net->part->mode == MODE_PART;
}

int rn_network_is_graph_only(const rn_network *net) {
  return net && net->part && net->part->mode == MODE_GRAPH;
}

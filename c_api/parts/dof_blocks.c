/* dof_blocks.c - the rod / interface classification of the reduced DOFs that
 * rod-level domain decomposition needs (rn_network_dof_blocks).
 *
 * A reduced DOF is a rod-interior DOF of rod r when every stencil containing it
 * belongs to rod r or couples it with interface DOFs only; otherwise it is an
 * interface DOF.  Rod stencils (stretch, bend, twist, couples) are slices of one
 * rod's vector; a rod end at a joint aliases the joint position.  The joint
 * stencil holds the joint position, its rotation (rigid kernel: rigid joints and
 * clamped joints of either model) and per end the vertex next to the joint and
 * the terminal edge's angle.  With the rigid kernel the joint energy is a sum of
 * end terms, each coupling one end only with the joint's own DOFs, so the ends
 * stay rod-interior; the elastic joint's rotation fit couples every end with
 * every other, so there the ends' DOFs are interface DOFs too.  Contact: the
 * vertices of both edges of every pair in the Hessian pattern that joins two
 * rods, or two edges of one rod at least 3 apart, are interface DOFs (edges j
 * and j + 2 of a rod, within reach on every straight rod, couple DOFs inside
 * the rod's band). */
#include <math.h>
#include <string.h>

#include "contact/contact.h"

static void set_dof(const rn_network *net, size_t a, int32_t blk, const double p[3],
                    const double t[3], int32_t *block, double *point, double *axis) {
  static const double zero[3] = {0.0, 0.0, 0.0};
  int64_t m = net->map[a];
  if (m < 0) return;
  block[m] = blk;
  if (point) memcpy(point + 3 * m, p, 3 * sizeof(double));
  if (axis) memcpy(axis + 3 * m, t ? t : zero, 3 * sizeof(double));
}

/* Every DOF of rod ir as interior to it: vertices, then material angles (point:
 * the edge's midpoint, axis: its unit tangent). */
static void classify_rod(const rn_network *net, int ir, int32_t *block, double *point,
                         double *axis) {
  const rn_rod *r = &net->rods[ir];
  for (int i = 0; i < r->nv; ++i) {
    const double *xi = net->xfull + rn_dof_vertex(r->off, i);
    for (int k = 0; k < 3; ++k)
      set_dof(net, rn_dof_vertex(r->off, i) + (size_t)k, ir, xi, NULL, block, point,
              axis);
  }
  for (int j = 0; j < r->ne; ++j) {
    const double *a = net->xfull + rn_dof_vertex(r->off, j);
    const double *b = net->xfull + rn_dof_vertex(r->off, j + 1);
    double mid[3], t[3], len = 0.0;
    for (int k = 0; k < 3; ++k) {
      mid[k] = 0.5 * (a[k] + b[k]);
      t[k] = b[k] - a[k];
      len += t[k] * t[k];
    }
    len = sqrt(len);
    for (int k = 0; k < 3; ++k) t[k] = len > 0.0 ? t[k] / len : 0.0;
    set_dof(net, rn_dof_theta(r->off, j), ir, mid, t, block, point, axis);
  }
}

rn_status rn_network_dof_blocks(const rn_network *net, int32_t *block, double *point,
                                double *axis) {
  static const char *where = "rn_network_dof_blocks";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!block && net->nred) return rn_fail(net->ctx, RN_ERR_ARG, where, "block is NULL");
  /* a DOF of neither a rod nor a joint (none today) is an interface DOF at the
   * origin: never left unset */
  for (size_t m = 0; m < net->nred; ++m) {
    block[m] = RN_DOF_INTERFACE;
    if (point) memset(point + 3 * m, 0, 3 * sizeof(double));
    if (axis) memset(axis + 3 * m, 0, 3 * sizeof(double));
  }
  for (int ir = 0; ir < net->nrods; ++ir) classify_rod(net, ir, block, point, axis);
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    const double *xj = net->xfull + rn_dof_joint_position(J->off);
    for (int k = 0; k < 3; ++k)
      set_dof(net, rn_dof_joint_position(J->off) + (size_t)k, RN_DOF_INTERFACE, xj, NULL,
              block, point, axis);
    if (rn_joint_has_rotation(J)) {
      for (int k = 0; k < 3; ++k)
        set_dof(net, rn_dof_joint_rotation(J->off) + (size_t)k, RN_DOF_INTERFACE, xj,
                NULL, block, point, axis);
      continue; /* rigid kernel: the ends do not couple with each other */
    }
    for (int k = 0; k < J->valence; ++k) {
      const rn_rod *r = &net->rods[J->rod[k]];
      size_t v = rn_dof_vertex(r->off, rn_end_neighbor(r->nv, J->end[k]));
      size_t th = rn_dof_theta(r->off, rn_end_edge(r->nv, J->end[k]));
      for (size_t a = v; a < v + 3; ++a)
        if (net->map[a] >= 0) block[net->map[a]] = RN_DOF_INTERFACE;
      if (net->map[th] >= 0) block[net->map[th]] = RN_DOF_INTERFACE;
    }
  }
  for (size_t i = 0; i < rn_contact_pattern_count(net); ++i) {
    size_t idx[12];
    if (!rn_contact_pattern_far(net, i)) continue;
    rn_contact_pattern_idx(net, i, idx);
    for (int k = 0; k < 12; ++k)
      if (net->map[idx[k]] >= 0) block[net->map[idx[k]]] = RN_DOF_INTERFACE;
  }
  return RN_OK;
}

/* joint_results.c - joint position and rotation at the current state. */
#include <string.h>

#include "joints/joints.h"
#include "periodic/periodic.h"

/* Checks a result call on joint *joint (whole-network index) and translates it
 * into the local index; RN_ERR_RANGE also for a joint held by another part and,
 * if need_owned, for a ghost joint (whose stencil is not held here). */
static rn_status check_joint_result(const rn_network *net, const char *where, int *joint,
                                    const void *out, int need_owned) {
  rn_status st;
  int g = *joint;
  if ((st = rn_net_check_final(net, where))) return st;
  st = rn_net_joint(net, where, joint);
  if (st == RN_NOT_HERE || (!st && need_owned && net->joints[*joint].ghost))
    return rn_fail(net->ctx, RN_ERR_RANGE, where,
                   "joint %d is held by another part of the network", g);
  if (st) return st;
  if (!out) return rn_fail(net->ctx, RN_ERR_ARG, where, "output is NULL");
  return RN_OK;
}

rn_status rn_network_joint_position(const rn_network *net, int joint, double x[3]) {
  static const char *where = "rn_network_joint_position";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = check_joint_result(net, where, &joint, x, 0))) return st;
  memcpy(x, net->xfull + rn_dof_joint_position(net->joints[joint].off),
         3 * sizeof(double));
  return RN_OK;
}

rn_status rn_network_joint_rotation(const rn_network *net, int joint, double R[9]) {
  static const char *where = "rn_network_joint_rotation";
  const rn_joint *J;
  rn_joint_scratch s;
  rnk_joint kj;
  rn_status st;
  int rc;
  if (!net) return RN_ERR_ARG;
  if ((st = check_joint_result(net, where, &joint, R, 1))) return st;
  J = &net->joints[joint];
  if (rn_joint_scratch_init(J, &s))
    return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  rn_joint_kernel(net, joint, net->lambda, s.refs, &kj);
  rn_joint_gather_full(net, J, net->xfull, s.q);
  rc = rnk_joint_rotation(s.q, &kj, R);
  rn_joint_scratch_free(&s);
  if (rc != RNK_OK)
    return rn_fail(net->ctx, RN_DEGENERATE, where,
                   "joint %d ('%s'): the rotation fit is singular at the current state",
                   J->gid, J->name ? J->name : "");
  return RN_OK;
}

rn_status rn_network_joint_twist(const rn_network *net, int joint, double *twist) {
  static const char *where = "rn_network_joint_twist";
  const rn_joint *J;
  rn_joint_scratch s;
  rnk_joint kj;
  rn_status st;
  double q11[11], kappa[2];
  int rc;
  if (!net) return RN_ERR_ARG;
  if ((st = check_joint_result(net, where, &joint, twist, 1))) return st;
  J = &net->joints[joint];
  if (J->model != RN_JOINT_SMOOTH)
    return rn_fail(net->ctx, RN_ERR_ARG, where, "joint %d ('%s') is not a smooth joint",
                   J->gid, J->name ? J->name : "");
  if (rn_joint_scratch_init(J, &s))
    return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  rn_joint_kernel(net, joint, net->lambda, s.refs, &kj);
  rn_joint_gather_full(net, J, net->xfull, s.q);
  rnk_smooth_joint_vertex(s.q, q11);
  rc = rnk_strains(q11, s.refs, J->ends[0].twist.ref_twist, kappa, twist);
  rn_joint_scratch_free(&s);
  if (rc != RNK_OK)
    return rn_fail(net->ctx, RN_DEGENERATE, where,
                   "joint %d ('%s'): degenerate vertex at the current state", J->gid,
                   J->name ? J->name : "");
  return RN_OK;
}

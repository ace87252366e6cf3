/* joints.h - joints (joints.c, joint_stencil.c, joint_results.c; docs/joints.md):
 * finalize steps, placement under the load factor, the kernel parameters and
 * the evaluation scratch of a joint stencil. */
#ifndef RN_JOINTS_MODULE_H
#define RN_JOINTS_MODULE_H

#include "core/network_internal.h"

void rn_joint_free(rn_joint *J);

/* Finalize steps: BC conflicts with rod vertices, coincident joints
 * (validate); kernel parameters and stencil index lists (build, after the
 * DOF offsets are set); the fit at the initial state (check_initial). */
rn_status rn_joints_validate(const rn_network *net, const char *where);
rn_status rn_joint_points_check(rn_context *ctx, const char *where, int n,
                                const rn_joint_point *p);
rn_status rn_joints_build(rn_network *net);
rn_status rn_joints_check_initial(const rn_network *net, const char *where);
void rn_joints_unbuild(rn_network *net);
/* Fixed joint DOFs (positions, prescribed rotations Qhat) for the current
 * load factor, copied to the aliased rod end vertices of net->xfull (place);
 * then, once every fixed DOF is placed, the stored twists of clamped joints
 * with a prescribed motion are continued (continue_twists). */
void rn_joints_place(rn_network *net);
void rn_joints_continue_twists(rn_network *net);
/* Copies each joint position in net->xfull to its rod end vertices. */
void rn_joints_sync(rn_network *net);

/* Kernel parameters of joint ij: copies the terminal edges' current
 * reference frames to refs[valence] and fills kj, the couple scaled by
 * load_scale (the network's load factor, or 1 for the load rate). */
void rn_joint_kernel(const rn_network *net, int ij, double load_scale, rnk_frame *refs,
                     rnk_joint *kj);
/* Scratch of one joint evaluation (declared by the caller, on its stack:
 * evaluation stays reentrant): q[n], v[n], loc[n n] (gradient or Hessian
 * block), the kernel workspace and the reference frames; in the embedded
 * buffers up to valence 8, on the heap beyond. */
enum { RN_JOINT_STACK = 5120, RN_JOINT_STACK_ENDS = 8 };
typedef struct rn_joint_scratch {
  int n; /* stencil size */
  double *q, *v, *loc, *work;
  double *fix; /* a fixed couple's force and Jacobian (n + n n), NULL if the
                  joint has none */
  rnk_frame *refs;
  double *heap; /* NULL if the buffers below suffice */
  rnk_frame *heap_refs;
  double buf[RN_JOINT_STACK];
  rnk_frame frames[RN_JOINT_STACK_ENDS];
} rn_joint_scratch;
/* RN_ERR_ALLOC if the heap fallback fails. */
rn_status rn_joint_scratch_init(const rn_joint *J, rn_joint_scratch *s);
void rn_joint_scratch_free(rn_joint_scratch *s);

#endif

/* dof_layout.h - the ONE definition of rodnet's DOF layout (private).
 *
 * Full DOF vector of a rod with n vertices (4n - 1 entries, seed 000):
 *   (x_0[3], theta^0, x_1[3], theta^1, ..., theta^{n-2}, x_{n-1}[3]);
 * rods are concatenated, each starting at its offset.  The stencils of the
 * energy kernels are contiguous slices of that vector:
 *   edge stencil j   (x_j, theta^j, x_{j+1})                    7 DOFs at 4j,
 *   vertex stencil i (x_{i-1}, theta^{i-1}, x_i, theta^i, x_{i+1}) 11 DOFs at 4(i-1).
 *
 * Joints follow all rods, each at its offset: position x_J (3) and, for
 * joints with a rotation (rigid, or clamped), the rotation vector w (3).  A
 * rod end vertex attached to a joint keeps its slot in the rod's vector but
 * aliases the joint position (same reduced index).  The joint kernel stencil
 * of rnk.h is gathered by an index list:
 *   (x_J[3], w[3] if the kernel treats the joint as rigid, then per end k:
 *    x_n[3] of the rod vertex next to the joint, theta of the terminal edge).
 * Every other file uses these functions; no index arithmetic elsewhere. */
#ifndef RODNET_DOF_LAYOUT_H
#define RODNET_DOF_LAYOUT_H

#include <stddef.h>

enum {
  RN_DOFS_PER_VERTEX = 3,  /* position */
  RN_EDGE_STENCIL = 7,     /* q[7] of rnk.h */
  RN_VERTEX_STENCIL = 11,  /* q[11] of rnk.h */
  RN_EDGE_LOCAL_X0 = 0,    /* x_j in an edge stencil */
  RN_EDGE_LOCAL_THETA = 3, /* theta^j in an edge stencil */
  RN_EDGE_LOCAL_X1 = 4     /* x_{j+1} in an edge stencil */
};

/* Number of full DOFs of a rod with nv vertices. */
static inline size_t rn_dof_rod_count(int nv) { return 4 * (size_t)nv - 1; }

/* Full index of the first coordinate of vertex i of a rod at offset off. */
static inline size_t rn_dof_vertex(size_t off, int i) { return off + 4 * (size_t)i; }

/* Full index of the material angle theta^j of edge j. */
static inline size_t rn_dof_theta(size_t off, int j) { return off + 4 * (size_t)j + 3; }

/* First full index of the edge stencil of edge j (7 DOFs). */
static inline size_t rn_dof_edge_stencil(size_t off, int j) {
  return off + 4 * (size_t)j;
}

/* First full index of the vertex stencil of interior vertex i (11 DOFs). */
static inline size_t rn_dof_vertex_stencil(size_t off, int i) {
  return off + 4 * (size_t)(i - 1);
}

/* Local index, inside any stencil slice, of the k-th vertex's first
 * coordinate and of the k-th edge's material angle (k = 0, 1, 2). */
static inline int rn_stencil_x(int k) { return 4 * k; }
static inline int rn_stencil_theta(int k) { return 4 * k + 3; }

/* ---- joints ---------------------------------------------------------------- */
/* Full DOFs of a joint with (1) or without (0) rotation DOFs. */
static inline size_t rn_dof_joint_count(int has_rotation) { return has_rotation ? 6 : 3; }
/* Full index of a joint's position and rotation vector (joint at offset off). */
static inline size_t rn_dof_joint_position(size_t off) { return off; }
static inline size_t rn_dof_joint_rotation(size_t off) { return off + 3; }

/* Rod end (0 = start, 1 = end) of a rod with nv vertices: the end vertex, the
 * vertex next to it and the terminal edge. */
static inline int rn_end_vertex(int nv, int end) { return end == 0 ? 0 : nv - 1; }
static inline int rn_end_neighbor(int nv, int end) { return end == 0 ? 1 : nv - 2; }
static inline int rn_end_edge(int nv, int end) { return end == 0 ? 0 : nv - 2; }

/* Local index in the joint kernel stencil of x_J, w and end k's x_n (theta
 * follows at + 3); rigid = 1 if the kernel has rotation DOFs. */
enum { RN_JOINT_LOCAL_X = 0, RN_JOINT_LOCAL_W = 3 };
static inline int rn_joint_local_end(int rigid, int k) {
  return 3 + (rigid ? 3 : 0) + 4 * k;
}
static inline int rn_joint_stencil_count(int rigid, int valence) {
  return rn_joint_local_end(rigid, valence);
}

#endif

/* rnk_couple.h - a couple fixed in space on an edge's material frame (not
 * conservative in 3D: a generalised force and its nonsymmetric Jacobian, no
 * energy).  Kernels layer: libm only. */
#ifndef RODNET_RNK_COUPLE_H
#define RODNET_RNK_COUPLE_H

#include "rnk.h"

/* Edge stencil q[7] = (x0[3], theta, x1[3]) with reference frame ref.  The
 * couple M (a constant vector in the global frame) does the virtual work
 * M . omega, omega the angular velocity of the edge's material frame
 * (t, d1, d2): omega = 1/2 sum_k d_k x d_k'.  Writes the generalised force
 * Q[i] = M . d omega / d q_i (Q = -gradient of the work's "potential" where
 * one exists: in a plane) and, if J is not NULL, its Jacobian
 * J[7 i + j] = d Q_i / d q_j (nonsymmetric in 3D).  RNK_DEGENERATE for a zero
 * edge or a tangent opposite to the reference tangent. */
int rnk_couple_fixed_force(const double q[7], const rnk_frame *ref, const double M[3],
                           double Q[7], double *J);

/* The same couple on the rotation Q of a joint (rnk_joint of rnk.h, rigid or
 * elastic; j->M is ignored): the generalised force Q[i] = M . d omega / d q_i
 * on the joint stencil q (size rnk_joint_stencil_size(j)), omega the angular
 * velocity of Q ([omega] = dQ Q^T), and, if J is not NULL, its Jacobian
 * J[n i + j] = d Q_i / d q_j (nonsymmetric).  Rigid joints: only the rotation
 * DOFs w get a force; elastic joints: every end through the fit's rotation.
 * work: rnk_joint_work_size(j) doubles.  RNK_DEGENERATE at a degenerate fit
 * and for a smooth joint (no rotation). */
int rnk_joint_couple_fixed_force(const double *q, const rnk_joint *j, const double M[3],
                                 double *work, double *Q, double *J);

/* The spatial moment that the conservative couple rnk_moment_* applies at
 * the frame (t, d1, d2) = F[9]: with f = b1 t + b2 d1 + b3 d2 (unit) and
 * n = M / |M|, m = f x (M x f) / |n x f|^2 (docs/model.md, "Loads").  Its
 * gradient equals -rnk_couple_fixed_force(m) at that frame.  RNK_DEGENERATE
 * if f is parallel to M. */
int rnk_moment_spatial(const double F[9], const double b[3], const double M[3],
                       double m[3]);

#endif

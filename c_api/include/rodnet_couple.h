/* rodnet_couple.h - the models of a couple (a `moment` load) on a rod vertex
 * or a joint (docs/model.md, "Loads").
 *
 * RN_COUPLE_CONSERVATIVE (rn_network_add_moment): the potential
 * -|M| phi, phi the rotation about the fixed axis n = M/|M| of a vector f
 * fixed in the edge's material frame and perpendicular to n at the start.
 * It applies the spatial moment m = f x (M x f) / |n x f|^2: m = M while f
 * stays in the plane normal to M (in particular in planar problems), and m
 * departs from M, keeping m . n = |M|, once the edge turns f out of that plane.
 *
 * RN_COUPLE_FIXED: a couple fixed in space, the virtual work M . omega with
 * omega the angular velocity of the edge's material frame (on a joint: of the
 * joint's rotation Q, [omega] = dQ Q^T; the rotation DOFs of a rigid joint,
 * the terminal edges through the rotation fit of an elastic one).  It has no
 * potential in 3D: it enters the network's gradient (the residual; the
 * energy gets no term) and Hessian (its Jacobian, nonsymmetric), so a
 * network with one is solved only by RN_SOLVER_NOX (Newton on the residual
 * with GMRES); the energy minimisers, path following, the stability checks
 * (rn_network_stability, rn_hessian_min_eigenvalue), homogenisation
 * (rn_homogenize) and the periodic cell's relaxation and Bloch analysis
 * (rn_cell_relax, rn_cell_minimize, rn_cell_bloch, rn_cell_bloch_eigen)
 * refuse it with RN_ERR_ARG naming the couple.
 *
 * The conservative couple's potential is singular where f reaches the axis n
 * and not bounded below in 3D (each passage of f around n adds 2 pi to phi):
 * rn_network_update_reference fails with RN_ERR_SOLVER, naming the couple, on a
 * state that turns f more than 80 degrees out of the plane normal to M (so an
 * energy minimiser stops there instead of running away; docs/model.md,
 * Couples), unless rn_network_set_couple_tilt_check switched that off.
 *
 * rn_network_applied_resultant counts each couple as the spatial moment it
 * applies at the current state: m for the conservative couple (of a rod
 * edge or a joint), M for the fixed one (so the reactions balance it in 3D
 * too). */
#ifndef RODNET_COUPLE_H
#define RODNET_COUPLE_H

#include <stddef.h>

#include "rodnet.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum rn_couple_model {
  RN_COUPLE_CONSERVATIVE = 0, /* the potential above (rn_network_add_moment) */
  RN_COUPLE_FIXED = 1         /* a couple fixed in space (nonconservative) */
} rn_couple_model;

/* As rn_network_add_moment (a couple m on the edge at vertex `vertex` of rod
 * `rod`, the last edge for the last vertex), with the model named.  Building
 * phase only.  RN_ERR_ARG for an unknown model.  In a part of a distributed
 * network every part must make the same calls (whole-network indices). */
rn_status rn_network_add_moment_model(rn_network *net, int rod, int vertex,
                                      const double m[3], rn_couple_model model);

/* As rn_network_add_joint_moment (a couple m on the rotation of joint
 * `joint`), with the model named.  RN_COUPLE_FIXED: on a rigid joint it acts
 * on the rotation DOFs, on an elastic joint on the rotation of the fit (so on
 * the terminal edges), on a clamped joint it does nothing (its rotation is
 * held); a smooth joint refuses it at finalize (RN_ERR_BC, no rotation).
 * Both models may load the same joint.  Building phase only.  RN_ERR_ARG for
 * an unknown model.  In a part of a distributed network every part must make
 * the same calls (whole-network indices). */
rn_status rn_network_add_joint_moment_model(rn_network *net, int joint, const double m[3],
                                            rn_couple_model model);

/* Switches the tilt check of the conservative couples on accepted states
 * (above) on (on != 0, the default) or off; rn_solve switches it off for the
 * duration of a RN_SOLVER_NOX solve (Newton on the residual finds stationary
 * points, which may tilt the arm further, and does not descend the energy).
 * Returns the previous setting (1 or 0), -1 for a NULL network. */
int rn_network_set_couple_tilt_check(rn_network *net, int on);

/* Number of RN_COUPLE_FIXED couples added to the whole network, on rods and
 * on joints (0: the problem is conservative), and the rod and vertex of the
 * first of them into *rod and *vertex (either may be NULL; untouched when
 * there is none; -1 and -1 when the first is on a joint:
 * rn_network_fixed_couple_joint).  Not collective (every part makes the same
 * building calls). */
int rn_network_fixed_couples(const rn_network *net, int *rod, int *vertex);

/* The same count; *joint (may be NULL) gets the joint of the first
 * RN_COUPLE_FIXED couple, -1 if it is on a rod (untouched when there is
 * none). */
int rn_network_fixed_couple_joint(const rn_network *net, int *joint);

/* The first RN_COUPLE_FIXED couple for messages: "rod 'name' vertex V" or
 * "joint 'name'" (the index instead of a name that is empty or held by
 * another part), "" if there is none, into buf[n] (truncated; n > 0).
 * Returns buf. */
const char *rn_network_fixed_couple_where(const rn_network *net, char *buf, size_t n);

#ifdef __cplusplus
}
#endif

#endif

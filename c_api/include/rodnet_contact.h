/* rodnet_contact.h - rod-rod and rod-self contact (docs/contact.md).
 *
 * Contact is an energy term summing over pairs of edges the barrier of
 * incremental potential contact, -stiffness (g - distance)^2 log(g / distance)
 * for 0 < g < distance, of their gap g (the distance between the two segments
 * minus twice the radius).  Pairs of edges joined within 2 radius + distance of
 * rest arc length (along a rod, or through a joint both rods meet at) are
 * excluded: neighbouring edges and edges meeting at a joint.  In the energy
 * split (rn_network_energy_terms) the barrier counts as RN_TERM_LOAD (the work
 * of the contact forces, as of the applied loads); rn_network_contact_stats
 * gives it alone.
 *
 * Evaluations at a trial state return RN_DEGENERATE (recoverable: the solver
 * rejects or shortens the step) when a pair interpenetrates, or when the
 * straight motion from the accepted state (the last
 * rn_network_update_reference or rn_network_set_dofs) would bring a pair
 * below 20% of its gap (or of distance) on the way (a continuous collision check by
 * conservative advancement over the pairs of a broad phase), so no accepted state
 * interpenetrates and no step tunnels through.  Nothing here is collective:
 * contact is evaluated on whole networks only (serial solves). */
#ifndef RODNET_CONTACT_H
#define RODNET_CONTACT_H

#include <stddef.h>

#include "rodnet.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Switches contact on, before finalize (off by default); radius is every
 * rod's unless rn_network_set_rod_contact_radius sets another.  RN_ERR_ARG
 * unless distance > 0, stiffness > 0 and radius >= 0 (finite); RN_ERR_STATE
 * after finalize or in a part of a distributed network.  Finalize then fails
 * with RN_ERR_GEOMETRY if the initial state interpenetrates (naming the pair),
 * RN_ERR_STATE for a periodic cell. */
rn_status rn_network_set_contact(rn_network *net, double distance, double stiffness,
                                 double radius);

/* The contact radius of one rod (0-based index of an added rod), before
 * finalize and after rn_network_set_contact: a pair's gap is the distance of
 * its edges minus the sum of their rods' radii.  RN_ERR_STATE without contact
 * or after finalize, RN_ERR_ARG for a bad rod or a radius < 0. */
rn_status rn_network_set_rod_contact_radius(rn_network *net, int rod, double radius);
/* A rod's contact radius (NaN without contact or for a bad rod). */
double rn_network_rod_contact_radius(const rn_network *net, int rod);

/* The version of the Hessian's CSR pattern (rn_network_hessian_pattern).  With
 * contact the pattern holds the contact pairs near the accepted state (pairs
 * whose edge boxes, inflated by the radii, distance and a margin, overlap) and
 * is rebuilt when a new accepted state (rn_network_update_reference,
 * rn_network_set_dofs, rn_network_state_restore, rn_network_set_load_factor)
 * brings other pairs near: then the version changes and the pointers the last
 * rn_network_hessian_pattern returned are invalid.  Evaluations at a trial
 * state where a pair outside the pattern comes within distance return
 * RN_DEGENERATE.  Without contact the version never changes. */
unsigned long rn_network_pattern_version(const rn_network *net);

/* 1 (and the settings; any pointer may be NULL) if contact is on, else 0. */
int rn_network_get_contact(const rn_network *net, double *distance, double *stiffness,
                           double *radius);

/* Contact at the reduced state x (after finalize; pure).  Any output may be
 * NULL. */
typedef struct rn_contact_stats {
  double min_gap; /* smallest gap over the pairs within the barrier's reach
                     (INFINITY if none, or without contact) */
  size_t active;  /* pairs whose gap is below the activation distance */
  double energy;  /* the barrier energy (part of RN_TERM_LOAD) */
  double force;   /* sum over active pairs of the barrier force |dE/dgap| */
} rn_contact_stats;
rn_status rn_network_contact_stats(const rn_network *net, const double *x,
                                   rn_contact_stats *stats);

#ifdef __cplusplus
}
#endif
#endif

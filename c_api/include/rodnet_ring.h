/* rodnet_ring.h - twist stored in a closed rod as a total twist (public;
 * docs/scene-format.md "closed rods").  Declared apart from rodnet.h so that
 * the solver shim does not depend on it. */
#ifndef RODNET_RING_H
#define RODNET_RING_H

#include "rodnet.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Total twist of a closed rod (before finalize): joint is the smooth joint that
 * closes it (rn_network_add_closed_rod).  The material frame turns by total
 * (radians) around the ring, against h + 2 pi link with
 * rn_network_set_joint_link (h the holonomy of the input frame, 0 for a planar
 * ring): the whole turns k nearest to (total - h - s) / 2 pi (s the input twist
 * of the ring's other vertices, 0 for parallel-transported input frames) go
 * into the closing vertex's reference twist, h + 2 pi k, which stays the
 * geometric angle between its edges' frames; the remainder r, |r| <= pi,
 * lowers the rest twist of every vertex of the ring in proportion to its
 * Voronoi length (r in all).  So the ring stores the twist total - h - s
 * relative to its input rest shape, evenly (a planar ring with input frames:
 * total itself; total = 2 pi n is link n), and its geometric total twist
 * (rn_network_joint_twist plus the rod's tau of rn_network_rod_strains) starts
 * at total - r.  For a non-planar ring total fixes the twist Tw = total / 2 pi
 * of Lk = Tw + Wr (Calugareanu-White-Fuller), not the link.  Overrides an
 * earlier rn_network_set_joint_link on the joint and is overridden by a later
 * one.  RN_ERR_ARG for a joint that does not close a ring, RN_ERR_NOT_FINITE
 * for a non-finite total, RN_ERR_STATE after finalize.  Not collective. */
rn_status rn_network_set_ring_total_twist(rn_network *net, int joint, double total);

#ifdef __cplusplus
}
#endif

#endif

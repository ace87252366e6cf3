// equilibrium_scale.hpp - the internal moment of a state, part of the scale of the
// stopping test (equilibrium.hpp; serial Equilibrium and DistSystem::equilibrium).
// A self-stressed state without loads or reactions (a ring with stored twist or
// rest curvature) carries moments all the same: its equilibrium is measured
// against them.  From the stencil force magnitudes the round-off floor needs
// anyway: no extra evaluation.
#ifndef RODNET_SHIM_EQUILIBRIUM_SCALE_HPP
#define RODNET_SHIM_EQUILIBRIUM_SCALE_HPP

#include <cstddef>
#include <vector>

#include "rodnet.h"

namespace rodnet {

// Lever arm of every reduced DOF of net (kind: rn_network_dof_kinds) for
// eq_internal_moment: at a rod vertex the mean rest length of its edges, at a joint
// position (or a ghost rod's) the shortest rest edge of the local rods, 1 for angles
// and rotations (whose gradient is a moment already), 0 for strains.  O(n); throws.
std::vector<double> eq_levers(rn_network *net, const std::vector<int> &kind);

// The internal moment of the state from gabs (rn_network_gradient_magnitude: at each
// DOF the sum of the magnitudes of its stencils' forces or moments), over the first
// n DOFs: the largest of gabs / 2 at angles and rotations (two twist stencils share
// an edge angle, each with the twisting moment G J tau) and gabs lever / 4 at
// positions (a bending moment M makes stencil forces M / l, 2 M / l, M / l at the
// vertices before, at and after the stencil's: 4 M / l at a vertex of a uniformly
// bent rod).
double eq_internal_moment(const std::vector<int> &kind, const std::vector<double> &lever,
                          const double *gabs, size_t n);

} // namespace rodnet

#endif

// rigid_body_modes.hpp - the rigid-body modes of a network's DOFs: the near-null space
// of the Hessian that the multigrid and two-level Schwarz preconditioners are given
// (MueLu, FROSch, the DD's AMG coarse solve).
#ifndef RODNET_SHIM_RIGID_BODY_MODES_HPP
#define RODNET_SHIM_RIGID_BODY_MODES_HPP

#include "system/system.hpp"

namespace rodnet {

// Rigid-body modes (6 columns: translations x, y, z, rotations about x, y, z through
// the origin) of DOFs of the given DofBlocks kinds (0-2 position, 3-5 rotation, 6
// angle), points and axes (3 per DOF, rn_network_dof_blocks), on map (one entry per
// local element).
Teuchos::RCP<TMV> rigid_body_modes(const Teuchos::RCP<const TMap> &map, const int *kind,
                                   const double *point, const double *axis);

// The rigid-body modes of every DOF of sys where sys is one whole network on one rank
// (a SerialSystem); null otherwise (a part of a distributed network: the
// preconditioners then use their own default near-null space).  Throws Error.
Teuchos::RCP<const TMV> network_rigid_body_modes(const System &sys);

} // namespace rodnet

#endif

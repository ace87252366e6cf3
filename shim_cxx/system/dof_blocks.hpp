// dof_blocks.hpp - the DofBlocks (system.hpp) of a network's reduced DOFs, from the C
// API's rod / interface classification (rn_network_dof_blocks) and DOF kinds
// (rn_network_dof_info), for any set of owned DOFs.  No Trilinos objects here beyond
// the types of system.hpp.
#ifndef RODNET_SHIM_DOF_BLOCKS_HPP
#define RODNET_SHIM_DOF_BLOCKS_HPP

#include <vector>

#include "system/system.hpp"

namespace rodnet {

// Per reduced DOF of a finalized network: the rod whose interior it is (-1:
// interface), its DofBlocks kind (0-2 position, 3-5 rotation, 6 material angle), the
// point it moves and the axis of an angle (3 each).  Throws Error.
struct NetworkDofs {
  std::vector<int32_t> block;
  std::vector<int> kind;
  std::vector<double> point, axis;
};
NetworkDofs network_dofs(const rn_network *net);

// DofBlocks of the owned DOFs owned[l] (reduced indices; local index l): owned rods
// numbered 0, 1, ... in the order of their first owned DOF.
DofBlocks make_dof_blocks(const NetworkDofs &d, const std::vector<GO> &owned);

// DofBlocks kinds.
constexpr int kDofRotation = 3; // 3, 4, 5: rotation-vector components
constexpr int kDofAngle = 6;    // a material angle

} // namespace rodnet

#endif

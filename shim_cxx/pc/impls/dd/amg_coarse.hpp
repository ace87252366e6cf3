// amg_coarse.hpp - the structure of the DD's coarse matrix that its AMG coarse solve
// ("dd-amg", make_amg_coarse_solver in pc/impls/muelu/) needs: the interface DOFs
// grouped into nodes of 6 rows (algebraic multigrid aggregates whole nodes), and the
// rigid-body modes of the padded coarse rows as near-null space.
#ifndef RODNET_SHIM_DD_AMG_COARSE_HPP
#define RODNET_SHIM_DD_AMG_COARSE_HPP

#include <vector>

#include "system/system.hpp"

namespace rodnet {
namespace dd {

// Groups the owned interface DOFs into nodes of 6 coarse rows for the coarse
// matrix's block structure (algebraic multigrid aggregates whole nodes).  The DOFs at
// one point form a node: a joint's position and rotation, a vertex's position; each
// material angle joins the nearest node with a free rotation slot (the vertex next
// to it).  Row 6 n + j of node n holds its DOF of kind j (positions 0-2, rotations
// or an angle 3-5); the other rows are dummies (decoupled), which carry the rigid
// modes of their kind at the node's point in the near-null space, so that every node
// supports all six rigid-body modes: an aggregate that misses one (nodes pinned
// along x at a gripped face, say) is rejected by MueLu (a zero near-null-space
// column, seen on 2 ranks).  Returns the coarse slot of every interface DOF; node
// n's point in points[3 n ..].
std::vector<int> coarse_nodes(const DofBlocks &blk, std::vector<double> &points);

// Rigid-body modes of the owned coarse rows (cmap, 6 per node): those of the interface
// DOF in each slot (coarse_nodes), a dummy row in slot j those of a DOF of kind j at
// its node's point.
Teuchos::RCP<TMV> coarse_nullspace(const Teuchos::RCP<const TMap> &cmap,
                                   const DofBlocks &blk, const std::vector<int> &slot,
                                   const std::vector<double> &node_points);

} // namespace dd
} // namespace rodnet

#endif

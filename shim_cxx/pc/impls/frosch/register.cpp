// register.cpp - the factory of the "frosch" row of the preconditioner registry
// (pc/registry.hpp, RN_PRECONDITIONER_LIST in rodnet_registry.h).
#include "pc/registry.hpp"

#include "pc/impls/frosch/frosch.hpp"
#include "system/rigid_body_modes.hpp"

namespace rodnet {

std::unique_ptr<Preconditioner> make_RN_PRECOND_FROSCH(const System &sys,
                                                       const rn_solve_options &) {
  // coarse space: the rigid-body modes of the whole network (none on a part)
  return std::make_unique<FroschPreconditioner>(network_rigid_body_modes(sys));
}

} // namespace rodnet

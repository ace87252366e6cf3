// register.cpp - the factory of the "muelu" row of the preconditioner registry
// (pc/registry.hpp, RN_PRECONDITIONER_LIST in rodnet_registry.h).
#include "pc/registry.hpp"

#include "pc/impls/muelu/muelu.hpp"
#include "system/rigid_body_modes.hpp"

namespace rodnet {

std::unique_ptr<Preconditioner> make_RN_PRECOND_MUELU(const System &sys,
                                                      const rn_solve_options &) {
  // near-null space: the rigid-body modes of the whole network (none on a part)
  return std::make_unique<MueluPreconditioner>(network_rigid_body_modes(sys));
}

} // namespace rodnet

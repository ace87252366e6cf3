// register.cpp - the factory of the "gathered" row of the preconditioner registry
// (pc/registry.hpp, RN_PRECONDITIONER_LIST in rodnet_registry.h).
#include "pc/registry.hpp"

#include "pc/impls/gathered/gathered_preconditioner.hpp"

namespace rodnet {

std::unique_ptr<Preconditioner> make_RN_PRECOND_GATHERED(const System &,
                                                         const rn_solve_options &) {
  return std::make_unique<GatheredPreconditioner>();
}

} // namespace rodnet

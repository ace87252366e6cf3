// register.cpp - the factory of the "local" row of the preconditioner registry
// (pc/registry.hpp, RN_PRECONDITIONER_LIST in rodnet_registry.h).
#include "pc/registry.hpp"

#include "pc/impls/local/local_preconditioner.hpp"

namespace rodnet {

std::unique_ptr<Preconditioner> make_RN_PRECOND_LOCAL(const System &,
                                                      const rn_solve_options &) {
  return std::make_unique<LocalPreconditioner>();
}

} // namespace rodnet

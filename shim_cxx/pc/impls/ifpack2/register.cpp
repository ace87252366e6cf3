// register.cpp - the factory of the "ifpack2" row of the preconditioner registry
// (pc/registry.hpp, RN_PRECONDITIONER_LIST in rodnet_registry.h).
#include "pc/registry.hpp"

#include "pc/impls/ifpack2/ifpack2.hpp"

namespace rodnet {

std::unique_ptr<Preconditioner> make_RN_PRECOND_IFPACK2(const System &,
                                                        const rn_solve_options &) {
  return std::make_unique<SchwarzPreconditioner>();
}

} // namespace rodnet

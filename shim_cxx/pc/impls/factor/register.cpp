// register.cpp - the factory of the "factor" row of the preconditioner registry
// (pc/registry.hpp, RN_PRECONDITIONER_LIST in rodnet_registry.h).
#include "pc/registry.hpp"

#include "pc/impls/factor/factor_preconditioner.hpp"

namespace rodnet {

std::unique_ptr<Preconditioner> make_RN_PRECOND_FACTOR(const System &sys,
                                                       const rn_solve_options &opt) {
  return make_factor_preconditioner(sys, opt.factorization);
}

} // namespace rodnet

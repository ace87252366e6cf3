// register.cpp - the factory of the "dd" row and its dd-amg variant of the preconditioner
// registry (pc/registry.hpp, RN_PRECONDITIONER_LIST in rodnet_registry.h).
#include "pc/registry.hpp"

#include "pc/impls/dd/dd_preconditioner.hpp"

namespace rodnet {

std::unique_ptr<Preconditioner> make_RN_PRECOND_DD(const System &,
                                                   const rn_solve_options &) {
  DdOptions o;
  o.coarse = DdOptions::Coarse::Auto;
  return std::make_unique<DdPreconditioner>(o);
}

std::unique_ptr<Preconditioner> make_RN_PRECOND_DD_AMG(const System &,
                                                       const rn_solve_options &) {
  DdOptions o;
  o.coarse = DdOptions::Coarse::Amg;
  return std::make_unique<DdPreconditioner>(o);
}

} // namespace rodnet

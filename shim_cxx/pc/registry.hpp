// registry.hpp - the preconditioners of the Newton-Krylov solvers (tr-krylov, NOX, the
// LOBPCG stability check): one row per rn_preconditioner (rodnet_solve.h), its
// factory (registry.cpp).  Adding a preconditioner: its folder pc/impls/<name>/ and
// one row there (names, help and capabilities: the C table of c_api).  No Trilinos
// types here (newton/solvers.hpp declares make_preconditioner too, for its callers).
#ifndef RODNET_SHIM_PC_REGISTRY_HPP
#define RODNET_SHIM_PC_REGISTRY_HPP

#include <memory>

#include "rodnet_solve.h"

namespace rodnet {

class System;
class Preconditioner;

struct PreconditionerRow {
  rn_preconditioner kind;
  // The preconditioner for sys (not set up); throws Error (RN_ERR_ARG where it cannot
  // work on sys, e.g. "factor" on a part of a distributed network).
  std::unique_ptr<Preconditioner> (*make)(const System &sys, const rn_solve_options &opt);
};

// The row of kind, or null (RN_PRECOND_AUTO and values without a preconditioner).
const PreconditionerRow *find_preconditioner(rn_preconditioner kind);

// The preconditioner opt.preconditioner names for sys (auto: dd, the rod-level domain
// decomposition; factor on several ranks is RN_ERR_ARG); *used is the kind chosen.
std::unique_ptr<Preconditioner> make_preconditioner(const System &sys,
                                                    const rn_solve_options &opt,
                                                    rn_preconditioner *used);

} // namespace rodnet

#endif

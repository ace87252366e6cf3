// registry.hpp - the preconditioners of the Newton-Krylov solvers (tr-krylov, NOX, the
// LOBPCG stability check): one row per rn_preconditioner (rodnet_solve.h), its
// factory (registry.cpp).  Adding a preconditioner: its enum value, one row of
// RN_PRECONDITIONER_LIST (c_api/include/rodnet_registry.h: name, help, capabilities) and
// its folder pc/impls/<name>/ with the factory make_<enum value> (register.cpp); the
// table below is made from the list.  No Trilinos
// types here (newton/solvers.hpp declares make_preconditioner too, for its callers).
#ifndef RODNET_SHIM_PC_REGISTRY_HPP
#define RODNET_SHIM_PC_REGISTRY_HPP

#include <memory>

#include "rodnet_registry.h"
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

// The factory of every row of RN_PRECONDITIONER_LIST (rodnet_registry.h), named after
// its enum value: make_RN_PRECOND_DD, ...  Each implementation defines its own in its
// folder (pc/impls/<name>/register.cpp); an alias row (auto) uses its target's.
#define RN_PC_FACTORY_DECLARE(id, name, to, flags, help)       \
  std::unique_ptr<Preconditioner> make_##id(const System &sys, \
                                            const rn_solve_options &opt);
RN_PRECONDITIONER_LIST(RN_PC_FACTORY_DECLARE)
#undef RN_PC_FACTORY_DECLARE

// The row of kind, or null (RN_PRECOND_AUTO and values without a preconditioner).
const PreconditionerRow *find_preconditioner(rn_preconditioner kind);

// The preconditioner opt.preconditioner names for sys (auto: dd, the rod-level domain
// decomposition; factor on several ranks is RN_ERR_ARG); *used is the kind chosen.
std::unique_ptr<Preconditioner> make_preconditioner(const System &sys,
                                                    const rn_solve_options &opt,
                                                    rn_preconditioner *used);

} // namespace rodnet

#endif

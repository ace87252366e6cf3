// registry.cpp - the preconditioner factories by rn_preconditioner (registry.hpp).
#include "pc/registry.hpp"

#include "base/shim_error.hpp"
#include "pc/impls/dd/dd_preconditioner.hpp"
#include "pc/impls/factor/factor_preconditioner.hpp"
#include "pc/impls/frosch/frosch.hpp"
#include "pc/impls/gathered/gathered_preconditioner.hpp"
#include "pc/impls/ifpack2/ifpack2.hpp"
#include "pc/impls/local/local_preconditioner.hpp"
#include "pc/impls/muelu/muelu.hpp"
#include "system/rigid_body_modes.hpp"

namespace rodnet {

namespace {

std::unique_ptr<Preconditioner> dd(DdOptions::Coarse coarse) {
  DdOptions o;
  o.coarse = coarse;
  return std::make_unique<DdPreconditioner>(o);
}

// One row per preconditioner.  MueLu's near-null space and FROSch's coarse space: the
// rigid-body modes of the whole network (none on a part of a distributed network).
const PreconditionerRow kRows[] = {
    {RN_PRECOND_FACTOR,
     [](const System &sys, const rn_solve_options &opt) {
       return make_factor_preconditioner(sys, opt.factorization);
     }},
    {RN_PRECOND_LOCAL,
     [](const System &, const rn_solve_options &) -> std::unique_ptr<Preconditioner> {
       return std::make_unique<LocalPreconditioner>();
     }},
    {RN_PRECOND_GATHERED,
     [](const System &, const rn_solve_options &) -> std::unique_ptr<Preconditioner> {
       return std::make_unique<GatheredPreconditioner>();
     }},
    {RN_PRECOND_DD, [](const System &,
                       const rn_solve_options &) { return dd(DdOptions::Coarse::Auto); }},
    {RN_PRECOND_DD_AMG,
     [](const System &, const rn_solve_options &) { return dd(DdOptions::Coarse::Amg); }},
    {RN_PRECOND_MUELU,
     [](const System &sys, const rn_solve_options &) -> std::unique_ptr<Preconditioner> {
       return std::make_unique<MueluPreconditioner>(network_rigid_body_modes(sys));
     }},
    {RN_PRECOND_IFPACK2,
     [](const System &, const rn_solve_options &) -> std::unique_ptr<Preconditioner> {
       return std::make_unique<SchwarzPreconditioner>();
     }},
    {RN_PRECOND_FROSCH,
     [](const System &sys, const rn_solve_options &) -> std::unique_ptr<Preconditioner> {
       return std::make_unique<FroschPreconditioner>(network_rigid_body_modes(sys));
     }},
};

} // namespace

const PreconditionerRow *find_preconditioner(rn_preconditioner kind) {
  for (const PreconditionerRow &row : kRows)
    if (row.kind == kind) return &row;
  return nullptr;
}

std::unique_ptr<Preconditioner> make_preconditioner(const System &sys,
                                                    const rn_solve_options &opt,
                                                    rn_preconditioner *used) {
  rn_preconditioner kind = opt.preconditioner;
  // auto: the rod-level domain decomposition (docs/solvers.md, "Preconditioners for
  // networks")
  if (kind == RN_PRECOND_AUTO) kind = RN_PRECOND_DD;
  const PreconditionerRow *row = find_preconditioner(kind);
  if (!row) throw Error(RN_ERR_ARG, "rn_solve: unknown preconditioner");
  std::unique_ptr<Preconditioner> p = row->make(sys, opt);
  *used = kind;
  return p;
}

} // namespace rodnet

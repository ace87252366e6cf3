// registry.cpp - the preconditioner factories by rn_preconditioner (registry.hpp),
// made from RN_PRECONDITIONER_LIST (rodnet_registry.h).
#include "pc/registry.hpp"

#include "base/shim_error.hpp"
#include "pc/preconditioner.hpp"

namespace rodnet {

namespace {

struct Entry {
  rn_preconditioner kind, resolves_to;
  PreconditionerRow row;
};

// One entry per row of RN_PRECONDITIONER_LIST, in enum order; an alias (auto) takes
// its target's factory but is not a row of its own (find_preconditioner).
#define RN_PC_ENTRY(id, name, to, flags, help) {id, to, {to, &make_##to}},
const Entry kEntries[] = {RN_PRECONDITIONER_LIST(RN_PC_ENTRY)};
#undef RN_PC_ENTRY

} // namespace

const PreconditionerRow *find_preconditioner(rn_preconditioner kind) {
  for (const Entry &e : kEntries)
    if (e.kind == kind && e.resolves_to == kind) return &e.row;
  return nullptr;
}

std::unique_ptr<Preconditioner> make_preconditioner(const System &sys,
                                                    const rn_solve_options &opt,
                                                    rn_preconditioner *used) {
  rn_preconditioner kind = opt.preconditioner;
  // auto: the rod-level domain decomposition (docs/solvers.md, "Preconditioners for
  // networks"), as its registry row says
  for (const Entry &e : kEntries)
    if (e.kind == kind) kind = e.resolves_to;
  const PreconditionerRow *row = find_preconditioner(kind);
  if (!row) throw Error(RN_ERR_ARG, "rn_solve: unknown preconditioner");
  std::unique_ptr<Preconditioner> p = row->make(sys, opt);
  *used = kind;
  return p;
}

} // namespace rodnet

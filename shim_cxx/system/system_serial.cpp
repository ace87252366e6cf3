// system_serial.cpp - the System of one rn_network on one rank (system_serial.hpp).
#include "system/system_serial.hpp"

#include <algorithm>
#include <cstring>

#include <Tpetra_CrsGraph.hpp>

#include "system/dof_blocks.hpp"
#include "krylov/minres.hpp"
#include "base/shim_error.hpp"

namespace rodnet {

SerialSystem::SerialSystem(Problem &p) : p_(p) {
  map_ = make_local_map(p.size());
  build_graph();
  equilibrium_.reset(new Equilibrium(p));
  build_blocks();
}

// The Hessian's CrsMatrix on the graph of the Problem's CSR pattern (sorted columns,
// all of them local), of pattern version version_.
void SerialSystem::build_graph() {
  const Problem &p = p_;
  const size_t n = p.size();
  Teuchos::ArrayRCP<size_t> rowptr(n + 1);
  const size_t nnz = static_cast<size_t>(p.rowptr()[n]);
  Teuchos::ArrayRCP<LO> col(std::max<size_t>(nnz, 1));
  for (size_t i = 0; i <= n; ++i) rowptr[i] = static_cast<size_t>(p.rowptr()[i]);
  for (size_t k = 0; k < nnz; ++k) col[k] = static_cast<LO>(p.col()[k]);
  if (nnz == 0) col = Teuchos::ArrayRCP<LO>();
  auto graph = Teuchos::rcp(new Tpetra::CrsGraph<>(map_, map_, rowptr, col));
  graph->fillComplete(map_, map_);
  H_ = Teuchos::rcp(new TCrs(Teuchos::rcp_const_cast<const Tpetra::CrsGraph<>>(graph)));
  H_->fillComplete(map_, map_);
  if (H_->getNodeNumEntries() != nnz)
    throw Error(RN_ERR_INTERNAL,
                "rn_solve: Tpetra Hessian graph differs from the pattern");
  version_ = p.pattern_version();
}

SerialSystem::~SerialSystem() { rn_state_destroy(&snapshot_); }

void SerialSystem::get_state(TMV &x) const {
  check_status(rn_network_get_dofs(p_.network(), host_data(x)), "rn_network_get_dofs");
}

void SerialSystem::set_state(const TMV &x) {
  check_status(rn_network_set_dofs(p_.network(), host_data(x)), "rn_network_set_dofs");
}

rn_status SerialSystem::energy(const TMV &x, double *E) {
  return p_.energy(host_data(x), E);
}

rn_status SerialSystem::gradient(const TMV &x, double *E, TMV &g) {
  return p_.gradient(host_data(x), E, host_data(g));
}

rn_status SerialSystem::stretch_correction(const TMV &x, const TMV &s, TMV &f) {
  return rn_network_stretch_correction(p_.network(), host_data(x), host_data(s),
                                       host_data(f));
}

Counters &SerialSystem::report_counters() { return p_.counters; }

void SerialSystem::assemble_hessian(const TMV &x) {
  p_.assemble_hessian(host_data(x));
  // Contact: a new accepted state may have changed the pattern; then a new matrix
  // (users that cache its structure compare its graph, dd_preconditioner.cpp) and
  // new blocks (the pairs' vertices are interface DOFs).
  if (p_.pattern_version() != version_) {
    build_graph();
    build_blocks();
  }
  auto vals = H_->getLocalMatrixDevice().values; // Serial node: host memory
  const size_t nnz = vals.extent(0);
  if (nnz) std::memcpy(vals.data(), p_.values(), nnz * sizeof(double));
}

void SerialSystem::accept(TMV &x) { p_.accept(host_data(x)); }

EquilibriumView SerialSystem::equilibrium(const TMV &x, const TMV &g) {
  return equilibrium_->measure(host_data(x), host_data(g));
}

bool SerialSystem::save_state() {
  rn_state_destroy(&snapshot_);
  check_status(rn_network_state_save(p_.network(), &snapshot_), "rn_network_state_save");
  return true;
}

void SerialSystem::restore_state() {
  if (!snapshot_) throw Error(RN_ERR_INTERNAL, "rn_solve: no state snapshot to restore");
  check_status(rn_network_state_restore(p_.network(), snapshot_),
               "rn_network_state_restore");
}

// Rod interiors and interface DOFs (rn_network_dof_blocks: a joint's DOFs, and the
// terminal-edge DOFs at elastic joints; at rigid joints, whose stencil pattern is
// dense but whose values between two ends are zero, the ends stay rod-interior).
void SerialSystem::build_blocks() {
  std::vector<GO> all(p_.size());
  for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<GO>(i);
  blocks_ = make_dof_blocks(network_dofs(p_.network()), all);
}

} // namespace rodnet

// system_serial.cpp - the System of one rn_network on one rank (system_serial.hpp).
#include "system_serial.hpp"

#include <algorithm>
#include <cstring>

#include <Tpetra_CrsGraph.hpp>

#include "minres.hpp"
#include "shim_error.hpp"

namespace rodnet {

SerialSystem::SerialSystem(Problem &p) : p_(p) {
  const size_t n = p.size();
  map_ = make_local_map(n);
  // The graph of the network's CSR pattern (sorted columns, all of them local).
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
  equilibrium_.reset(new Equilibrium(p));
  build_blocks();
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

void SerialSystem::assemble_hessian(const TMV &x) {
  p_.assemble_hessian(host_data(x));
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

// Rod interiors and interface DOFs: a joint's DOFs, and rod DOFs that the Hessian
// couples with another rod's (terminal edges at elastic joints).
void SerialSystem::build_blocks() {
  rn_network *net = p_.network();
  const size_t n = p_.size();
  std::vector<rn_dof_info> info(n);
  if (n) check_status(rn_network_dof_info(net, info.data()), "rn_network_dof_info");
  blocks_.num_rods = rn_network_num_rods(net);
  blocks_.block.assign(n, -1);
  for (size_t i = 0; i < n; ++i) {
    int owner = info[i].rod;
    for (int64_t k = p_.rowptr()[i]; k < p_.rowptr()[i + 1] && owner >= 0; ++k) {
      const int other = info[static_cast<size_t>(p_.col()[k])].rod;
      if (other >= 0 && other != owner) owner = -1;
    }
    blocks_.block[i] = owner;
  }
  std::vector<std::vector<double>> verts(static_cast<size_t>(blocks_.num_rods));
  for (int r = 0; r < blocks_.num_rods; ++r) {
    verts[static_cast<size_t>(r)].resize(
        3 * static_cast<size_t>(rn_network_rod_num_vertices(net, r)));
    check_status(rn_network_rod_vertices(net, r, verts[static_cast<size_t>(r)].data()),
                 "rn_network_rod_vertices");
  }
  for (size_t i = 0; i < n; ++i) {
    if (blocks_.block[i] >= 0) continue;
    DofBlocks::Interface f;
    const rn_dof_info &d = info[i];
    f.local = static_cast<LO>(i);
    f.kind = d.kind == RN_DOF_POSITION   ? d.component
             : d.kind == RN_DOF_ROTATION ? 3 + d.component
                                         : 6;
    if (d.joint >= 0) {
      check_status(rn_network_joint_position(net, d.joint, f.point),
                   "rn_network_joint_position");
    } else if (d.rod < 0) { // a macroscopic strain DOF of a periodic cell
      for (int k = 0; k < 3; ++k) f.point[k] = 0.0;
    } else { // a vertex, or the midpoint of the edge of an angle
      const std::vector<double> &v = verts[static_cast<size_t>(d.rod)];
      for (int k = 0; k < 3; ++k)
        f.point[k] = d.kind == RN_DOF_THETA
                         ? 0.5 * (v[3 * static_cast<size_t>(d.index) + k] +
                                  v[3 * static_cast<size_t>(d.index + 1) + k])
                         : v[3 * static_cast<size_t>(d.index) + k];
    }
    blocks_.interface.push_back(f);
  }
}

} // namespace rodnet

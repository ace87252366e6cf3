// replicated_system.cpp - System over a rank partition of a replicated network (see
// replicated_system.hpp).
#include "system/replicated_system.hpp"

#include <algorithm>

#include <Teuchos_OrdinalTraits.hpp>

#include "system/rigid_body_modes.hpp"
#include "system/dof_blocks.hpp"
#include "base/shim_error.hpp"

namespace rodnet {

namespace {

// Owner rank of every reduced DOF: the rank of its rod for rod-interior DOFs; for
// interface DOFs the rank of the lowest rod whose interior it couples with (the
// lowest GID's rank if none does).
std::vector<int> dof_ranks(const Problem &p, const std::vector<int32_t> &block, int nrods,
                           int nranks) {
  const size_t n = p.size();
  auto rod_rank = [&](int r) {
    return static_cast<int>((static_cast<long long>(r) * nranks) / std::max(nrods, 1));
  };
  std::vector<int> rank(n, 0);
  for (size_t i = 0; i < n; ++i) {
    if (block[i] >= 0) {
      rank[i] = rod_rank(block[i]);
      continue;
    }
    int rod = -1;
    for (int64_t k = p.rowptr()[i]; k < p.rowptr()[i + 1]; ++k) {
      int32_t b = block[p.col()[k]];
      if (b >= 0 && (rod < 0 || b < rod)) rod = b;
    }
    rank[i] = rod >= 0 ? rod_rank(rod)
                       : static_cast<int>((static_cast<long long>(i) * nranks) /
                                          static_cast<long long>(n));
  }
  return rank;
}

} // namespace

ReplicatedSystem::ReplicatedSystem(rn_network *net,
                                   const Teuchos::RCP<const Teuchos::Comm<int>> &comm)
    : problem_(net) {
  const size_t n = problem_.size();
  const int nranks = comm->getSize(), me = comm->getRank();
  const int nrods = rn_network_num_rods(net);
  const NetworkDofs dofs = network_dofs(net);
  const std::vector<int32_t> &block = dofs.block;
  const std::vector<int> rank = dof_ranks(problem_, block, nrods, nranks);
  for (size_t i = 0; i < n; ++i)
    if (rank[i] == me) owned_.push_back(static_cast<GO>(i));
  const auto invalid = Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  map_ = Teuchos::rcp(new TMap(static_cast<Tpetra::global_size_t>(n),
                               Teuchos::ArrayView<const GO>(owned_.data(), owned_.size()),
                               GO(0), comm));
  std::vector<GO> all(n);
  for (size_t i = 0; i < n; ++i) all[i] = static_cast<GO>(i);
  all_ = Teuchos::rcp(
      new TMap(invalid, Teuchos::ArrayView<const GO>(all.data(), n), GO(0), comm));
  import_ = Teuchos::rcp(new Tpetra::Import<>(map_, all_));
  all_vec_ = Teuchos::rcp(new TMV(all_, 1));
  full_.assign(n, 0.0);
  gfull_.assign(n, 0.0);

  take_owned_dofs(dofs);
  build_hessian();
}

// Blocks: owned rods renumbered 0, 1, ... in rod order; kinds, points and axes of the
// owned DOFs for rigid_body_modes().
void ReplicatedSystem::take_owned_dofs(const NetworkDofs &dofs) {
  blocks_ = make_dof_blocks(dofs, owned_);
  for (GO g : owned_) {
    const size_t i = static_cast<size_t>(g);
    kind_.push_back(dofs.kind[i]);
    point_.insert(point_.end(), dofs.point.begin() + 3 * i,
                  dofs.point.begin() + 3 * i + 3);
    axis_.insert(axis_.end(), dofs.axis.begin() + 3 * i, dofs.axis.begin() + 3 * i + 3);
  }
}

// The Hessian of the owned rows on the network's pattern, and the position of each
// owned CSR entry in the local matrix (rows sorted by local column).
void ReplicatedSystem::build_hessian() {
  const int64_t *rp = problem_.rowptr();
  const int32_t *col = problem_.col();
  std::vector<size_t> counts(owned_.size());
  for (size_t l = 0; l < owned_.size(); ++l)
    counts[l] = static_cast<size_t>(rp[owned_[l] + 1] - rp[owned_[l]]);
  Teuchos::ArrayView<const size_t> cv(counts.data(), counts.size());
  H_ = Teuchos::rcp(new TCrs(map_, cv));
  std::vector<GO> gcols;
  std::vector<double> zeros;
  for (size_t l = 0; l < owned_.size(); ++l) {
    const GO g = owned_[l];
    gcols.assign(col + rp[g], col + rp[g + 1]);
    zeros.assign(gcols.size(), 0.0);
    H_->insertGlobalValues(g, Teuchos::ArrayView<const GO>(gcols.data(), gcols.size()),
                           Teuchos::ArrayView<const double>(zeros.data(), zeros.size()));
  }
  H_->fillComplete(map_, map_);
  auto lcl = H_->getLocalMatrixHost();
  auto colmap = H_->getColMap();
  for (size_t l = 0; l < owned_.size(); ++l) {
    const GO g = owned_[l];
    const size_t beg = lcl.graph.row_map(l), end = lcl.graph.row_map(l + 1);
    for (int64_t k = rp[g]; k < rp[g + 1]; ++k) {
      const LO lc = colmap->getLocalElement(col[k]);
      size_t q = beg;
      while (q < end && lcl.graph.entries(q) != lc) ++q;
      if (q == end) throw Error(RN_ERR_INTERNAL, "ReplicatedSystem: Hessian entry lost");
      value_pos_.push_back(q);
    }
  }
}

Teuchos::RCP<TMV> ReplicatedSystem::rigid_body_modes() const {
  return rodnet::rigid_body_modes(map_, kind_.data(), point_.data(), axis_.data());
}

void ReplicatedSystem::set_load_factor(double t) {
  check_status(rn_network_set_load_factor(problem_.network(), t),
               "rn_network_set_load_factor");
}

void ReplicatedSystem::load_increment(const TMV &x, double t0, double t1, TMV &dg) {
  gather(x, full_);
  if (check_status(rn_network_load_increment(problem_.network(), full_.data(), t0, t1,
                                             gfull_.data()),
                   "rn_network_load_increment") != RN_OK)
    throw Error(RN_ERR_SOLVER, "ReplicatedSystem: load increment at a degenerate state");
  scatter(gfull_, dg);
}

void ReplicatedSystem::gather(const TMV &x, std::vector<double> &full) const {
  all_vec_->doImport(x, *import_, Tpetra::INSERT);
  auto v = all_vec_->getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t i = 0; i < full.size(); ++i) full[i] = v(i, 0);
}

void ReplicatedSystem::scatter(const std::vector<double> &full, TMV &x) const {
  auto v = x.getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (size_t l = 0; l < owned_.size(); ++l)
    v(l, 0) = full[static_cast<size_t>(owned_[l])];
}

void ReplicatedSystem::get_state(TMV &x) const {
  check_status(rn_network_get_dofs(problem_.network(), full_.data()),
               "rn_network_get_dofs");
  scatter(full_, x);
}

void ReplicatedSystem::set_state(const TMV &x) {
  gather(x, full_);
  check_status(rn_network_set_dofs(problem_.network(), full_.data()),
               "rn_network_set_dofs");
}

rn_status ReplicatedSystem::energy(const TMV &x, double *E) {
  gather(x, full_);
  return problem_.energy(full_.data(), E);
}

rn_status ReplicatedSystem::gradient(const TMV &x, double *E, TMV &g) {
  gather(x, full_);
  rn_status s = problem_.gradient(full_.data(), E, gfull_.data());
  if (s == RN_OK) scatter(gfull_, g);
  return s;
}

void ReplicatedSystem::assemble_hessian(const TMV &x) {
  gather(x, full_);
  problem_.assemble_hessian(full_.data());
  ++counters.hessian;
  H_->resumeFill();
  auto lcl = H_->getLocalMatrixHost();
  const int64_t *rp = problem_.rowptr();
  const double *vals = problem_.values();
  size_t p = 0;
  for (size_t l = 0; l < owned_.size(); ++l)
    for (int64_t k = rp[owned_[l]]; k < rp[owned_[l] + 1]; ++k)
      lcl.values(value_pos_[p++]) = vals[k];
  H_->fillComplete(map_, map_);
}

void ReplicatedSystem::accept(TMV &x) {
  gather(x, full_);
  problem_.accept(full_.data());
  scatter(full_, x);
}

} // namespace rodnet

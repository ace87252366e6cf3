// dist_system.cpp - the distributed System (see dist_system.hpp).
#include "system/dist_system.hpp"

#include <mpi.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>

#include <Teuchos_DefaultMpiComm.hpp>
#include <Tpetra_CrsGraph.hpp>

#include "system/dof_blocks.hpp"
#include "system/equilibrium_scale.hpp"
#include "base/shim_error.hpp"

namespace rodnet {
namespace {

// The MPI communicator under comm; MPI_COMM_NULL for a serial (Teuchos::SerialComm)
// one, on which no MPI call is made (MPI may not even be initialised).
MPI_Comm raw_comm(const Teuchos::RCP<const Teuchos::Comm<int>> &comm) {
  auto mpi = Teuchos::rcp_dynamic_cast<const Teuchos::MpiComm<int>>(comm);
  if (mpi.is_null()) return MPI_COMM_NULL;
  return *mpi->getRawMpiComm();
}

template <class T>
void allreduce(T *in, T *out, int n, MPI_Datatype t, MPI_Op op, MPI_Comm c) {
  if (c == MPI_COMM_NULL) {
    std::copy(in, in + n, out);
    return;
  }
  MPI_Allreduce(in, out, n, t, op, c);
}

double *col0(TMV &v) { return v.getDataNonConst(0).getRawPtr(); }

// The last error message recorded in the network's context.
std::string last_error(rn_network *net) {
  const char *m = rn_context_last_error(rn_network_context(net));
  return (m && *m) ? m : "unknown error";
}

// The global ids of the ghost DOFs n_owned .. n_local - 1 of this part (gids),
// asked from their owners by key (offset: this rank's first owned id); the bytes
// sent are added to *bytes.  RN_ERR_INTERNAL if an owner does not know a key.
rn_status ghost_ids(rn_network *net, MPI_Comm c, int size, size_t n_owned, size_t n_local,
                    long long offset, std::vector<GO> &gids, double *bytes) {
  rn_status st = RN_OK;
  const int64_t *keys = nullptr;
  const int *owners = nullptr;
  check_status(rn_network_part_dofs(net, nullptr, &keys, &owners),
               "rn_network_part_dofs");
  // requests: ghost keys grouped by owner
  std::vector<int> scount(static_cast<size_t>(size), 0),
      rcount(static_cast<size_t>(size));
  for (size_t i = n_owned; i < n_local; ++i) ++scount[static_cast<size_t>(owners[i])];
  MPI_Alltoall(scount.data(), 1, MPI_INT, rcount.data(), 1, MPI_INT, c);
  std::vector<int> sdisp(static_cast<size_t>(size) + 1, 0),
      rdisp(static_cast<size_t>(size) + 1, 0);
  for (int q = 0; q < size; ++q) {
    sdisp[static_cast<size_t>(q) + 1] =
        sdisp[static_cast<size_t>(q)] + scount[static_cast<size_t>(q)];
    rdisp[static_cast<size_t>(q) + 1] =
        rdisp[static_cast<size_t>(q)] + rcount[static_cast<size_t>(q)];
  }
  std::vector<long long> sk(static_cast<size_t>(sdisp[static_cast<size_t>(size)]));
  std::vector<size_t> slot(sk.size());
  std::vector<int> fill(sdisp.begin(), sdisp.end() - 1);
  for (size_t i = n_owned; i < n_local; ++i) {
    const int q = owners[i];
    slot[static_cast<size_t>(fill[static_cast<size_t>(q)])] = i;
    sk[static_cast<size_t>(fill[static_cast<size_t>(q)]++)] = keys[i];
  }
  std::vector<long long> rk(static_cast<size_t>(rdisp[static_cast<size_t>(size)]));
  MPI_Alltoallv(sk.data(), scount.data(), sdisp.data(), MPI_LONG_LONG, rk.data(),
                rcount.data(), rdisp.data(), MPI_LONG_LONG, c);
  // answers: owned keys are increasing in the part's order
  for (long long &k : rk) {
    const int64_t *e = keys + n_owned,
                  *p = std::lower_bound(keys, e, static_cast<int64_t>(k));
    if (p == e || *p != k) {
      st = RN_ERR_INTERNAL;
      k = -1;
    } else {
      k = offset + (p - keys);
    }
  }
  std::vector<long long> ans(sk.size());
  MPI_Alltoallv(rk.data(), rcount.data(), rdisp.data(), MPI_LONG_LONG, ans.data(),
                scount.data(), sdisp.data(), MPI_LONG_LONG, c);
  for (size_t a = 0; a < ans.size(); ++a) {
    if (ans[a] < 0) st = RN_ERR_INTERNAL;
    gids[slot[a]] = static_cast<GO>(ans[a]);
  }
  *bytes += 16.0 * static_cast<double>(sk.size() + rk.size());
  return st;
}

// The diagonal of the structure's bounding box (the initial vertices of the rods of
// every part).
double structure_size(rn_network *net, MPI_Comm c) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL},
         hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (int r = 0; r < rn_network_num_rods(net); ++r) {
    if (!rn_network_rod_is_local(net, r)) continue;
    std::vector<double> xyz(3 * static_cast<size_t>(rn_network_rod_num_vertices(net, r)));
    if (rn_network_rod_initial_vertices(net, r, xyz.data()) != RN_OK) continue;
    for (size_t i = 0; i < xyz.size(); ++i) {
      lo[i % 3] = std::min(lo[i % 3], xyz[i]);
      hi[i % 3] = std::max(hi[i % 3], xyz[i]);
    }
  }
  double glo[3], ghi[3];
  allreduce(lo, glo, 3, MPI_DOUBLE, MPI_MIN, c);
  allreduce(hi, ghi, 3, MPI_DOUBLE, MPI_MAX, c);
  double size = 0.0;
  for (int k = 0; k < 3; ++k)
    if (ghi[k] >= glo[k]) size += (ghi[k] - glo[k]) * (ghi[k] - glo[k]);
  return std::sqrt(size);
}

} // namespace

rn_status DistSystem::agree(rn_status local, const std::string &msg) const {
  const int size = comm_->getSize(), rank = comm_->getRank();
  int in[2] = {local < 0 ? static_cast<int>(local) : 0,
               local > 0 ? -static_cast<int>(local) : 0};
  int out[2] = {0, 0};
  ++stats_.reductions;
  stats_.bytes_sent += sizeof in;
  allreduce(in, out, 2, MPI_INT, MPI_MIN, raw_comm(comm_));
  if (out[0] == 0) return static_cast<rn_status>(-out[1]);
  if (raw_comm(comm_) == MPI_COMM_NULL) { // one rank: its own message
    const std::string text = msg.empty() ? last_error(net_) : msg;
    if (!msg.empty())
      rn_context_set_error(rn_network_context(net_), local, "%s", text.c_str());
    throw Error(local, text, true);
  }
  // the first failing rank's message goes to every rank
  int mine = local < 0 ? rank : size, first = size;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, raw_comm(comm_));
  std::string text = local < 0 ? (msg.empty() ? last_error(net_) : msg) : std::string();
  int len = static_cast<int>(text.size()), st = local;
  MPI_Bcast(&len, 1, MPI_INT, first, raw_comm(comm_));
  MPI_Bcast(&st, 1, MPI_INT, first, raw_comm(comm_));
  text.resize(static_cast<size_t>(len));
  MPI_Bcast(&text[0], len, MPI_CHAR, first, raw_comm(comm_));
  if (size > 1 && first != rank) text = "rank " + std::to_string(first) + ": " + text;
  rn_context_set_error(rn_network_context(net_), static_cast<rn_status>(st), "%s",
                       text.c_str());
  throw Error(static_cast<rn_status>(st), text, true);
}

DistSystem::DistSystem(rn_network *net,
                       const Teuchos::RCP<const Teuchos::Comm<int>> &comm)
    : net_(net), comm_(comm) {
  rn_status st = RN_OK;
  std::string msg;
  if (!net_) {
    st = RN_ERR_ARG;
    msg = "rn_solve: network is NULL";
  } else if (rn_network_is_part(net_)) {
    rn_part_info info;
    st = rn_network_part_info(net_, &info);
    if (!st && (info.nparts != comm_->getSize() || info.part != comm_->getRank())) {
      st = RN_ERR_ARG;
      msg = "rn_solve: part " + std::to_string(info.part) + " of " +
            std::to_string(info.nparts) + " on rank " + std::to_string(comm_->getRank()) +
            " of " + std::to_string(comm_->getSize()) +
            " (each rank must hold the part of its rank, over all ranks)";
    }
  } else if (net_ && comm_->getSize() > 1) {
    st = RN_ERR_ARG;
    msg = "rn_solve: a whole network on " + std::to_string(comm_->getSize()) +
          " ranks (build each rank's part with rn_network_set_part)";
  }
  agree(st, msg);
  n_local_ = rn_network_num_dofs(net_);
  n_owned_ = n_local_;
  if (rn_network_is_part(net_))
    agree(rn_network_part_dofs(net_, &n_owned_, nullptr, nullptr));
  build_maps();
  build_hessian_graph();
}

DistSystem::~DistSystem() { rn_state_destroy(&snapshot_); }

bool DistSystem::save_state() {
  rn_state_destroy(&snapshot_);
  agree(rn_network_state_save(net_, &snapshot_));
  return true;
}

void DistSystem::restore_state() { agree(rn_network_state_restore(net_, snapshot_)); }

// Owned ids: contiguous in rank order.  Ghost ids: asked from their owners by key.
void DistSystem::build_maps() {
  const MPI_Comm c = raw_comm(comm_);
  const int size = comm_->getSize();
  long long owned = static_cast<long long>(n_owned_), offset = 0;
  if (c != MPI_COMM_NULL) MPI_Exscan(&owned, &offset, 1, MPI_LONG_LONG, MPI_SUM, c);
  if (comm_->getRank() == 0) offset = 0;
  std::vector<GO> gids(n_local_);
  for (size_t i = 0; i < n_owned_; ++i)
    gids[i] = static_cast<GO>(offset + static_cast<long long>(i));
  rn_status st = RN_OK;
  if (c != MPI_COMM_NULL && (n_local_ > n_owned_ || size > 1))
    st = ghost_ids(net_, c, size, n_owned_, n_local_, offset, gids, &stats_.bytes_sent);
  agree(st, "rn_solve: the parts of the network do not agree on their DOFs (a ghost "
            "DOF is not owned by the part its key names)");
  const Tpetra::global_size_t any =
      Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  owned_ = Teuchos::rcp(new TMap(any, n_owned_, 0, comm_));
  overlap_ = Teuchos::rcp(
      new TMap(any, Teuchos::ArrayView<const GO>(gids.data(), gids.size()), 0, comm_));
  importer_ = Teuchos::rcp(new Tpetra::Import<>(owned_, overlap_));
  exporter_ = Teuchos::rcp(new Tpetra::Export<>(overlap_, owned_));
  xov_ = Teuchos::rcp(new TMV(overlap_, 1));
  gov_ = Teuchos::rcp(new TMV(overlap_, 1));
  sov_ = Teuchos::rcp(new TMV(overlap_, 1));
}

// The overlap graph is the part's CSR pattern (rows and columns in the overlap map's
// local numbering); the owned graph its export to the owners, built once.  Each
// assembly then sums the owned rows into the owned matrix by local column (hcols_) and
// exports only the ghost rows (the interface).
void DistSystem::build_hessian_graph() {
  size_t nnz = 0;
  const int64_t *rowptr = nullptr;
  const int32_t *col = nullptr;
  check_status(rn_network_hessian_pattern(net_, &nnz, &rowptr, &col),
               "rn_network_hessian_pattern");
  using Graph = Tpetra::CrsGraph<>;
  const size_t own_nnz = static_cast<size_t>(rowptr[n_owned_]);
  ghost_nnz_ = static_cast<double>(nnz - own_nnz);
  Teuchos::RCP<Graph> owned;
  {
    Teuchos::ArrayRCP<size_t> rp(n_local_ + 1);
    Teuchos::ArrayRCP<LO> ci(nnz);
    for (size_t i = 0; i <= n_local_; ++i) rp[i] = static_cast<size_t>(rowptr[i]);
    for (size_t k = 0; k < nnz; ++k) ci[k] = static_cast<LO>(col[k]);
    auto ov = Teuchos::rcp(new Graph(overlap_, overlap_, rp, ci));
    ov->fillComplete(owned_, owned_);
    owned = Teuchos::rcp(new Graph(owned_, 0));
    owned->doExport(*ov, *exporter_, Tpetra::INSERT);
    owned->fillComplete(owned_, owned_);
  }
  h_ = Teuchos::rcp(new TCrs(Teuchos::rcp_const_cast<const Graph>(owned)));
  h_->fillComplete(owned_, owned_);
  // owned rows: the local column in h_ of each entry
  hcols_.resize(own_nnz);
  auto cmap = h_->getColMap();
  for (size_t k = 0; k < own_nnz; ++k)
    hcols_[k] =
        cmap->getLocalElement(overlap_->getGlobalElement(static_cast<LO>(col[k])));
  // ghost rows: their own map, graph and export
  const size_t ng = n_local_ - n_owned_;
  std::vector<GO> gg(ng);
  for (size_t i = 0; i < ng; ++i)
    gg[i] = overlap_->getGlobalElement(static_cast<LO>(n_owned_ + i));
  const Tpetra::global_size_t any =
      Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid();
  auto gmap =
      Teuchos::rcp(new TMap(any, Teuchos::ArrayView<const GO>(gg.data(), ng), 0, comm_));
  Teuchos::ArrayRCP<size_t> grp(ng + 1);
  Teuchos::ArrayRCP<LO> gci(nnz - own_nnz);
  for (size_t i = 0; i <= ng; ++i)
    grp[i] = static_cast<size_t>(rowptr[n_owned_ + i]) - own_nnz;
  for (size_t k = own_nnz; k < nnz; ++k) gci[k - own_nnz] = static_cast<LO>(col[k]);
  auto gg_graph = Teuchos::rcp(new Graph(gmap, overlap_, grp, gci));
  gg_graph->fillComplete(owned_, owned_);
  hgh_ = Teuchos::rcp(new TCrs(Teuchos::rcp_const_cast<const Graph>(gg_graph)));
  hgh_->fillComplete(owned_, owned_);
  ghost_exporter_ = Teuchos::rcp(new Tpetra::Export<>(gmap, owned_));
  vals_.assign(nnz, 0.0);
}

void DistSystem::import_to(const TMV &x, TMV &ov) {
  ov.doImport(x, *importer_, Tpetra::INSERT);
  ++stats_.imports;
  stats_.bytes_sent += 8.0 * static_cast<double>(importer_->getNumExportIDs());
}

void DistSystem::export_gov(TMV &out) {
  out.putScalar(0.0);
  out.doExport(*gov_, *exporter_, Tpetra::ADD);
  ++stats_.exports;
  stats_.bytes_sent += 8.0 * static_cast<double>(exporter_->getNumExportIDs());
}

void DistSystem::get_state(TMV &x) const {
  std::vector<double> all(n_local_ + 1);
  agree(rn_network_get_dofs(net_, all.data()));
  std::copy(all.begin(), all.begin() + static_cast<long>(n_owned_), col0(x));
}

void DistSystem::set_state(const TMV &x) {
  import_state(x);
  agree(rn_network_set_dofs(net_, col0(*xov_)));
}

rn_status DistSystem::energy(const TMV &x, double *E) {
  ++counters.energy;
  import_state(x);
  double local = 0.0;
  const rn_status st = evaluate(
      [&] { return rn_network_energy(net_, col0(*xov_), &local); }, "rn_network_energy");
  double sum = 0.0;
  allreduce(&local, &sum, 1, MPI_DOUBLE, MPI_SUM, raw_comm(comm_));
  ++stats_.reductions;
  stats_.bytes_sent += 8.0;
  if (E) *E = sum;
  return st;
}

rn_status DistSystem::gradient(const TMV &x, double *E, TMV &g) {
  ++counters.gradient;
  import_state(x);
  double local = 0.0;
  const rn_status st = evaluate(
      [&] { return rn_network_gradient(net_, col0(*xov_), &local, col0(*gov_)); },
      "rn_network_gradient");
  if (E) {
    double sum = 0.0;
    allreduce(&local, &sum, 1, MPI_DOUBLE, MPI_SUM, raw_comm(comm_));
    ++stats_.reductions;
    stats_.bytes_sent += 8.0;
    *E = sum;
  }
  if (st == RN_OK) export_gov(g);
  return st;
}

rn_status DistSystem::stretch_correction(const TMV &x, const TMV &s, TMV &f) {
  import_state(x);
  import_to(s, *sov_);
  const rn_status st = evaluate(
      [&] {
        return rn_network_stretch_correction(net_, col0(*xov_), col0(*sov_), col0(*gov_));
      },
      "rn_network_stretch_correction");
  if (st == RN_OK) export_gov(f);
  return st;
}

void DistSystem::assemble_hessian(const TMV &x) {
  ++counters.hessian;
  const double t0 = steady_now();
  struct Timer { // also when it throws
    Counters &c;
    double t0;
    ~Timer() { c.hessian_seconds += seconds_since_steady(t0); }
  } timer{counters, t0};
  import_state(x);
  if (evaluate([&] { return rn_network_hessian_values(net_, col0(*xov_), vals_.data()); },
               "rn_network_hessian_values") != RN_OK)
    throw Error(RN_ERR_SOLVER, "rn_solve: Hessian at a degenerate state");
  size_t nnz = 0;
  const int64_t *rowptr = nullptr;
  const int32_t *col = nullptr;
  check_status(rn_network_hessian_pattern(net_, &nnz, &rowptr, &col),
               "rn_network_hessian_pattern");
  h_->resumeFill();
  h_->setAllToScalar(0.0);
  for (size_t i = 0; i < n_owned_; ++i) {
    const size_t a = static_cast<size_t>(rowptr[i]),
                 b = static_cast<size_t>(rowptr[i + 1]);
    if (h_->sumIntoLocalValues(static_cast<LO>(i), static_cast<LO>(b - a),
                               vals_.data() + a,
                               hcols_.data() + a) != static_cast<LO>(b - a))
      throw Error(RN_ERR_INTERNAL, "rn_solve: the Hessian's graph lacks an entry");
  }
  hgh_->resumeFill();
  std::vector<LO> cols;
  for (size_t i = n_owned_; i < n_local_; ++i) {
    const size_t a = static_cast<size_t>(rowptr[i]),
                 b = static_cast<size_t>(rowptr[i + 1]);
    cols.assign(col + a, col + b);
    hgh_->replaceLocalValues(static_cast<LO>(i - n_owned_),
                             Teuchos::ArrayView<const LO>(cols),
                             Teuchos::ArrayView<const double>(vals_.data() + a, b - a));
  }
  hgh_->fillComplete(owned_, owned_);
  h_->doExport(*hgh_, *ghost_exporter_, Tpetra::ADD);
  h_->fillComplete(owned_, owned_);
  ++stats_.exports;
  stats_.bytes_sent += 16.0 * ghost_nnz_;
}

void DistSystem::load_increment(const TMV &x, double t_prev, double t, TMV &dg) {
  import_state(x);
  agree(rn_network_load_increment(net_, col0(*xov_), t_prev, t, col0(*gov_)));
  export_gov(dg);
}

void DistSystem::accept(TMV &x) {
  import_state(x);
  rn_state *saved = nullptr;
  rn_status st = rn_network_state_save(net_, &saved);
  if (st == RN_OK) st = rn_network_update_reference(net_, col0(*xov_));
  // all parts or none: a part that updated while another failed goes back
  rn_status all = RN_OK;
  try {
    all = agree(st);
  } catch (...) {
    if (st == RN_OK) rn_network_state_restore(net_, saved);
    rn_state_destroy(&saved);
    throw;
  }
  if (all != RN_OK) {
    if (st == RN_OK) rn_network_state_restore(net_, saved);
    rn_state_destroy(&saved);
    throw Error(all, "rn_solve: reference update at a degenerate state");
  }
  rn_state_destroy(&saved);
  std::copy(col0(*xov_), col0(*xov_) + n_owned_, col0(x));
}

const DofBlocks &DistSystem::blocks() const {
  if (!blocks_done_) build_blocks();
  return blocks_;
}

// As SerialSystem::build_blocks (rn_network_dof_blocks) on the owned DOFs of the
// part: the classification sees every joint stencil a rod end takes part in, owned
// here or not (a ghost joint lists the ends at the rods held here), so rod interiors
// never couple across rods in the assembled Hessian.
void DistSystem::build_blocks() const {
  std::vector<GO> owned(n_owned_);
  for (size_t i = 0; i < n_owned_; ++i) owned[i] = static_cast<GO>(i);
  blocks_ = n_local_ ? make_dof_blocks(network_dofs(net_), owned) : DofBlocks{};
  blocks_done_ = true;
}

} // namespace rodnet

namespace rodnet {

// The largest support reaction force and moment: each part's partial reactions (its
// owned stencils) of the supports it holds, gathered and summed by support.
void DistSystem::reaction_scales(double *f0, double *m0) {
  const int ns = rn_network_num_supports(net_);
  std::vector<rn_reaction> r(static_cast<size_t>(ns));
  rn_status st = ns ? rn_network_reactions(net_, col0(*xov_), r.data(), ns) : RN_OK;
  if (agree(st) != RN_OK) r.clear(); // degenerate: no reactions (as one rank)
  std::vector<double> mine;          // kind, rod, index, force[3], moment[3]
  for (const rn_reaction &s : r) {
    mine.insert(mine.end(), {static_cast<double>(s.kind), static_cast<double>(s.rod),
                             static_cast<double>(s.index), s.force[0], s.force[1],
                             s.force[2], s.moment[0], s.moment[1], s.moment[2]});
  }
  const MPI_Comm c = raw_comm(comm_);
  std::vector<double> all = mine;
  if (c != MPI_COMM_NULL && comm_->getSize() > 1) {
    const int size = comm_->getSize();
    int cnt = static_cast<int>(mine.size());
    std::vector<int> counts(static_cast<size_t>(size)),
        disp(static_cast<size_t>(size) + 1, 0);
    MPI_Allgather(&cnt, 1, MPI_INT, counts.data(), 1, MPI_INT, c);
    for (int q = 0; q < size; ++q)
      disp[static_cast<size_t>(q) + 1] =
          disp[static_cast<size_t>(q)] + counts[static_cast<size_t>(q)];
    all.resize(static_cast<size_t>(disp[static_cast<size_t>(size)]));
    MPI_Allgatherv(mine.data(), cnt, MPI_DOUBLE, all.data(), counts.data(), disp.data(),
                   MPI_DOUBLE, c);
    stats_.bytes_sent += 8.0 * static_cast<double>(mine.size()) * (size - 1);
  }
  // sum by support (kind, rod, index), in rank order: the same on every rank
  std::vector<size_t> order(all.size() / 9);
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return std::lexicographical_compare(&all[9 * a], &all[9 * a + 3], &all[9 * b],
                                        &all[9 * b + 3]);
  });
  *f0 = *m0 = 0.0;
  for (size_t i = 0; i < order.size();) {
    double f[3] = {0.0, 0.0, 0.0}, m[3] = {0.0, 0.0, 0.0};
    size_t j = i;
    for (; j < order.size() &&
           std::equal(&all[9 * order[i]], &all[9 * order[i] + 3], &all[9 * order[j]]);
         ++j)
      for (int k = 0; k < 3; ++k) {
        f[k] += all[9 * order[j] + 3 + static_cast<size_t>(k)];
        m[k] += all[9 * order[j] + 6 + static_cast<size_t>(k)];
      }
    *f0 = std::max(*f0, eq_norm3(f));
    *m0 = std::max(*m0, eq_norm3(m));
    i = j;
  }
}

EquilibriumView DistSystem::equilibrium(const TMV &x, const TMV &g) {
  const MPI_Comm c = raw_comm(comm_);
  if (size_ < 0.0) { // once: DOF kinds, the size of the structure
    kind_.assign(n_local_, RN_DOF_POSITION);
    if (n_local_)
      agree(rn_network_dof_kinds(net_, kind_.data()));
    else
      agree(RN_OK);
    size_ = structure_size(net_, c);
  }
  EquilibriumView v = last_eq_;
  auto gd = g.getData(0), xd = x.getData(0);
  double loc[3] = {0.0, 0.0, 0.0}, glob[3]; // force, moment residual, max |x|
  for (size_t i = 0; i < n_owned_; ++i) {
    const double a = std::fabs(gd[static_cast<LO>(i)]);
    if (kind_[i] == RN_DOF_POSITION) {
      loc[0] = std::max(loc[0], a);
      loc[2] = std::max(loc[2], std::fabs(xd[static_cast<LO>(i)]));
    } else {
      loc[1] = std::max(loc[1], a);
    }
  }
  allreduce(loc, glob, 3, MPI_DOUBLE, MPI_MAX, c);
  v.force_residual = glob[0];
  v.moment_residual = glob[1];
  const double xmax = glob[2];
  // scales and floors change slowly: again only near the last scale (as equilibrium.cpp)
  if (last_eq_.valid && v.force_residual > 1e-3 * last_eq_.force_scale &&
      v.moment_residual > 1e-3 * last_eq_.moment_scale)
    return v;
  import_state(x);
  double load[2] = {0.0, 0.0}, gload[2];
  agree(rn_network_applied_load_max(net_, &load[0], &load[1]));
  allreduce(load, gload, 2, MPI_DOUBLE, MPI_MAX, c);
  double freac = 0.0, mreac = 0.0;
  reaction_scales(&freac, &mreac);
  // round-off floor: |H delta| + eps * (sum of stencil force magnitudes)
  TMV delta(owned_, 1), hd(owned_, 1), ga(owned_, 1);
  {
    auto dd = delta.getDataNonConst(0);
    for (size_t i = 0; i < n_owned_; ++i)
      dd[static_cast<LO>(i)] = eq_sign_of(static_cast<uint64_t>(
                                   owned_->getGlobalElement(static_cast<LO>(i)))) *
                               DBL_EPSILON * (kind_[i] == RN_DOF_POSITION ? xmax : 1.0);
  }
  TMV dov(overlap_, 1);
  dov.doImport(delta, *importer_, Tpetra::INSERT);
  rn_status st = rn_network_hvp(net_, col0(*xov_), col0(dov), col0(*gov_));
  agree(st < 0 ? st : RN_OK);
  ++counters.hvp;
  hd.doExport(*gov_, *exporter_, Tpetra::ADD);
  st = rn_network_gradient_magnitude(net_, col0(*xov_), col0(*gov_));
  agree(st < 0 ? st : RN_OK);
  ga.doExport(*gov_, *exporter_, Tpetra::ADD);
  stats_.bytes_sent += 8.0 * static_cast<double>(importer_->getNumExportIDs() +
                                                 2 * exporter_->getNumExportIDs());
  double fl[2] = {0.0, 0.0}, gfl[2];
  auto hdd = hd.getData(0), gad = ga.getData(0);
  // the internal moment of the state over the owned DOFs (as equilibrium.cpp)
  std::vector<double> lever;
  rn_status lst = RN_OK;
  try {
    lever = eq_levers(net_, kind_);
  } catch (const Error &e) {
    lst = e.status();
  }
  agree(lst);
  double mint = eq_internal_moment(kind_, lever, gad.getRawPtr(), n_owned_), gmint = 0.0;
  allreduce(&mint, &gmint, 1, MPI_DOUBLE, MPI_MAX, c);
  const double f0 = std::max(gload[0], freac), m0 = std::max({gload[1], mreac, gmint});
  v.force_scale = size_ > 0.0 ? std::max(f0, m0 / size_) : f0;
  v.moment_scale = std::max(m0, f0 * size_);
  for (size_t i = 0; i < n_owned_; ++i) {
    double &floor = kind_[i] == RN_DOF_POSITION ? fl[0] : fl[1];
    floor = std::max(floor, std::fabs(hdd[static_cast<LO>(i)]) +
                                DBL_EPSILON * gad[static_cast<LO>(i)]);
  }
  allreduce(fl, gfl, 2, MPI_DOUBLE, MPI_MAX, c);
  v.force_floor = gfl[0];
  v.moment_floor = gfl[1];
  v.valid = true;
  last_eq_ = v;
  return v;
}

} // namespace rodnet

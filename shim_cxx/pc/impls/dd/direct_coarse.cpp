// direct_coarse.cpp - the exact coarse solve of the rod-level domain decomposition
// (make_direct_coarse_solver, coarse_solver.hpp): rodnet's sparse Cholesky of the
// coarse matrix, substructured over the ranks (SubstructuredCoarse), the reduced
// inter-rank separator matrix gathered to rank 0 and factored there
// (GatheredCholesky).
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_OrdinalTraits.hpp>
#include <Tpetra_CrsGraph.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>

#include "base/shim_error.hpp"
#include "factor/sparse_cholesky.hpp"
#include "pc/coarse_solver.hpp"
#include "pc/impls/dd/dd_common.hpp"

namespace rodnet {

using namespace dd;

namespace {

// Sparse Cholesky of a matrix R gathered to rank 0 (the reduced separator matrix of
// SubstructuredCoarse; never a distributed direct solve, TRILINOS.md), no shift.
class GatheredCholesky {
public:
  explicit GatheredCholesky(double max_flops) : max_flops_(max_flops) {}
  // Factors R (collective).  True on every rank if R is positive definite or the
  // factorisation was declined (it would take more than max_flops > 0 flops).
  bool setup(const Teuchos::RCP<const TCrs> &R);
  void solve(const TMV &b, TMV &y) const; // y = R^-1 b, collective
  double bytes() const { return bytes_; }
  bool declined() const { return declined_; }
  double flops() const { return flops_; }

private:
  void analyse(const TCrs &R0);
  const void *graph_ = nullptr; // the structure analysed
  Teuchos::RCP<const TMap> map0_;
  Teuchos::RCP<const Tpetra::Import<>> imp0_;
  Teuchos::RCP<TCrs> R0_; // R gathered on rank 0
  mutable Teuchos::RCP<TMV> b0_, y0_;
  std::vector<int64_t> rowptr_;
  std::vector<int32_t> col_;
  std::vector<size_t> perm_; // CSR entry -> R0 value
  std::vector<double> vals_;
  std::shared_ptr<SparseAnalysis> analysis_;
  std::unique_ptr<SparseCholesky> chol_;
  double bytes_ = 0.0, max_flops_ = 0.0, flops_ = 0.0;
  bool declined_ = false;
};

// The CSR arrays (sorted columns) of R0's pattern and where each entry's value is in
// R0's local matrix, once per pattern; the symbolic analysis with them.
void GatheredCholesky::analyse(const TCrs &R0) {
  auto lcl = R0.getLocalMatrixHost();
  auto colmap = R0.getColMap();
  const size_t n = R0.getNodeNumRows();
  rowptr_.assign(n + 1, 0);
  col_.clear();
  perm_.clear();
  size_t ndiag = 0;
  std::vector<std::pair<int32_t, size_t>> row;
  for (size_t i = 0; i < n; ++i) {
    row.clear();
    for (size_t q = lcl.graph.row_map(i); q < lcl.graph.row_map(i + 1); ++q)
      row.emplace_back(
          static_cast<int32_t>(colmap->getGlobalElement(lcl.graph.entries(q))), q);
    std::sort(row.begin(), row.end());
    for (const auto &e : row) {
      ndiag += static_cast<size_t>(e.first) == i;
      col_.push_back(e.first);
      perm_.push_back(e.second);
    }
    rowptr_[i + 1] = static_cast<int64_t>(col_.size());
  }
  if (ndiag != n)
    throw Error(RN_ERR_INTERNAL,
                "dd preconditioner: separator matrix without its diagonal");
  analysis_ = std::make_shared<SparseAnalysis>(n, rowptr_.data(), col_.data());
  chol_.reset(new SparseCholesky(analysis_));
}

bool GatheredCholesky::setup(const Teuchos::RCP<const TCrs> &R) {
  auto comm = R->getComm();
  const Tpetra::global_size_t N = R->getGlobalNumRows();
  if (graph_ != R->getCrsGraph().get()) { // a new structure
    graph_ = R->getCrsGraph().get();
    analysis_.reset();
    const size_t nloc = comm->getRank() == 0 ? static_cast<size_t>(N) : 0;
    map0_ = Teuchos::rcp(new TMap(N, nloc, GO(0), comm));
    imp0_ = Teuchos::rcp(new Tpetra::Import<>(R->getRowMap(), map0_));
    auto first = Tpetra::importAndFillCompleteCrsMatrix<TCrs>(R, *imp0_, map0_, map0_);
    R0_ = Teuchos::rcp(new TCrs(first->getCrsGraph())); // static graph: refilled below
    b0_ = Teuchos::rcp(new TMV(map0_, 1));
    y0_ = Teuchos::rcp(new TMV(map0_, 1));
  }
  R0_->resumeFill();
  R0_->setAllToScalar(0.0);
  R0_->doImport(*R, *imp0_, Tpetra::ADD);
  R0_->fillComplete(map0_, map0_);
  bool ok = true, failed = false;
  if (comm->getRank() == 0) {
    try {
      if (!analysis_) analyse(*R0_);
      flops_ = analysis_->factor_flops();
      declined_ = max_flops_ > 0.0 && flops_ > max_flops_;
      if (!declined_) {
        auto lcl = R0_->getLocalMatrixHost();
        vals_.resize(perm_.size());
        for (size_t q = 0; q < perm_.size(); ++q) vals_[q] = lcl.values(perm_[q]);
        ok = chol_->factor(vals_.data(), 0.0, nullptr);
      }
      bytes_ = 8.0 * static_cast<double>(analysis_->factor_entries()) +
               28.0 * static_cast<double>(vals_.size());
    } catch (const Error &) {
      failed = true;
    }
  }
  double sh[4] = {ok ? 1.0 : 0.0, declined_ ? 1.0 : 0.0, flops_, failed ? 1.0 : 0.0};
  Teuchos::broadcast(*comm, 0, 4, sh);
  declined_ = sh[1] != 0.0;
  flops_ = sh[2];
  if (sh[3] != 0.0)
    throw Error(RN_ERR_INTERNAL, "dd preconditioner: the separator matrix cannot be "
                                 "ordered (METIS)");
  return sh[0] != 0.0;
}

// All of b's columns at once: one gather to rank 0, one scatter back.
void GatheredCholesky::solve(const TMV &b, TMV &y) const {
  const size_t nc = b.getNumVectors();
  dd::ensure_columns(b0_, map0_, nc);
  dd::ensure_columns(y0_, map0_, nc);
  b0_->doImport(b, *imp0_, Tpetra::INSERT);
  if (map0_->getNodeNumElements() > 0) {
    auto v = b0_->getLocalViewHost(Tpetra::Access::ReadOnly);
    auto w = y0_->getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (size_t j = 0; j < nc; ++j) {
      for (size_t i = 0; i < v.extent(0); ++i) w(i, j) = v(i, j);
      chol_->solve(&w(0, j));
    }
  }
  y.doExport(*y0_, *imp0_, Tpetra::INSERT);
}

// The direct coarse solve, exact and balanced over the ranks by a second static
// condensation (substructuring).  A coarse row owned by rank p is on the inter-rank
// separator Γ if S couples it to a row of a higher rank (a vertex separator: every
// coupling between two ranks has its lower rank's end on Γ); the other rows of p
// form I_p, coupled only to I_p and Γ.  Each rank factors S_{I_p I_p} (sparse
// Cholesky, partial factorisation with the rows of Γ that I_p touches, Γ_p, last)
// and so gets its contribution -S_{Γ_p I_p} S_{I_p I_p}^-1 S_{I_p Γ_p} (dense on Γ_p);
// these and S_ΓΓ are summed into the reduced matrix R on Γ (a Tpetra matrix, rows
// owned by Γ's owners), which GatheredCholesky solves on rank 0.  solve(): forward
// elimination on every rank, the condensed right-hand sides summed onto Γ, R's solve,
// x_Γ back to the ranks that touch it, back substitution.  One rank: Γ is empty and
// this is the sparse Cholesky of S.
// S not positive definite: the exact solve of S + t D_S (D_S = |diag S| floored at
// 1e-8 of its largest entry, t the smallest of smallest_shift's ladder for which
// every S_{I_p I_p} + t D and the reduced matrix of S + t D_S factor; S + t D_S is
// positive definite iff they are), the same t and M on any number of ranks.
class SubstructuredCoarse : public CoarseSolver {
public:
  explicit SubstructuredCoarse(double max_flops) : max_flops_(max_flops) {}
  void setup(const Teuchos::RCP<const TCrs> &S, const Teuchos::RCP<const TMV> &) override;
  void solve(const TMV &b, TMV &y) const override;
  double shift() const override { return shift_; }
  double bytes() const override { return bytes_; }
  std::string name() const override { return "direct"; }
  void set_strict(bool strict) override { strict_ = strict; }
  bool failed() const override { return failed_; }
  bool declined() const override { return declined_; }
  double flops() const override { return flops_; }
  long long separator_rows() const override { return nred_; }

private:
  // analyse(): the structure of S, once per graph, in four steps.
  void analyse(const TCrs &S);
  void split_rows(const TCrs &S, std::vector<long long> &red, long long &ngam,
                  long long &incl);
  void index_columns(const TCrs &S, const std::vector<long long> &red,
                     std::vector<long long> &cred, std::vector<int32_t> &cidx) const;
  size_t local_csr(const TCrs &S, const std::vector<long long> &cred,
                   const std::vector<int32_t> &cidx);
  void reduced_matrix(const TCrs &S, const std::vector<long long> &cred, long long ngam,
                      long long incl);
  void locate_reduced(const std::vector<GO> &ovg,
                      const std::vector<std::pair<size_t, GO>> &ss,
                      const std::vector<LO> &ss_row);
  void analyse_local(const Comm &comm, size_t n);
  // setup(): the metric D_S and the factorisations of S + t D_S.
  void interface_metric(const TCrs &S, std::vector<double> &dg);
  bool factor_with_shift(const TCrs &S, double t, const std::vector<double> &dg);
  void assemble_reduced(const TCrs &S, double t, const std::vector<double> &dg);
  const void *graph_ = nullptr; // the structure analysed
  // the local matrix [S_II S_IΓ; S_ΓI 0] in CSR: rows I (S's local rows irows_), then
  // the separator rows Γ_p (sep_: their reduced GIDs, ascending)
  std::vector<LO> irows_;
  std::vector<GO> sep_;
  std::vector<int64_t> rowptr_;
  std::vector<int32_t> col_;
  std::vector<size_t> src_, diag_; // S value index of each entry (npos: 0); I diagonals
  std::vector<double> vals_, m_;
  std::shared_ptr<SparseAnalysis> analysis_;
  std::unique_ptr<SparseCholesky> chol_;
  // the reduced matrix R on Γ: rows of gmap_ (owned Γ, S's rows gam_rows_), summed
  // from Rov_ (owned Γ, then the other ranks' rows of sep_)
  long long nred_ = 0;
  std::vector<LO> gam_rows_;
  std::vector<LO> sep_ov_;                    // Rov_ row of each separator row
  std::vector<size_t> ss_src_, ss_dst_;       // S_ΓΓ: S value index -> Rov_ value index
  std::vector<size_t> gdiag_src_, gdiag_dst_; // S, Rov_ value index of Γ diagonals
  std::vector<size_t> schur_dst_;             // Rov_ value index of Schur entry (a, b)
  Teuchos::RCP<const TMap> gmap_, gov_;
  Teuchos::RCP<TCrs> Rov_, R_;
  Teuchos::RCP<const Tpetra::Export<>> exporter_;
  Teuchos::RCP<const Tpetra::Import<>> importer_;
  std::unique_ptr<GatheredCholesky> root_;
  mutable Teuchos::RCP<TMV> bov_, yov_, br_, yr_;
  mutable std::vector<double> x_;
  mutable std::vector<double> xb_; // solve(): x_ per column of a block
  double shift_ = 0.0, bytes_ = 0.0, max_flops_ = 0.0, flops_ = 0.0;
  bool strict_ = false, failed_ = false;
  bool declined_ = false;
};

// The split into I_p and Γ, the local CSR and its partial analysis, the reduced
// matrix's maps and graph: once per structure of S.
void SubstructuredCoarse::analyse(const TCrs &S) {
  if (!S.getRowMap()->isContiguous())
    throw Error(RN_ERR_INTERNAL, "dd preconditioner: coarse map not contiguous");
  std::vector<long long> red, cred;
  std::vector<int32_t> cidx;
  long long ngam = 0, incl = 0;
  split_rows(S, red, ngam, incl);
  index_columns(S, red, cred, cidx);
  x_.assign(local_csr(S, cred, cidx), 0.0);
  if (nred_ == 0) return;
  reduced_matrix(S, cred, ngam, incl);
}

// Γ rows (coupled to a higher rank's row) and I rows; red: the reduced GID of every
// owned Γ row (-1: an I row), ngam of them here, incl the inclusive prefix sum of
// ngam over the ranks.
void SubstructuredCoarse::split_rows(const TCrs &S, std::vector<long long> &red,
                                     long long &ngam, long long &incl) {
  auto rowmap = S.getRowMap();
  auto colmap = S.getColMap();
  auto lcl = S.getLocalMatrixHost();
  const size_t nrow = S.getNodeNumRows();
  const GO gmax = rowmap->getMaxGlobalIndex();
  gam_rows_.clear();
  irows_.clear();
  red.assign(nrow, -1); // reduced GID of an owned Γ row
  for (size_t i = 0; i < nrow; ++i) {
    bool gam = false;
    for (size_t q = lcl.graph.row_map(i); q < lcl.graph.row_map(i + 1); ++q)
      gam = gam || colmap->getGlobalElement(lcl.graph.entries(q)) > gmax;
    if (gam) {
      red[i] = static_cast<long long>(gam_rows_.size());
      gam_rows_.push_back(static_cast<LO>(i));
    } else {
      irows_.push_back(static_cast<LO>(i));
    }
  }
  ngam = static_cast<long long>(gam_rows_.size());
  incl = 0;
  Teuchos::scan(*rowmap->getComm(), Teuchos::REDUCE_SUM, ngam, Teuchos::outArg(incl));
  for (long long &r : red)
    if (r >= 0) r += incl - ngam;
  nred_ = sum_over_ranks(*rowmap->getComm(), ngam);
}

// The reduced GID of every column of S (cred, -1: not on Γ) and its I index (cidx,
// -1: not an owned I row).
void SubstructuredCoarse::index_columns(const TCrs &S, const std::vector<long long> &red,
                                        std::vector<long long> &cred,
                                        std::vector<int32_t> &cidx) const {
  auto rowmap = S.getRowMap();
  auto colmap = S.getColMap();
  const size_t nrow = S.getNodeNumRows(), ncol = colmap->getNodeNumElements();
  cred.assign(ncol, -1);
  if (nred_ > 0) {
    TMV f(rowmap, 1), fc(colmap, 1);
    {
      auto v = f.getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (size_t i = 0; i < nrow; ++i) v(i, 0) = static_cast<double>(red[i]);
    }
    fc.doImport(f, Tpetra::Import<>(rowmap, colmap), Tpetra::INSERT);
    auto v = fc.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (size_t c = 0; c < ncol; ++c) cred[c] = static_cast<long long>(v(c, 0));
  }
  cidx.assign(ncol, -1);
  std::vector<int32_t> ipos(nrow, -1);
  for (size_t a = 0; a < irows_.size(); ++a)
    ipos[static_cast<size_t>(irows_[a])] = static_cast<int32_t>(a);
  for (size_t c = 0; c < ncol; ++c) {
    const LO r = rowmap->getLocalElement(colmap->getGlobalElement(static_cast<LO>(c)));
    if (r != Teuchos::OrdinalTraits<LO>::invalid())
      cidx[c] = ipos[static_cast<size_t>(r)];
  }
}

// The separator rows Γ_p (Γ columns of the I rows), the CSR of the local matrix
// [S_II S_IΓ; S_ΓI 0] and its partial analysis (Γ_p last); returns its order.
size_t SubstructuredCoarse::local_csr(const TCrs &S, const std::vector<long long> &cred,
                                      const std::vector<int32_t> &cidx) {
  auto lcl = S.getLocalMatrixHost();
  // The separator rows Γ_p: Γ columns of the I rows.
  sep_.clear();
  for (LO i : irows_)
    for (size_t q = lcl.graph.row_map(i); q < lcl.graph.row_map(i + 1); ++q) {
      const size_t c = static_cast<size_t>(lcl.graph.entries(q));
      if (cred[c] >= 0)
        sep_.push_back(static_cast<GO>(cred[c]));
      else if (cidx[c] < 0)
        throw Error(RN_ERR_INTERNAL,
                    "dd preconditioner: the coarse matrix's pattern is not symmetric");
    }
  std::sort(sep_.begin(), sep_.end());
  sep_.erase(std::unique(sep_.begin(), sep_.end()), sep_.end());
  const size_t ni = irows_.size(), n = ni + sep_.size();
  auto sep_index = [&](GO g) {
    return static_cast<int32_t>(
        ni + static_cast<size_t>(std::lower_bound(sep_.begin(), sep_.end(), g) -
                                 sep_.begin()));
  };
  // CSR of the local matrix, both triangles: rows I from S, rows Γ_p transposed
  // (with their diagonal, zero).
  rowptr_.assign(n + 1, 0);
  col_.clear();
  src_.clear();
  diag_.clear();
  std::vector<std::pair<int32_t, size_t>> row;
  std::vector<std::array<size_t, 3>> tr; // (separator row, I column, S value index)
  for (size_t a = 0; a < ni; ++a) {
    const LO i = irows_[a];
    row.clear();
    for (size_t q = lcl.graph.row_map(i); q < lcl.graph.row_map(i + 1); ++q) {
      const size_t c = static_cast<size_t>(lcl.graph.entries(q));
      const int32_t j = cred[c] >= 0 ? sep_index(static_cast<GO>(cred[c])) : cidx[c];
      row.emplace_back(j, q);
      if (cred[c] >= 0) tr.push_back({static_cast<size_t>(j), a, q});
    }
    std::sort(row.begin(), row.end());
    for (const auto &e : row) {
      if (static_cast<size_t>(e.first) == a) diag_.push_back(col_.size());
      col_.push_back(e.first);
      src_.push_back(e.second);
    }
    rowptr_[a + 1] = static_cast<int64_t>(col_.size());
  }
  for (size_t k = ni; k < n; ++k) tr.push_back({k, k, kNone});
  std::sort(tr.begin(), tr.end());
  for (const auto &e : tr) {
    col_.push_back(static_cast<int32_t>(e[1]));
    src_.push_back(e[2]);
    rowptr_[e[0] + 1] = static_cast<int64_t>(col_.size());
  }
  if (diag_.size() != ni)
    throw Error(RN_ERR_INTERNAL, "dd preconditioner: coarse matrix without its diagonal");
  analyse_local(*S.getComm(), n);
  return n;
}

// The partial analysis of the local matrix of order n (Γ_p last) and its factor.
void SubstructuredCoarse::analyse_local(const Comm &comm, size_t n) {
  analysis_.reset();
  chol_.reset();
  bool failed = false;
  try {
    if (n > 0) {
      analysis_ =
          std::make_shared<SparseAnalysis>(n, rowptr_.data(), col_.data(), sep_.size());
      chol_.reset(new SparseCholesky(analysis_));
    }
  } catch (const Error &) {
    failed = true;
  }
  throw_if_any(comm, failed, RN_ERR_INTERNAL,
               "dd preconditioner: the coarse matrix cannot be ordered (METIS)");
}

// The reduced matrix R on Γ: its maps and the graph of Rov_ (owned Γ rows, then the
// separator rows of other ranks; each separator row dense over the separator, each
// owned Γ row with its S_ΓΓ entries); then locate_reduced.
void SubstructuredCoarse::reduced_matrix(const TCrs &S,
                                         const std::vector<long long> &cred,
                                         long long ngam, long long incl) {
  auto comm = S.getComm();
  auto lcl = S.getLocalMatrixHost();
  gmap_ = Teuchos::rcp(new TMap(static_cast<Tpetra::global_size_t>(nred_),
                                static_cast<size_t>(ngam), GO(0), comm));
  std::vector<GO> ovg;
  for (long long k = 0; k < ngam; ++k) ovg.push_back(static_cast<GO>(incl - ngam + k));
  for (GO g : sep_)
    if (!gmap_->isNodeGlobalElement(g)) ovg.push_back(g);
  gov_ = Teuchos::rcp(new TMap(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                               Teuchos::ArrayView<const GO>(ovg.data(), ovg.size()),
                               GO(0), comm));
  sep_ov_.resize(sep_.size());
  for (size_t k = 0; k < sep_.size(); ++k) sep_ov_[k] = gov_->getLocalElement(sep_[k]);
  std::vector<std::vector<GO>> rc(ovg.size());
  for (LO l : sep_ov_) rc[static_cast<size_t>(l)] = sep_;
  std::vector<std::pair<size_t, GO>> ss; // (S value index, column) per owned Γ row
  std::vector<LO> ss_row;
  gdiag_src_.assign(gam_rows_.size(), kNone);
  for (size_t j = 0; j < gam_rows_.size(); ++j) {
    const LO i = gam_rows_[j];
    rc[j].push_back(ovg[j]);
    for (size_t q = lcl.graph.row_map(i); q < lcl.graph.row_map(i + 1); ++q) {
      const size_t c = static_cast<size_t>(lcl.graph.entries(q));
      if (static_cast<GO>(cred[c]) == ovg[j]) gdiag_src_[j] = q;
      if (cred[c] < 0) continue; // S_ΓI: in the other rank's local matrix
      rc[j].push_back(static_cast<GO>(cred[c]));
      ss.emplace_back(q, static_cast<GO>(cred[c]));
      ss_row.push_back(static_cast<LO>(j));
    }
  }
  std::vector<size_t> counts(ovg.size());
  for (size_t l = 0; l < ovg.size(); ++l) {
    std::sort(rc[l].begin(), rc[l].end());
    rc[l].erase(std::unique(rc[l].begin(), rc[l].end()), rc[l].end());
    counts[l] = rc[l].size();
  }
  auto graph = Teuchos::rcp(new TCrs::crs_graph_type(
      gov_, Teuchos::ArrayView<const size_t>(counts.data(), counts.size())));
  for (size_t l = 0; l < ovg.size(); ++l)
    graph->insertGlobalIndices(ovg[l],
                               Teuchos::ArrayView<const GO>(rc[l].data(), rc[l].size()));
  rc.clear();
  graph->fillComplete(gmap_, gmap_);
  Rov_ = Teuchos::rcp(new TCrs(graph));
  locate_reduced(ovg, ss, ss_row);
}

// Where S_ΓΓ (ss: S value index and column of each entry, ss_row its owned Γ row),
// the Γ diagonals and the Schur entries go in Rov_'s values; the export and import
// between gov_ and gmap_, R_ on the owned rows, the work vectors of solve().
void SubstructuredCoarse::locate_reduced(const std::vector<GO> &ovg,
                                         const std::vector<std::pair<size_t, GO>> &ss,
                                         const std::vector<LO> &ss_row) {
  auto rl = Rov_->getLocalMatrixHost();
  auto rcol = Rov_->getColMap();
  ss_src_.clear();
  ss_dst_.clear();
  for (size_t e = 0; e < ss.size(); ++e) {
    ss_src_.push_back(ss[e].first);
    ss_dst_.push_back(find_entry(rl, ss_row[e], rcol->getLocalElement(ss[e].second)));
  }
  gdiag_dst_.resize(gam_rows_.size());
  for (size_t j = 0; j < gam_rows_.size(); ++j) {
    if (gdiag_src_[j] == kNone)
      throw Error(RN_ERR_INTERNAL,
                  "dd preconditioner: coarse matrix without its diagonal");
    gdiag_dst_[j] = find_entry(rl, static_cast<LO>(j), rcol->getLocalElement(ovg[j]));
  }
  const size_t m = sep_.size();
  schur_dst_.resize(m * m);
  for (size_t a = 0; a < m; ++a)
    for (size_t b2 = 0; b2 < m; ++b2)
      schur_dst_[a + b2 * m] =
          find_entry(rl, sep_ov_[a], rcol->getLocalElement(sep_[b2]));
  exporter_ = Teuchos::rcp(new Tpetra::Export<>(gov_, gmap_));
  importer_ = Teuchos::rcp(new Tpetra::Import<>(gmap_, gov_));
  auto made =
      Tpetra::exportAndFillCompleteCrsMatrix<TCrs>(Rov_, *exporter_, gmap_, gmap_);
  R_ = Teuchos::rcp(new TCrs(made->getCrsGraph())); // static graph: refilled in setup
  bov_ = Teuchos::rcp(new TMV(gov_, 1));
  yov_ = Teuchos::rcp(new TMV(gov_, 1));
  br_ = Teuchos::rcp(new TMV(gmap_, 1));
  yr_ = Teuchos::rcp(new TMV(gmap_, 1));
}

void SubstructuredCoarse::setup(const Teuchos::RCP<const TCrs> &S,
                                const Teuchos::RCP<const TMV> &) {
  auto comm = S->getComm();
  if (graph_ != S->getCrsGraph().get()) { // a new structure
    graph_ = S->getCrsGraph().get();
    analyse(*S);
    root_.reset();
  }
  // The local partial factorisations first: their flops decide on the AMG switch.
  const double local_flops = analysis_ ? analysis_->factor_flops() : 0.0;
  double lf = 0.0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_SUM, local_flops, Teuchos::outArg(lf));
  flops_ = lf;
  declined_ = max_flops_ > 0.0 && lf > max_flops_;
  if (declined_) return;
  auto sv = S->getLocalMatrixHost().values;
  if (chol_) {
    vals_.resize(src_.size());
    for (size_t e = 0; e < src_.size(); ++e)
      vals_[e] = src_[e] == kNone ? 0.0 : sv(src_[e]);
  }
  std::vector<double> dg;
  interface_metric(*S, dg);
  if (nred_ > 0 && !root_)
    root_.reset(new GatheredCholesky(max_flops_ > 0.0 ? max_flops_ - lf : 0.0));
  auto try_factor = [&](double t) { return factor_with_shift(*S, t, dg); };
  failed_ = false;
  if (strict_) {
    shift_ = 0.0;
    failed_ = !try_factor(0.0);
    if (failed_) return;
  } else {
    shift_ = smallest_shift(try_factor);
    throw_if_any(
        *comm, shift_ < 0.0, RN_ERR_LAPACK,
        "dd preconditioner: the coarse matrix has no positive definite shift up to "
        "1e10 |diag| (non-finite entries?)");
  }
  bytes_ = analysis_ ? 8.0 * static_cast<double>(analysis_->factor_entries()) +
                           36.0 * static_cast<double>(src_.size())
                     : 0.0;
  if (nred_ == 0) return;
  flops_ = lf + root_->flops();
  declined_ = root_->declined();
  bytes_ +=
      root_->bytes() +
      12.0 * static_cast<double>(Rov_->getNodeNumEntries() + R_->getNodeNumEntries()) +
      8.0 * static_cast<double>(schur_dst_.size());
}

// D_S = |diag S| floored at 1e-8 of its largest entry (over the ranks): on the local
// pattern (I, m_) and on the owned Γ rows (dg).
void SubstructuredCoarse::interface_metric(const TCrs &S, std::vector<double> &dg) {
  auto sv = S.getLocalMatrixHost().values;
  dg.assign(gam_rows_.size(), 0.0);
  double mx = 0.0, gmx = 0.0;
  for (size_t i = 0; i < diag_.size(); ++i) mx = std::max(mx, std::fabs(vals_[diag_[i]]));
  for (size_t j = 0; j < dg.size(); ++j)
    mx = std::max(mx, dg[j] = std::fabs(sv(gdiag_src_[j])));
  Teuchos::reduceAll(*S.getComm(), Teuchos::REDUCE_MAX, mx, Teuchos::outArg(gmx));
  auto floored = [&](double v) { return gmx > 0.0 ? std::max(v, 1e-8 * gmx) : 1.0; };
  m_.assign(vals_.size(), 0.0);
  for (size_t i = 0; i < diag_.size(); ++i)
    m_[diag_[i]] = floored(std::fabs(vals_[diag_[i]]));
  for (double &v : dg) v = floored(v);
}

// True if S + t D_S is positive definite, i.e. every rank's S_II + t D_II and the
// reduced matrix factor (then factored; also true if the reduced matrix's
// factorisation was declined: that ends the search).
bool SubstructuredCoarse::factor_with_shift(const TCrs &S, double t,
                                            const std::vector<double> &dg) {
  const bool ok = !chol_ || chol_->factor(vals_.data(), t, m_.data());
  int okl = ok ? 1 : 0, all = 0;
  Teuchos::reduceAll(*S.getComm(), Teuchos::REDUCE_MIN, okl, Teuchos::outArg(all));
  if (!all) return false;
  if (nred_ == 0) return true;
  assemble_reduced(S, t, dg);
  return root_->setup(R_);
}

// R = S_ΓΓ + t D_Γ + the Schur complements of the ranks (the last partial
// factorisations), summed onto the owners of Γ.
void SubstructuredCoarse::assemble_reduced(const TCrs &S, double t,
                                           const std::vector<double> &dg) {
  auto sv = S.getLocalMatrixHost().values;
  Rov_->resumeFill();
  Rov_->setAllToScalar(0.0);
  {
    auto rv = Rov_->getLocalMatrixHost().values;
    for (size_t e = 0; e < ss_src_.size(); ++e) rv(ss_dst_[e]) += sv(ss_src_[e]);
    for (size_t k = 0; k < dg.size(); ++k) rv(gdiag_dst_[k]) += t * dg[k];
    const size_t m = sep_.size();
    if (m > 0) {
      const double *C = chol_->schur();
      for (size_t b2 = 0; b2 < m; ++b2)
        for (size_t a = b2; a < m; ++a) {
          rv(schur_dst_[a + b2 * m]) += C[a + b2 * m];
          if (a != b2) rv(schur_dst_[b2 + a * m]) += C[a + b2 * m];
        }
    }
  }
  Rov_->fillComplete(gmap_, gmap_);
  R_->resumeFill();
  R_->setAllToScalar(0.0);
  R_->doExport(*Rov_, *exporter_, Tpetra::ADD);
  R_->fillComplete(gmap_, gmap_);
}

// All of b's columns at once: one export onto Γ, one solve of R with them, one
// import back (the messages of a block are those of one vector).
void SubstructuredCoarse::solve(const TMV &b, TMV &y) const {
  const size_t ni = irows_.size(), n = x_.size(), nc = b.getNumVectors();
  xb_.assign(n * nc, 0.0);
  auto bv = b.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t j = 0; j < nc; ++j) {
    double *x = xb_.data() + j * n;
    for (size_t a = 0; a < ni; ++a) x[a] = bv(static_cast<size_t>(irows_[a]), j);
    if (n > 0) chol_->forward(x);
  }
  auto yv = y.getLocalViewHost(Tpetra::Access::ReadWrite);
  if (nred_ > 0) {
    // b_Γ - sum_p S_ΓI_p S_I_pI_p^-1 b_I_p onto Γ; R's solve; x_Γ back.
    dd::ensure_columns(bov_, gov_, nc);
    dd::ensure_columns(yov_, gov_, nc);
    dd::ensure_columns(br_, gmap_, nc);
    dd::ensure_columns(yr_, gmap_, nc);
    {
      auto v = bov_->getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (size_t j = 0; j < nc; ++j) {
        for (size_t l = 0; l < v.extent(0); ++l) v(l, j) = 0.0;
        for (size_t k = 0; k < gam_rows_.size(); ++k)
          v(k, j) = bv(static_cast<size_t>(gam_rows_[k]), j);
        for (size_t k = 0; k < sep_ov_.size(); ++k)
          v(static_cast<size_t>(sep_ov_[k]), j) += xb_[j * n + ni + k];
      }
    }
    br_->putScalar(0.0);
    br_->doExport(*bov_, *exporter_, Tpetra::ADD);
    root_->solve(*br_, *yr_);
    yov_->doImport(*yr_, *importer_, Tpetra::INSERT);
    auto v = yov_->getLocalViewHost(Tpetra::Access::ReadOnly);
    for (size_t j = 0; j < nc; ++j) {
      for (size_t k = 0; k < sep_ov_.size(); ++k)
        xb_[j * n + ni + k] = v(static_cast<size_t>(sep_ov_[k]), j);
      for (size_t k = 0; k < gam_rows_.size(); ++k)
        yv(static_cast<size_t>(gam_rows_[k]), j) = v(k, j);
    }
  }
  for (size_t j = 0; j < nc; ++j) {
    double *x = xb_.data() + j * n;
    if (n > 0) chol_->backward(x);
    for (size_t a = 0; a < ni; ++a) yv(static_cast<size_t>(irows_[a]), j) = x[a];
  }
}

} // namespace

std::unique_ptr<CoarseSolver> make_direct_coarse_solver(double max_flops) {
  return std::unique_ptr<CoarseSolver>(new SubstructuredCoarse(max_flops));
}

} // namespace rodnet

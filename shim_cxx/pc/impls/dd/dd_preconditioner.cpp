// dd_preconditioner.cpp - rod-level domain decomposition and the direct coarse solve
// (see dd_preconditioner.hpp).
#include "pc/impls/dd/dd_preconditioner.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <cmath>
#include <string>
#include <vector>

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_OrdinalTraits.hpp>
#include <Tpetra_CrsGraph.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>

#include "base/clock.hpp"
#include "base/lapack.hpp"
#include "pc/spd_guard.hpp"
#include "system/rigid_body_modes.hpp"
#include "system/dof_blocks.hpp"
#include "base/shim_error.hpp"
#include "factor/sparse_cholesky.hpp"

namespace rodnet {

namespace {

// A rod coupled to at least this many interface DOFs forms its Schur block by BLAS
// (dsyrk) instead of sparse-aware loops (the usual 6 to 24 at joints).
constexpr int kSyrkMin = 48;

using Comm = Teuchos::Comm<int>;

// Global sum of a count over the ranks.
long long sum_over_ranks(const Comm &comm, long long v) {
  long long s = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_SUM, v, Teuchos::outArg(s));
  return s;
}

// Throws Error on every rank if any rank reports a failure (never on one only).
void throw_if_any(const Comm &comm, bool failed, rn_status status,
                  const std::string &what) {
  int f = failed ? 1 : 0, any = 0;
  Teuchos::reduceAll(comm, Teuchos::REDUCE_MAX, f, Teuchos::outArg(any));
  if (any) throw Error(status, what);
}

// Smallest shift s in {0} u {1e-10, 1e-9, ..., 1e10} for which try_factor(s)
// succeeds (bisection on the exponent; the factorisation of the returned shift is
// the last one made).  Returns -1 if none does.  zero_failed: 0 is known to fail.
// hint (an exponent in [-10, 10], e.g. the last set-up's shift): 10^(hint-1) and
// 10^hint are tried first, two factorisations where the shift has not changed by a
// decade (the bisection takes six).
template <class F>
double smallest_shift(F &&try_factor, bool zero_failed = false, int hint = 99) {
  if (!zero_failed && try_factor(0.0)) return 0.0;
  int lo = -11, hi = 11; // 10^lo fails (-11 stands for 0), 10^hi works (11: unknown)
  bool last_hi = false;  // the last factorisation made is that of 10^hi
  const auto test = [&](int e) {
    last_hi = try_factor(std::pow(10.0, e));
    (last_hi ? hi : lo) = e;
  };
  if (hint >= -10 && hint <= 10) {
    if (hint > -10) test(hint - 1);
    if (hi == 11) test(hint);
  }
  if (hi == 11) {
    test(10);
    if (hi == 11) return -1.0;
  }
  while (hi - lo > 1) test((lo + hi) / 2);
  const double s = std::pow(10.0, hi);
  if (!last_hi) try_factor(s); // leave the factorisation of the returned shift
  return s;
}

// |diag| floored at 1e-8 of its maximum (1 if it vanishes).
void floored_abs(std::vector<double> &d) {
  double mx = 0.0;
  for (double &v : d) mx = std::max(mx, v = std::fabs(v));
  for (double &v : d) v = mx > 0.0 ? std::max(v, 1e-8 * mx) : 1.0;
}

// One rod's interior block (banded, factored) and its coupling H_rG to the interface.
struct Rod {
  std::vector<LO> rows; // owned local rows of the interior, ascending
  int kd = 0;
  std::vector<size_t> band_src;  // H value index of each lower band entry
  std::vector<size_t> band_dst;  // its place in the band (LAPACK lower storage)
  std::vector<double> fac;       // factored band of H_rr (+ shift D_r)
  std::vector<LO> coarse;        // overlapping-coarse local index of each coupled DOF
  std::vector<int> b_row, b_col; // entries of H_rG: rod position, index in coarse
  std::vector<size_t> b_src;
  std::vector<double> b_val;
  std::vector<size_t> s_pos; // Sov value index of (a, b), a * m + b
  double shift = 0.0;
  // D_r of the uniform shift: |diag H_rr| (floored) at the first set-up that shifts
  // uniformly, then the entrywise largest of the set-ups since, for the
  // preconditioner's life (DdPreconditioner::setup)
  std::vector<double> d_uniform;
  int n() const { return static_cast<int>(rows.size()); }
  int m() const { return static_cast<int>(coarse.size()); }
};

// Factor the band of rod r from H's values plus shift D_r.  shift < 0: the smallest
// of smallest_shift's ladder (shifted only if indefinite), false if none up to 1e10
// works; shift >= 0: that shift only (the uniform-shift search,
// DdPreconditioner::setup), false if it is not positive definite.
bool factor_rod(Rod &r, const double *vals, std::vector<double> &ab,
                double shift = -1.0) {
  const int n = r.n(), ld = r.kd + 1;
  ab.assign(static_cast<size_t>(ld) * static_cast<size_t>(n), 0.0);
  for (size_t e = 0; e < r.band_src.size(); ++e) ab[r.band_dst[e]] = vals[r.band_src[e]];
  std::vector<double> d(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) d[static_cast<size_t>(i)] = ab[static_cast<size_t>(i * ld)];
  floored_abs(d);
  if (shift >= 0.0) { // the uniform shift's D_r: the largest since the first set-up
    if (r.d_uniform.empty())
      r.d_uniform = d;
    else
      for (size_t i = 0; i < d.size(); ++i)
        r.d_uniform[i] = std::max(r.d_uniform[i], d[i]);
    d = r.d_uniform;
  }
  auto try_factor = [&](double s) {
    r.fac = ab;
    for (int i = 0; i < n; ++i)
      r.fac[static_cast<size_t>(i * ld)] += s * d[static_cast<size_t>(i)];
    int info = 0;
    dpbtrf_("L", &n, &r.kd, r.fac.data(), &ld, &info, 1);
    return info == 0;
  };
  if (shift >= 0.0) {
    r.shift = shift;
    return try_factor(shift);
  }
  r.shift = smallest_shift(try_factor);
  return r.shift >= 0.0;
}

// y <- L^-1 y (length n) for y zero before row j0, L the factor of dpbtrf in lower
// band storage.
void forward_rod(const Rod &r, double *y, size_t j0) {
  const size_t n = r.rows.size(), kd = static_cast<size_t>(r.kd), ld = kd + 1;
  const double *L = r.fac.data();
  for (size_t j = j0; j < n; ++j) {
    const double *Lj = L + j * ld;
    const double yj = (y[j] /= Lj[0]);
    const size_t m = std::min(kd, n - 1 - j);
    for (size_t i = 1; i <= m; ++i) y[j + i] -= Lj[i] * yj;
  }
}

// z <- (L L^T)^-1 z for nrhs columns of length n (leading dimension n), L the factor
// of dpbtrf in lower band storage.  Written out: for the small bands of rods (kd ~ 10)
// LAPACK's dpbtrs spends its time in per-column BLAS calls (dtbsv -> ddot / daxpy).
void solve_rod(const Rod &r, double *z, int nrhs) {
  const size_t n = r.rows.size(), kd = static_cast<size_t>(r.kd), ld = kd + 1;
  const double *L = r.fac.data();
  for (int c = 0; c < nrhs; ++c) {
    double *y = z + static_cast<size_t>(c) * n;
    forward_rod(r, y, 0);          // L y = b
    for (size_t j = n; j-- > 0;) { // L^T x = y
      const double *Lj = L + j * ld;
      const size_t m = std::min(kd, n - 1 - j);
      double t = y[j];
      for (size_t i = 1; i <= m; ++i) t -= Lj[i] * y[j + i];
      y[j] = t / Lj[0];
    }
  }
}

// Position of local column lc in row row of a fill-complete local matrix (sorted rows).
template <class Local>
size_t find_entry(const Local &lcl, LO row, LO lc) {
  const size_t beg = lcl.graph.row_map(row), end = lcl.graph.row_map(row + 1);
  size_t lo = beg, hi = end;
  while (lo < hi) {
    const size_t mid = (lo + hi) / 2;
    if (lcl.graph.entries(mid) < lc)
      lo = mid + 1;
    else
      hi = mid;
  }
  if (lo == end || lcl.graph.entries(lo) != lc)
    throw Error(RN_ERR_INTERNAL, "dd preconditioner: coarse matrix entry missing");
  return lo;
}

// Groups the owned interface DOFs into nodes of 6 coarse rows for the coarse
// matrix's block structure (algebraic multigrid aggregates whole nodes).  The DOFs at
// one point form a node: a joint's position and rotation, a vertex's position; each
// material angle joins the nearest node with a free rotation slot (the vertex next
// to it).  Row 6 n + j of node n holds its DOF of kind j (positions 0-2, rotations
// or an angle 3-5); the other rows are dummies (decoupled), which carry the rigid
// modes of their kind at the node's point in the near-null space, so that every node
// supports all six rigid-body modes: an aggregate that misses one (nodes pinned
// along x at a gripped face, say) is rejected by MueLu (a zero near-null-space
// column, seen on 2 ranks).  Returns the coarse slot of every interface DOF; node
// n's point in points[3 n ..].
std::vector<int> coarse_nodes(const DofBlocks &blk, std::vector<double> &points) {
  using Point = std::array<double, 3>;
  std::map<Point, int> at;
  std::vector<Point> where;
  std::vector<std::array<int, 6>> used; // interface index in each slot, -1: free
  std::vector<size_t> angles;
  std::vector<int> slot(blk.interface.size(), -1);
  auto new_node = [&](const Point &p) {
    where.push_back(p);
    used.push_back({-1, -1, -1, -1, -1, -1});
    return static_cast<int>(where.size()) - 1;
  };
  for (size_t k = 0; k < blk.interface.size(); ++k) {
    const DofBlocks::Interface &f = blk.interface[k];
    if (f.kind == kDofAngle) {
      angles.push_back(k);
      continue;
    }
    const Point p{f.point[0], f.point[1], f.point[2]};
    auto it = at.find(p);
    if (it == at.end()) it = at.emplace(p, new_node(p)).first;
    const int n = it->second;
    if (used[static_cast<size_t>(n)][static_cast<size_t>(f.kind)] >= 0)
      throw Error(RN_ERR_INTERNAL,
                  "dd preconditioner: two interface DOFs of one kind at one point");
    used[static_cast<size_t>(n)][static_cast<size_t>(f.kind)] = static_cast<int>(k);
    slot[k] = 6 * n + f.kind;
  }
  // Nearest node with a free rotation slot, searched over the nodes sorted by x.
  std::vector<int> byx(where.size());
  for (size_t i = 0; i < byx.size(); ++i) byx[i] = static_cast<int>(i);
  std::sort(byx.begin(), byx.end(), [&](int a, int b) {
    return where[static_cast<size_t>(a)][0] < where[static_cast<size_t>(b)][0];
  });
  std::vector<double> xs(byx.size());
  for (size_t i = 0; i < byx.size(); ++i) xs[i] = where[static_cast<size_t>(byx[i])][0];
  auto free_slot = [&](size_t n) {
    for (int j = 3; j < 6; ++j)
      if (used[n][static_cast<size_t>(j)] < 0) return j;
    return -1;
  };
  for (size_t k : angles) {
    const double *p = blk.interface[k].point;
    int best = -1;
    double bd = HUGE_VAL;
    const long mid =
        static_cast<long>(std::lower_bound(xs.begin(), xs.end(), p[0]) - xs.begin());
    for (int dir = -1; dir <= 1; dir += 2)
      for (long i = dir < 0 ? mid - 1 : mid; i >= 0 && i < static_cast<long>(xs.size());
           i += dir) {
        const double dx = xs[static_cast<size_t>(i)] - p[0];
        if (dx * dx >= bd) break;
        const size_t n = static_cast<size_t>(byx[static_cast<size_t>(i)]);
        if (free_slot(n) < 0) continue;
        double d = 0.0;
        for (size_t c = 0; c < 3; ++c) d += (where[n][c] - p[c]) * (where[n][c] - p[c]);
        if (d < bd) bd = d, best = static_cast<int>(n);
      }
    if (best < 0) best = new_node(Point{p[0], p[1], p[2]}); // not searched again
    const int j = free_slot(static_cast<size_t>(best));
    used[static_cast<size_t>(best)][static_cast<size_t>(j)] = static_cast<int>(k);
    slot[k] = 6 * best + j;
  }
  points.clear();
  for (const Point &p : where) points.insert(points.end(), p.begin(), p.end());
  return slot;
}

} // namespace

// ---- the direct coarse solve ---------------------------------------------------------
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

void GatheredCholesky::solve(const TMV &b, TMV &y) const {
  for (size_t j = 0; j < b.getNumVectors(); ++j) {
    auto bj = b.getVector(j);
    auto yj = y.getVectorNonConst(j);
    b0_->doImport(*bj, *imp0_, Tpetra::INSERT);
    if (map0_->getNodeNumElements() > 0) {
      auto v = b0_->getLocalViewHost(Tpetra::Access::ReadOnly);
      auto w = y0_->getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (size_t i = 0; i < v.extent(0); ++i) w(i, 0) = v(i, 0);
      chol_->solve(w.data());
    }
    yj->doExport(*y0_, *imp0_, Tpetra::INSERT);
  }
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
  void analyse(const TCrs &S);
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
  double shift_ = 0.0, bytes_ = 0.0, max_flops_ = 0.0, flops_ = 0.0;
  bool strict_ = false, failed_ = false;
  bool declined_ = false;
};

constexpr size_t kNone = static_cast<size_t>(-1);

// The split into I_p and Γ, the local CSR and its partial analysis, the reduced
// matrix's maps and graph: once per structure of S.
void SubstructuredCoarse::analyse(const TCrs &S) {
  auto rowmap = S.getRowMap();
  auto colmap = S.getColMap();
  auto comm = rowmap->getComm();
  if (!rowmap->isContiguous())
    throw Error(RN_ERR_INTERNAL, "dd preconditioner: coarse map not contiguous");
  auto lcl = S.getLocalMatrixHost();
  const size_t nrow = S.getNodeNumRows(), ncol = colmap->getNodeNumElements();
  const GO gmax = rowmap->getMaxGlobalIndex();
  // Γ rows (coupled to a higher rank's row) and their reduced GIDs.
  gam_rows_.clear();
  irows_.clear();
  std::vector<long long> red(nrow, -1); // reduced GID of an owned Γ row
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
  const long long ngam = static_cast<long long>(gam_rows_.size());
  long long incl = 0;
  Teuchos::scan(*comm, Teuchos::REDUCE_SUM, ngam, Teuchos::outArg(incl));
  for (long long &r : red)
    if (r >= 0) r += incl - ngam;
  nred_ = sum_over_ranks(*comm, ngam);
  // Reduced GID of every column (-1: not on Γ).
  std::vector<long long> cred(ncol, -1);
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
  // I-index of every column (-1: not an owned I row).
  std::vector<int32_t> cidx(ncol, -1);
  {
    std::vector<int32_t> ipos(nrow, -1);
    for (size_t a = 0; a < irows_.size(); ++a)
      ipos[static_cast<size_t>(irows_[a])] = static_cast<int32_t>(a);
    for (size_t c = 0; c < ncol; ++c) {
      const LO r = rowmap->getLocalElement(colmap->getGlobalElement(static_cast<LO>(c)));
      if (r != Teuchos::OrdinalTraits<LO>::invalid())
        cidx[c] = ipos[static_cast<size_t>(r)];
    }
  }
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
  throw_if_any(*comm, failed, RN_ERR_INTERNAL,
               "dd preconditioner: the coarse matrix cannot be ordered (METIS)");
  x_.assign(n, 0.0);
  if (nred_ == 0) return;
  // The reduced matrix: Rov_ rows the owned Γ (gmap_ order), then the separator rows
  // of other ranks; each separator row dense over the separator, each owned Γ row
  // with its S_ΓΓ entries.
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
  // D_S = |diag S| floored at 1e-8 of its largest entry (over the ranks): on the
  // local pattern (I) and on the owned Γ rows.
  std::vector<double> dg(gam_rows_.size());
  double mx = 0.0, gmx = 0.0;
  for (size_t i = 0; i < diag_.size(); ++i) mx = std::max(mx, std::fabs(vals_[diag_[i]]));
  for (size_t j = 0; j < dg.size(); ++j)
    mx = std::max(mx, dg[j] = std::fabs(sv(gdiag_src_[j])));
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, mx, Teuchos::outArg(gmx));
  auto floored = [&](double v) { return gmx > 0.0 ? std::max(v, 1e-8 * gmx) : 1.0; };
  m_.assign(vals_.size(), 0.0);
  for (size_t i = 0; i < diag_.size(); ++i)
    m_[diag_[i]] = floored(std::fabs(vals_[diag_[i]]));
  for (double &v : dg) v = floored(v);
  if (nred_ > 0 && !root_)
    root_.reset(new GatheredCholesky(max_flops_ > 0.0 ? max_flops_ - lf : 0.0));
  // S + t D_S factors iff every rank's S_II + t D_II and the reduced matrix do.
  auto try_factor = [&](double t) {
    const bool ok = !chol_ || chol_->factor(vals_.data(), t, m_.data());
    int okl = ok ? 1 : 0, all = 0;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MIN, okl, Teuchos::outArg(all));
    if (!all) return false;
    if (nred_ == 0) return true;
    // R = S_ΓΓ + t D_Γ + the Schur complements of the ranks.
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
    return root_->setup(R_); // true if declined: ends the search
  };
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

void SubstructuredCoarse::solve(const TMV &b, TMV &y) const {
  const size_t ni = irows_.size(), n = x_.size();
  for (size_t j = 0; j < b.getNumVectors(); ++j) {
    auto bj = b.getVector(j);
    auto bv = bj->getLocalViewHost(Tpetra::Access::ReadOnly);
    auto yj = y.getVectorNonConst(j);
    auto yv = yj->getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (size_t a = 0; a < ni; ++a) x_[a] = bv(static_cast<size_t>(irows_[a]), 0);
    std::fill(x_.begin() + static_cast<std::ptrdiff_t>(ni), x_.end(), 0.0);
    if (n > 0) chol_->forward(x_.data());
    if (nred_ > 0) {
      // b_Γ - sum_p S_ΓI_p S_I_pI_p^-1 b_I_p onto Γ; R's solve; x_Γ back.
      {
        auto v = bov_->getLocalViewHost(Tpetra::Access::OverwriteAll);
        for (size_t l = 0; l < v.extent(0); ++l) v(l, 0) = 0.0;
        for (size_t k = 0; k < gam_rows_.size(); ++k)
          v(k, 0) = bv(static_cast<size_t>(gam_rows_[k]), 0);
        for (size_t k = 0; k < sep_ov_.size(); ++k)
          v(static_cast<size_t>(sep_ov_[k]), 0) += x_[ni + k];
      }
      br_->putScalar(0.0);
      br_->doExport(*bov_, *exporter_, Tpetra::ADD);
      root_->solve(*br_, *yr_);
      yov_->doImport(*yr_, *importer_, Tpetra::INSERT);
      auto v = yov_->getLocalViewHost(Tpetra::Access::ReadOnly);
      for (size_t k = 0; k < sep_ov_.size(); ++k)
        x_[ni + k] = v(static_cast<size_t>(sep_ov_[k]), 0);
      for (size_t k = 0; k < gam_rows_.size(); ++k)
        yv(static_cast<size_t>(gam_rows_[k]), 0) = v(k, 0);
    }
    if (n > 0) chol_->backward(x_.data());
    for (size_t a = 0; a < ni; ++a) yv(static_cast<size_t>(irows_[a]), 0) = x_[a];
  }
}

} // namespace

std::unique_ptr<CoarseSolver> make_direct_coarse_solver(double max_flops) {
  return std::unique_ptr<CoarseSolver>(new SubstructuredCoarse(max_flops));
}

// ---- the domain decomposition -------------------------------------------------------
struct DdPreconditioner::Impl {
  // structure, built at the first setup (and again if the Hessian's graph changes)
  Teuchos::RCP<const TCrs::crs_graph_type> hgraph;
  Teuchos::RCP<const TMap> map, cmap, cov; // system map, owned / overlapping coarse
  std::vector<LO> iface_rows;              // owned local row of owned coarse row k
  std::vector<Rod> rods;
  std::vector<size_t> gg_src, gg_dst; // H_GG: H value index -> Sov value index
  std::vector<size_t> gg_diag;        // the gg entries on H's diagonal
  std::vector<size_t> cross;  // H entries between two rods' interiors: must be zero
  std::vector<size_t> sdiag;  // S value index of each owned coarse row's diagonal
  std::vector<size_t> s_copy; // S value index of each Sov value (no ghosts: no export)
  Teuchos::RCP<TCrs> Sov, S;
  Teuchos::RCP<const Tpetra::Export<>> exporter; // cov -> cmap
  Teuchos::RCP<const Tpetra::Import<>> importer; // cmap -> cov
  Teuchos::RCP<TMV> nullspace;
  std::unique_ptr<CoarseSolver> coarse;
  long long coarse_rows = 0, rods_shifted = 0;
  double declined_flops = 0.0; // of the direct coarse solve the automatic choice declined
  bool S_built = false;
  // work (apply)
  mutable Teuchos::RCP<TMV> bov, b, y, yov;
  mutable std::vector<double> t, w;

  void build(const System &sys, const TCrs &H);
  // The numeric setup.  uniform < 0: every indefinite piece shifted by its own
  // smallest decade (rod blocks, coarse matrix).  uniform >= 0: the DD of
  // H + uniform D (D = |diag H| floored per rod and on the interface), no other
  // shift; returns false on every rank if a rod block or the coarse matrix is then
  // not positive definite (only with the direct coarse solve).
  bool numeric(const TCrs &H, double uniform = -1.0);
  double uniform_shift = 0.0;     // of the last setup (0: none)
  std::vector<double> dg_uniform; // D_G of the uniform shift (per gg_diag entry)
  // dg_uniform made (on every rank at once: a rank without interface rows has an
  // empty one, so its emptiness cannot tell, and the first making is collective)
  bool dg_uniform_made = false;
  void apply(const TMV &X, TMV &Y, double alpha, double beta) const;
  double bytes() const;
};

void DdPreconditioner::Impl::build(const System &sys, const TCrs &H) {
  const DofBlocks &blk = sys.blocks();
  map = H.getRowMap();
  auto comm = map->getComm();
  auto colmap = H.getColMap();
  const size_t nloc = map->getNodeNumElements(), ncol = colmap->getNodeNumElements();
  if (blk.block.size() != nloc)
    throw Error(RN_ERR_INTERNAL, "dd preconditioner: DofBlocks do not match the map");
  // Coarse numbering: nodes of 6 rows (coarse_nodes), those of rank p after those of
  // ranks < p; dummy rows (iface_rows -1) pad every node to 6.
  std::vector<double> node_points;
  const std::vector<int> slot = coarse_nodes(blk, node_points);
  const size_t nnodes = node_points.size() / 3;
  const long long nif = 6LL * static_cast<long long>(nnodes);
  long long incl = 0;
  Teuchos::scan(*comm, Teuchos::REDUCE_SUM, nif, Teuchos::outArg(incl));
  const GO offset = static_cast<GO>(incl - nif);
  coarse_rows = sum_over_ranks(*comm, static_cast<long long>(blk.interface.size()));
  const long long padded = sum_over_ranks(*comm, nif);
  cmap = Teuchos::rcp(new TMap(static_cast<Tpetra::global_size_t>(padded),
                               static_cast<size_t>(nif), GO(0), comm));
  iface_rows.assign(static_cast<size_t>(nif), -1);
  TMV cg(map, 1);
  {
    auto v = cg.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (size_t i = 0; i < nloc; ++i) v(i, 0) = -1.0;
    for (size_t k = 0; k < blk.interface.size(); ++k) {
      const size_t c = static_cast<size_t>(slot[k]);
      iface_rows[c] = blk.interface[k].local;
      v(static_cast<size_t>(blk.interface[k].local), 0) =
          static_cast<double>(offset + GO(c));
    }
  }
  TMV cgc(colmap, 1); // coarse GID of every column (-1: a rod-interior DOF)
  cgc.doImport(cg, Tpetra::Import<>(map, colmap), Tpetra::INSERT);
  std::vector<GO> ccol(ncol);
  std::vector<LO> col2row(ncol);
  {
    auto v = cgc.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (size_t c = 0; c < ncol; ++c) {
      ccol[c] = static_cast<GO>(v(c, 0));
      col2row[c] = map->getLocalElement(colmap->getGlobalElement(static_cast<LO>(c)));
    }
  }
  // Rods: interiors, bands, couplings.
  rods.assign(static_cast<size_t>(blk.num_rods), Rod());
  std::vector<int> pos(nloc, -1);
  for (size_t i = 0; i < nloc; ++i)
    if (blk.block[i] >= 0) {
      Rod &r = rods.at(static_cast<size_t>(blk.block[i]));
      pos[i] = r.n();
      r.rows.push_back(static_cast<LO>(i));
    }
  auto lcl = H.getLocalMatrixHost();
  cross.clear();
  std::vector<GO> ghosts;
  std::vector<std::vector<GO>> rod_gids(rods.size()); // coupled coarse GIDs, sorted
  for (size_t ir = 0; ir < rods.size(); ++ir) {
    Rod &r = rods[ir];
    std::vector<GO> &coupled = rod_gids[ir], bgid;
    for (int i = 0; i < r.n(); ++i) {
      const LO lr = r.rows[static_cast<size_t>(i)];
      for (size_t q = lcl.graph.row_map(lr); q < lcl.graph.row_map(lr + 1); ++q) {
        const LO lc = lcl.graph.entries(q);
        if (ccol[static_cast<size_t>(lc)] >= 0) {
          coupled.push_back(ccol[static_cast<size_t>(lc)]);
          bgid.push_back(ccol[static_cast<size_t>(lc)]);
          r.b_row.push_back(i);
          r.b_src.push_back(q);
          continue;
        }
        const LO lr2 = col2row[static_cast<size_t>(lc)];
        if (lr2 == Teuchos::OrdinalTraits<LO>::invalid() ||
            blk.block[static_cast<size_t>(lr2)] != static_cast<int>(ir)) {
          // Another rod's interior: a structural zero of the pattern (rigid joints'
          // stencils are dense in it, their values are not); checked at every setup.
          cross.push_back(q);
          continue;
        }
        const int j = pos[static_cast<size_t>(lr2)];
        if (j <= i) {
          r.kd = std::max(r.kd, i - j);
          r.band_src.push_back(q);
          r.band_dst.push_back(static_cast<size_t>(i - j)); // column j added below
        }
      }
    }
    // band_dst = (i - j) + j (kd + 1): recompute with the final kd
    {
      size_t e = 0;
      for (int i = 0; i < r.n(); ++i) {
        const LO lr = r.rows[static_cast<size_t>(i)];
        for (size_t q = lcl.graph.row_map(lr); q < lcl.graph.row_map(lr + 1); ++q) {
          if (e < r.band_src.size() && r.band_src[e] == q) {
            const size_t diff = r.band_dst[e];
            const size_t j = static_cast<size_t>(i) - diff;
            r.band_dst[e] = diff + j * static_cast<size_t>(r.kd + 1);
            ++e;
          }
        }
      }
    }
    std::sort(coupled.begin(), coupled.end());
    coupled.erase(std::unique(coupled.begin(), coupled.end()), coupled.end());
    for (GO g : bgid)
      r.b_col.push_back(static_cast<int>(
          std::lower_bound(coupled.begin(), coupled.end(), g) - coupled.begin()));
    for (GO g : coupled)
      if (g < offset || g >= offset + nif) ghosts.push_back(g);
  }
  std::sort(ghosts.begin(), ghosts.end());
  ghosts.erase(std::unique(ghosts.begin(), ghosts.end()), ghosts.end());
  std::vector<GO> ovg(static_cast<size_t>(nif));
  for (long long k = 0; k < nif; ++k) ovg[static_cast<size_t>(k)] = offset + GO(k);
  ovg.insert(ovg.end(), ghosts.begin(), ghosts.end());
  cov = Teuchos::rcp(new TMap(Teuchos::OrdinalTraits<Tpetra::global_size_t>::invalid(),
                              Teuchos::ArrayView<const GO>(ovg.data(), ovg.size()), GO(0),
                              comm));
  auto ov_local = [&](GO g) { return cov->getLocalElement(g); };

  // The graph of Sov: rows of cov; every rod's dense block, the H_GG entries.
  std::vector<std::vector<GO>> rowcols(ovg.size());
  for (const auto &gids : rod_gids)
    for (GO a : gids)
      for (GO b2 : gids) rowcols[static_cast<size_t>(ov_local(a))].push_back(b2);
  std::vector<std::pair<size_t, GO>> gg; // (H value index, column GID) per owned row k
  std::vector<size_t> gg_row;
  for (size_t k = 0; k < iface_rows.size(); ++k) {
    const LO lr = iface_rows[k];
    rowcols[k].push_back(offset + GO(k)); // the diagonal always
    if (lr < 0) continue;                 // a dummy row: its diagonal only
    for (size_t q = lcl.graph.row_map(lr); q < lcl.graph.row_map(lr + 1); ++q) {
      const GO c = ccol[static_cast<size_t>(lcl.graph.entries(q))];
      if (c < 0) continue;
      rowcols[k].push_back(c);
      gg.emplace_back(q, c);
      gg_row.push_back(k);
    }
  }
  std::vector<size_t> counts(ovg.size());
  for (size_t l = 0; l < ovg.size(); ++l) {
    auto &c = rowcols[l];
    std::sort(c.begin(), c.end());
    c.erase(std::unique(c.begin(), c.end()), c.end());
    counts[l] = c.size();
  }
  auto graph = Teuchos::rcp(new TCrs::crs_graph_type(
      cov, Teuchos::ArrayView<const size_t>(counts.data(), counts.size())));
  for (size_t l = 0; l < ovg.size(); ++l)
    graph->insertGlobalIndices(
        ovg[l], Teuchos::ArrayView<const GO>(rowcols[l].data(), rowcols[l].size()));
  rowcols.clear();
  rowcols.shrink_to_fit();
  graph->fillComplete(cmap, cmap);
  Sov = Teuchos::rcp(new TCrs(graph));
  auto slcl = Sov->getLocalMatrixHost();
  auto scol = Sov->getColMap();
  for (size_t ir = 0; ir < rods.size(); ++ir) {
    Rod &r = rods[ir];
    const std::vector<GO> &gids = rod_gids[ir];
    const size_t m = gids.size();
    r.coarse.resize(m);
    r.s_pos.resize(m * m);
    for (size_t a = 0; a < m; ++a) {
      r.coarse[a] = ov_local(gids[a]);
      for (size_t b2 = 0; b2 < m; ++b2)
        r.s_pos[a * m + b2] =
            find_entry(slcl, r.coarse[a], scol->getLocalElement(gids[b2]));
    }
  }
  gg_src.clear();
  gg_dst.clear();
  for (size_t e = 0; e < gg.size(); ++e) {
    gg_src.push_back(gg[e].first);
    gg_dst.push_back(find_entry(slcl, static_cast<LO>(gg_row[e]),
                                scol->getLocalElement(gg[e].second)));
  }
  gg_diag.clear();
  dg_uniform.clear();
  dg_uniform_made = false;
  for (size_t e = 0; e < gg.size(); ++e)
    if (cov->getGlobalElement(static_cast<LO>(gg_row[e])) == gg[e].second)
      gg_diag.push_back(e);
  exporter = Teuchos::rcp(new Tpetra::Export<>(cov, cmap));
  importer = Teuchos::rcp(new Tpetra::Import<>(cmap, cov));
  S_built = false;
  // Rigid-body modes of the interface DOFs; a dummy row in slot j of a node those of
  // a DOF of kind j at the node's point.
  {
    std::vector<int> kinds(static_cast<size_t>(nif));
    std::vector<double> points(3 * static_cast<size_t>(nif)), axes(points.size(), 0.0);
    for (size_t c = 0; c < kinds.size(); ++c) {
      kinds[c] = static_cast<int>(c % 6);
      std::copy(node_points.begin() + 3 * (c / 6), node_points.begin() + 3 * (c / 6) + 3,
                points.begin() + 3 * c);
    }
    for (size_t k = 0; k < blk.interface.size(); ++k) {
      const DofBlocks::Interface &f = blk.interface[k];
      const size_t c = static_cast<size_t>(slot[k]);
      kinds[c] = f.kind;
      std::copy(f.point, f.point + 3, points.begin() + 3 * c);
      std::copy(f.axis, f.axis + 3, axes.begin() + 3 * c);
    }
    nullspace = rigid_body_modes(cmap, kinds.data(), points.data(), axes.data());
  }
  bov = Teuchos::rcp(new TMV(cov, 1));
  yov = Teuchos::rcp(new TMV(cov, 1));
  b = Teuchos::rcp(new TMV(cmap, 1));
  y = Teuchos::rcp(new TMV(cmap, 1));
  t.assign(nloc, 0.0);
}

bool DdPreconditioner::Impl::numeric(const TCrs &H, double uniform) {
  auto comm = map->getComm();
  auto lcl = H.getLocalMatrixHost();
  const double *vals = lcl.values.data();
  Sov->resumeFill();
  Sov->setAllToScalar(0.0);
  auto sv = Sov->getLocalMatrixHost().values;
  for (size_t e = 0; e < gg_src.size(); ++e) sv(gg_dst[e]) += vals[gg_src[e]];
  if (uniform > 0.0) {
    // + uniform D_G on the interface diagonal, D_G = |diag H_GG| floored at 1e-8 of
    // its largest entry over the ranks at the first set-up that shifts uniformly,
    // then the entrywise largest |diag H_GG| of the set-ups since (as the rods' D_r)
    if (!dg_uniform_made) { // (collective: decided alike on every rank)
      dg_uniform_made = true;
      double mx = 0.0, gmx = 0.0;
      for (size_t e : gg_diag) mx = std::max(mx, std::fabs(vals[gg_src[e]]));
      Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, mx, Teuchos::outArg(gmx));
      dg_uniform.reserve(gg_diag.size());
      for (size_t e : gg_diag) {
        const double d = std::fabs(vals[gg_src[e]]);
        dg_uniform.push_back(gmx > 0.0 ? std::max(d, 1e-8 * gmx) : 1.0);
      }
    } else {
      for (size_t q = 0; q < gg_diag.size(); ++q)
        dg_uniform[q] = std::max(dg_uniform[q], std::fabs(vals[gg_src[gg_diag[q]]]));
    }
    for (size_t q = 0; q < gg_diag.size(); ++q)
      sv(gg_dst[gg_diag[q]]) += uniform * dg_uniform[q];
  }
  uniform_shift = uniform > 0.0 ? uniform : 0.0;
  bool coupled = false;
  for (size_t q : cross) coupled = coupled || vals[q] != 0.0;
  throw_if_any(
      *comm, coupled, RN_ERR_INTERNAL,
      "dd preconditioner: the Hessian couples the interiors of two rods (DofBlocks "
      "do not match the Hessian)");
  long long shifted = 0;
  bool failed = false;
  std::vector<double> ab, Z, C;
  std::vector<int> first;
  for (Rod &r : rods) {
    r.b_val.resize(r.b_src.size());
    for (size_t e = 0; e < r.b_src.size(); ++e) r.b_val[e] = vals[r.b_src[e]];
    if (r.n() == 0) continue;
    if (!factor_rod(r, vals, ab, uniform)) {
      failed = true;
      continue;
    }
    shifted += r.shift > 0.0;
    const int n = r.n(), m = r.m();
    if (m == 0) continue;
    // W = L^-1 H_rG (H_rr = L L^T), C = W^T W = H_Gr H_rr^-1 H_rG; Sov -= C.  Each
    // column's forward sweep starts at its first nonzero (the rows next to the end
    // the coupled DOF sits at).
    Z.assign(static_cast<size_t>(n) * static_cast<size_t>(m), 0.0);
    first.assign(static_cast<size_t>(m), n);
    for (size_t e = 0; e < r.b_val.size(); ++e) {
      Z[static_cast<size_t>(r.b_row[e] + r.b_col[e] * n)] = r.b_val[e];
      int &f = first[static_cast<size_t>(r.b_col[e])];
      f = std::min(f, r.b_row[e]);
    }
    for (int a = 0; a < m; ++a)
      forward_rod(r, Z.data() + static_cast<size_t>(a) * static_cast<size_t>(n),
                  static_cast<size_t>(first[static_cast<size_t>(a)]));
    C.assign(static_cast<size_t>(m) * static_cast<size_t>(m), 0.0);
    if (m >= kSyrkMin) { // many coupled DOFs (a rod in self contact): BLAS
      const double one = 1.0, zero = 0.0;
      dsyrk_("U", "T", &m, &n, &one, Z.data(), &n, &zero, C.data(), &m, 1, 1);
      for (int a = 0; a < m; ++a) // column-major upper -> both triangles
        for (int b2 = 0; b2 < a; ++b2)
          C[static_cast<size_t>(b2 * m + a)] = C[static_cast<size_t>(a * m + b2)];
    }
    for (int a = 0; a < m && m < kSyrkMin; ++a)
      for (int b2 = a; b2 < m; ++b2) {
        const double *za = Z.data() + static_cast<size_t>(a) * static_cast<size_t>(n);
        const double *zb = Z.data() + static_cast<size_t>(b2) * static_cast<size_t>(n);
        double sum = 0.0;
        for (int i =
                 std::max(first[static_cast<size_t>(a)], first[static_cast<size_t>(b2)]);
             i < n; ++i)
          sum += za[i] * zb[i];
        C[static_cast<size_t>(a * m + b2)] = C[static_cast<size_t>(b2 * m + a)] = sum;
      }
    for (size_t e = 0; e < C.size(); ++e) sv(r.s_pos[e]) -= C[e];
  }
  if (uniform >= 0.0) {
    int f = failed ? 1 : 0, any = 0;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, f, Teuchos::outArg(any));
    if (any) {
      Sov->fillComplete(cmap, cmap);
      return false;
    }
  }
  throw_if_any(*comm, failed, RN_ERR_LAPACK,
               "dd preconditioner: a rod block has no positive definite shift up to 1e10 "
               "|diag| (non-finite entries?)");
  rods_shifted = sum_over_ranks(*comm, shifted);
  Sov->fillComplete(cmap, cmap);
  if (coarse_rows == 0) return true;
  if (!S_built) {
    // The graph of the owned rows once; then S on that (static) graph is refilled by
    // summing the exported values into it.
    auto made = Tpetra::exportAndFillCompleteCrsMatrix<TCrs>(Sov, *exporter, cmap, cmap);
    S = Teuchos::rcp(new TCrs(made->getCrsGraph()));
    S_built = true;
    auto l = S->getLocalMatrixHost();
    sdiag.resize(iface_rows.size());
    for (size_t c = 0; c < sdiag.size(); ++c)
      sdiag[c] = find_entry(
          l, static_cast<LO>(c),
          S->getColMap()->getLocalElement(cmap->getGlobalElement(static_cast<LO>(c))));
    // Without ghost rows on any rank (one rank) the export is a copy: each Sov value's
    // S position once, instead of Tpetra's search by global index per value and
    // set-up (cubic in the row length: a rod in self contact has long coarse rows).
    int ghosted = cov->getNodeNumElements() > cmap->getNodeNumElements() ? 1 : 0, any = 0;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, ghosted, Teuchos::outArg(any));
    s_copy.clear();
    if (!any) {
      auto ol = Sov->getLocalMatrixHost();
      auto ocol = Sov->getColMap(), scol = S->getColMap();
      s_copy.resize(ol.values.extent(0));
      for (LO row = 0; row < static_cast<LO>(ol.numRows()); ++row) {
        const LO srow = cmap->getLocalElement(cov->getGlobalElement(row));
        for (size_t q = ol.graph.row_map(row); q < ol.graph.row_map(row + 1); ++q)
          s_copy[q] = find_entry(
              l, srow,
              scol->getLocalElement(ocol->getGlobalElement(ol.graph.entries(q))));
      }
    }
  }
  S->resumeFill();
  S->setAllToScalar(0.0);
  if (!s_copy.empty()) {
    auto ov = Sov->getLocalMatrixHost().values;
    auto sv2 = S->getLocalMatrixHost().values;
    for (size_t q = 0; q < s_copy.size(); ++q) sv2(s_copy[q]) += ov(q);
  } else {
    S->doExport(*Sov, *exporter, Tpetra::ADD);
  }
  {
    // Dummy rows: 1e-6 of the mean |diagonal| of their node's real rows.  Decoupled,
    // they change nothing in the solution; small, they add almost no energy to the
    // coarse-level rigid modes that they carry (coarse_nodes).
    auto v = S->getLocalMatrixHost().values;
    for (size_t n = 0; n + 5 < iface_rows.size(); n += 6) {
      double sum = 0.0;
      int cnt = 0;
      for (size_t j = n; j < n + 6; ++j)
        if (iface_rows[j] >= 0) sum += std::fabs(v(sdiag[j])), ++cnt;
      const double d = cnt > 0 && sum > 0.0 ? 1e-6 * sum / cnt : 1.0;
      for (size_t j = n; j < n + 6; ++j)
        if (iface_rows[j] < 0) v(sdiag[j]) = d;
    }
  }
  S->fillComplete(cmap, cmap);
  coarse->set_strict(uniform >= 0.0);
  coarse->setup(S, nullspace);
  return !coarse->failed();
}

void DdPreconditioner::Impl::apply(const TMV &X, TMV &Y, double alpha,
                                   double beta) const {
  const size_t nloc = map->getNodeNumElements();
  w.resize(nloc);
  for (size_t j = 0; j < X.getNumVectors(); ++j) {
    auto xv = X.getVector(j);
    auto x = xv->getLocalViewHost(Tpetra::Access::ReadOnly);
    // 1. z_r = H_rr^-1 x_r, into t.
    for (const Rod &r : rods) {
      if (r.n() == 0) continue;
      double *z = w.data();
      for (int i = 0; i < r.n(); ++i)
        z[i] = x(static_cast<size_t>(r.rows[static_cast<size_t>(i)]), 0);
      solve_rod(r, z, 1);
      for (int i = 0; i < r.n(); ++i)
        t[static_cast<size_t>(r.rows[static_cast<size_t>(i)])] = z[i];
    }
    if (coarse_rows > 0) {
      // 2. b_G = x_G - sum_r H_Gr z_r (exported to the owners).
      {
        auto bv = bov->getLocalViewHost(Tpetra::Access::OverwriteAll);
        for (size_t l = 0; l < bv.extent(0); ++l) bv(l, 0) = 0.0;
        for (size_t k = 0; k < iface_rows.size(); ++k)
          if (iface_rows[k] >= 0) bv(k, 0) = x(static_cast<size_t>(iface_rows[k]), 0);
        for (const Rod &r : rods)
          for (size_t e = 0; e < r.b_val.size(); ++e)
            bv(static_cast<size_t>(r.coarse[static_cast<size_t>(r.b_col[e])]), 0) -=
                r.b_val[e] *
                t[static_cast<size_t>(r.rows[static_cast<size_t>(r.b_row[e])])];
      }
      b->putScalar(0.0);
      b->doExport(*bov, *exporter, Tpetra::ADD);
      // 3. coarse solve; 4. y_G to the ranks of the rods that touch it.
      coarse->solve(*b, *y);
      yov->doImport(*y, *importer, Tpetra::INSERT);
    }
    // 5. y_r = H_rr^-1 (x_r - H_rG y_G); interface rows y_G.
    auto yv = Y.getVectorNonConst(j);
    auto out = yv->getLocalViewHost(Tpetra::Access::ReadWrite);
    auto put = [&](size_t row, double v) {
      out(row, 0) = beta == 0.0 ? alpha * v : beta * out(row, 0) + alpha * v;
    };
    auto yo = yov->getLocalViewHost(Tpetra::Access::ReadOnly);
    for (const Rod &r : rods) {
      if (r.n() == 0) continue;
      double *z = w.data();
      for (int i = 0; i < r.n(); ++i)
        z[i] = x(static_cast<size_t>(r.rows[static_cast<size_t>(i)]), 0);
      if (coarse_rows > 0)
        for (size_t e = 0; e < r.b_val.size(); ++e)
          z[r.b_row[e]] -=
              r.b_val[e] *
              yo(static_cast<size_t>(r.coarse[static_cast<size_t>(r.b_col[e])]), 0);
      solve_rod(r, z, 1);
      for (int i = 0; i < r.n(); ++i)
        put(static_cast<size_t>(r.rows[static_cast<size_t>(i)]), z[i]);
    }
    if (coarse_rows > 0) {
      auto yc = y->getLocalViewHost(Tpetra::Access::ReadOnly);
      for (size_t k = 0; k < iface_rows.size(); ++k)
        if (iface_rows[k] >= 0) put(static_cast<size_t>(iface_rows[k]), yc(k, 0));
    }
  }
}

double DdPreconditioner::Impl::bytes() const {
  double b0 = 0.0;
  for (const Rod &r : rods)
    b0 += 8.0 * static_cast<double>(r.fac.size() + r.b_val.size() + r.s_pos.size()) +
          8.0 * static_cast<double>(r.band_src.size() + r.band_dst.size() +
                                    r.b_src.size()) +
          4.0 * static_cast<double>(r.rows.size() + r.coarse.size() + 2 * r.b_row.size());
  if (!Sov.is_null()) b0 += 12.0 * static_cast<double>(Sov->getNodeNumEntries());
  if (!S.is_null()) b0 += 12.0 * static_cast<double>(S->getNodeNumEntries());
  if (coarse) b0 += coarse->bytes();
  return b0;
}

namespace {

class DdOperator : public Tpetra::Operator<> {
public:
  explicit DdOperator(const Teuchos::RCP<const DdPreconditioner::Impl> &impl,
                      PreconditionerStats *stats)
      : impl_(impl), stats_(stats) {}
  Teuchos::RCP<const TMap> getDomainMap() const override { return impl_->map; }
  Teuchos::RCP<const TMap> getRangeMap() const override { return impl_->map; }
  void apply(const TMV &X, TMV &Y, Teuchos::ETransp, double alpha,
             double beta) const override {
    const auto t0 = Clock::now();
    impl_->apply(X, Y, alpha, beta);
    stats_->applies++;
    stats_->apply_seconds += seconds_since(t0);
  }

private:
  Teuchos::RCP<const DdPreconditioner::Impl> impl_;
  PreconditionerStats *stats_;
};

// A = the coarse solver's SPD approximation of S: y = alpha A^{-1} x + beta y.
class CoarseInverse : public Tpetra::Operator<> {
public:
  explicit CoarseInverse(const Teuchos::RCP<const DdPreconditioner::Impl> &impl)
      : impl_(impl) {}
  Teuchos::RCP<const TMap> getDomainMap() const override { return impl_->cmap; }
  Teuchos::RCP<const TMap> getRangeMap() const override { return impl_->cmap; }
  void apply(const TMV &X, TMV &Y, Teuchos::ETransp, double alpha,
             double beta) const override {
    if (X.getNumVectors() != 1 || Y.getNumVectors() != 1)
      throw Error(RN_ERR_INTERNAL,
                  "dd preconditioner: coarse inverse applied to a block");
    if (tmp_.is_null() || tmp_->getMap().get() != impl_->cmap.get())
      tmp_ = Teuchos::rcp(new TMV(impl_->cmap, 1));
    impl_->coarse->solve(X, *tmp_);
    Y.update(alpha, *tmp_, beta);
  }

private:
  Teuchos::RCP<const DdPreconditioner::Impl> impl_;
  mutable Teuchos::RCP<TMV> tmp_;
};

} // namespace

DdPreconditioner::DdPreconditioner(const DdOptions &opt) : opt_(opt), impl_(new Impl) {}
DdPreconditioner::~DdPreconditioner() = default;

void DdPreconditioner::setup(System &sys) {
  const auto t0 = Clock::now();
  auto H = sys.hessian();
  if (H.is_null()) throw Error(RN_ERR_STATE, "dd preconditioner: no Hessian assembled");
  if (impl_->hgraph.get() != H->getCrsGraph().get()) {
    impl_->build(sys, *H);
    impl_->hgraph = H->getCrsGraph();
    switch (opt_.coarse) {
    case DdOptions::Coarse::Direct:
      impl_->coarse = make_direct_coarse_solver();
      break;
    case DdOptions::Coarse::Amg:
      impl_->coarse = make_amg_coarse_solver(opt_.amg_xml);
      break;
    case DdOptions::Coarse::Auto: // no limit when AMG cannot run (serial runtime)
      impl_->coarse = make_direct_coarse_solver(
          mpi_backed(*H->getComm()) ? opt_.direct_max_flops : 0.0);
      break;
    }
  }
  const double prev_uniform = impl_->uniform_shift; // the last set-up's (0: none)
  impl_->numeric(*H);
  if (opt_.uniform_shift && (impl_->rods_shifted > 0 || coarse_shift() > 0.0)) {
    // H indefinite (rod blocks or the coarse matrix): each piece shifted by its own
    // decade, M would be the inverse of no single modification of H, and the trust
    // region in its norm cycles; the coarse matrix alone shifted, S + t D_S, makes M
    // nearly singular along the buckling mode (docs/solvers.md).  Instead the DD of
    // H + sigma D for the smallest decade sigma that makes every rod block and (with
    // the direct coarse solve) the coarse matrix positive definite: M = (H + sigma
    // D)^-1 exactly, the factor preconditioner's norm.  D (D_r, D_G) is |diag H| of
    // the first such set-up, raised entrywise to |diag H| of each later one, for the
    // preconditioner's life (a load step): a metric that changes little from step to
    // step, as the factor preconditioner's fixed one, but follows a structure that
    // stiffens (a folded rod straightening; docs/solvers.md).  The multigrid coarse
    // solve, which cannot certify, shifts S further itself if it must.
    Impl &im = *impl_;
    const int hint =
        prev_uniform > 0.0 ? static_cast<int>(std::lround(std::log10(prev_uniform))) : 99;
    const double sigma =
        smallest_shift([&](double t) { return im.numeric(*H, t); }, true, hint);
    if (sigma < 0.0)
      throw Error(RN_ERR_LAPACK, "dd preconditioner: no shift up to 1e10 |diag| makes "
                                 "the Hessian positive definite (non-finite entries?)");
  }
  if (impl_->coarse->declined() && mpi_backed(*H->getComm())) {
    // Auto: the direct factorisation costs too much
    impl_->declined_flops = impl_->coarse->flops();
    impl_->coarse = make_amg_coarse_solver(opt_.amg_xml);
    impl_->coarse->setup(impl_->S, impl_->nullspace);
  }
  stats_.setups++;
  stats_.setup_seconds += seconds_since(t0);
  stats_.bytes = impl_->bytes();
  stats_.shifted =
      impl_->rods_shifted > 0 || coarse_shift() > 0.0 || impl_->uniform_shift > 0.0;
}

Teuchos::RCP<const Tpetra::Operator<>> DdPreconditioner::inverse() const {
  if (op_.is_null()) // one operator for the preconditioner's life (callers keep it)
    op_ = Teuchos::rcp(new DdOperator(impl_, const_cast<PreconditionerStats *>(&stats_)));
  return op_;
}

long long DdPreconditioner::coarse_rows() const { return impl_->coarse_rows; }
long long DdPreconditioner::rods_shifted() const { return impl_->rods_shifted; }
double DdPreconditioner::uniform_shift() const { return impl_->uniform_shift; }
double DdPreconditioner::coarse_shift() const {
  return impl_->coarse ? impl_->coarse->shift() : 0.0;
}
bool DdPreconditioner::exact() const {
  return impl_->rods_shifted == 0 && coarse_shift() == 0.0 &&
         impl_->uniform_shift == 0.0 &&
         (impl_->coarse_rows == 0 || coarse_solver() == "direct");
}

bool DdPreconditioner::coarse_pencil(Teuchos::RCP<const Tpetra::Operator<>> &S,
                                     Teuchos::RCP<const Tpetra::Operator<>> &Ainv) const {
  if (impl_->rods_shifted != 0 || coarse_shift() != 0.0 || impl_->uniform_shift != 0.0 ||
      impl_->coarse_rows == 0 || !impl_->coarse || impl_->S.is_null())
    return false;
  S = impl_->S;
  Ainv = Teuchos::rcp(new CoarseInverse(impl_));
  return true;
}

double DdPreconditioner::coarse_flops() const {
  const double f = impl_->coarse ? impl_->coarse->flops() : 0.0;
  return f > 0.0 ? f : impl_->declined_flops;
}

long long DdPreconditioner::coarse_separator_rows() const {
  return impl_->coarse ? impl_->coarse->separator_rows() : 0;
}

std::string DdPreconditioner::coarse_solver() const {
  return impl_->coarse ? impl_->coarse->name() : "none";
}

} // namespace rodnet

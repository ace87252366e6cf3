// local_preconditioner.cpp - block Jacobi over the ranks with a sparse Cholesky
// factorisation of each rank's owned block (local_preconditioner.hpp).
#include "pc/impls/local/local_preconditioner.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include <Teuchos_CommHelpers.hpp>

#include "base/clock.hpp"
#include "base/shim_error.hpp"
#include "factor/sparse_cholesky.hpp"
#include "pc/shifted_cholesky.hpp"
#include "pc/stats_operator.hpp"

namespace rodnet {

LocalPreconditioner::LocalPreconditioner() = default;
LocalPreconditioner::~LocalPreconditioner() = default;

// The owned block of H's local rows: columns that are owned rows (in owned order),
// sorted; src_ keeps where each entry sits in H's local values.
void LocalPreconditioner::build_pattern(const TCrs &H) {
  auto rows = H.getRowMap(), cols = H.getColMap();
  auto lcl = H.getLocalMatrixHost();
  n_ = rows->getNodeNumElements();
  rowptr_.assign(n_ + 1, 0);
  col_.clear();
  src_.clear();
  std::vector<std::pair<int32_t, size_t>> row;
  for (size_t i = 0; i < n_; ++i) {
    row.clear();
    for (size_t k = lcl.graph.row_map(i); k < lcl.graph.row_map(i + 1); ++k) {
      const LO c = rows->getLocalElement(cols->getGlobalElement(lcl.graph.entries(k)));
      if (c != Teuchos::OrdinalTraits<LO>::invalid())
        row.emplace_back(static_cast<int32_t>(c), k);
    }
    std::sort(row.begin(), row.end());
    for (const auto &e : row) {
      col_.push_back(e.first);
      src_.push_back(e.second);
    }
    rowptr_[i + 1] = static_cast<int64_t>(col_.size());
  }
  vals_.assign(col_.size(), 0.0);
  if (n_) analysis_ = std::make_shared<SparseAnalysis>(n_, rowptr_.data(), col_.data());
}

void LocalPreconditioner::setup(System &sys) {
  const Clock::time_point t0 = Clock::now();
  const TCrs &H = *sys.hessian();
  const auto comm = sys.map()->getComm();
  if (rowptr_.empty()) build_pattern(H);
  auto values = H.getLocalMatrixHost().values;
  for (size_t k = 0; k < vals_.size(); ++k) vals_[k] = values(src_[k]);
  if (!metric_done_) {   // D = |diag H|, floored at 1e-8 of its largest entry (all ranks)
    metric_done_ = true; // (on every rank, also one that owns nothing: collective)
    const double local = max_abs_diagonal(n_, rowptr_.data(), col_.data(), vals_.data());
    double dmax = 0.0;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &local, &dmax);
    m_ = floored_diagonal(n_, rowptr_.data(), col_.data(), vals_.data(), dmax);
  }
  if (!chol_ && n_) chol_ = std::make_unique<SparseCholesky>(analysis_);
  int failed = 0;
  sigma_ = 0.0;
  if (n_) {
    const double s = factor_smallest_shift(*chol_, vals_.data(), m_.data());
    failed = s < 0.0;
    if (!failed) sigma_ = s;
  }
  int any_failed = 0, shifted = sigma_ > 0.0, any_shifted = 0;
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &failed, &any_failed);
  Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, 1, &shifted, &any_shifted);
  if (any_failed)
    throw Error(RN_ERR_LAPACK, "rn_solve: no diagonal shift makes a rank's block of the "
                               "Hessian positive definite (non-finite Hessian?)");
  if (op_.is_null()) {
    const SparseCholesky *const *f = &chol_ptr_; // the current factor (set below)
    op_ = stats_operator(
        sys.map(),
        [f](const TMV &x, TMV &y) { // M^{-1} the rank's factorisation (no communication)
          if (x.getNumVectors() != 1 || y.getNumVectors() != 1)
            throw Error(RN_ERR_INTERNAL, "rn_solve: preconditioner applied to a block");
          y.assign(x);
          if (y.getLocalLength()) (*f)->solve(y.getDataNonConst(0).getRawPtr());
        },
        &stats_);
  }
  chol_ptr_ = chol_.get();
  ++stats_.setups;
  stats_.shifted = any_shifted != 0;
  stats_.bytes = 8.0 * static_cast<double>(vals_.size() + m_.size());
  stats_.setup_seconds += seconds_since(t0);
}

} // namespace rodnet

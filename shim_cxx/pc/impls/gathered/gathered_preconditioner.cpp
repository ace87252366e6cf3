// gathered_preconditioner.cpp - the whole shifted Hessian factored on rank 0
// (gathered_preconditioner.hpp).
#include "pc/impls/gathered/gathered_preconditioner.hpp"

#include <algorithm>
#include <cmath>

#include <Teuchos_CommHelpers.hpp>

#include "base/clock.hpp"
#include "base/shim_error.hpp"
#include "factor/sparse_cholesky.hpp"
#include "pc/shifted_cholesky.hpp"
#include "pc/stats_operator.hpp"

namespace rodnet {

GatheredPreconditioner::GatheredPreconditioner() = default;
GatheredPreconditioner::~GatheredPreconditioner() = default;

// The values of the gathered Hessian Hg on rank 0 in CSR (sorted rows); at the first
// call its pattern, the symbolic analysis and the metric D = |diag H| floored at 1e-8
// of its largest entry.
void GatheredPreconditioner::gather_values(const TCrs &Hg) {
  const size_t nl = root_->getNodeNumElements();
  auto lcl = Hg.getLocalMatrixHost();
  auto cols = Hg.getColMap();
  std::vector<std::pair<int32_t, double>> row;
  const bool first = rowptr_.empty();
  if (first) rowptr_.assign(nl + 1, 0);
  vals_.clear();
  for (size_t i = 0; i < nl; ++i) {
    row.clear();
    for (size_t k = lcl.graph.row_map(i); k < lcl.graph.row_map(i + 1); ++k)
      row.emplace_back(static_cast<int32_t>(cols->getGlobalElement(lcl.graph.entries(k))),
                       lcl.values(k));
    std::sort(row.begin(), row.end());
    for (const auto &e : row) {
      if (first) col_.push_back(e.first);
      vals_.push_back(e.second);
    }
    if (first) rowptr_[i + 1] = static_cast<int64_t>(col_.size());
  }
  if (vals_.size() != col_.size())
    throw Error(RN_ERR_INTERNAL, "rn_solve: the gathered Hessian changed its pattern");
  if (first) {
    analysis_ = std::make_shared<SparseAnalysis>(nl, rowptr_.data(), col_.data());
    chol_ = std::make_unique<SparseCholesky>(analysis_);
    chol_ptr_ = chol_.get();
  }
  if (!metric_done_) {
    metric_done_ = true;
    m_ =
        floored_diagonal(nl, rowptr_.data(), col_.data(), vals_.data(),
                         max_abs_diagonal(nl, rowptr_.data(), col_.data(), vals_.data()));
  }
}

void GatheredPreconditioner::setup(System &sys) {
  const Clock::time_point t0 = Clock::now();
  const auto H = sys.hessian();
  const auto comm = sys.map()->getComm();
  const Tpetra::global_size_t n = sys.map()->getGlobalNumElements();
  if (root_.is_null()) {
    root_ = Teuchos::rcp(new TMap(n, comm->getRank() == 0 ? n : 0, 0, comm));
    gather_ = Teuchos::rcp(new Tpetra::Import<>(sys.map(), root_));
  }
  TCrs Hg(root_, 0);
  Hg.doImport(*H, *gather_, Tpetra::INSERT);
  Hg.fillComplete(sys.map(), sys.map());
  int failed = 0, shifted = 0;
  if (root_->getNodeNumElements()) { // rank 0
    gather_values(Hg);
    const double sigma = factor_smallest_shift(*chol_, vals_.data(), m_.data());
    shifted = sigma != 0.0;
    failed = sigma < 0.0;
  }
  Teuchos::broadcast(*comm, 0, &failed);
  Teuchos::broadcast(*comm, 0, &shifted);
  if (failed)
    throw Error(RN_ERR_LAPACK, "rn_solve: no diagonal shift makes the gathered Hessian "
                               "positive definite (non-finite Hessian?)");
  if (op_.is_null()) {
    // x gathered on rank 0, solved there, scattered back
    const SparseCholesky *const *f = &chol_ptr_;
    Teuchos::RCP<const Tpetra::Import<>> gather = gather_;
    Teuchos::RCP<TMV> xg = Teuchos::rcp(new TMV(root_, 1));
    op_ = stats_operator(
        sys.map(),
        [f, gather, xg](const TMV &x, TMV &y) {
          if (x.getNumVectors() != 1 || y.getNumVectors() != 1)
            throw Error(RN_ERR_INTERNAL, "rn_solve: preconditioner applied to a block");
          xg->doImport(x, *gather, Tpetra::INSERT);
          if (xg->getLocalLength()) (*f)->solve(xg->getDataNonConst(0).getRawPtr());
          y.doExport(*xg, *gather, Tpetra::INSERT);
        },
        &stats_);
  }
  ++stats_.setups;
  stats_.shifted = shifted != 0;
  stats_.bytes = 8.0 * static_cast<double>(vals_.size() + m_.size());
  stats_.setup_seconds += seconds_since(t0);
}

} // namespace rodnet

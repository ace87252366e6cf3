// csr_matrix.cpp - pattern and shared symbolic analyses of a CSR matrix (see
// csr_matrix.hpp).
#include "factor/csr_matrix.hpp"

#include "factor/cholmod_factor.hpp"
#include "factor/sparse_cholesky.hpp"

namespace rodnet {

void CsrMatrix::set_pattern(size_t n, size_t nnz, const int64_t *rowptr,
                            const int32_t *col, size_t kd, unsigned long version,
                            bool varies) {
  n_ = n;
  kd_ = kd;
  version_ = version;
  varies_ = varies;
  rowptr_.assign(rowptr, rowptr + n + 1);
  col_.assign(col, col + nnz);
  if (col_.empty()) col_.push_back(0); // (data() never NULL)
  vals_.assign(nnz, 0.0);
  analysis_.reset();
  cholmod_analysis_.reset();
}

std::shared_ptr<const SparseAnalysis> CsrMatrix::sparse_analysis() const {
  if (!analysis_)
    analysis_ = std::make_shared<SparseAnalysis>(n_, rowptr_.data(), col_.data());
  return analysis_;
}

std::shared_ptr<const CholmodAnalysis> CsrMatrix::cholmod_analysis() const {
  if (!cholmod_analysis_)
    cholmod_analysis_ =
        std::make_shared<CholmodAnalysis>(n_, rowptr_.data(), col_.data());
  return cholmod_analysis_;
}

} // namespace rodnet

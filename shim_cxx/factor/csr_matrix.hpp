// csr_matrix.hpp - the symmetric sparse matrix the SPD factorisations take (no
// Trilinos here).
//
// CsrMatrix holds a symmetric matrix in CSR form (both triangles), the version of its
// pattern, its half bandwidth, and the symbolic analyses of the pattern for the
// sparse Cholesky factorisations (sparse_cholesky.hpp, cholmod_factor.hpp), computed
// on first use and shared by every factorisation of the same pattern.  The owner
// (Problem, system/problem.hpp: the assembled Hessian) sets the pattern and the
// values; SpdFactor (spd_factor.hpp) factors A = values + shift M from it.
#ifndef RODNET_SHIM_CSR_MATRIX_HPP
#define RODNET_SHIM_CSR_MATRIX_HPP

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace rodnet {

class SparseAnalysis;
class CholmodAnalysis;

class CsrMatrix {
public:
  virtual ~CsrMatrix() = default;

  size_t size() const { return n_; }
  size_t bandwidth() const { return kd_; }
  // The version of the pattern held here (set_pattern); whatever is built on the
  // pattern (factorisations, metrics on the pattern, Tpetra graphs) is rebuilt when
  // it changes.
  unsigned long pattern_version() const { return version_; }
  // Whether a later pattern may differ (contact): the band may then change too.
  bool pattern_varies() const { return varies_; }
  // Entry (i, j) in CSR form.
  const int64_t *rowptr() const { return rowptr_.data(); }
  const int32_t *col() const { return col_.data(); }
  const double *values() const { return vals_.data(); }
  // The values, to be modified in place (e.g. a constrained Hessian for path
  // following: path.cpp); the factorisations use them.
  double *mutable_values() { return vals_.data(); }

  // Symbolic analysis of the pattern for the sparse Cholesky factorisation
  // (sparse_cholesky.hpp), computed on first use and shared by every factorisation.
  // (Of the pattern of pattern_version().)
  std::shared_ptr<const SparseAnalysis> sparse_analysis() const;
  // The same for CHOLMOD (cholmod_factor.hpp).
  std::shared_ptr<const CholmodAnalysis> cholmod_analysis() const;

  // Called by every numeric factorisation of the matrix (SpdFactor::factor): the
  // owner counts them (Problem: counters.factorizations).
  virtual void count_factorization() const {}

protected:
  // A new pattern of n rows and nnz entries (copied), half bandwidth kd and version;
  // the values are zeroed and the symbolic analyses dropped.
  void set_pattern(size_t n, size_t nnz, const int64_t *rowptr, const int32_t *col,
                   size_t kd, unsigned long version, bool varies);

private:
  size_t n_ = 0, kd_ = 0;
  unsigned long version_ = 0;
  bool varies_ = false;
  std::vector<int64_t> rowptr_;
  std::vector<int32_t> col_;
  std::vector<double> vals_;
  mutable std::shared_ptr<const SparseAnalysis> analysis_;
  mutable std::shared_ptr<const CholmodAnalysis> cholmod_analysis_;
};

} // namespace rodnet

#endif

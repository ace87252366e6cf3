// cholmod_factor.hpp - sparse Cholesky factorisation of symmetric matrices on a fixed
// CSR pattern (the Hessian's), by SuiteSparse CHOLMOD (Debian libsuitesparse-dev):
// RN_FACTOR_CHOLMOD, the library alternative to rodnet's own multifrontal
// factorisation (sparse_cholesky.hpp), with the same interface; the tests solve with
// both and compare.  No Trilinos here.
//
// CholmodAnalysis is the symbolic phase, done once per pattern: CHOLMOD's analysis
// with METIS nested dissection (METIS_NodeND) and a postordered, relaxed supernodal
// symbolic factor.  CholmodCholesky is the numeric phase on a copy of that symbolic
// factor: CHOLMOD's supernodal LL' (LAPACK dpotrf / BLAS dtrsm, dsyrk, dgemm per
// supernode).  A non-positive (or non-finite) pivot makes factor() return false: the
// matrix is not (numerically) positive definite.  Nothing is printed (CHOLMOD's
// print level is 0) and nothing is thrown for that case, which the trust region needs
// because it probes indefinite matrices on purpose.
#ifndef RODNET_SHIM_CHOLMOD_FACTOR_HPP
#define RODNET_SHIM_CHOLMOD_FACTOR_HPP

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace rodnet {

struct CholmodState; // CHOLMOD's workspace and the symbolic factor (cholmod_factor.cpp)

class CholmodAnalysis {
public:
  // Pattern of an n x n symmetric matrix in CSR, both triangles, sorted columns,
  // every diagonal entry present (borrowed: must outlive the analysis).  Throws
  // Error if CHOLMOD cannot analyse it (out of memory, invalid pattern).
  CholmodAnalysis(size_t n, const int64_t *rowptr, const int32_t *col);
  ~CholmodAnalysis();
  CholmodAnalysis(const CholmodAnalysis &) = delete;
  CholmodAnalysis &operator=(const CholmodAnalysis &) = delete;

  size_t size() const { return n_; }
  size_t num_supernodes() const { return nsuper_; }
  // Stored entries of the factor (dense supernode blocks, explicit zeros included),
  // the floating-point operations of one numeric factorisation (CHOLMOD's count for
  // the nonzeros of L), and the most rows of any supernode.
  size_t factor_entries() const { return lx_size_; }
  double factor_flops() const { return flops_; }
  size_t largest_front() const { return max_front_; }

private:
  friend class CholmodCholesky;
  size_t n_;
  // The upper triangle of the matrix in compressed columns (= the lower triangle of
  // the CSR rows): column j holds rows i <= j; csr_pos_ maps each entry to its
  // position in the CSR arrays.
  std::vector<int64_t> colptr_, rowind_, csr_pos_;
  std::unique_ptr<CholmodState> st_; // shared by every CholmodCholesky (sequential use)
  size_t nsuper_ = 0, lx_size_ = 0, max_front_ = 0;
  double flops_ = 0.0;
};

class CholmodCholesky {
public:
  explicit CholmodCholesky(std::shared_ptr<const CholmodAnalysis> analysis);
  ~CholmodCholesky();
  CholmodCholesky(const CholmodCholesky &) = delete;
  CholmodCholesky &operator=(const CholmodCholesky &) = delete;

  // Factor A = V + shift M, V and M given by their values on the analysed pattern (m
  // may be NULL: A = V).  True if A is positive definite (every pivot > 0).  Throws
  // Error if CHOLMOD fails for another reason (out of memory).
  bool factor(const double *vals, double shift, const double *m);
  // x <- A^{-1} x (requires a successful factor()).
  void solve(double *x) const;
  bool factored() const { return factored_; }

private:
  struct Impl;
  std::shared_ptr<const CholmodAnalysis> a_;
  std::unique_ptr<Impl> impl_;
  bool factored_ = false;
};

// The sparse LDL' factorisation of a symmetric indefinite matrix (CHOLMOD's
// simplicial LDL', METIS ordering, no pivoting: D may be negative) and the SPD
// operator M^-1 = (P' L |D| L' P)^-1 of it: with M as the preconditioner, MINRES on
// the matrix sees the eigenvalues +1 and -1 only (exactly so for an exact
// factorisation), the classic preconditioner of an indefinite Newton system.  For
// Newton steps on the principal branch of a periodic cell past an instability
// (periodic/cell_path.cpp), where K_uu has many negative modes.  No Trilinos here.
class CholmodLdl {
public:
  // The pattern as CholmodAnalysis's (borrowed).  Throws Error if CHOLMOD cannot
  // analyse it.
  CholmodLdl(size_t n, const int64_t *rowptr, const int32_t *col);
  ~CholmodLdl();
  CholmodLdl(const CholmodLdl &) = delete;
  CholmodLdl &operator=(const CholmodLdl &) = delete;
  // Factor A (values on the pattern); false if a pivot is zero or not finite (the
  // factor is then unusable) or some |D_jj| is below rel_floor times the largest.
  bool factor(const double *vals, double rel_floor = 1e-13);
  // x <- M^-1 x, M = P' L |D| L' P (requires a successful factor()).
  void solve_abs(double *x) const;
  // Negative pivots of the last factor (the inertia of A: its negative eigenvalues).
  size_t negative_pivots() const { return negative_; }

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  size_t n_ = 0, negative_ = 0;
  bool factored_ = false;
};

} // namespace rodnet

#endif

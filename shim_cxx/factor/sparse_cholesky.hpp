// sparse_cholesky.hpp - supernodal multifrontal sparse Cholesky factorisation of
// symmetric matrices on a fixed CSR pattern (the Hessian's).  No Trilinos here.
//
// SparseAnalysis is the symbolic phase, done once per pattern: a fill-reducing
// nested-dissection ordering (METIS_NodeND), the elimination tree of the permuted
// matrix relabelled in postorder, column counts, fundamental supernodes merged into
// relaxed ones (a child into its parent when few explicit zeros are added), and the
// row structure of every supernode.  SparseCholesky is the numeric phase: for each
// supernode in postorder a frontal matrix is assembled from the matrix entries and
// the children's update matrices (extend-add, kept on a stack), its pivot block is
// factored by LAPACK dpotrf, the rows below by dtrsm, and the update matrix by dsyrk.
// A non-positive (or non-finite) pivot makes factor() return false: the matrix is
// not (numerically) positive definite.  Nothing is printed.
//
// Partial factorisation (static condensation): an analysis made with nlast > 0 keeps
// the last nlast rows/columns (the "separator" Γ, in their given order) out of the
// ordering and eliminates the others (I) only: factor() factors A_II = L_II L_II' and
// leaves the Schur complement A_ΓΓ - A_ΓI A_II^-1 A_IΓ (dense, lower triangle) in
// schur(); forward() / backward() are the two halves of the block solve around it.
#ifndef RODNET_SHIM_SPARSE_CHOLESKY_HPP
#define RODNET_SHIM_SPARSE_CHOLESKY_HPP

#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

namespace rodnet {

class SparseAnalysis {
public:
  // Pattern of an n x n symmetric matrix in CSR, both triangles, sorted columns,
  // every diagonal entry present (borrowed: must outlive the analysis).  nlast > 0:
  // the last nlast rows are the separator of a partial factorisation (see above;
  // their block's pattern may be anything that includes the diagonal).  Throws
  // Error for a pattern METIS cannot order or that exceeds its 32-bit indices.
  SparseAnalysis(size_t n, const int64_t *rowptr, const int32_t *col, size_t nlast = 0);

  size_t size() const { return n_; }
  size_t separator() const { return nlast_; } // nlast of the constructor
  size_t num_supernodes() const { return super_.size() - 1; }
  // Stored entries of the factor (dense supernode blocks, explicit zeros included,
  // the separator's Schur complement too), and the floating-point operations of one
  // numeric (partial) factorisation.
  size_t factor_entries() const { return lx_size_; }
  double factor_flops() const { return flops_; }
  size_t largest_front() const { return max_front_; }

private:
  friend class SparseCholesky;
  void order(); // perm_, iperm_ (METIS)
  void elimination_tree(std::vector<int32_t> &parent) const;
  void postorder(std::vector<int32_t> &parent);
  void column_counts(const std::vector<int32_t> &parent, std::vector<int64_t> &cc) const;
  void supernodes(const std::vector<int32_t> &parent, const std::vector<int64_t> &cc);
  void row_structure(const std::vector<int32_t> &parent);
  void storage_plan();
  // Lower entries (new indices >= j) of column j of the permuted matrix: callback
  // f(new_row, csr_position).
  template <class F>
  void for_lower(int32_t j, F &&f) const;

  size_t n_, nlast_;
  const int64_t *rowptr_;
  const int32_t *col_;
  std::vector<int32_t> perm_, iperm_;      // new -> old, old -> new
  std::vector<int32_t> super_;             // first column of each supernode [ns + 1]
  std::vector<int32_t> sparent_;           // supernodal tree parent (-1: root) [ns]
  std::vector<int32_t> child_ptr_, child_; // children of each supernode, increasing
  std::vector<int64_t> rows_ptr_;          // row structure of each supernode [ns + 1]
  std::vector<int32_t> rows_;              // sorted, starting with its own columns
  std::vector<size_t> lx_ptr_;             // offset of each block in the factor [ns + 1]
  size_t lx_size_ = 0, stack_size_ = 0, max_update_ = 0, max_front_ = 0;
  double flops_ = 0.0;
};

class SparseCholesky {
public:
  explicit SparseCholesky(std::shared_ptr<const SparseAnalysis> analysis);

  // Factor A = V + shift M, V and M given by their values on the analysed pattern (m
  // may be NULL: A = V).  True if A is positive definite (every pivot > 0).
  bool factor(const double *vals, double shift, const double *m);
  // x <- A^{-1} x (requires a successful factor() of a full analysis, nlast 0).
  // Reentrant: allocates its own workspace.
  void solve(double *x) const;
  // The separator's Schur complement after factor() of a partial analysis: nlast x
  // nlast, column-major, lower triangle (the upper one is not set).
  const double *schur() const;
  // The block solve of a partial factorisation, in place on x (length n):
  // forward(): x_I <- (the forward-eliminated x_I, internal), x_Γ <- x_Γ - A_ΓI
  // A_II^-1 x_I (the condensed right-hand side); then the caller puts the separator's
  // solution into x_Γ, and backward(): x_I <- A_II^-1 (x_I - A_IΓ x_Γ) (x_I as forward()
  // left it).  For nlast 0, forward() then backward() is solve().
  void forward(double *x) const;
  void backward(double *x) const;
  bool factored() const { return factored_; }

private:
  void assemble(size_t s, const double *vals, double shift, const double *m,
                const std::vector<int32_t> &relpos, double *L) const;
  void extend_add(size_t s, const std::vector<int32_t> &relpos, double *L, double *W,
                  size_t &top);

  std::shared_ptr<const SparseAnalysis> a_;
  struct Block; // a supernode's block in the solves
  Block block(size_t s) const;
  size_t factored_supernodes() const; // all but the separator's
  std::vector<double> lx_, stack_, work_;
  bool factored_ = false;
};

} // namespace rodnet

#endif

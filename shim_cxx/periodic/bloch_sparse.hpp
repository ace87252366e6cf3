// bloch_sparse.hpp - the lowest eigenvalue of a cell's Bloch Hessian H(xi) without a
// dense matrix (cells beyond the dense analysis' 4,000 DOFs; docs/homogenization.md,
// "Sparse Bloch eigenvalues"): H = A + i B from rn_network_bloch_hessian_csr,
// restricted to the examined DOFs, as the real symmetric form K = [A -B; B A] (each
// eigenvalue of H twice), factored by the sparse Cholesky of K + sigma I (sigma 0 where
// K is positive definite, else the smallest decade of the largest diagonal entry that
// makes it so), and the largest eigenvalue 1 / (lambda + sigma) of (K + sigma I)^-1
// by Lanczos with full reorthogonalisation (krylov/lanczos.hpp).  No Trilinos here.
#ifndef RODNET_SHIM_BLOCH_SPARSE_HPP
#define RODNET_SHIM_BLOCH_SPARSE_HPP

#include <cstdint>
#include <memory>
#include <vector>

#include "rodnet.h"

namespace rodnet {

class SparseAnalysis;

class SparseBloch {
public:
  // The network at the reduced state x (borrowed), n its Bloch DOFs.
  SparseBloch(const rn_network *net, const double *x, size_t n);
  ~SparseBloch();
  // The lowest eigenvalue of H(xi) on the Bloch DOFs sel (ascending indices); vec
  // (2 n: re, im per Bloch DOF, zero outside sel, unit norm) its eigenvector if not
  // NULL.  Throws Error if Lanczos does not converge.
  double lowest(const double *xi, const std::vector<int> &sel, double *vec);
  // The largest |H_ij| over all entries and over those with mask[i] != mask[j].
  void coupling(const double *xi, const std::vector<char> &mask, double *big,
                double *cross);
  int steps() const { return steps_; }    // Lanczos steps of the last lowest()
  double shift() const { return shift_; } // sigma of the last lowest()

private:
  void assemble(const double *xi);
  void real_form(const std::vector<int> &sel);
  const rn_network *net_;
  const double *x_;
  size_t n_;
  // H(xi) in CSR (rn_network_bloch_hessian_csr)
  std::vector<int64_t> rp_, col_;
  std::vector<double> re_, im_;
  // K on the selection: pattern (owned here, borrowed by the analysis), values, the
  // identity on the pattern
  std::vector<int64_t> krp_;
  std::vector<int32_t> kcol_;
  std::vector<double> kval_, kid_;
  std::shared_ptr<SparseAnalysis> analysis_;
  int steps_ = 0;
  double shift_ = 0.0;
};

} // namespace rodnet

#endif

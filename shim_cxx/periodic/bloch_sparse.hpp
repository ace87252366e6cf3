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

// Q_JL[a][b] -= B_J[:, a] . X_L[:, b] (m rows; B_J, X_L column-major m x na): the
// fluctuation part of the brackets, shared by the dense and the sparse acoustic tensor.
void subtract_bx(int d, int na, size_t m, const std::vector<std::vector<double>> &B,
                 const std::vector<std::vector<double>> &X, std::vector<double> &Q);
// The brackets Q[d][d][na][na] of the acoustic tensor (cell_path.cpp,
// AcousticTensor) from the sparse moments (rn_network_bloch_moment_csr): Q_JL[a][b] =
// -1/2 T_a' M2_JL T_b - B_J' K^-1 B_L, B_J = M1_J' T on the rows sel0, K = H(0) on
// sel0 by its sparse Cholesky factor; amp_of[i] the amplitude index a of Bloch DOF i
// where it is the translation component amp[a], else -1.  False (Q untouched) if K is
// not positive definite.
bool sparse_acoustic_brackets(const rn_network *net, const double *x, size_t n, int d,
                              int na, const std::vector<int> &sel0,
                              const std::vector<int> &amp_of, std::vector<double> &Q);

class SparseBloch {
public:
  // The network at the reduced state x (borrowed), n its Bloch DOFs.
  SparseBloch(const rn_network *net, const double *x, size_t n);
  ~SparseBloch();
  // The lowest eigenvalue of H(xi) on the Bloch DOFs sel (ascending indices); vec
  // (2 n: re, im per Bloch DOF, zero outside sel, unit norm) its eigenvector if not
  // NULL.  Throws Error if Lanczos does not converge.
  double lowest(const double *xi, const std::vector<int> &sel, double *vec);
  // The lowest k eigenvalues w[k] (ascending, with their multiplicities in H) by
  // Lanczos runs deflated by the eigenvectors found before (each with its partner
  // (-y, x) of the real form); vec as for lowest() (the lowest one's).  Returns k.
  int lowest_k(const double *xi, const std::vector<int> &sel, int k, double *w,
               double *vec);
  // The gradient g[d] in xi (reciprocal coordinates) of an eigenvalue of H(xi) whose
  // unit eigenvector is vec (2 n: re, im per Bloch DOF) by Hellmann-Feynman:
  // g_a = vec^H (dH/dxi_a) vec, dH/dxi_a = sum_t 2 pi i n_t,a exp(2 pi i xi . n_t) T_t.
  // Exact for a simple eigenvalue; at a multiple one the derivative along vec.
  void gradient(const double *xi, const double *vec, int d, double *g);
  // The largest |H_ij| over all entries and over those with mask[i] != mask[j].
  void coupling(const double *xi, const std::vector<char> &mask, double *big,
                double *cross);
  int steps() const { return steps_; }    // Lanczos steps of the last lowest()
  double shift() const { return shift_; } // sigma of the last lowest()

private:
  void fetch_terms();
  void assemble(const double *xi);
  void real_form(const std::vector<int> &sel);
  const rn_network *net_;
  const double *x_;
  size_t n_;
  // H(xi) in CSR, from the terms of the state (rn_network_bloch_terms, fetched once)
  std::vector<int64_t> rp_, col_;
  std::vector<double> re_, im_;
  int nterms_ = 0;
  std::vector<int> shift_n_;
  std::vector<double> terms_;
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

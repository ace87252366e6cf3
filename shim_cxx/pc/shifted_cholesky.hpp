// shifted_cholesky.hpp - the diagonal shift of a sparse Cholesky factorisation of a
// CSR matrix (sorted rows, both triangles), shared by the "local" and "gathered"
// preconditioners: the metric D = |diag A| floored at 1e-8 of its largest entry, and
// the smallest sigma in {0, 1e-10, ..., 1e10} for which A + sigma D factors.
#ifndef RODNET_SHIM_SHIFTED_CHOLESKY_HPP
#define RODNET_SHIM_SHIFTED_CHOLESKY_HPP

#include <cstddef>
#include <cstdint>
#include <vector>

namespace rodnet {

class SparseCholesky;

// The largest |diagonal entry| of the n x n CSR matrix (rowptr, col, vals); 0 if n = 0.
double max_abs_diagonal(size_t n, const int64_t *rowptr, const int32_t *col,
                        const double *vals);

// D on the pattern: D_ii = max(|a_ii|, 1e-8 dmax) (1 if dmax is not positive and
// finite), 0 off the diagonal; dmax: the largest |diagonal entry| (of every rank's
// block where the metric is shared).
std::vector<double> floored_diagonal(size_t n, const int64_t *rowptr, const int32_t *col,
                                     const double *vals, double dmax);

// Factors vals + sigma m with chol for the smallest sigma in {0, 1e-10, ..., 1e10} for
// which it is positive definite (bisection on the exponent; the factorisation of the
// returned sigma is chol's); -1 if none is.
double factor_smallest_shift(SparseCholesky &chol, const double *vals, const double *m);

} // namespace rodnet

#endif

// lanczos.hpp - the largest eigenpair of T = A^{-1} M by the Lanczos process in the
// M inner product, with full reorthogonalisation (no Trilinos here).
//
// A is SPD and given by its inverse (x <- A^{-1} x, e.g. SpdFactor::solve), M =
// diag(d), d > 0.  T is
// self-adjoint in <a, b>_M = a' M b, and its largest eigenvalue theta is
// 1 / (lambda_1 + sigma) for A = H + sigma M, lambda_1 the lowest eigenvalue of the
// pencil (H, M): shift-and-invert Lanczos for the trust region's negative curvature.
// Ritz values approach theta from below, so 1 / theta_ritz - sigma >= lambda_1.
#ifndef RODNET_SHIM_LANCZOS_HPP
#define RODNET_SHIM_LANCZOS_HPP

#include <cstddef>
#include <functional>
#include <vector>

namespace rodnet {

struct LanczosResult {
  double theta = 0.0; // largest Ritz value
  int steps = 0;      // Lanczos steps (= solves with A)
  bool converged = false;
};

// solve_A(x): x <- A^{-1} x (length n = d.size()).  At most max_steps steps (<= n),
// from the start vector v (overwritten with the Ritz
// vector, ||v||_M = 1); stops when the Ritz residual estimate |beta_j y_j| falls below
// rel_tol theta.  locked (may be NULL): M-orthonormal vectors that every Lanczos
// vector is kept M-orthogonal to (deflation: T restricted to their complement, e.g.
// for the next eigenpair after the found ones; they should span an invariant
// subspace of T).  Memory: max_steps vectors of length n.  Throws Error if LAPACK's
// tridiagonal eigensolver fails.
LanczosResult lanczos_largest(const std::function<void(double *)> &solve_A,
                              const std::vector<double> &d, int max_steps, double rel_tol,
                              std::vector<double> &v,
                              const std::vector<std::vector<double>> *locked = nullptr);

} // namespace rodnet

#endif

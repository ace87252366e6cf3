// minres_local.hpp - Belos MINRES (minres.hpp) on plain arrays of one process, for
// callers that keep Tpetra's headers out of their translation unit (periodic/): the
// operator and the SPD preconditioner as callbacks on double arrays of length n.
// Initialises the solver runtime (Kokkos) on first use.
#ifndef RODNET_SHIM_MINRES_LOCAL_HPP
#define RODNET_SHIM_MINRES_LOCAL_HPP

#include <cstddef>
#include <functional>

namespace rodnet {

struct LocalMinresResult {
  int iterations = 0;
  bool converged = false;
  double achieved_tol = 0.0; // MINRES's residual in the preconditioner's norm
};

using LocalApply = std::function<void(const double *x, double *y)>; // y = op x

// x = A^-1 b (x overwritten, zero initial guess) by MINRES with the left
// preconditioner Minv (applies the inverse of an SPD matrix); stops at rel_tol or
// max_iterations.  Throws Error.
LocalMinresResult minres_local(size_t n, const LocalApply &A, const LocalApply &Minv,
                               const double *b, double *x, double rel_tol,
                               int max_iterations);

} // namespace rodnet

#endif

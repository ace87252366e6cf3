// stability.hpp - is the current state a local minimum?  The lowest eigenvalues of
// the reduced Hessian H (fixed DOFs removed), Jacobi-scaled: the pencil (H, D), D =
// |diag H| (floored at 1e-20 of its largest entry), i.e. the eigenvalues of
// D^{-1/2} H D^{-1/2}.  The scaling makes them dimensionless and independent of the
// units of the DOFs (positions and angles, a structure of size 1e-6 or 1e6, one
// tiny edge among long ones); by Sylvester's law the signs and the zero modes are
// those of H itself.  By Cholesky inertia and shift-and-invert iterations on the
// solver's factorisation (banded or sparse); no Trilinos here.
//
// scale = ||D^{-1/2} H D^{-1/2}||_inf (an upper bound of every |lambda|, at least 1
// when no diagonal entry is floored); eigenvalues with |lambda| <= kZeroModeTol *
// scale are zero modes (rigid-body motions of unsupported parts, mechanisms).  The
// method:
//  1. Cholesky of H - delta D (delta = kZeroModeTol * scale) succeeds: every
//     eigenvalue exceeds delta (inertia) - a verified minimum, no zero modes; the
//     lowest eigenvalue is then estimated by shift-and-invert Lanczos with that
//     factorisation (an upper bound within 1e-6 relative).
//  2. Otherwise the smallest shift s in {delta, 1e-10 scale, 1e-9 scale, ...} with
//     H + s D positive definite is found (lambda_min > -s), and subspace iteration
//     with (H + s D)^{-1} D on a block of kStabilityBlock vectors (Rayleigh-Ritz with
//     H each sweep) gives the lowest Ritz pairs: the zero modes (multiple eigenvalues
//     are found with their multiplicity) and the lowest eigenvalue outside the zero
//     band; a negative one means unstable.
#ifndef RODNET_SHIM_STABILITY_HPP
#define RODNET_SHIM_STABILITY_HPP

#include "problem.hpp"
#include "rodnet_solve.h"

namespace rodnet {

constexpr double kZeroModeTol = 1e-12;
constexpr int kStabilityBlock = 10;

// The stability of the state whose Hessian p holds (assemble_hessian first), with
// the factorisation kind (choose_factor_kind).  verified_minimum says only that the
// Hessian is positive definite outside its zero modes (the caller ANDs equilibrium).
// checked = 1.  Throws Error.
rn_stability hessian_stability(Problem &p, rn_factorization kind);

} // namespace rodnet

#endif

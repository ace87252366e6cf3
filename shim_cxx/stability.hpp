// stability.hpp - is the current state a local minimum?  The lowest eigenvalues of
// the reduced Hessian (fixed DOFs removed) by Cholesky inertia and shift-and-invert
// iterations on the solver's factorisation (banded or sparse); no Trilinos here.
//
// scale = ||H||_inf (the largest absolute row sum, an upper bound of |lambda| over
// the spectrum); eigenvalues with |lambda| <= kZeroModeTol * scale are zero modes
// (rigid-body motions of unsupported parts, mechanisms): at double precision the
// assembled Hessian is exact only to about 1e-14 scale, so a mode that soft cannot
// be told from a zero mode.  The method:
//  1. Cholesky of H - delta I (delta = kZeroModeTol * scale) succeeds: every
//     eigenvalue exceeds delta (Sylvester's inertia) - a verified minimum, no zero
//     modes; the lowest eigenvalue is then estimated by shift-and-invert Lanczos
//     with that factorisation (an upper bound within 1e-6 relative).
//  2. Otherwise the smallest shift s in {delta, 1e-10 scale, 1e-9 scale, ...} with
//     H + s I positive definite is found (inertia again: lambda_min > -s), and
//     subspace iteration with (H + s I)^{-1} on a block of kStabilityBlock vectors
//     (Rayleigh-Ritz with H each sweep) gives the lowest Ritz pairs: the zero modes
//     (multiple eigenvalues are found with their multiplicity) and the lowest
//     eigenvalue outside the zero band; a negative one means unstable.
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

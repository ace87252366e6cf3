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
// when no diagonal entry is floored).  Zero modes are of two kinds, told apart:
// - symmetries: exact zero modes of the energy, the rigid motions no constraint
//   blocks and the spins of rods' material frames.  Candidates are built from the
//   model (the six rigid motions at the current positions, each rod's spin on
//   networks of at most 64 rods); the combinations H maps to zero (residual <=
//   1e-8 scale) are the symmetries, a D-orthonormal basis S.  They are excluded.
// - soft modes: eigenvalues outside the symmetries with |lambda| <= delta =
//   kZeroModeTol * scale.  Not necessarily zero: the scaled spectrum of a rod of N
//   edges reaches down to ~(pi/N)^4 / 6 (the clamped 3200-edge cantilever: its two
//   lowest bending modes in each plane, 2e-14 and 8e-13 at scale 5.9), and a
//   mechanism is one too.  Verified positive or not (soft_positive).
// The method:
//  1. No symmetries and the Cholesky of H - delta D succeeds: every eigenvalue
//     exceeds delta (inertia) - a verified minimum, no soft modes; the lowest
//     eigenvalue is then estimated by shift-and-invert Lanczos with that
//     factorisation (an upper bound within 1e-6 relative).
//  2. Otherwise the smallest shift s in {delta, 1e-10 scale, 1e-9 scale, ...} with
//     H + s D positive definite is found (lambda_min > -s), and subspace iteration
//     with (H + s D)^{-1} D on a block of kStabilityBlock vectors D-orthogonal to S
//     (Rayleigh-Ritz with H each sweep) gives the lowest Ritz pairs outside the
//     symmetries: the soft modes (with their multiplicity) and the lowest
//     eigenvalue; one below -delta means unstable.  Soft modes are shown positive
//     by the Cholesky factorisation of H itself (no symmetries: inertia, the lowest
//     eigenvalue then by Lanczos on H^{-1} D) or by Ritz values above their
//     residuals; verified_minimum needs every one shown positive.
#ifndef RODNET_SHIM_STABILITY_HPP
#define RODNET_SHIM_STABILITY_HPP

#include "system/problem.hpp"
#include "rodnet_solve.h"

namespace rodnet {

constexpr double kZeroModeTol = 1e-12;
constexpr int kStabilityBlock = 10;

// The stability of the state whose Hessian p holds (assemble_hessian first), with
// the factorisation kind (choose_factor_kind).  verified_minimum says only that the
// Hessian is positive definite outside its zero modes (the caller ANDs equilibrium).
// checked = 1.  Throws Error.
rn_stability hessian_stability(Problem &p, rn_factorization kind);

class System;

// The same check without factorising the whole Hessian (stability_lobpcg.cpp): the
// lowest min(n, kStabilityBlock - 2) eigenvalues of D^{-1/2} H D^{-1/2} by Anasazi
// LOBPCG (block kStabilityBlock), preconditioned by the SPD preconditioner opt
// names for sys (make_preconditioner, set up on sys.hessian(), which must be
// assembled at the state).  A Ritz pair is converged when ||A y - mu y|| <= 1e-10
// scale (||y|| = 1, A the scaled Hessian); verified_minimum needs every requested
// pair converged and the lowest outside the zero band above it.  symmetries >= 0
// (count_symmetries, serial runs): that many band values nearest 0 are the
// symmetries, the rest soft modes, and a soft mode means no verified minimum
// (LOBPCG cannot resolve its sign); -1 (distributed): not separated, zero_modes
// counts all, symmetries = soft_modes = -1.  No inertia
// certificate: an eigenvalue LOBPCG misses is not seen.  factorizations counts
// none (the preconditioner's own are not counted).  Collective over sys's
// communicator; memory ~ 6 kStabilityBlock vectors per rank plus the
// preconditioner.  prec: an SPD preconditioner already set up on sys (the
// solver's, at or near the state: it only speeds LOBPCG up) instead of a new one
// made and set up here.  symmetries: the number of exact symmetries of the
// state (count_symmetries, one process), or -1 if not known (distributed).
// Throws Error.
class Preconditioner;
rn_stability lobpcg_stability(System &sys, const rn_solve_options &opt,
                              Preconditioner *prec = nullptr, int symmetries = -1);

// Smallest eigenvalue of the assembled Hessian by bisection on the inertia (sparse
// Cholesky of H - sigma I) and inverse iteration (min_eigenvalue.cpp).  Throws Error.
double sparse_min_eigenvalue(Problem &p);

// The number of symmetries at the state p's Hessian holds (hessian_stability's
// basis; one process, assemble_hessian first).  Throws Error.
int count_symmetries(Problem &p);

// The stability check after rn_solve, by opt.stability_method (rn_solve_options):
// on dist (a distributed System, not null: LOBPCG; checked = 0 if CHOLESKY is
// forced, which needs the whole Hessian) or on p (one process; the
// Hessian assembled at the state) with the factorisation kind.  AUTO: the Cholesky
// check when the solver factors the whole Hessian itself (every kind but
// tr-krylov and nox with a preconditioner other than factor) or when one
// factorisation costs at most RN_STABILITY_MAX_FLOPS (banded: n (kd+1)^2; sparse:
// the symbolic analysis's count), LOBPCG otherwise.  ws: tr-krylov's System and
// preconditioner of the last load step (set up at the returned state), which
// LOBPCG then uses instead of setting up a preconditioner of its own; nullptr:
// none.  Collective.  Throws Error.
class KrylovWorkspace;
rn_stability solve_stability(Problem &p, System *dist, const rn_solve_options &opt,
                             rn_factorization kind, KrylovWorkspace *ws = nullptr);

} // namespace rodnet

#endif

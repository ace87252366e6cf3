// coarse_solver.hpp - solvers of a coarse (interface) matrix made symmetric positive
// definite: the rod-level domain decomposition's coarse solve (dd_preconditioner.hpp),
// direct (pc/impls/dd/) or one algebraic-multigrid V-cycle (pc/impls/muelu/).
#ifndef RODNET_SHIM_COARSE_SOLVER_HPP
#define RODNET_SHIM_COARSE_SOLVER_HPP

#include <memory>
#include <string>

#include "system/system.hpp"

namespace rodnet {

// Solver of the SPD-made coarse matrix.  Collective over the matrix's communicator.
class CoarseSolver {
public:
  virtual ~CoarseSolver() = default;
  // S: fill-complete, on a one-to-one row map equal to its domain and range maps.
  // nullspace (may be null): near-null-space vectors on the same map.  Makes S SPD
  // when it is not (a diagonal shift, reported by shift()).  Throws Error on every
  // rank if it cannot.
  virtual void setup(const Teuchos::RCP<const TCrs> &S,
                     const Teuchos::RCP<const TMV> &nullspace) = 0;
  // y = A^-1 b for an SPD A close to S (exact inverse for the direct solver).
  virtual void solve(const TMV &b, TMV &y) const = 0;
  virtual double shift() const = 0; // t of S + t D_S in the last setup (0: none)
  virtual double bytes() const = 0; // memory held on this rank after setup
  virtual std::string name() const = 0;
  // True if the last setup declined to solve (the direct solver when its
  // factorisation would cost more than the limit it was made with): use another.
  virtual bool declined() const { return false; }
  // Floating-point operations of one factorisation (direct solver; 0 otherwise).
  virtual double flops() const { return 0.0; }
  // Rows of the reduced (inter-rank separator) matrix of the direct solver (0 on one
  // rank and for the other solvers).
  virtual long long separator_rows() const { return 0; }
  // Strict: the next setup tries S itself (no shift) and reports failure by failed()
  // instead of shifting (the direct solver; the others ignore it and never fail).
  virtual void set_strict(bool) {}
  virtual bool failed() const { return false; }
};

// Exact solve of the coarse matrix by rodnet's sparse Cholesky (pc/impls/dd/
// direct_coarse.cpp; METIS ordering),
// substructured over the ranks: a coarse row is on the inter-rank separator if S
// couples it to a higher rank's row; each rank factors its other rows (a partial
// factorisation leaving their Schur complement on the separator rows they touch),
// and the reduced separator matrix is gathered to rank 0 and factored there (never
// a distributed direct solve: Amesos2 is wrong on several ranks, see TRILINOS.md).
// One rank: the Cholesky of S.  Indefinite S: S + t D_S with the smallest t in
// {1e-10, ..., 1e10} (the same t on any number of ranks).  max_flops > 0: decline
// (declined()) when the factorisations (the ranks' and rank 0's) would take more
// floating-point operations (symbolic analysis only, once per structure).
std::unique_ptr<CoarseSolver> make_direct_coarse_solver(double max_flops = 0.0);
// One MueLu V-cycle (smoothed aggregation, Chebyshev smoothing, rigid-body
// near-null space; coarsest level: direct on one rank, relaxation on several),
// pc/impls/muelu/muelu.cpp.  Indefinite S (detected by a short preconditioned CG probe,
// see there): S + t D_S, t raised by decades. The coarse matrix's rows come in nodes of 6
// (6 n .. 6 n + 5), padded with decoupled dummy rows.  xml: a MueLu parameter file whose
// entries override the defaults (empty: none).
std::unique_ptr<CoarseSolver>
make_amg_coarse_solver(const std::string &xml = std::string());

} // namespace rodnet

#endif

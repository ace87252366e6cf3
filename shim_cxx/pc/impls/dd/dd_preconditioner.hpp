// dd_preconditioner.hpp - rod-level domain decomposition: the default SPD
// preconditioner of the Newton systems of rod networks (issue 7, docs/solvers.md).
//
// The owned DOFs of a System split into rod interiors (DofBlocks) and interface
// DOFs.  No Hessian entry couples two rod interiors, so after ordering each rod's
// interior r before the interface G
//   H = [ H_rr  H_rG ]      H^-1 = L^-T diag(H_rr^-1, S^-1) L^-1,
//       [ H_Gr  H_GG ]      S = H_GG - sum_r H_Gr H_rr^-1 H_rG  (exact static
//       condensation).
// Each rod's interior block H_rr is banded (LAPACK dpbtrf/dpbtrs); each rod adds
// the small dense block -H_Gr H_rr^-1 H_rG on the interface DOFs it touches,
// computed with banded solves on the rod's rank.  The coarse (interface) matrix S
// is assembled as a Tpetra::CrsMatrix (contributions exported to the owners of the
// interface DOFs) and solved by a CoarseSolver: sparse Cholesky when small
// (substructured over the ranks: each rank's part condensed onto the inter-rank
// separator, whose small matrix is factored on rank 0), one algebraic-multigrid
// V-cycle (MueLu, rigid-body modes as near-null space) when large.  apply(x) = forward
// elimination of the rod interiors, coarse solve, back substitution.
//
// M is symmetric positive definite in every case: an indefinite rod block is
// replaced by H_rr + s_r D_r (D_r = |diag H_rr|, s_r the smallest of 1e-10, 1e-9,
// ..., 1e10 for which it factors), and the coarse solver makes the condensed
// matrix SPD (S + t D_S, likewise).  With H positive definite and the direct
// coarse solve, no shift is needed and M = H (MINRES converges in one iteration).
#ifndef RODNET_SHIM_DD_PRECONDITIONER_HPP
#define RODNET_SHIM_DD_PRECONDITIONER_HPP

#include <memory>
#include <string>

#include "pc/coarse_solver.hpp"
#include "pc/preconditioner.hpp"

namespace rodnet {

struct DdOptions {
  enum class Coarse { Auto, Direct, Amg };
  Coarse coarse = Coarse::Auto;
  // Auto: the direct coarse solve unless its sparse Cholesky factorisation would take
  // more floating-point operations than this (measured choice, docs/solvers.md);
  // then the AMG one (only with an MPI runtime, mpi_backed(); otherwise the
  // direct one whatever it costs).
  double direct_max_flops = 5e10;
  // H indefinite (rod blocks or the coarse matrix): true, the DD of H + sigma D with
  // one shift sigma for every piece (the smallest decade that makes them all
  // positive definite; with the direct coarse solve M is then exactly (H + sigma
  // D)^-1), D = |diag H| of the first such set-up raised entrywise to that of each
  // later one; false, each rod block and the coarse matrix shifted by its own
  // smallest decade (docs/solvers.md).
  bool uniform_shift = true;
  // MueLu parameter file overriding the AMG coarse solve's defaults (empty: none).
  std::string amg_xml;
};

class DdPreconditioner : public Preconditioner {
public:
  explicit DdPreconditioner(const DdOptions &opt = DdOptions());
  ~DdPreconditioner() override;
  void setup(System &sys) override;
  Teuchos::RCP<const Tpetra::Operator<>> inverse() const override;
  std::string name() const override { return "dd"; }
  // A block in one application: the rod solves per column, one export, coarse solve
  // and import for all columns.
  bool takes_blocks() const override { return true; }

  // Of the last setup: global rows of the coarse matrix, rods (on all ranks) whose
  // interior block had to be shifted, the coarse shift, the coarse solver's name
  // ("direct", "amg", "none" without interface).
  long long coarse_rows() const;
  long long rods_shifted() const;
  double coarse_shift() const;
  // sigma of the DD of H + sigma D (DdOptions::uniform_shift; 0: none)
  double uniform_shift() const;
  std::string coarse_solver() const;
  // Factorisation flops of the direct coarse solve (also when it declined), else 0.
  double coarse_flops() const;
  // Rows of the direct coarse solve's inter-rank separator (0 on one rank).
  long long coarse_separator_rows() const;
  // The last setup was an exact block factorisation of H (no rod block nor the coarse
  // matrix shifted, the coarse solve direct): M = H, which proves H positive definite
  // (the inertia of H is that of the rod blocks plus that of the Schur complement).
  bool exact() const override;
  // The pencil (S, A) of the last setup's coarse matrix S (the Schur complement of
  // the rod interiors, its decoupled padding rows positive) and the coarse solver's
  // SPD approximation A (an operator applying A^-1), on the coarse map; false where
  // a rod block or the coarse matrix was shifted or there is no coarse matrix.
  // With unshifted rod blocks, H's inertia is that of the rod blocks (positive
  // definite) plus that of S (Haynsworth): H is positive definite iff S is, which a
  // Lanczos process on this pencil checks at a fraction of the cost of one on
  // (H, M) (tr_krylov.cpp).  The operators share the preconditioner's state: valid
  // until its next setup.
  bool coarse_pencil(Teuchos::RCP<const Tpetra::Operator<>> &S,
                     Teuchos::RCP<const Tpetra::Operator<>> &Ainv) const override;

  struct Impl;

private:
  DdOptions opt_;
  Teuchos::RCP<Impl> impl_;
  mutable Teuchos::RCP<const Tpetra::Operator<>> op_;
};

} // namespace rodnet

#endif

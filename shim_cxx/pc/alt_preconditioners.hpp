// alt_preconditioners.hpp - the preconditioners measured against the rod-level domain
// decomposition (docs/solvers.md), and the factory of the preconditioner names.
//
//  muelu    one MueLu smoothed-aggregation V-cycle on the whole Hessian (Chebyshev
//           smoothing, rigid-body modes of every DOF as near-null space when given);
//  ifpack2  Ifpack2 additive Schwarz: one subdomain per rank with overlap 1, combined
//           by addition (symmetric), each solved exactly by a local sparse LU
//           (Amesos2 KLU2 on the rank's own matrix: never a distributed Amesos2
//           solve).
//  frosch   FROSch (ShyLU-DD) two-level overlapping Schwarz: one subdomain per rank
//           with algebraic overlap 1 (local sparse LU, Amesos2 KLU2), combined
//           additively, and an energy-minimising (IPOU harmonic, GDSW interface
//           partition of unity) coarse space spanned by the rigid-body modes,
//           its coarse matrix gathered to one rank and factored there (KLU2).
// All three are made SPD for an indefinite Hessian the way the DD's AMG coarse solve is
// (multigrid.cpp): A + t |diag A| with t raised by factors of 100 until a short
// preconditioned CG probe meets no nonpositive curvature.
#ifndef RODNET_SHIM_ALT_PRECONDITIONERS_HPP
#define RODNET_SHIM_ALT_PRECONDITIONERS_HPP

#include <memory>
#include <string>

#include "pc/impls/dd/dd_preconditioner.hpp"

namespace rodnet {

class MueluPreconditioner : public Preconditioner {
public:
  // nullspace: rigid-body modes on the System's map (may be null: MueLu's constants).
  explicit MueluPreconditioner(const Teuchos::RCP<const TMV> &nullspace = Teuchos::null);
  ~MueluPreconditioner() override;
  void setup(System &sys) override;
  Teuchos::RCP<const Tpetra::Operator<>> inverse() const override;
  std::string name() const override { return "muelu"; }
  double shift() const; // t of H + t |diag H| in the last setup

private:
  Teuchos::RCP<const TMV> nullspace_;
  Teuchos::RCP<const TMap> map_;
  std::shared_ptr<CoarseSolver> amg_;
  mutable Teuchos::RCP<const Tpetra::Operator<>> op_;
};

class SchwarzPreconditioner : public Preconditioner {
public:
  SchwarzPreconditioner();
  ~SchwarzPreconditioner() override;
  void setup(System &sys) override;
  Teuchos::RCP<const Tpetra::Operator<>> inverse() const override;
  std::string name() const override { return "ifpack2"; }
  double shift() const;
  struct Impl;

private:
  std::shared_ptr<Impl> impl_;
  mutable Teuchos::RCP<const Tpetra::Operator<>> op_;
};

class FroschPreconditioner : public Preconditioner {
public:
  // nullspace: rigid-body modes on the System's map (null: FROSch's constants).
  explicit FroschPreconditioner(const Teuchos::RCP<const TMV> &nullspace = Teuchos::null);
  ~FroschPreconditioner() override;
  void setup(System &sys) override;
  Teuchos::RCP<const Tpetra::Operator<>> inverse() const override;
  std::string name() const override { return "frosch"; }
  double shift() const;
  struct Impl;

private:
  std::shared_ptr<Impl> impl_;
  mutable Teuchos::RCP<const Tpetra::Operator<>> op_;
};

// Rigid-body modes (6 columns: translations x, y, z, rotations about x, y, z through
// the origin) of DOFs of the given DofBlocks kinds (0-2 position, 3-5 rotation, 6
// angle), points and axes (3 per DOF, rn_network_dof_blocks), on map (one entry per
// local element).
Teuchos::RCP<TMV> rigid_body_modes(const Teuchos::RCP<const TMap> &map, const int *kind,
                                   const double *point, const double *axis);

// A preconditioner by name: "dd" (coarse solve chosen by size), "dd-direct",
// "dd-amg", "muelu", "ifpack2", "frosch".  nullspace: for "muelu" and "frosch" (may
// be null).  Returns null
// for an unknown name.
std::unique_ptr<Preconditioner>
make_preconditioner(const std::string &name,
                    const Teuchos::RCP<const TMV> &nullspace = Teuchos::null);

} // namespace rodnet

#endif

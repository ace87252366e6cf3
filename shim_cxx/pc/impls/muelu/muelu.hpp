// muelu.hpp - the "muelu" preconditioner (preconditioner.hpp), measured against the
// rod-level domain decomposition (docs/solvers.md): one MueLu smoothed-aggregation
// V-cycle on the whole Hessian (Chebyshev smoothing, rigid-body modes of every DOF as
// near-null space when given).  Made SPD for an indefinite Hessian as the DD's AMG
// coarse solve is (the same code, muelu.cpp; spd_guard.hpp): A + t |diag A| with t
// raised by factors of 100 until a short preconditioned CG probe meets no
// nonpositive curvature.  Needs the MPI runtime (mpi_backed).
#ifndef RODNET_SHIM_MUELU_HPP
#define RODNET_SHIM_MUELU_HPP

#include <memory>
#include <string>

#include "pc/coarse_solver.hpp"
#include "pc/preconditioner.hpp"

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

} // namespace rodnet

#endif

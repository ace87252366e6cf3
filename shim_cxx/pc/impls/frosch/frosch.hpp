// frosch.hpp - the "frosch" preconditioner (preconditioner.hpp), measured against the
// rod-level domain decomposition (docs/solvers.md): FROSch (ShyLU-DD) two-level
// overlapping Schwarz, one subdomain per rank with algebraic overlap 1 (local sparse
// LU, Amesos2 KLU2), combined additively, and an energy-minimising (IPOU harmonic,
// GDSW interface partition of unity) coarse space spanned by the rigid-body modes,
// its coarse matrix gathered to one rank and factored there (KLU2).  Made SPD for an
// indefinite Hessian by SpdGuard (spd_guard.hpp).  Needs the MPI runtime
// (mpi_backed).
#ifndef RODNET_SHIM_FROSCH_HPP
#define RODNET_SHIM_FROSCH_HPP

#include <string>

#include "pc/spd_guard.hpp"

namespace rodnet {

class FroschPreconditioner : public GuardedPreconditioner {
public:
  // nullspace: rigid-body modes on the System's map (null: FROSch's constants).
  explicit FroschPreconditioner(const Teuchos::RCP<const TMV> &nullspace = Teuchos::null)
      : nullspace_(nullspace) {}
  void setup(System &sys) override;
  std::string name() const override { return "frosch"; }

private:
  Teuchos::RCP<const TMV> nullspace_;
};

} // namespace rodnet

#endif

// ifpack2.hpp - the "ifpack2" preconditioner (preconditioner.hpp), measured against
// the rod-level domain decomposition (docs/solvers.md): Ifpack2 additive Schwarz, one
// subdomain per rank with overlap 1, combined by addition (symmetric), each solved
// exactly by a local sparse LU (Amesos2 KLU2 on the rank's own matrix: never a
// distributed Amesos2 solve).  Made SPD for an indefinite Hessian by SpdGuard
// (spd_guard.hpp).  Needs the MPI runtime (mpi_backed).
#ifndef RODNET_SHIM_IFPACK2_HPP
#define RODNET_SHIM_IFPACK2_HPP

#include <string>

#include "pc/spd_guard.hpp"

namespace rodnet {

class SchwarzPreconditioner : public GuardedPreconditioner {
public:
  void setup(System &sys) override;
  std::string name() const override { return "ifpack2"; }
};

} // namespace rodnet

#endif

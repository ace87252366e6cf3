// preconditioner.hpp - symmetric positive definite preconditioners of the Newton
// systems H s = -g of the Newton-Krylov trust region (issue 7).
//
// A Preconditioner is set up once per Newton iteration from the assembled Hessian of a
// System (system.hpp), which may be indefinite (buckling, snap-through): it must
// nevertheless apply the inverse of a symmetric positive definite matrix M (shifting
// or modifying indefinite pieces), since preconditioned MINRES needs an SPD M and the
// trust region measures steps in the norm ||s||_M.  All members are collective over
// the System's communicator.
#ifndef RODNET_SHIM_PRECONDITIONER_HPP
#define RODNET_SHIM_PRECONDITIONER_HPP

#include <memory>
#include <string>

#include <Teuchos_RCP.hpp>
#include <Tpetra_Operator.hpp>

#include "system/system.hpp"

namespace rodnet {

// Work and cost of a preconditioner, summed over the solve on this rank.
struct PreconditionerStats {
  long setups = 0, applies = 0;
  double setup_seconds = 0.0, apply_seconds = 0.0;
  double bytes = 0.0;   // memory held after the last setup (this rank)
  bool shifted = false; // the last setup had to modify an indefinite piece
};

class Preconditioner {
public:
  virtual ~Preconditioner() = default;
  // Build M from the Hessian sys.hessian() assembled at the current state.
  virtual void setup(System &sys) = 0;
  // y = M^{-1} x on sys.map() (domain and range); valid after setup.
  virtual Teuchos::RCP<const Tpetra::Operator<>> inverse() const = 0;
  // Name as the user selects it ("factor", "dd", ...).
  virtual std::string name() const = 0;
  // True if the last setup made M = H exactly (an unshifted exact factorisation, e.g.
  // "factor", or "dd" with unshifted pieces and the direct coarse solve): M then
  // proves H positive definite, and the trust region needs no Lanczos test of it.
  virtual bool exact() const { return false; }
  // A pencil (S, A) whose definiteness is H's, smaller than (H, M), for the trust
  // region's Lanczos test (tr_krylov.cpp): S and an operator applying A^-1 (SPD),
  // valid until the next setup; false where the preconditioner has none (the
  // default) or the last setup gives none.  The DD's coarse pencil
  // (DdPreconditioner::coarse_pencil).
  virtual bool coarse_pencil(Teuchos::RCP<const Tpetra::Operator<>> & /*S*/,
                             Teuchos::RCP<const Tpetra::Operator<>> & /*Ainv*/) const {
    return false;
  }
  // True if inverse() takes a block of several columns in one call, with the messages
  // of one vector (the DD: one halo exchange and one coarse solve for the block); the
  // stability check's LOBPCG then applies it to the whole block, else column by column.
  virtual bool takes_blocks() const { return false; }
  const PreconditionerStats &stats() const { return stats_; }

protected:
  PreconditionerStats stats_;
};

} // namespace rodnet

#endif

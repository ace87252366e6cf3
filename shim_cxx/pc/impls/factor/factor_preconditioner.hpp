// factor_preconditioner.hpp - the "factor" preconditioner (preconditioner.hpp): the
// Cholesky factorisation (spd_factor.hpp: banded, sparse or CHOLMOD) of
// M = H + sigma D, D = |diag H| of the first setup (floored; fixed for the
// preconditioner's life, i.e. one load step), sigma >= 0 the smallest of 0, 1e-10,
// ..., 1e10 for which M factors (factor_shifted).  M = H (the exact inverse: MINRES
// converges in one iteration) when H is positive definite; stats().shifted says
// whether sigma > 0, i.e. whether H is not positive definite.  Serial: it needs a
// SerialSystem (the factorisation works on the whole matrix of one rank).
#ifndef RODNET_SHIM_FACTOR_PRECONDITIONER_HPP
#define RODNET_SHIM_FACTOR_PRECONDITIONER_HPP

#include <memory>
#include <vector>

#include "pc/preconditioner.hpp"
#include "rodnet_solve.h"
#include "factor/spd_factor.hpp"

namespace rodnet {

class FactorPreconditioner : public Preconditioner {
public:
  explicit FactorPreconditioner(rn_factorization kind) : kind_(kind) {}
  // Throws Error (RN_ERR_ARG) unless sys is a SerialSystem.
  void setup(System &sys) override;
  Teuchos::RCP<const Tpetra::Operator<>> inverse() const override { return op_; }
  std::string name() const override { return "factor"; }
  bool exact() const override { return sigma_ == 0.0; } // M = H: H positive definite
  double shift() const { return sigma_; }               // sigma of the last setup

private:
  rn_factorization kind_;
  std::unique_ptr<SpdFactor> factor_;
  std::vector<double> metric_;       // D as CSR values on the Hessian's pattern
  std::vector<double> metric_d_;     // D itself
  unsigned long metric_version_ = 0; // of the pattern metric_ is on
  double sigma_ = 0.0;
  Teuchos::RCP<const Tpetra::Operator<>> op_;
};

// The factor preconditioner of sys with the factorisation kind; throws Error
// (RN_ERR_ARG) unless sys is one whole network on one rank (a SerialSystem).
std::unique_ptr<Preconditioner> make_factor_preconditioner(const System &sys,
                                                           rn_factorization kind);

} // namespace rodnet

#endif

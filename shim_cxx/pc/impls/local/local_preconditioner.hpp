// local_preconditioner.hpp - the "local" preconditioner (preconditioner.hpp): block
// Jacobi over the ranks.  Each rank factors (rodnet's sparse Cholesky, METIS
// ordering) M_p = H_pp + sigma_p D_p, H_pp the block of the assembled Hessian on its
// owned DOFs (the rows and columns it owns: couplings to other ranks' DOFs are
// dropped), D = |diag H| of the first setup, floored at 1e-8 of its largest entry
// over all ranks (fixed for the preconditioner's life, one load step), sigma_p >= 0
// the smallest of 0, 1e-10, ..., 1e10 for which M_p factors.  M = diag(M_p) is
// symmetric positive definite; applying M^{-1} needs no communication.  On one rank
// M = H + sigma D, the factor preconditioner's matrix (MINRES takes one iteration
// where H is positive definite); on several ranks MINRES also resolves the coupling
// across the interface.  stats().shifted is true on every rank if some rank had to
// shift.  Works on any System (serial or distributed).
#ifndef RODNET_SHIM_LOCAL_PRECONDITIONER_HPP
#define RODNET_SHIM_LOCAL_PRECONDITIONER_HPP

#include <cstdint>
#include <memory>
#include <vector>

#include "pc/preconditioner.hpp"

namespace rodnet {

class SparseAnalysis;
class SparseCholesky;

class LocalPreconditioner : public Preconditioner {
public:
  LocalPreconditioner();
  ~LocalPreconditioner() override;
  void setup(System &sys) override;
  Teuchos::RCP<const Tpetra::Operator<>> inverse() const override { return op_; }
  std::string name() const override { return "local"; }
  double shift() const { return sigma_; } // this rank's sigma of the last setup

private:
  void build_pattern(const TCrs &H);

  size_t n_ = 0;                 // owned rows
  std::vector<int64_t> rowptr_;  // owned block: CSR, sorted columns
  std::vector<int32_t> col_;     //
  std::vector<size_t> src_;      // position of each entry in H's local values
  std::vector<double> vals_, m_; // block values; metric D on the pattern
  bool metric_done_ = false;
  std::shared_ptr<const SparseAnalysis> analysis_;
  std::unique_ptr<SparseCholesky> chol_;
  const SparseCholesky *chol_ptr_ = nullptr; // what the inverse operator applies
  double sigma_ = 0.0;
  Teuchos::RCP<const Tpetra::Operator<>> op_;
};

} // namespace rodnet

#endif

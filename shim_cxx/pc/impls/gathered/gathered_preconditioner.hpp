// gathered_preconditioner.hpp - the "gathered" preconditioner (preconditioner.hpp):
// the factor preconditioner's matrix M = H + sigma D (D = |diag H| of the first
// setup floored at 1e-8 of its largest entry, sigma the smallest of 0, 1e-10, ...,
// 1e10 for which M factors) on any number of ranks, by gathering the whole Hessian
// onto rank 0 (an Import to a map that lives there), factoring it there with rodnet's
// sparse Cholesky, and gathering / scattering the vectors of every apply.  Exact like
// the factor preconditioner (MINRES takes one iteration where H is positive definite,
// so a distributed solve takes the Newton steps of one rank), but rank 0 holds and
// factors the whole matrix: a reference for tests and small problems, not a scalable
// preconditioner (docs/parallel.md).  TRILINOS.md: Amesos2 on a distributed matrix is
// unreliable in 13.2, hence the gather.
#ifndef RODNET_SHIM_GATHERED_PRECONDITIONER_HPP
#define RODNET_SHIM_GATHERED_PRECONDITIONER_HPP

#include <cstdint>
#include <memory>
#include <vector>

#include <Tpetra_Import.hpp>

#include "pc/preconditioner.hpp"

namespace rodnet {

class SparseAnalysis;
class SparseCholesky;

class GatheredPreconditioner : public Preconditioner {
public:
  GatheredPreconditioner();
  ~GatheredPreconditioner() override;
  void setup(System &sys) override;
  Teuchos::RCP<const Tpetra::Operator<>> inverse() const override { return op_; }
  std::string name() const override { return "gathered"; }

private:
  void gather_values(const TCrs &Hg);

  Teuchos::RCP<const TMap> root_;               // every DOF on rank 0
  Teuchos::RCP<const Tpetra::Import<>> gather_; // owned -> root
  std::vector<int64_t> rowptr_;                 // rank 0: the whole pattern
  std::vector<int32_t> col_;
  std::vector<double> vals_, m_;
  std::shared_ptr<const SparseAnalysis> analysis_;
  std::unique_ptr<SparseCholesky> chol_;
  const SparseCholesky *chol_ptr_ = nullptr;
  bool metric_done_ = false;
  Teuchos::RCP<const Tpetra::Operator<>> op_;
};

} // namespace rodnet

#endif

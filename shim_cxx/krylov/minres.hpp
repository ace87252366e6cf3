// minres.hpp - Belos MINRES on Tpetra vectors for symmetric (possibly indefinite)
// Newton systems with a symmetric positive definite preconditioner.
//
// Operators are given as VectorOperator (y = A x on one-column Tpetra multivectors);
// MinresSolver adapts them to Tpetra::Operator (cached work vector: no allocation
// per apply) and runs Belos::MinresSolMgr from a zero initial guess.
#ifndef RODNET_SHIM_MINRES_HPP
#define RODNET_SHIM_MINRES_HPP

#include <cstddef>
#include <memory>

#include <Teuchos_RCP.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>

namespace rodnet {

using Map = Tpetra::Map<>;
using MV = Tpetra::MultiVector<>;

// One-rank map of n entries over self_comm() (runtime.hpp: MPI_COMM_SELF in MPI mode,
// a serial communicator otherwise).
Teuchos::RCP<const Map> make_local_map(size_t n);

// Host pointer to the (single) column of a multivector (Serial node: host = device).
double *host_data(MV &v);
const double *host_data(const MV &v);

class VectorOperator {
public:
  virtual ~VectorOperator() = default;
  virtual void apply(const MV &x, MV &y) const = 0; // y = A x
};

struct MinresResult {
  int iterations = 0;
  bool converged = false;
  double achieved_tol = 0.0; // relative residual reached
};

class MinresSolver {
public:
  MinresSolver(const Teuchos::RCP<const Map> &map, double rel_tol, int max_iterations);
  ~MinresSolver();
  MinresSolver(const MinresSolver &) = delete;
  MinresSolver &operator=(const MinresSolver &) = delete;

  // Solves A x = b (x is overwritten; the initial guess is zero) with the left
  // preconditioner prec (applies the inverse of an SPD matrix).
  MinresResult solve(const VectorOperator &A, const VectorOperator &prec, const MV &b,
                     MV &x);

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace rodnet

#endif

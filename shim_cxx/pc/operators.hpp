// operators.hpp - the VectorOperators (krylov/minres.hpp) of a System's assembled
// Hessian and of a Preconditioner's inverse, for MINRES solves on a distributed System
// (newton/dist_predictor.cpp, periodic/homogenize_dist.cpp).
#ifndef RODNET_SHIM_PC_OPERATORS_HPP
#define RODNET_SHIM_PC_OPERATORS_HPP

#include "krylov/minres.hpp"
#include "pc/preconditioner.hpp"
#include "system/system.hpp"

namespace rodnet {

// y = H x with the System's assembled Hessian.
class SystemHessianOp : public VectorOperator {
public:
  explicit SystemHessianOp(const System &s) : s_(s) {}
  void apply(const MV &x, MV &y) const override { s_.hessian()->apply(x, y); }

private:
  const System &s_;
};

// y = M^{-1} x with a preconditioner (after its setup).
class PreconditionerInverseOp : public VectorOperator {
public:
  explicit PreconditionerInverseOp(const Preconditioner &p) : p_(p) {}
  void apply(const MV &x, MV &y) const override { p_.inverse()->apply(x, y); }

private:
  const Preconditioner &p_;
};

} // namespace rodnet

#endif

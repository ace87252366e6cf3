// spd_factor.cpp - choice of the factorisation, the sparse implementation of
// SpdFactor, and the shifted factorisation (see spd_factor.hpp).
#include "spd_factor.hpp"

#include <string>

#include "banded.hpp"
#include "shim_error.hpp"
#include "sparse_cholesky.hpp"

namespace rodnet {

namespace {

class SparseSpd : public SpdFactor {
public:
  explicit SparseSpd(Problem &p) : chol_(p.sparse_analysis()) {}
  bool factor(const Problem &p, double shift, const double *m) override {
    return chol_.factor(p.values(), shift, m);
  }
  void solve(double *x) const override { chol_.solve(x); }
  bool factored() const override { return chol_.factored(); }

private:
  SparseCholesky chol_;
};

} // namespace

rn_factorization choose_factor_kind(const Problem &p, rn_factorization requested) {
  if (requested == RN_FACTOR_BANDED || requested == RN_FACTOR_SPARSE) return requested;
  return p.bandwidth() <= kBandedMaxBandwidth ? RN_FACTOR_BANDED : RN_FACTOR_SPARSE;
}

std::unique_ptr<SpdFactor> make_spd_factor(Problem &p, rn_factorization requested) {
  if (choose_factor_kind(p, requested) == RN_FACTOR_SPARSE)
    return std::make_unique<SparseSpd>(p);
  const double bytes =
      8.0 * static_cast<double>(p.size()) * static_cast<double>(p.bandwidth() + 1);
  if (bytes > 4.0 * 1024.0 * 1024.0 * 1024.0)
    throw Error(RN_ERR_ARG, "rn_solve: the banded factorisation would need " +
                                std::to_string(bytes / (1024.0 * 1024.0 * 1024.0)) +
                                " GiB (half bandwidth " + std::to_string(p.bandwidth()) +
                                "); use the sparse factorisation");
  return std::make_unique<BandedSpd>(p.size(), p.bandwidth());
}

double factor_shifted(SpdFactor &f, const Problem &p, double shift, const double *m) {
  if (f.factor(p, shift, m)) return 0.0;
  for (double sigma = 1e-10; sigma <= 1e10; sigma *= 10.0)
    if (f.factor(p, shift + sigma, m)) return sigma;
  throw Error(RN_ERR_LAPACK,
              "rn_solve: no diagonal shift makes the Hessian positive definite "
              "(non-finite Hessian?)");
}

} // namespace rodnet

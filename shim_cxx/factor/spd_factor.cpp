// spd_factor.cpp - choice of the factorisation, the sparse implementation of
// SpdFactor, and the shifted factorisation (see spd_factor.hpp).
#include "factor/spd_factor.hpp"

#include <cmath>
#include <string>

#include "factor/banded.hpp"
#include "factor/cholmod_factor.hpp"
#include "base/shim_error.hpp"
#include "factor/sparse_cholesky.hpp"

namespace rodnet {

namespace {

// The matrix's symbolic analysis for a sparse Cholesky class.
std::shared_ptr<const SparseAnalysis> analysis_for(const CsrMatrix &p, SparseCholesky *) {
  return p.sparse_analysis();
}
std::shared_ptr<const CholmodAnalysis> analysis_for(const CsrMatrix &p,
                                                    CholmodCholesky *) {
  return p.cholmod_analysis();
}

// SpdFactor on a sparse Cholesky class (SparseCholesky, CholmodCholesky) whose
// symbolic analysis the CsrMatrix computes once per pattern and shares; a new pattern
// (contact: CsrMatrix::pattern_version) takes the new analysis.
template <class Cholesky>
class SparseSpd : public SpdFactor {
public:
  explicit SparseSpd(const CsrMatrix &p)
      : chol_(new Cholesky(analysis_for(p, static_cast<Cholesky *>(nullptr)))),
        version_(p.pattern_version()) {}
  bool factor(const CsrMatrix &p, double shift, const double *m) override {
    if (p.pattern_version() != version_) {
      chol_.reset(); // (the old factor first: one in memory at a time)
      chol_.reset(new Cholesky(analysis_for(p, static_cast<Cholesky *>(nullptr))));
      version_ = p.pattern_version();
    }
    p.count_factorization();
    return chol_->factor(p.values(), shift, m);
  }
  void solve(double *x) const override { chol_->solve(x); }
  bool factored() const override { return chol_->factored(); }

private:
  std::unique_ptr<Cholesky> chol_;
  unsigned long version_;
};

} // namespace

rn_factorization choose_factor_kind(const CsrMatrix &p, rn_factorization requested) {
  if (requested == RN_FACTOR_BANDED || requested == RN_FACTOR_SPARSE ||
      requested == RN_FACTOR_CHOLMOD)
    return requested;
  if (p.pattern_varies()) return RN_FACTOR_SPARSE; // its pattern, and band, may change
  return p.bandwidth() <= kBandedMaxBandwidth ? RN_FACTOR_BANDED : RN_FACTOR_SPARSE;
}

std::unique_ptr<SpdFactor> make_spd_factor(const CsrMatrix &p,
                                           rn_factorization requested) {
  const rn_factorization kind = choose_factor_kind(p, requested);
  if (kind == RN_FACTOR_SPARSE) return std::make_unique<SparseSpd<SparseCholesky>>(p);
  if (kind == RN_FACTOR_CHOLMOD) return std::make_unique<SparseSpd<CholmodCholesky>>(p);
  const double bytes =
      8.0 * static_cast<double>(p.size()) * static_cast<double>(p.bandwidth() + 1);
  if (bytes > 4.0 * 1024.0 * 1024.0 * 1024.0)
    throw Error(RN_ERR_ARG, "rn_solve: the banded factorisation would need " +
                                std::to_string(bytes / (1024.0 * 1024.0 * 1024.0)) +
                                " GiB (half bandwidth " + std::to_string(p.bandwidth()) +
                                "); use the sparse factorisation");
  return std::make_unique<BandedSpd>(p.size(), p.bandwidth());
}

namespace {

// Gershgorin bound of the shift: with d the diagonal of M and A = H + shift M,
// A + sigma M is strictly diagonally dominant in the scaling D^-1/2 (so positive
// definite) for every sigma > max_i (sum_{j != i} |A_ij| / sqrt(d_i d_j) - A_ii / d_i).
// NaN if an entry of A is not finite or M has a diagonal entry that is not positive.
double gershgorin_shift(const CsrMatrix &p, double shift, const double *m) {
  const size_t n = p.size();
  const int64_t *rp = p.rowptr();
  const int32_t *col = p.col();
  const double *v = p.values();
  std::vector<double> d(n, 0.0);
  for (size_t i = 0; i < n; ++i)
    for (int64_t k = rp[i]; k < rp[i + 1]; ++k)
      if (static_cast<size_t>(col[k]) == i) d[i] = m[k];
  for (double di : d)
    if (!(di > 0.0) || !std::isfinite(di)) return std::nan("");
  double bound = 0.0;
  for (size_t i = 0; i < n; ++i) {
    double off = 0.0, diag = 0.0;
    for (int64_t k = rp[i]; k < rp[i + 1]; ++k) {
      const size_t j = static_cast<size_t>(col[k]);
      const double a = v[k] + shift * m[k];
      if (!std::isfinite(a)) return std::nan("");
      if (j == i)
        diag = a / d[i];
      else
        off += std::fabs(a) / std::sqrt(d[i] * d[j]);
    }
    bound = std::max(bound, off - diag);
  }
  return bound;
}

} // namespace

double factor_shifted(SpdFactor &f, const CsrMatrix &p, double shift, const double *m,
                      bool try_zero) {
  if (try_zero && f.factor(p, shift, m)) return 0.0;
  // Smallest k >= -10 with H + (shift + 10^k) M positive definite: bisection on k
  // (positive definiteness is monotone in the shift), then factor there.  The search
  // ends one decade above the Gershgorin bound, where the shifted matrix is
  // diagonally dominant with a margin, so a shift exists within the search whenever
  // the entries are finite.  (A fixed end, 10^10, failed where H had outgrown the
  // metric M: tr-minres fixes M = |diag H_0| for a load step, and on a rod started
  // nearly folded, 179 degrees, H grew 10^4-fold in two iterations and needed a shift
  // of about 10^12: docs/hard-cases.md.)
  const double g = m ? gershgorin_shift(p, shift, m) : std::nan("");
  if (!std::isfinite(g))
    throw Error(RN_ERR_LAPACK, "rn_solve: no diagonal shift makes the Hessian positive "
                               "definite (non-finite Hessian or metric)");
  const int top = std::min(
      300, std::max(10, static_cast<int>(std::ceil(std::log10(std::max(g, 1.0)))) + 1));
  // 10^lo fails (-11 stands for 0), 10^hi works (top + 1: not known yet)
  int lo = -11, hi = top + 1;
  bool holds_hi = false; // f holds the factorisation at 10^hi
  while (hi - lo > 1) {
    const int mid = lo + (hi - lo) / 2;
    holds_hi = f.factor(p, shift + std::pow(10.0, mid), m);
    (holds_hi ? hi : lo) = mid;
  }
  if (hi > top)
    throw Error(RN_ERR_LAPACK,
                "rn_solve: no diagonal shift up to 1e" + std::to_string(top) +
                    " (past the Gershgorin bound) makes the Hessian positive "
                    "definite (the factorisation breaks down)");
  const double sigma = std::pow(10.0, hi);
  if (!holds_hi && !f.factor(p, shift + sigma, m))
    throw Error(RN_ERR_LAPACK, "rn_solve: shifted factorisation failed");
  return sigma;
}

} // namespace rodnet

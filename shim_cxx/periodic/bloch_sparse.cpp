// bloch_sparse.cpp - SparseBloch (bloch_sparse.hpp).
#include "periodic/bloch_sparse.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "base/shim_error.hpp"
#include "factor/sparse_cholesky.hpp"
#include "krylov/lanczos.hpp"
#include "pc/shifted_cholesky.hpp"

namespace rodnet {
namespace {

constexpr double kLanczosTol = 1e-12; // Ritz residual estimate / theta
constexpr int kLanczosSteps = 400;

} // namespace

SparseBloch::SparseBloch(const rn_network *net, const double *x, size_t n)
    : net_(net), x_(x), n_(n), rp_(n + 1) {}

SparseBloch::~SparseBloch() = default;

// H(xi) into rp_, col_, re_, im_ (the arrays kept from the last call: one assembly
// unless the pattern grew).
void SparseBloch::assemble(const double *xi) {
  size_t nnz = col_.size();
  rn_status st = col_.empty()
                     ? RN_ERR_RANGE
                     : rn_network_bloch_hessian_csr(net_, x_, xi, &nnz, rp_.data(),
                                                    col_.data(), re_.data(), im_.data());
  if (st == RN_ERR_RANGE) {
    if (col_.empty() && (st = rn_network_bloch_hessian_csr(net_, x_, xi, &nnz, rp_.data(),
                                                           nullptr, nullptr, nullptr)))
      throw Error(st, rn_context_last_error(rn_network_context(net_)));
    col_.resize(nnz);
    re_.resize(nnz);
    im_.resize(nnz);
    st = rn_network_bloch_hessian_csr(net_, x_, xi, &nnz, rp_.data(), col_.data(),
                                      re_.data(), im_.data());
  }
  if (st) throw Error(st, rn_context_last_error(rn_network_context(net_)));
  col_.resize(nnz);
  re_.resize(nnz);
  im_.resize(nnz);
}

// K = [A -B; B A] of H on sel into kval_, its pattern into krp_, kcol_ (the analysis
// made again only where the pattern changed); kid_ the identity on it.
void SparseBloch::real_form(const std::vector<int> &sel) {
  const size_t m = sel.size();
  std::vector<int64_t> pos(n_, -1);
  for (size_t a = 0; a < m; ++a)
    pos[static_cast<size_t>(sel[a])] = static_cast<int64_t>(a);
  std::vector<int64_t> rp(2 * m + 1, 0);
  std::vector<int32_t> col;
  std::vector<double> val, id;
  col.reserve(4 * col_.size());
  val.reserve(4 * col_.size());
  // rows a (block row 1: A, -B) and m + a (block row 2: B, A); columns ascending as
  // H's are, the second block's after the first's
  for (int half = 0; half < 2; ++half)
    for (size_t a = 0; a < m; ++a) {
      const size_t i = static_cast<size_t>(sel[a]), row = half * m + a;
      bool diag = false;
      for (int blk = 0; blk < 2; ++blk)
        for (int64_t q = rp_[i]; q < rp_[i + 1]; ++q) {
          const int64_t b = pos[static_cast<size_t>(col_[static_cast<size_t>(q)])];
          if (b < 0) continue;
          const size_t c = static_cast<size_t>(blk) * m + static_cast<size_t>(b);
          const double re = re_[static_cast<size_t>(q)], im = im_[static_cast<size_t>(q)];
          col.push_back(static_cast<int32_t>(c));
          val.push_back(half == blk ? re : (half == 0 ? -im : im));
          id.push_back(c == row ? 1.0 : 0.0);
          diag |= c == row;
        }
      if (!diag)
        throw Error(RN_ERR_INTERNAL, "sparse Bloch: a diagonal entry of H is missing");
      rp[row + 1] = static_cast<int64_t>(col.size());
    }
  if (!analysis_ || rp != krp_ || col != kcol_) {
    analysis_.reset();
    krp_.swap(rp);
    kcol_.swap(col);
    analysis_ = std::make_shared<SparseAnalysis>(2 * m, krp_.data(), kcol_.data());
  }
  kval_.swap(val);
  kid_.swap(id);
}

double SparseBloch::lowest(const double *xi, const std::vector<int> &sel, double *vec) {
  assemble(xi);
  real_form(sel);
  const size_t m2 = 2 * sel.size();
  double dmax = 0.0;
  for (size_t i = 0; i < m2; ++i)
    for (int64_t q = krp_[i]; q < krp_[i + 1]; ++q)
      if (static_cast<size_t>(kcol_[static_cast<size_t>(q)]) == i)
        dmax = std::max(dmax, std::fabs(kval_[static_cast<size_t>(q)]));
  if (!(dmax > 0.0) || !std::isfinite(dmax))
    throw Error(RN_ERR_SOLVER,
                "sparse Bloch: the Bloch Hessian has no positive diagonal");
  for (double &e : kid_) e *= dmax; // the shifts in units of the largest diagonal entry
  SparseCholesky chol(analysis_);
  const double sigma = factor_smallest_shift(chol, kval_.data(), kid_.data());
  if (sigma < 0.0)
    throw Error(RN_ERR_SOLVER, "sparse Bloch: no shift up to 1e10 makes K + sigma I "
                               "positive definite");
  shift_ = sigma * dmax;
  std::vector<double> d(m2, 1.0), v(m2);
  for (size_t i = 0; i < m2; ++i)
    v[i] = 1.0 + 0.5 * std::sin(1.3 * static_cast<double>(i));
  const LanczosResult r = lanczos_largest(
      [&](double *z) { chol.solve(z); }, d,
      static_cast<int>(std::min<size_t>(m2, kLanczosSteps)), kLanczosTol, v);
  steps_ = r.steps;
  if (!r.converged || !(r.theta > 0.0))
    throw Error(RN_ERR_SOLVER, "sparse Bloch: Lanczos did not converge in " +
                                   std::to_string(r.steps) + " steps");
  if (vec) {
    std::fill(vec, vec + 2 * n_, 0.0);
    const size_t m = sel.size();
    double nv = 0.0;
    for (size_t a = 0; a < m2; ++a) nv += v[a] * v[a];
    nv = std::sqrt(nv);
    for (size_t a = 0; a < m; ++a) {
      const size_t dof = static_cast<size_t>(sel[a]);
      vec[2 * dof] = v[a] / nv;
      vec[2 * dof + 1] = v[m + a] / nv;
    }
  }
  return 1.0 / r.theta - shift_;
}

void SparseBloch::coupling(const double *xi, const std::vector<char> &mask, double *big,
                           double *cross) {
  assemble(xi);
  *big = *cross = 0.0;
  for (size_t i = 0; i < n_; ++i)
    for (int64_t q = rp_[i]; q < rp_[i + 1]; ++q) {
      const size_t j = static_cast<size_t>(col_[static_cast<size_t>(q)]);
      const double v =
          std::hypot(re_[static_cast<size_t>(q)], im_[static_cast<size_t>(q)]);
      *big = std::max(*big, v);
      if (mask[i] != mask[j]) *cross = std::max(*cross, v);
    }
}

} // namespace rodnet

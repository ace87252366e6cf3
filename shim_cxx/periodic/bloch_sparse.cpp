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

// The terms of the state (rn_network_bloch_terms) into rp_, col_, shift_n_, terms_,
// once.
void SparseBloch::fetch_terms() {
  if (terms_.empty()) {
    size_t nnz = 0;
    rn_status st = rn_network_bloch_terms(net_, x_, &nterms_, nullptr, &nnz, rp_.data(),
                                          nullptr, nullptr);
    if (!st) {
      col_.resize(nnz);
      shift_n_.resize(3 * static_cast<size_t>(nterms_));
      terms_.resize(static_cast<size_t>(nterms_) * nnz);
      st = rn_network_bloch_terms(net_, x_, &nterms_, shift_n_.data(), &nnz, rp_.data(),
                                  col_.data(), terms_.data());
    }
    if (st) throw Error(st, rn_context_last_error(rn_network_context(net_)));
    re_.resize(nnz);
    im_.resize(nnz);
  }
}

// H(xi) into rp_, col_, re_, im_: H(xi) = sum_t exp(2 pi i xi . n_t) T_t per wave
// vector, from the terms fetched once.
void SparseBloch::assemble(const double *xi) {
  fetch_terms();
  const size_t nnz = col_.size();
  std::fill(re_.begin(), re_.end(), 0.0);
  std::fill(im_.begin(), im_.end(), 0.0);
  for (int t = 0; t < nterms_; ++t) {
    const int *n = &shift_n_[3 * static_cast<size_t>(t)];
    const double ph =
        2.0 * M_PI * (xi[0] * n[0] + xi[1] * n[1] + (n[2] != 0 ? xi[2] * n[2] : 0.0));
    const double c = std::cos(ph), s = std::sin(ph);
    const double *v = &terms_[static_cast<size_t>(t) * nnz];
    for (size_t q = 0; q < nnz; ++q) {
      re_[q] += c * v[q];
      im_[q] += s * v[q];
    }
  }
}

void SparseBloch::gradient(const double *xi, const double *vec, int d, double *g) {
  fetch_terms();
  const size_t nnz = col_.size();
  // conj(v_i) v_j = a_q + i b_q per pattern entry q = (i, j)
  std::vector<double> a(nnz), b(nnz);
  for (size_t i = 0; i < n_; ++i)
    for (int64_t q = rp_[i]; q < rp_[i + 1]; ++q) {
      const size_t j = static_cast<size_t>(col_[static_cast<size_t>(q)]);
      const double vri = vec[2 * i], vii = vec[2 * i + 1], vrj = vec[2 * j],
                   vij = vec[2 * j + 1];
      a[static_cast<size_t>(q)] = vri * vrj + vii * vij;
      b[static_cast<size_t>(q)] = vri * vij - vii * vrj;
    }
  for (int k = 0; k < d; ++k) g[k] = 0.0;
  for (int t = 0; t < nterms_; ++t) {
    const int *n = &shift_n_[3 * static_cast<size_t>(t)];
    if (n[0] == 0 && n[1] == 0 && n[2] == 0) continue; // T_0 does not depend on xi
    const double *v = &terms_[static_cast<size_t>(t) * nnz];
    double cr = 0.0, ci = 0.0; // c_t = v^H T_t v
    for (size_t q = 0; q < nnz; ++q) {
      cr += v[q] * a[q];
      ci += v[q] * b[q];
    }
    double ph = 0.0;
    for (int k = 0; k < d; ++k) ph += xi[k] * n[k];
    ph *= 2.0 * M_PI;
    // Re(2 pi i n_a exp(i ph) c_t) = -2 pi n_a (sin(ph) cr + cos(ph) ci)
    const double f = -2.0 * M_PI * (std::sin(ph) * cr + std::cos(ph) * ci);
    for (int k = 0; k < d; ++k) g[k] += f * n[k];
  }
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
  double w = 0.0;
  lowest_k(xi, sel, 1, &w, vec);
  return w;
}

int SparseBloch::lowest_k(const double *xi, const std::vector<int> &sel, int k, double *w,
                          double *vec) {
  assemble(xi);
  real_form(sel);
  const size_t m2 = 2 * sel.size(), m = sel.size();
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
  const int kk = static_cast<int>(std::min<size_t>(static_cast<size_t>(k), m));
  std::vector<double> d(m2, 1.0), v(m2);
  std::vector<std::vector<double>> locked;
  steps_ = 0;
  for (int e = 0; e < kk; ++e) {
    for (size_t i = 0; i < m2; ++i)
      v[i] = 1.0 + 0.5 * std::sin(1.3 * static_cast<double>(i) + 0.7 * e);
    const int room = static_cast<int>(m2 - locked.size());
    const LanczosResult r = lanczos_largest([&](double *z) { chol.solve(z); }, d,
                                            std::min(room, kLanczosSteps), kLanczosTol, v,
                                            locked.empty() ? nullptr : &locked);
    steps_ += r.steps;
    if (!r.converged || !(r.theta > 0.0))
      throw Error(RN_ERR_SOLVER, "sparse Bloch: Lanczos did not converge in " +
                                     std::to_string(r.steps) + " steps");
    w[e] = 1.0 / r.theta - shift_;
    if (e == 0 && vec) {
      std::fill(vec, vec + 2 * n_, 0.0);
      for (size_t a = 0; a < m; ++a) {
        const size_t dof = static_cast<size_t>(sel[a]);
        vec[2 * dof] = v[a];
        vec[2 * dof + 1] = v[m + a];
      }
    }
    if (e + 1 < kk) { // lock v and its partner (-y, x): the same eigenvalue of H
      std::vector<double> p(m2);
      for (size_t a = 0; a < m; ++a) {
        p[a] = -v[m + a];
        p[m + a] = v[a];
      }
      locked.push_back(v);
      locked.push_back(p);
    }
  }
  return kk;
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

namespace rodnet {
namespace {

struct RealCsr {
  std::vector<int64_t> rp, col;
  std::vector<double> val;
};

// A real moment (rn_network_bloch_moment_csr; k1, k2 may be NULL) in CSR.
void moment_csr(const rn_network *net, const double *x, size_t n, const double *k1,
                const double *k2, RealCsr &m) {
  size_t nnz = 0;
  m.rp.assign(n + 1, 0);
  rn_status st =
      rn_network_bloch_moment_csr(net, x, k1, k2, &nnz, m.rp.data(), nullptr, nullptr);
  if (!st) {
    m.col.resize(nnz);
    m.val.resize(nnz);
    st = rn_network_bloch_moment_csr(net, x, k1, k2, &nnz, m.rp.data(), m.col.data(),
                                     m.val.data());
  }
  if (st) throw Error(st, rn_context_last_error(rn_network_context(net)));
}

} // namespace

bool sparse_acoustic_brackets(const rn_network *net, const double *x, size_t n, int d,
                              int na, const std::vector<int> &sel0,
                              const std::vector<int> &amp_of, std::vector<double> &Q) {
  const size_t m = sel0.size(), nA = static_cast<size_t>(na);
  std::vector<int64_t> pos(n, -1);
  for (size_t r = 0; r < m; ++r)
    pos[static_cast<size_t>(sel0[r])] = static_cast<int64_t>(r);
  // K = H(0) on sel0 and its factor
  RealCsr M;
  moment_csr(net, x, n, nullptr, nullptr, M);
  std::vector<int64_t> krp(m + 1, 0);
  std::vector<int32_t> kcol;
  std::vector<double> kval;
  for (size_t r = 0; r < m; ++r) {
    const size_t i = static_cast<size_t>(sel0[r]);
    for (int64_t q = M.rp[i]; q < M.rp[i + 1]; ++q) {
      const int64_t c = pos[static_cast<size_t>(M.col[static_cast<size_t>(q)])];
      if (c < 0) continue;
      kcol.push_back(static_cast<int32_t>(c));
      kval.push_back(M.val[static_cast<size_t>(q)]);
    }
    krp[r + 1] = static_cast<int64_t>(kcol.size());
  }
  auto analysis = std::make_shared<SparseAnalysis>(m, krp.data(), kcol.data());
  SparseCholesky chol(analysis);
  if (!chol.factor(kval.data(), 0.0, nullptr)) return false;
  // B_J = M1_J' T on sel0 (m x na, column-major) and X_J = K^-1 B_J
  std::vector<std::vector<double>> B(static_cast<size_t>(d)), X(static_cast<size_t>(d));
  for (int J = 0; J < d; ++J) {
    double e[3] = {0.0, 0.0, 0.0};
    e[J] = 1.0;
    moment_csr(net, x, n, e, nullptr, M);
    std::vector<double> &b = B[static_cast<size_t>(J)];
    b.assign(m * nA, 0.0);
    for (size_t i = 0; i < n; ++i) {
      const int a = amp_of[i];
      if (a < 0) continue;
      for (int64_t q = M.rp[i]; q < M.rp[i + 1]; ++q) {
        const int64_t r = pos[static_cast<size_t>(M.col[static_cast<size_t>(q)])];
        if (r >= 0)
          b[static_cast<size_t>(r) + static_cast<size_t>(a) * m] +=
              M.val[static_cast<size_t>(q)];
      }
    }
    X[static_cast<size_t>(J)] = b;
    for (int a = 0; a < na; ++a)
      chol.solve(X[static_cast<size_t>(J)].data() + static_cast<size_t>(a) * m);
  }
  auto q = [&](int J, int L, int a, int b) -> double & {
    return Q[static_cast<size_t>(((J * d + L) * na + a) * na + b)];
  };
  Q.assign(static_cast<size_t>(d * d * na * na), 0.0);
  for (int J = 0; J < d; ++J)
    for (int L = J; L < d; ++L) {
      double e1[3] = {0.0, 0.0, 0.0}, e2[3] = {0.0, 0.0, 0.0};
      e1[J] = 1.0;
      e2[L] = 1.0;
      moment_csr(net, x, n, e1, e2, M);
      std::vector<double> s(nA * nA, 0.0);
      for (size_t i = 0; i < n; ++i) {
        const int a = amp_of[i];
        if (a < 0) continue;
        for (int64_t p = M.rp[i]; p < M.rp[i + 1]; ++p) {
          const int b = amp_of[static_cast<size_t>(M.col[static_cast<size_t>(p)])];
          if (b >= 0) s[static_cast<size_t>(a * na + b)] += M.val[static_cast<size_t>(p)];
        }
      }
      for (int a = 0; a < na; ++a)
        for (int b = 0; b < na; ++b) {
          q(J, L, a, b) += -0.5 * s[static_cast<size_t>(a * na + b)];
          if (L != J) q(L, J, a, b) += -0.5 * s[static_cast<size_t>(a * na + b)];
        }
    }
  subtract_bx(d, na, m, B, X, Q);
  return true;
}

void subtract_bx(int d, int na, size_t m, const std::vector<std::vector<double>> &B,
                 const std::vector<std::vector<double>> &X, std::vector<double> &Q) {
  for (int J = 0; J < d; ++J)
    for (int L = 0; L < d; ++L)
      for (int a = 0; a < na; ++a)
        for (int b = 0; b < na; ++b) {
          double s = 0.0;
          const double *bj =
              B[static_cast<size_t>(J)].data() + static_cast<size_t>(a) * m;
          const double *xl =
              X[static_cast<size_t>(L)].data() + static_cast<size_t>(b) * m;
          for (size_t r = 0; r < m; ++r) s += bj[r] * xl[r];
          Q[static_cast<size_t>(((J * d + L) * na + a) * na + b)] -= s;
        }
}

} // namespace rodnet

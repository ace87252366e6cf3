// cholmod_factor.cpp - sparse Cholesky by CHOLMOD (see cholmod_factor.hpp).
//
// CHOLMOD's 64-bit interface (cholmod_l_*) on matrices whose arrays rodnet owns: the
// cholmod_sparse and cholmod_dense headers below point into std::vectors and are never
// freed by CHOLMOD.  One cholmod_common (workspace, settings, status) belongs to the
// analysis and is used by every factorisation made from it, one at a time.
#include "factor/cholmod_factor.hpp"

#include <cholmod.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "base/shim_error.hpp"

namespace rodnet {

struct CholmodState {
  cholmod_common c;
  cholmod_factor *symbolic = nullptr;
  CholmodState() {
    cholmod_l_start(&c);
    c.print = 0;                          // a library never prints
    c.error_handler = nullptr;            // errors are read from c.status
    c.nmethods = 1;                       // one ordering, no trials:
    c.method[0].ordering = CHOLMOD_METIS; // METIS_NodeND nested dissection
    c.postorder = 1;
    c.supernodal = CHOLMOD_SUPERNODAL; // dense BLAS/LAPACK blocks, LL'
    c.final_asis = 1;                  // keep the factor supernodal for reuse
    c.quick_return_if_not_posdef = 1;  // stop at the first non-positive pivot
  }
  ~CholmodState() {
    cholmod_l_free_factor(&symbolic, &c);
    cholmod_l_finish(&c);
  }
  CholmodState(const CholmodState &) = delete;
  CholmodState &operator=(const CholmodState &) = delete;

  // Throws Error for a failed CHOLMOD call (status < 0).
  void check(int ok, const char *what) {
    if (ok && c.status >= CHOLMOD_OK) return;
    const rn_status s = c.status == CHOLMOD_OUT_OF_MEMORY ? RN_ERR_ALLOC : RN_ERR_SOLVER;
    throw Error(s, std::string("rn_solve: CHOLMOD ") + what + " failed (status " +
                       std::to_string(c.status) + ")");
  }
};

namespace {

// Header of the upper triangle stored in a's arrays, values x (NULL: pattern only).
cholmod_sparse upper_header(size_t n, const std::vector<int64_t> &colptr,
                            const std::vector<int64_t> &rowind, double *x) {
  cholmod_sparse A{};
  A.nrow = A.ncol = n;
  A.nzmax = rowind.size();
  A.p = const_cast<int64_t *>(colptr.data());
  A.i = const_cast<int64_t *>(rowind.data());
  A.x = x;
  A.stype = 1; // symmetric, upper triangle stored
  A.itype = CHOLMOD_LONG;
  A.xtype = x ? CHOLMOD_REAL : CHOLMOD_PATTERN;
  A.dtype = CHOLMOD_DOUBLE;
  A.sorted = 1;
  A.packed = 1;
  return A;
}

// A dense single-column header over x[n].
cholmod_dense column_header(size_t n, double *x) {
  cholmod_dense B{};
  B.nrow = n;
  B.ncol = 1;
  B.nzmax = n;
  B.d = n;
  B.x = x;
  B.xtype = CHOLMOD_REAL;
  B.dtype = CHOLMOD_DOUBLE;
  return B;
}

// The upper triangle of a CSR pattern (both triangles, sorted columns) in compressed
// columns: row r of the CSR with columns c <= r is column r, rows ascending; csr_pos
// maps each entry to its CSR position.
void upper_of_csr(size_t n, const int64_t *rowptr, const int32_t *col,
                  std::vector<int64_t> &colptr, std::vector<int64_t> &rowind,
                  std::vector<int64_t> &csr_pos) {
  colptr.assign(n + 1, 0);
  for (size_t r = 0; r < n; ++r) {
    for (int64_t k = rowptr[r]; k < rowptr[r + 1]; ++k)
      if (static_cast<size_t>(col[k]) <= r) {
        rowind.push_back(col[k]);
        csr_pos.push_back(k);
      }
    colptr[r + 1] = static_cast<int64_t>(rowind.size());
  }
}

} // namespace

CholmodAnalysis::CholmodAnalysis(size_t n, const int64_t *rowptr, const int32_t *col)
    : n_(n), st_(std::make_unique<CholmodState>()) {
  upper_of_csr(n, rowptr, col, colptr_, rowind_, csr_pos_);
  cholmod_sparse A = upper_header(n, colptr_, rowind_, nullptr);
  st_->symbolic = cholmod_l_analyze(&A, &st_->c);
  st_->check(st_->symbolic != nullptr, "analysis");
  const cholmod_factor *L = st_->symbolic;
  if (!L->is_super)
    throw Error(RN_ERR_INTERNAL, "rn_solve: CHOLMOD factor not supernodal");
  nsuper_ = L->nsuper;
  lx_size_ = L->xsize;
  flops_ = st_->c.fl;
  const auto *pi = static_cast<const int64_t *>(L->pi);
  for (size_t s = 0; s < nsuper_; ++s)
    max_front_ = std::max(max_front_, static_cast<size_t>(pi[s + 1] - pi[s]));
}

CholmodAnalysis::~CholmodAnalysis() = default;

struct CholmodCholesky::Impl {
  cholmod_factor *L = nullptr;
  std::vector<double> ax;                                 // values of the upper triangle
  cholmod_dense *X = nullptr, *Y = nullptr, *E = nullptr; // solve2 workspace
};

CholmodCholesky::CholmodCholesky(std::shared_ptr<const CholmodAnalysis> analysis)
    : a_(std::move(analysis)), impl_(std::make_unique<Impl>()) {
  CholmodState &st = *a_->st_;
  impl_->L = cholmod_l_copy_factor(st.symbolic, &st.c);
  st.check(impl_->L != nullptr, "copy of the symbolic factor");
  impl_->ax.resize(a_->rowind_.size());
}

CholmodCholesky::~CholmodCholesky() {
  cholmod_common *c = &a_->st_->c;
  cholmod_l_free_factor(&impl_->L, c);
  cholmod_l_free_dense(&impl_->X, c);
  cholmod_l_free_dense(&impl_->Y, c);
  cholmod_l_free_dense(&impl_->E, c);
}

bool CholmodCholesky::factor(const double *vals, double shift, const double *m) {
  factored_ = false;
  std::vector<double> &ax = impl_->ax;
  const std::vector<int64_t> &pos = a_->csr_pos_;
  for (size_t k = 0; k < ax.size(); ++k) {
    ax[k] = m ? vals[pos[k]] + shift * m[pos[k]] : vals[pos[k]];
    if (!std::isfinite(ax[k])) return false; // not (numerically) positive definite
  }
  CholmodState &st = *a_->st_;
  cholmod_sparse A = upper_header(a_->n_, a_->colptr_, a_->rowind_, ax.data());
  const int ok = cholmod_l_factorize(&A, impl_->L, &st.c);
  if (st.c.status == CHOLMOD_NOT_POSDEF) return false;
  st.check(ok, "factorisation");
  factored_ = impl_->L->minor == a_->n_;
  return factored_;
}

void CholmodCholesky::solve(double *x) const {
  if (!factored_) throw Error(RN_ERR_INTERNAL, "rn_solve: sparse solve before factor");
  const size_t n = a_->n_;
  if (n == 0) return;
  cholmod_dense B = column_header(n, x);
  CholmodState &st = *a_->st_;
  const int ok = cholmod_l_solve2(CHOLMOD_A, impl_->L, &B, nullptr, &impl_->X, nullptr,
                                  &impl_->Y, &impl_->E, &st.c);
  st.check(ok, "solve");
  const auto *sol = static_cast<const double *>(impl_->X->x);
  std::copy(sol, sol + n, x);
}

// ---- LDL' -------------------------------------------------------------------------
struct CholmodLdl::Impl {
  cholmod_common c;
  cholmod_factor *L = nullptr;
  std::vector<int64_t> colptr, rowind, csr_pos;
  std::vector<double> ax, absd; // values of the upper triangle; |D| in P order
  Impl() {
    cholmod_l_start(&c);
    c.print = 0;
    c.error_handler = nullptr;
    c.nmethods = 1;
    c.method[0].ordering = CHOLMOD_METIS;
    c.postorder = 1;
    c.supernodal = CHOLMOD_SIMPLICIAL; // LDL' (a supernodal factor is LL' only)
    c.final_ll = 0;
    c.final_asis = 1;
    c.quick_return_if_not_posdef = 0; // negative pivots are expected
  }
  ~Impl() {
    cholmod_l_free_factor(&L, &c);
    cholmod_l_finish(&c);
  }
  void check(int ok, const char *what) {
    if (ok && c.status >= CHOLMOD_OK) return;
    const rn_status s = c.status == CHOLMOD_OUT_OF_MEMORY ? RN_ERR_ALLOC : RN_ERR_SOLVER;
    throw Error(s, std::string("CHOLMOD LDL' ") + what + " failed (status " +
                       std::to_string(c.status) + ")");
  }
};

CholmodLdl::CholmodLdl(size_t n, const int64_t *rowptr, const int32_t *col)
    : impl_(std::make_unique<Impl>()), n_(n) {
  Impl &m = *impl_;
  upper_of_csr(n, rowptr, col, m.colptr, m.rowind, m.csr_pos);
  m.ax.resize(m.rowind.size());
  cholmod_sparse A = upper_header(n, m.colptr, m.rowind, nullptr);
  m.L = cholmod_l_analyze(&A, &m.c);
  m.check(m.L != nullptr, "analysis");
}

CholmodLdl::~CholmodLdl() = default;

bool CholmodLdl::factor(const double *vals, double rel_floor) {
  Impl &m = *impl_;
  factored_ = false;
  negative_ = 0;
  for (size_t k = 0; k < m.ax.size(); ++k) {
    m.ax[k] = vals[m.csr_pos[k]];
    if (!std::isfinite(m.ax[k])) return false;
  }
  cholmod_sparse A = upper_header(n_, m.colptr, m.rowind, m.ax.data());
  const int ok = cholmod_l_factorize(&A, m.L, &m.c);
  if (m.c.status == CHOLMOD_NOT_POSDEF) return false; // a zero pivot
  m.check(ok, "factorisation");
  if (m.L->minor != n_ || m.L->is_ll || m.L->is_super) return false;
  // simplicial LDL': column j of L starts with D_jj (unit diagonal of L implied)
  const auto *lp = static_cast<const int64_t *>(m.L->p);
  const auto *lx = static_cast<const double *>(m.L->x);
  m.absd.resize(n_);
  double dmax = 0.0;
  for (size_t j = 0; j < n_; ++j) {
    const double d = lx[lp[j]];
    if (!std::isfinite(d) || d == 0.0) return false;
    negative_ += d < 0.0;
    m.absd[j] = std::fabs(d);
    dmax = std::max(dmax, m.absd[j]);
  }
  for (size_t j = 0; j < n_; ++j)
    if (m.absd[j] < rel_floor * dmax) return false; // a (nearly) singular pivot
  factored_ = true;
  return true;
}

void CholmodLdl::solve_abs(double *x) const {
  if (!factored_) throw Error(RN_ERR_INTERNAL, "CHOLMOD LDL' solve before factor");
  if (n_ == 0) return;
  Impl &m = *impl_;
  cholmod_dense B = column_header(n_, x);
  // y = L^-1 P x, y /= |D|, x = P' L'^-1 y
  cholmod_dense *Y = cholmod_l_solve(CHOLMOD_P, m.L, &B, &m.c);
  m.check(Y != nullptr, "permutation");
  cholmod_dense *Z = cholmod_l_solve(CHOLMOD_L, m.L, Y, &m.c);
  cholmod_l_free_dense(&Y, &m.c);
  m.check(Z != nullptr, "forward solve");
  auto *z = static_cast<double *>(Z->x);
  for (size_t j = 0; j < n_; ++j) z[j] /= m.absd[j];
  Y = cholmod_l_solve(CHOLMOD_Lt, m.L, Z, &m.c);
  cholmod_l_free_dense(&Z, &m.c);
  m.check(Y != nullptr, "backward solve");
  Z = cholmod_l_solve(CHOLMOD_Pt, m.L, Y, &m.c);
  cholmod_l_free_dense(&Y, &m.c);
  m.check(Z != nullptr, "permutation");
  const auto *r = static_cast<const double *>(Z->x);
  std::copy(r, r + n_, x);
  cholmod_l_free_dense(&Z, &m.c);
}

} // namespace rodnet

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

} // namespace

CholmodAnalysis::CholmodAnalysis(size_t n, const int64_t *rowptr, const int32_t *col)
    : n_(n), st_(std::make_unique<CholmodState>()) {
  // Row r of the CSR with columns c <= r is column r of the upper triangle, rows
  // ascending (the CSR columns are sorted).
  colptr_.assign(n + 1, 0);
  for (size_t r = 0; r < n; ++r) {
    for (int64_t k = rowptr[r]; k < rowptr[r + 1]; ++k)
      if (static_cast<size_t>(col[k]) <= r) {
        rowind_.push_back(col[k]);
        csr_pos_.push_back(k);
      }
    colptr_[r + 1] = static_cast<int64_t>(rowind_.size());
  }
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
  cholmod_dense B{};
  B.nrow = n;
  B.ncol = 1;
  B.nzmax = n;
  B.d = n;
  B.x = x;
  B.xtype = CHOLMOD_REAL;
  B.dtype = CHOLMOD_DOUBLE;
  CholmodState &st = *a_->st_;
  const int ok = cholmod_l_solve2(CHOLMOD_A, impl_->L, &B, nullptr, &impl_->X, nullptr,
                                  &impl_->Y, &impl_->E, &st.c);
  st.check(ok, "solve");
  const auto *sol = static_cast<const double *>(impl_->X->x);
  std::copy(sol, sol + n, x);
}

} // namespace rodnet

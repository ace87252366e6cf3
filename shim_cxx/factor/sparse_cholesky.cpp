// sparse_cholesky.cpp - supernodal multifrontal Cholesky (see sparse_cholesky.hpp).
//
// Notation: "new" indices are those of the permuted matrix C = P A P', column j of C
// is row/column perm_[j] of A.  Supernode s owns the columns [super_[s],
// super_[s+1]); its row structure rows(s) (sorted) starts with those columns, and
// its factor block is dense, column-major, rows(s) x columns, leading dimension
// |rows(s)|.
#include "factor/sparse_cholesky.hpp"

#include <metis.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <string>

#include "base/lapack.hpp"
#include "base/shim_error.hpp"

extern "C" {
// LAPACK / BLAS (Fortran) with gfortran's hidden character-length arguments.
void dtrsm_(const char *side, const char *uplo, const char *transa, const char *diag,
            const int *m, const int *n, const double *alpha, const double *a,
            const int *lda, double *b, const int *ldb, size_t, size_t, size_t, size_t);
void dgemv_(const char *trans, const int *m, const int *n, const double *alpha,
            const double *a, const int *lda, const double *x, const int *incx,
            const double *beta, double *y, const int *incy, size_t);
void dtrsv_(const char *uplo, const char *trans, const char *diag, const int *n,
            const double *a, const int *lda, double *x, const int *incx, size_t, size_t,
            size_t);
}

namespace rodnet {

namespace {

[[noreturn]] void fail(const std::string &what) {
  throw Error(RN_ERR_SOLVER, "rn_solve: sparse Cholesky: " + what);
}

int to_int(size_t v) {
  if (v > static_cast<size_t>(INT_MAX)) fail("a front exceeds BLAS's int");
  return static_cast<int>(v);
}

// Relaxed supernode amalgamation: merge a supernode of ncols columns, nbelow rows
// below them and nnz true entries when the fraction of explicit zeros stays below a
// limit that shrinks with its size (no limit up to 4 columns).
bool relax_ok(int64_t ncols, int64_t nbelow, int64_t nnz) {
  const double storage =
      0.5 * static_cast<double>(ncols) * static_cast<double>(ncols + 1) +
      static_cast<double>(ncols) * static_cast<double>(nbelow);
  const double zeros = (storage - static_cast<double>(nnz)) / storage;
  if (ncols <= 4) return true;
  if (ncols <= 16) return zeros < 0.8;
  if (ncols <= 48) return zeros < 0.1;
  return zeros < 0.05;
}

} // namespace

// ---- symbolic ---------------------------------------------------------------------

template <class F>
void SparseAnalysis::for_lower(int32_t j, F &&f) const {
  const size_t r = static_cast<size_t>(perm_[static_cast<size_t>(j)]);
  for (int64_t k = rowptr_[r]; k < rowptr_[r + 1]; ++k) {
    const int32_t i = iperm_[static_cast<size_t>(col_[k])];
    if (i >= j) f(i, k);
  }
}

SparseAnalysis::SparseAnalysis(size_t n, const int64_t *rowptr, const int32_t *col,
                               size_t nlast)
    : n_(n), nlast_(nlast), rowptr_(rowptr), col_(col) {
  if (n > static_cast<size_t>(INT32_MAX) - 1) fail("too many rows");
  if (nlast > n) fail("separator larger than the matrix");
  order();
  std::vector<int32_t> parent;
  elimination_tree(parent);
  // The separator as if its block were dense (its Schur complement is): a chain.  The
  // tree of the other columns does not depend on that block.
  const size_t ni = n_ - nlast_;
  for (size_t j = ni; j < n_; ++j)
    parent[j] = j + 1 < n_ ? static_cast<int32_t>(j + 1) : -1;
  postorder(parent);
  // Children come before a parent and in increasing order, so the chain stays last.
  for (size_t j = ni; j < n_; ++j)
    if (perm_[j] != static_cast<int32_t>(j)) fail("the separator moved in the postorder");
  std::vector<int64_t> cc;
  column_counts(parent, cc);
  for (size_t j = ni; j < n_; ++j) cc[j] = static_cast<int64_t>(n_ - j);
  supernodes(parent, cc);
  row_structure(parent);
  storage_plan();
}

// METIS nested dissection of the graph of A (diagonal removed) without the separator
// (the last nlast_ rows), which follows in its order.  A graph with at least half of
// all possible edges keeps its order (no ordering saves much fill there).
void SparseAnalysis::order() {
  perm_.resize(n_);
  iperm_.resize(n_);
  for (size_t i = 0; i < n_; ++i) perm_[i] = iperm_[i] = static_cast<int32_t>(i);
  const size_t ni = n_ - nlast_;
  const int64_t nnz = rowptr_[ni];
  if (nnz - static_cast<int64_t>(ni) > static_cast<int64_t>(INT32_MAX))
    fail("too many entries for METIS's 32-bit indices");
  if (ni <= 2) return; // nothing to order (and METIS needs a graph)
  std::vector<idx_t> xadj(ni + 1), adj;
  adj.reserve(static_cast<size_t>(nnz) - ni);
  for (size_t i = 0; i < ni; ++i) {
    xadj[i] = static_cast<idx_t>(adj.size());
    for (int64_t k = rowptr_[i]; k < rowptr_[i + 1]; ++k)
      if (static_cast<size_t>(col_[k]) != i && static_cast<size_t>(col_[k]) < ni)
        adj.push_back(col_[k]);
  }
  xadj[ni] = static_cast<idx_t>(adj.size());
  const double dni = static_cast<double>(ni);
  if (adj.empty() || static_cast<double>(adj.size()) >= 0.5 * dni * (dni - 1.0))
    return; // diagonal or dense
  idx_t nv = static_cast<idx_t>(ni), options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 7; // deterministic orderings
  options[METIS_OPTION_NUMBERING] = 0;
  const int rc = METIS_NodeND(&nv, xadj.data(), adj.data(), nullptr, options,
                              perm_.data(), iperm_.data());
  if (rc != METIS_OK) fail("METIS_NodeND failed (code " + std::to_string(rc) + ")");
}

// Elimination tree of C (Liu's algorithm with path compression).
void SparseAnalysis::elimination_tree(std::vector<int32_t> &parent) const {
  parent.assign(n_, -1);
  std::vector<int32_t> anc(n_, -1);
  for (size_t ii = 0; ii < n_; ++ii) {
    const int32_t i = static_cast<int32_t>(ii);
    const size_t r = static_cast<size_t>(perm_[ii]);
    for (int64_t k = rowptr_[r]; k < rowptr_[r + 1]; ++k) {
      int32_t j = iperm_[static_cast<size_t>(col_[k])];
      while (j != -1 && j < i) { // climb from j towards i, compressing the path
        const int32_t next = anc[static_cast<size_t>(j)];
        anc[static_cast<size_t>(j)] = i;
        if (next == -1) parent[static_cast<size_t>(j)] = i;
        j = next;
      }
    }
  }
}

// Relabels the ordering (and parent) in a postorder of the elimination tree: same
// fill, and every subtree, hence every supernode, is a range of columns.
void SparseAnalysis::postorder(std::vector<int32_t> &parent) {
  std::vector<int32_t> head(n_, -1), next(n_, -1), post(n_), stack;
  for (size_t j = n_; j-- > 0;) {
    const int32_t p = parent[j];
    if (p < 0) continue;
    next[j] = head[static_cast<size_t>(p)];
    head[static_cast<size_t>(p)] = static_cast<int32_t>(j);
  }
  size_t k = 0;
  for (size_t root = 0; root < n_; ++root) {
    if (parent[root] != -1) continue;
    stack.push_back(static_cast<int32_t>(root));
    while (!stack.empty()) {
      const size_t p = static_cast<size_t>(stack.back());
      const int32_t c = head[p];
      if (c == -1) {
        stack.pop_back();
        post[k++] = static_cast<int32_t>(p);
      } else {
        head[p] = next[static_cast<size_t>(c)];
        stack.push_back(c);
      }
    }
  }
  std::vector<int32_t> ipost(n_), perm2(n_), parent2(n_);
  for (size_t q = 0; q < n_; ++q)
    ipost[static_cast<size_t>(post[q])] = static_cast<int32_t>(q);
  for (size_t q = 0; q < n_; ++q) {
    const size_t old = static_cast<size_t>(post[q]);
    perm2[q] = perm_[old];
    parent2[q] = parent[old] < 0 ? -1 : ipost[static_cast<size_t>(parent[old])];
  }
  perm_.swap(perm2);
  parent.swap(parent2);
  for (size_t q = 0; q < n_; ++q)
    iperm_[static_cast<size_t>(perm_[q])] = static_cast<int32_t>(q);
}

// Column counts of L (diagonal included) by traversing each row's subtree.
void SparseAnalysis::column_counts(const std::vector<int32_t> &parent,
                                   std::vector<int64_t> &cc) const {
  cc.assign(n_, 1);
  std::vector<int32_t> mark(n_, -1);
  for (size_t ii = 0; ii < n_; ++ii) {
    const int32_t i = static_cast<int32_t>(ii);
    mark[ii] = i;
    const size_t r = static_cast<size_t>(perm_[ii]);
    for (int64_t k = rowptr_[r]; k < rowptr_[r + 1]; ++k) {
      int32_t j = iperm_[static_cast<size_t>(col_[k])];
      if (j >= i) continue;
      while (mark[static_cast<size_t>(j)] != i) { // i is an ancestor of j
        cc[static_cast<size_t>(j)]++;
        mark[static_cast<size_t>(j)] = i;
        j = parent[static_cast<size_t>(j)];
      }
    }
  }
}

// Fundamental supernodes, then relaxed amalgamation of a supernode into its parent
// when it is the parent's last child (adjacent columns).
void SparseAnalysis::supernodes(const std::vector<int32_t> &parent,
                                const std::vector<int64_t> &cc) {
  std::vector<int32_t> nchild(n_, 0), fstart;
  for (size_t j = 0; j < n_; ++j)
    if (parent[j] >= 0) nchild[static_cast<size_t>(parent[j])]++;
  const size_t ni = n_ - nlast_; // the separator is one supernode, never merged
  for (size_t j = 0; j < n_; ++j) {
    const bool joins =
        j > ni || (j > 0 && j != ni && parent[j - 1] == static_cast<int32_t>(j) &&
                   cc[j - 1] == cc[j] + 1 && nchild[j] == 1);
    if (!joins) fstart.push_back(static_cast<int32_t>(j));
  }
  fstart.push_back(static_cast<int32_t>(n_));
  const size_t nf = fstart.size() - 1;
  // Groups grow downwards: the group led by s covers supernodes s .. (next leader - 1).
  std::vector<int64_t> ncols(nf), nbelow(nf), nnz(nf);
  std::vector<char> leader(nf, 1);
  for (size_t s = 0; s < nf; ++s) {
    const size_t c0 = static_cast<size_t>(fstart[s]),
                 c1 = static_cast<size_t>(fstart[s + 1]);
    ncols[s] = static_cast<int64_t>(c1 - c0);
    nbelow[s] = cc[c0] - ncols[s];
    nnz[s] = 0;
    for (size_t j = c0; j < c1; ++j) nnz[s] += cc[j];
  }
  for (size_t s = nf - 1; s-- > 0;) {
    const size_t last = static_cast<size_t>(fstart[s + 1]) - 1;
    if (parent[last] != fstart[s + 1]) continue; // not the last child of s + 1
    if (nlast_ > 0 && static_cast<size_t>(fstart[s + 1]) == ni) continue;
    const int64_t nc = ncols[s] + ncols[s + 1], nb = nbelow[s + 1],
                  nz = nnz[s] + nnz[s + 1];
    if (!relax_ok(nc, nb, nz)) continue;
    ncols[s] = nc;
    nbelow[s] = nb;
    nnz[s] = nz;
    leader[s + 1] = 0;
  }
  super_.clear();
  for (size_t s = 0; s < nf; ++s)
    if (leader[s]) super_.push_back(fstart[s]);
  super_.push_back(static_cast<int32_t>(n_));
}

// Row structure of every supernode: its columns, the entries of C below them and the
// children's structures below their own columns.
void SparseAnalysis::row_structure(const std::vector<int32_t> &parent) {
  const size_t ns = super_.size() - 1;
  std::vector<int32_t> super_of(n_);
  for (size_t s = 0; s < ns; ++s)
    for (int32_t j = super_[s]; j < super_[s + 1]; ++j)
      super_of[static_cast<size_t>(j)] = static_cast<int32_t>(s);
  sparent_.assign(ns, -1);
  child_ptr_.assign(ns + 1, 0);
  for (size_t s = 0; s < ns; ++s) {
    const int32_t p = parent[static_cast<size_t>(super_[s + 1] - 1)];
    if (p < 0) continue;
    sparent_[s] = super_of[static_cast<size_t>(p)];
    child_ptr_[static_cast<size_t>(sparent_[s]) + 1]++;
  }
  for (size_t s = 0; s < ns; ++s) child_ptr_[s + 1] += child_ptr_[s];
  child_.assign(static_cast<size_t>(child_ptr_[ns]), 0);
  {
    std::vector<int32_t> fill(child_ptr_.begin(), child_ptr_.end() - 1);
    for (size_t s = 0; s < ns; ++s) // increasing: the order of the update stack
      if (sparent_[s] >= 0)
        child_[static_cast<size_t>(fill[static_cast<size_t>(sparent_[s])]++)] =
            static_cast<int32_t>(s);
  }
  std::vector<int32_t> mark(n_, -1);
  rows_ptr_.assign(ns + 1, 0);
  rows_.clear();
  for (size_t s = 0; s < ns; ++s) {
    const int32_t c0 = super_[s], c1 = super_[s + 1], tag = static_cast<int32_t>(s);
    const size_t begin = rows_.size();
    for (int32_t j = c0; j < c1; ++j) {
      rows_.push_back(j);
      mark[static_cast<size_t>(j)] = tag;
    }
    auto add = [&](int32_t i) {
      if (mark[static_cast<size_t>(i)] == tag) return;
      mark[static_cast<size_t>(i)] = tag;
      rows_.push_back(i);
    };
    for (int32_t j = c0; j < c1; ++j) for_lower(j, [&](int32_t i, int64_t) { add(i); });
    for (int32_t c = child_ptr_[s]; c < child_ptr_[s + 1]; ++c) {
      const size_t t = static_cast<size_t>(child_[static_cast<size_t>(c)]);
      const int64_t kt = super_[t + 1] - super_[t];
      for (int64_t q = rows_ptr_[t] + kt; q < rows_ptr_[t + 1]; ++q)
        add(rows_[static_cast<size_t>(q)]);
    }
    std::sort(rows_.begin() + static_cast<std::ptrdiff_t>(begin) + (c1 - c0),
              rows_.end());
    rows_ptr_[s + 1] = static_cast<int64_t>(rows_.size());
  }
}

// Factor storage, flop count, and the peak of the update-matrix stack.
void SparseAnalysis::storage_plan() {
  const size_t ns = super_.size() - 1;
  lx_ptr_.assign(ns + 1, 0);
  size_t top = 0;
  std::vector<size_t> usize(ns, 0);
  for (size_t s = 0; s < ns; ++s) {
    const size_t k = static_cast<size_t>(super_[s + 1] - super_[s]);
    const size_t m = static_cast<size_t>(rows_ptr_[s + 1] - rows_ptr_[s]), mu = m - k;
    lx_ptr_[s + 1] = lx_ptr_[s] + m * k;
    const double kd = static_cast<double>(k), mud = static_cast<double>(mu);
    if (nlast_ == 0 || s + 1 < ns) // the separator's block is not factored
      flops_ += kd * kd * kd / 3.0 + mud * kd * kd + mud * mud * kd;
    for (int32_t c = child_ptr_[s]; c < child_ptr_[s + 1]; ++c)
      top -= usize[static_cast<size_t>(child_[static_cast<size_t>(c)])];
    usize[s] = mu * mu;
    top += usize[s];
    stack_size_ = std::max(stack_size_, top);
    max_update_ = std::max(max_update_, mu * mu);
    max_front_ = std::max(max_front_, m);
  }
  lx_size_ = lx_ptr_[ns];
}

// ---- numeric ----------------------------------------------------------------------

SparseCholesky::SparseCholesky(std::shared_ptr<const SparseAnalysis> analysis)
    : a_(std::move(analysis)) {
  if (!a_) throw Error(RN_ERR_INTERNAL, "rn_solve: sparse Cholesky without analysis");
}

// Entries of C in the columns of supernode s into its block L (rows(s) x k).
void SparseCholesky::assemble(size_t s, const double *vals, double shift, const double *m,
                              const std::vector<int32_t> &relpos, double *L) const {
  const SparseAnalysis &a = *a_;
  const int32_t c0 = a.super_[s], c1 = a.super_[s + 1];
  const size_t ld = static_cast<size_t>(a.rows_ptr_[s + 1] - a.rows_ptr_[s]);
  for (int32_t j = c0; j < c1; ++j) {
    double *Lj = L + static_cast<size_t>(j - c0) * ld;
    a.for_lower(j, [&](int32_t i, int64_t k) {
      const double v = m ? vals[k] + shift * m[k] : vals[k];
      Lj[static_cast<size_t>(relpos[static_cast<size_t>(i)])] += v;
    });
  }
}

// Adds the update matrices of the children of s (on top of the stack, in order) into
// the pivot block L and the update block W of s, and pops them.
void SparseCholesky::extend_add(size_t s, const std::vector<int32_t> &relpos, double *L,
                                double *W, size_t &top) {
  const SparseAnalysis &a = *a_;
  const size_t k = static_cast<size_t>(a.super_[s + 1] - a.super_[s]);
  const size_t m = static_cast<size_t>(a.rows_ptr_[s + 1] - a.rows_ptr_[s]), mu = m - k;
  size_t total = 0;
  for (int32_t c = a.child_ptr_[s]; c < a.child_ptr_[s + 1]; ++c) {
    const size_t t = static_cast<size_t>(a.child_[static_cast<size_t>(c)]);
    const size_t mt = static_cast<size_t>(a.rows_ptr_[t + 1] - a.rows_ptr_[t]) -
                      static_cast<size_t>(a.super_[t + 1] - a.super_[t]);
    total += mt * mt;
  }
  const double *U = stack_.data() + (top - total);
  for (int32_t c = a.child_ptr_[s]; c < a.child_ptr_[s + 1]; ++c) {
    const size_t t = static_cast<size_t>(a.child_[static_cast<size_t>(c)]);
    const size_t kt = static_cast<size_t>(a.super_[t + 1] - a.super_[t]);
    const int32_t *rt = a.rows_.data() + a.rows_ptr_[t] + static_cast<int64_t>(kt);
    const size_t mt = static_cast<size_t>(a.rows_ptr_[t + 1] - a.rows_ptr_[t]) - kt;
    for (size_t jj = 0; jj < mt; ++jj) {
      const size_t lc = static_cast<size_t>(relpos[static_cast<size_t>(rt[jj])]);
      const double *Uj = U + jj * mt;
      if (lc < k) { // a pivot column of s
        double *Lc = L + lc * m;
        for (size_t ii = jj; ii < mt; ++ii)
          Lc[static_cast<size_t>(relpos[static_cast<size_t>(rt[ii])])] += Uj[ii];
      } else {
        double *Wc = W + (lc - k) * mu;
        for (size_t ii = jj; ii < mt; ++ii)
          Wc[static_cast<size_t>(relpos[static_cast<size_t>(rt[ii])]) - k] += Uj[ii];
      }
    }
    U += mt * mt;
  }
  top -= total;
}

bool SparseCholesky::factor(const double *vals, double shift, const double *m) {
  const SparseAnalysis &a = *a_;
  const size_t ns = a.super_.size() - 1;
  factored_ = false;
  lx_.assign(a.lx_size_, 0.0);
  stack_.resize(a.stack_size_);
  work_.resize(a.max_update_);
  std::vector<int32_t> relpos(a.n_, 0);
  size_t top = 0;
  const double one = 1.0, minus_one = -1.0;
  for (size_t s = 0; s < ns; ++s) {
    const size_t k = static_cast<size_t>(a.super_[s + 1] - a.super_[s]);
    const size_t mm = static_cast<size_t>(a.rows_ptr_[s + 1] - a.rows_ptr_[s]),
                 mu = mm - k;
    const int32_t *rows = a.rows_.data() + a.rows_ptr_[s];
    for (size_t i = 0; i < mm; ++i)
      relpos[static_cast<size_t>(rows[i])] = static_cast<int32_t>(i);
    double *L = lx_.data() + a.lx_ptr_[s], *W = work_.data();
    std::fill(W, W + mu * mu, 0.0);
    assemble(s, vals, shift, m, relpos, L);
    extend_add(s, relpos, L, W, top);
    if (s >= factored_supernodes()) break; // the separator: its Schur complement
    const int ki = to_int(k), mi = to_int(mm), mui = to_int(mu);
    int info = 0;
    dpotrf_("L", &ki, L, &mi, &info, 1);
    if (info != 0) return false;
    for (size_t j = 0; j < k; ++j) // a NaN pivot passes dpotrf's test
      if (!std::isfinite(L[j * mm + j])) return false;
    if (mu == 0) continue;
    dtrsm_("R", "L", "T", "N", &mui, &ki, &one, L, &mi, L + k, &mi, 1, 1, 1, 1);
    dsyrk_("L", "N", &mui, &ki, &minus_one, L + k, &mi, &one, W, &mui, 1, 1);
    std::copy(W, W + mu * mu, stack_.begin() + static_cast<std::ptrdiff_t>(top));
    top += mu * mu;
  }
  factored_ = true;
  return true;
}

// Supernode s of a factor in the solves: columns [c0, c0 + k), rows below them
// rows[k .. mm), dense block L (leading dimension mm).
struct SparseCholesky::Block {
  size_t c0, k, mu;
  int ki, mi, mui;
  const int32_t *rows;
  const double *L;
};

SparseCholesky::Block SparseCholesky::block(size_t s) const {
  const SparseAnalysis &a = *a_;
  Block b;
  b.c0 = static_cast<size_t>(a.super_[s]);
  b.k = static_cast<size_t>(a.super_[s + 1]) - b.c0;
  const size_t mm = static_cast<size_t>(a.rows_ptr_[s + 1] - a.rows_ptr_[s]);
  b.mu = mm - b.k;
  b.ki = static_cast<int>(b.k);
  b.mi = static_cast<int>(mm);
  b.mui = static_cast<int>(b.mu);
  b.rows = a.rows_.data() + a.rows_ptr_[s];
  b.L = lx_.data() + a.lx_ptr_[s];
  return b;
}

size_t SparseCholesky::factored_supernodes() const {
  const size_t ns = a_->super_.size() - 1;
  return a_->nlast_ > 0 ? ns - 1 : ns;
}

const double *SparseCholesky::schur() const {
  if (!factored_ || a_->nlast_ == 0)
    throw Error(RN_ERR_INTERNAL, "rn_solve: no Schur complement of a sparse factor");
  return lx_.data() + a_->lx_ptr_[factored_supernodes()];
}

void SparseCholesky::forward(double *x) const {
  if (!factored_) throw Error(RN_ERR_INTERNAL, "rn_solve: sparse solve before factor");
  const SparseAnalysis &a = *a_;
  const size_t n = a.n_, ns = factored_supernodes();
  std::vector<double> y(n), t(a.max_front_);
  for (size_t i = 0; i < n; ++i) y[i] = x[a.perm_[i]];
  const int inc = 1;
  const double one = 1.0, zero = 0.0;
  for (size_t s = 0; s < ns; ++s) { // L y = P b
    const Block b = block(s);
    dtrsv_("L", "N", "N", &b.ki, b.L, &b.mi, y.data() + b.c0, &inc, 1, 1, 1);
    if (b.mu == 0) continue;
    dgemv_("N", &b.mui, &b.ki, &one, b.L + b.k, &b.mi, y.data() + b.c0, &inc, &zero,
           t.data(), &inc, 1);
    for (size_t i = 0; i < b.mu; ++i) y[static_cast<size_t>(b.rows[b.k + i])] -= t[i];
  }
  for (size_t i = 0; i < n; ++i) x[a.perm_[i]] = y[i];
}

void SparseCholesky::backward(double *x) const {
  if (!factored_) throw Error(RN_ERR_INTERNAL, "rn_solve: sparse solve before factor");
  const SparseAnalysis &a = *a_;
  const size_t n = a.n_, ns = factored_supernodes();
  std::vector<double> y(n), t(a.max_front_);
  for (size_t i = 0; i < n; ++i) y[i] = x[a.perm_[i]];
  const int inc = 1;
  const double one = 1.0, minus_one = -1.0;
  for (size_t s = ns; s-- > 0;) { // L' z = y
    const Block b = block(s);
    if (b.mu > 0) {
      for (size_t i = 0; i < b.mu; ++i) t[i] = y[static_cast<size_t>(b.rows[b.k + i])];
      dgemv_("T", &b.mui, &b.ki, &minus_one, b.L + b.k, &b.mi, t.data(), &inc, &one,
             y.data() + b.c0, &inc, 1);
    }
    dtrsv_("L", "T", "N", &b.ki, b.L, &b.mi, y.data() + b.c0, &inc, 1, 1, 1);
  }
  for (size_t i = 0; i < n; ++i) x[a.perm_[i]] = y[i];
}

void SparseCholesky::solve(double *x) const {
  if (a_->nlast_ > 0)
    throw Error(RN_ERR_INTERNAL, "rn_solve: full solve with a partial sparse factor");
  forward(x);
  backward(x);
}

} // namespace rodnet

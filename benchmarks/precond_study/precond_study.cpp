// precond_study.cpp - measures candidate SPD preconditioners / factorisations of the
// Newton systems of a rod network (docs/solvers.md, "Choosing the factorisation").
//
//   bench_lattice ... --dump-system SYSTEM.bin      (benchmarks/: writes H, g, blocks)
//   rodnet_precond_study SYSTEM.bin [--csv FILE] [--skip-trilinos] [--skip-tacho]
//                        [--max-its N]
//
// On the dumped system (Hessian H and gradient g at a network's initial state, and
// the number of reduced DOFs of each rod, rods first, joints after them) the Newton
// system H s = -g is solved by Belos MINRES (relative tolerance 1e-10, the solver's
// default) with
//   sparse      rodnet's supernodal Cholesky (METIS nested dissection), and the
//               indefinite H - D/2 (D = |diag H|) to see that failure is detected;
//   cholmod     the same with SuiteSparse CHOLMOD's supernodal Cholesky (METIS);
//   tacho       Tacho's Driver (supernodal Cholesky) with its own ordering, and
//               H - D/2 (called directly: Amesos2 13.2's Tacho adapter never calls
//               Driver::initialize and crashes in the numeric factorisation of any
//               matrix of 1024 rows or more).  Debian's Tacho is built without METIS
//               and Scotch, and its own ordering leaves the joint DOFs last: the
//               factor is nearly dense (--skip-tacho skips it);
//   tacho-metis the same with the METIS nested-dissection ordering given to it;
//   klu2        Amesos2 + KLU2 (LU with partial pivoting), and H - D/2;
//   blockjacobi per-rod banded Cholesky of the rod's interior DOFs and a dense
//               Cholesky per joint block, each shifted (sigma D_block, sigma the
//               smallest of 0, 1e-10, 1e-9, ... that factors) to be SPD;
//   riluk-k     Ifpack2 RILUK with level of fill k = 0, 1, 2.
// Prints one line per method (setup time, time per application, MINRES iterations
// and time, what happened on H - D/2) and optionally appends CSV rows.  A study
// tool, not a test: it asserts nothing.
#include <metis.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <functional>
#include <string>
#include <vector>

#include <Amesos2.hpp>
#include <Ifpack2_Factory.hpp>
#include <Tacho_Driver.hpp>
#include <Tpetra_Core.hpp>
#include <Tpetra_CrsMatrix.hpp>

#include "base/clock.hpp"
#include "base/lapack.hpp"
#include "krylov/minres.hpp"
#include "factor/cholmod_factor.hpp"
#include "factor/sparse_cholesky.hpp"

namespace {

using namespace rodnet;

// The dumped system (format: bench_lattice.c, dump_system): CSR Hessian (both
// triangles), gradient, reduced DOFs of each rod.
class System {
public:
  bool read(const char *path);
  size_t size() const { return n_; }
  const int64_t *rowptr() const { return rowptr_.data(); }
  const int32_t *col() const { return col_.data(); }
  const double *values() const { return vals_.data(); }
  const std::vector<double> &gradient() const { return g_; }
  const std::vector<int64_t> &rod_dofs() const { return rod_dofs_; }
  void hessian_apply(const double *v, double *y) const {
    for (size_t i = 0; i < n_; ++i) {
      double sum = 0.0;
      for (int64_t k = rowptr_[i]; k < rowptr_[i + 1]; ++k) sum += vals_[k] * v[col_[k]];
      y[i] = sum;
    }
  }

private:
  size_t n_ = 0;
  std::vector<int64_t> rowptr_, rod_dofs_;
  std::vector<int32_t> col_;
  std::vector<double> vals_, g_;
};

template <class T>
bool read_array(FILE *f, std::vector<T> &v, size_t n) {
  v.resize(n);
  return n == 0 || std::fread(v.data(), sizeof(T), n, f) == n;
}

bool System::read(const char *path) {
  FILE *f = std::fopen(path, "rb");
  if (!f) return false;
  char magic[8] = {0};
  int64_t head[3] = {0, 0, 0}; // n, nnz, rods
  bool ok = std::fread(magic, 1, 8, f) == 8 && std::memcmp(magic, "RNSYS1\0\0", 8) == 0 &&
            std::fread(head, sizeof(int64_t), 3, f) == 3 && head[0] > 0 && head[1] > 0 &&
            head[2] >= 0;
  if (ok) {
    n_ = static_cast<size_t>(head[0]);
    ok = read_array(f, rowptr_, n_ + 1) &&
         read_array(f, col_, static_cast<size_t>(head[1])) &&
         read_array(f, vals_, static_cast<size_t>(head[1])) && read_array(f, g_, n_) &&
         read_array(f, rod_dofs_, static_cast<size_t>(head[2]));
  }
  std::fclose(f);
  return ok && rowptr_[n_] == head[1];
}

// D = |diag H| floored at 1e-8 max, and its CSR values on the pattern.
std::vector<double> metric(const System &p) {
  std::vector<double> d(p.size(), 0.0);
  double dmax = 0.0;
  for (size_t i = 0; i < p.size(); ++i)
    for (int64_t k = p.rowptr()[i]; k < p.rowptr()[i + 1]; ++k)
      if (static_cast<size_t>(p.col()[k]) == i) d[i] = std::fabs(p.values()[k]);
  for (double v : d) dmax = std::max(dmax, v);
  for (double &v : d) v = std::max(v, 1e-8 * dmax);
  return d;
}

std::vector<double> on_pattern(const System &p, const std::vector<double> &d) {
  std::vector<double> m(static_cast<size_t>(p.rowptr()[p.size()]), 0.0);
  for (size_t i = 0; i < p.size(); ++i)
    for (int64_t k = p.rowptr()[i]; k < p.rowptr()[i + 1]; ++k)
      if (static_cast<size_t>(p.col()[k]) == i) m[static_cast<size_t>(k)] = d[i];
  return m;
}
using CRS = Tpetra::CrsMatrix<>;

struct Row {
  std::string method, note;
  double setup = 0.0, apply = 0.0, minres_s = 0.0;
  int its = -1;
  bool converged = false;
};

class HessianOp : public VectorOperator {
public:
  explicit HessianOp(const System &p) : p_(p) {}
  void apply(const MV &x, MV &y) const override {
    p_.hessian_apply(host_data(x), host_data(y));
  }

private:
  const System &p_;
};

// y = P^{-1} x for a function solving in place.
class SolveOp : public VectorOperator {
public:
  explicit SolveOp(std::function<void(double *)> f) : f_(std::move(f)) {}
  void apply(const MV &x, MV &y) const override {
    const double *in = host_data(x);
    double *out = host_data(y);
    std::copy(in, in + x.getLocalLength(), out);
    f_(out);
  }

private:
  std::function<void(double *)> f_;
};

// MINRES on H s = -g with preconditioner prec; fills its, converged, minres_s.
void run_minres(System &p, const Teuchos::RCP<const Map> &map, const double *g,
                const VectorOperator &prec, int max_its, Row &row) {
  MinresSolver minres(map, 1e-10, max_its);
  MV b(map, 1), x(map, 1);
  double *bp = host_data(b);
  for (size_t i = 0; i < p.size(); ++i) bp[i] = -g[i];
  HessianOp A(p);
  const Clock::time_point t0 = Clock::now();
  try {
    const MinresResult r = minres.solve(A, prec, b, x);
    row.its = r.iterations;
    row.converged = r.converged;
  } catch (const std::exception &e) {
    row.note += std::string(" minres failed: ") + e.what();
  }
  row.minres_s = seconds_since(t0);
}

// Time per application of an in-place solve (median-free: mean of reps).
double time_apply(const std::function<void(double *)> &f, const double *g, size_t n) {
  std::vector<double> v(g, g + n);
  const int reps = 3;
  const Clock::time_point t0 = Clock::now();
  for (int r = 0; r < reps; ++r) f(v.data());
  return seconds_since(t0) / reps;
}

// Tpetra matrix of H + shift D (D on the diagonal).
Teuchos::RCP<CRS> tpetra_matrix(const System &p, const Teuchos::RCP<const Map> &map,
                                double shift, const std::vector<double> &d) {
  using GO = Map::global_ordinal_type;
  std::vector<size_t> counts(p.size());
  for (size_t i = 0; i < p.size(); ++i)
    counts[i] = static_cast<size_t>(p.rowptr()[i + 1] - p.rowptr()[i]);
  auto A = Teuchos::rcp(new CRS(map, Teuchos::ArrayView<const size_t>(counts)));
  std::vector<GO> cols;
  std::vector<double> vals;
  for (size_t i = 0; i < p.size(); ++i) {
    cols.clear();
    vals.clear();
    for (int64_t k = p.rowptr()[i]; k < p.rowptr()[i + 1]; ++k) {
      const size_t c = static_cast<size_t>(p.col()[k]);
      cols.push_back(static_cast<GO>(c));
      vals.push_back(p.values()[k] + (c == i ? shift * d[i] : 0.0));
    }
    A->insertGlobalValues(static_cast<GO>(i), Teuchos::ArrayView<const GO>(cols),
                          Teuchos::ArrayView<const double>(vals));
  }
  A->fillComplete();
  return A;
}

template <class Analysis, class Cholesky>
Row study_sparse(const char *name, System &p, const Teuchos::RCP<const Map> &map,
                 const double *g, const std::vector<double> &m, int max_its) {
  Row row;
  row.method = name;
  Clock::time_point t0 = Clock::now();
  auto a = std::make_shared<const Analysis>(p.size(), p.rowptr(), p.col());
  const double t_an = seconds_since(t0);
  Cholesky chol(a);
  t0 = Clock::now();
  bool ok = chol.factor(p.values(), 0.0, nullptr);
  const double t_f = seconds_since(t0);
  row.setup = t_an + t_f;
  // A second factorisation of the same object: what each Newton step pays.
  t0 = Clock::now();
  ok = chol.factor(p.values(), 0.0, nullptr) && ok;
  const double t_re = seconds_since(t0);
  char buf[320];
  std::snprintf(
      buf, sizeof buf,
      "analysis %.3f s, factor %.3f s, refactor %.3f s, nnz(L) %zu, %.3g flops, "
      "%zu supernodes, largest front %zu;",
      t_an, t_f, t_re, a->factor_entries(), a->factor_flops(), a->num_supernodes(),
      a->largest_front());
  row.note = buf;
  if (!ok) {
    row.note += " H not positive definite";
    return row;
  }
  auto f = [&](double *v) { chol.solve(v); };
  row.apply = time_apply(f, g, p.size());
  run_minres(p, map, g, SolveOp(f), max_its, row);
  Cholesky ind(a);
  t0 = Clock::now();
  const bool ind_ok = ind.factor(p.values(), -0.5, m.data());
  std::snprintf(buf, sizeof buf, " H-D/2: %s (%.3f s)",
                ind_ok ? "factored (NOT detected)" : "returned false", seconds_since(t0));
  row.note += buf;
  return row;
}

Row study_amesos2(const char *name, System &p, const Teuchos::RCP<const Map> &map,
                  const double *g, const std::vector<double> &d, int max_its) {
  Row row;
  row.method = name;
  auto A = tpetra_matrix(p, map, 0.0, d);
  auto X = Teuchos::rcp(new MV(map, 1)), B = Teuchos::rcp(new MV(map, 1));
  Teuchos::RCP<Amesos2::Solver<CRS, MV>> solver;
  char buf[256];
  const Clock::time_point t0 = Clock::now();
  double t_sym = 0.0;
  try {
    solver = Amesos2::create<CRS, MV>(name, A, X, B);
    solver->symbolicFactorization();
    t_sym = seconds_since(t0);
    solver->numericFactorization();
  } catch (const std::exception &e) {
    row.note = std::string("factorisation threw: ") + e.what();
    return row;
  }
  row.setup = seconds_since(t0);
  std::snprintf(buf, sizeof buf, "symbolic %.3f s, numeric %.3f s;", t_sym,
                row.setup - t_sym);
  row.note = buf;
  auto f = [&](double *v) {
    double *bp = host_data(*B);
    std::copy(v, v + p.size(), bp);
    solver->solve();
    const double *xp = host_data(*X);
    std::copy(xp, xp + p.size(), v);
  };
  row.apply = time_apply(f, g, p.size());
  run_minres(p, map, g, SolveOp(f), max_its, row);
  // The indefinite H - D/2: does the factorisation report it?
  auto Ai = tpetra_matrix(p, map, -0.5, d);
  try {
    auto si = Amesos2::create<CRS, MV>(name, Ai, X, B);
    si->symbolicFactorization();
    si->numericFactorization();
    row.note += " H-D/2: factored without error (NOT detected)";
  } catch (const std::exception &e) {
    row.note += std::string(" H-D/2: threw '") + e.what() + "'";
  }
  return row;
}

// METIS nested-dissection ordering of the graph of H (perm: new -> old).
void metis_order(const System &p, std::vector<idx_t> &perm, std::vector<idx_t> &iperm) {
  const size_t n = p.size();
  std::vector<idx_t> xadj(n + 1), adj;
  for (size_t i = 0; i < n; ++i) {
    xadj[i] = static_cast<idx_t>(adj.size());
    for (int64_t k = p.rowptr()[i]; k < p.rowptr()[i + 1]; ++k)
      if (static_cast<size_t>(p.col()[k]) != i) adj.push_back(p.col()[k]);
  }
  xadj[n] = static_cast<idx_t>(adj.size());
  idx_t nv = static_cast<idx_t>(n), options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 7;
  perm.resize(n);
  iperm.resize(n);
  METIS_NodeND(&nv, xadj.data(), adj.data(), nullptr, options, perm.data(), iperm.data());
}

Row study_tacho(System &p, const Teuchos::RCP<const Map> &map, const double *g,
                const std::vector<double> &d, int max_its, bool metis) {
  using Driver = Tacho::Driver<double, Kokkos::Device<Kokkos::Serial, Kokkos::HostSpace>>;
  Row row;
  row.method = metis ? "tacho-metis" : "tacho";
  Driver::ordinal_type_array_host perm("perm", p.size()), peri("peri", p.size());
  double t_order = 0.0;
  if (metis) {
    const Clock::time_point t0 = Clock::now();
    std::vector<idx_t> pm, ip;
    metis_order(p, pm, ip);
    for (size_t i = 0; i < p.size(); ++i) {
      perm(i) = pm[i];
      peri(i) = ip[i];
    }
    t_order = seconds_since(t0);
  }
  const size_t n = p.size(), nnz = static_cast<size_t>(p.rowptr()[n]);
  Driver::size_type_array_host ap("ap", n + 1);
  Driver::ordinal_type_array_host aj("aj", nnz);
  Driver::value_type_array_host ax("ax", nnz), axi("axi", nnz);
  for (size_t i = 0; i <= n; ++i) ap(i) = static_cast<size_t>(p.rowptr()[i]);
  for (size_t i = 0; i < n; ++i)
    for (int64_t k = p.rowptr()[i]; k < p.rowptr()[i + 1]; ++k) {
      const size_t c = static_cast<size_t>(p.col()[k]);
      aj(static_cast<size_t>(k)) = p.col()[k];
      ax(static_cast<size_t>(k)) = p.values()[k];
      axi(static_cast<size_t>(k)) = p.values()[k] - (c == i ? 0.5 * d[i] : 0.0);
    }
  Driver solver;
  solver.setMatrixType(2, true); // symmetric positive definite: Cholesky
  char buf[256];
  double t_sym = 0.0;
  const Clock::time_point t0 = Clock::now();
  try {
    if (metis)
      solver.analyze(static_cast<int>(n), ap, aj, perm, peri);
    else
      solver.analyze(static_cast<int>(n), ap, aj);
    solver.initialize();
    t_sym = seconds_since(t0);
    solver.factorize(ax);
  } catch (const std::exception &e) {
    row.note = std::string("factorisation threw: ") + e.what();
    return row;
  }
  row.setup = seconds_since(t0) + t_order;
  std::snprintf(buf, sizeof buf,
                "ordering %.3f s, analyze+initialize %.3f s, factorize "
                "%.3f s;",
                t_order, t_sym, row.setup - t_order - t_sym);
  row.note = buf;
  Driver::value_type_matrix_host X("x", n, 1), B("b", n, 1), T("t", n, 1);
  auto f = [&](double *v) {
    for (size_t i = 0; i < n; ++i) B(i, 0) = v[i];
    solver.solve(X, B, T);
    for (size_t i = 0; i < n; ++i) v[i] = X(i, 0);
  };
  row.apply = time_apply(f, g, n);
  run_minres(p, map, g, SolveOp(f), max_its, row);
  Driver ind;
  ind.setMatrixType(2, true);
  try {
    if (metis)
      ind.analyze(static_cast<int>(n), ap, aj, perm, peri);
    else
      ind.analyze(static_cast<int>(n), ap, aj);
    ind.initialize();
    ind.factorize(axi);
    row.note += " H-D/2: factored without error (NOT detected)";
  } catch (const std::exception &e) {
    row.note +=
        std::string(" H-D/2: threw '") + e.what() + "' (after printing to stderr)";
  }
  ind.release();
  solver.release();
  return row;
}

// Block Jacobi: rod interior blocks (banded) and joint blocks (dense), shifted SPD.
class BlockJacobi {
public:
  BlockJacobi(const System &p, const std::vector<double> &d, size_t tail,
              const std::vector<size_t> &rod_start)
      : p_(p), d_(d) {
    for (size_t r = 0; r + 1 < rod_start.size(); ++r)
      add_banded(rod_start[r], rod_start[r + 1]);
    // Joint blocks: consecutive tail rows whose columns are within the block's
    // first row's columns (a rigid joint's rotation rows join its position rows).
    size_t b = tail;
    while (b < p.size()) {
      size_t e = b + 1;
      while (e < p.size() && subset(e, b)) ++e;
      add_dense(b, e);
      b = e;
    }
  }
  void solve(double *x) const {
    for (const Block &b : blocks_) {
      const int n = static_cast<int>(b.end - b.begin), one = 1, kd = b.kd, ld = kd + 1;
      int info = 0;
      if (b.dense)
        dpotrs_("L", &n, &one, b.a.data(), &n, x + b.begin, &n, &info, 1);
      else
        dpbtrs_("L", &n, &kd, &one, b.a.data(), &ld, x + b.begin, &n, &info, 1);
    }
  }
  int shifted = 0;
  size_t nblocks() const { return blocks_.size(); }

private:
  struct Block {
    size_t begin, end;
    int kd;
    bool dense;
    std::vector<double> a;
  };
  bool subset(size_t row, size_t first) const {
    for (int64_t k = p_.rowptr()[row]; k < p_.rowptr()[row + 1]; ++k) {
      const int32_t c = p_.col()[k];
      if (!std::binary_search(p_.col() + p_.rowptr()[first],
                              p_.col() + p_.rowptr()[first + 1], c))
        return false;
    }
    return true;
  }
  double entry(size_t i, size_t j) const {
    const int32_t *b = p_.col() + p_.rowptr()[i], *e = p_.col() + p_.rowptr()[i + 1];
    const int32_t *q = std::lower_bound(b, e, static_cast<int32_t>(j));
    return (q != e && static_cast<size_t>(*q) == j) ? p_.values()[q - p_.col()] : 0.0;
  }
  void add_banded(size_t b, size_t e) {
    int kd = 0;
    for (size_t i = b; i < e; ++i)
      for (int64_t k = p_.rowptr()[i]; k < p_.rowptr()[i + 1]; ++k) {
        const size_t c = static_cast<size_t>(p_.col()[k]);
        if (c >= b && c < i) kd = std::max(kd, static_cast<int>(i - c));
      }
    Block blk{b, e, kd, false, {}};
    const size_t n = e - b, ld = static_cast<size_t>(kd) + 1;
    for (double sigma = 0.0; sigma <= 1e10; sigma = sigma == 0.0 ? 1e-10 : 10 * sigma) {
      blk.a.assign(n * ld, 0.0);
      for (size_t j = 0; j < n; ++j)
        for (size_t i = j; i < std::min(n, j + ld); ++i)
          blk.a[(i - j) + j * ld] =
              entry(b + i, b + j) + (i == j ? sigma * d_[b + i] : 0.0);
      const int ni = static_cast<int>(n), ldi = kd + 1;
      int info = 0;
      dpbtrf_("L", &ni, &kd, blk.a.data(), &ldi, &info, 1);
      if (info == 0) {
        shifted += sigma > 0.0;
        break;
      }
    }
    blocks_.push_back(std::move(blk));
  }
  void add_dense(size_t b, size_t e) {
    Block blk{b, e, 0, true, {}};
    const size_t n = e - b;
    for (double sigma = 0.0; sigma <= 1e10; sigma = sigma == 0.0 ? 1e-10 : 10 * sigma) {
      blk.a.assign(n * n, 0.0);
      for (size_t j = 0; j < n; ++j)
        for (size_t i = 0; i < n; ++i)
          blk.a[i + j * n] = entry(b + i, b + j) + (i == j ? sigma * d_[b + i] : 0.0);
      const int ni = static_cast<int>(n);
      int info = 0;
      dpotrf_("L", &ni, blk.a.data(), &ni, &info, 1);
      if (info == 0) {
        shifted += sigma > 0.0;
        break;
      }
    }
    blocks_.push_back(std::move(blk));
  }
  const System &p_;
  const std::vector<double> &d_;
  std::vector<Block> blocks_;
};

Row study_block_jacobi(System &p, const Teuchos::RCP<const Map> &map, const double *g,
                       const std::vector<double> &d, int max_its) {
  Row row;
  row.method = "blockjacobi";
  std::vector<size_t> start(1, 0);
  for (int64_t nr : p.rod_dofs()) start.push_back(start.back() + static_cast<size_t>(nr));
  if (start.back() > p.size()) {
    row.note = "rod DOFs exceed the system";
    return row;
  }
  const Clock::time_point t0 = Clock::now();
  BlockJacobi bj(p, d, start.back(), start);
  row.setup = seconds_since(t0);
  char buf[128];
  std::snprintf(buf, sizeof buf, "%zu blocks, %d shifted to be SPD;", bj.nblocks(),
                bj.shifted);
  row.note = buf;
  auto f = [&](double *v) { bj.solve(v); };
  row.apply = time_apply(f, g, p.size());
  run_minres(p, map, g, SolveOp(f), max_its, row);
  return row;
}

Row study_riluk(int level, System &p, const Teuchos::RCP<const Map> &map, const double *g,
                const std::vector<double> &d, int max_its) {
  Row row;
  row.method = "riluk-" + std::to_string(level);
  auto A = tpetra_matrix(p, map, 0.0, d);
  Ifpack2::Factory factory;
  Teuchos::RCP<Ifpack2::Preconditioner<>> prec;
  const Clock::time_point t0 = Clock::now();
  try {
    prec = factory.create<CRS>("RILUK", A);
    Teuchos::ParameterList params;
    params.set("fact: iluk level-of-fill", level);
    prec->setParameters(params);
    prec->initialize();
    prec->compute();
  } catch (const std::exception &e) {
    row.note = std::string("setup threw: ") + e.what();
    return row;
  }
  row.setup = seconds_since(t0);
  MV in(map, 1), out(map, 1);
  auto f = [&](double *v) {
    std::copy(v, v + p.size(), host_data(in));
    prec->apply(in, out);
    const double *o = host_data(out);
    std::copy(o, o + p.size(), v);
  };
  row.apply = time_apply(f, g, p.size());
  run_minres(p, map, g, SolveOp(f), max_its, row);
  return row;
}

int study(const char *path, const char *csv, bool trilinos, bool tacho, int max_its) {
  System p;
  if (!p.read(path)) {
    std::fprintf(stderr, "precond_study: cannot read the system dump %s\n", path);
    return 1;
  }
  const size_t n = p.size();
  const double *g = p.gradient().data();
  const std::vector<double> d = metric(p);
  const std::vector<double> m = on_pattern(p, d);
  std::printf("%s: %zu DOFs, nnz(H) %lld, %zu rods\n", path, n,
              static_cast<long long>(p.rowptr()[n]), p.rod_dofs().size());
  auto map = make_local_map(n);
  std::vector<Row> rows;
  rows.push_back(
      study_sparse<SparseAnalysis, SparseCholesky>("sparse", p, map, g, m, max_its));
  rows.push_back(
      study_sparse<CholmodAnalysis, CholmodCholesky>("cholmod", p, map, g, m, max_its));
  if (trilinos) {
    if (tacho) rows.push_back(study_tacho(p, map, g, d, max_its, false));
    rows.push_back(study_tacho(p, map, g, d, max_its, true));
    rows.push_back(study_amesos2("KLU2", p, map, g, d, max_its));
  }
  rows.push_back(study_block_jacobi(p, map, g, d, max_its));
  if (trilinos)
    for (int level = 0; level <= 2; ++level)
      rows.push_back(study_riluk(level, p, map, g, d, max_its));
  FILE *out = csv ? std::fopen(csv, "a") : nullptr;
  if (out &&
      std::ftell(out) == 0) // the benchmarks' CSV convention (benchmarks/README.md)
    std::fprintf(out, "commit,compiler,flags,ranks,bench,case,size,repeats,median,min,"
                      "system,method,setup_s,apply_s,minres_iterations,minres_converged,"
                      "minres_s,note\n");
  const char *base = std::strrchr(path, '/') ? std::strrchr(path, '/') + 1 : path;
  for (const Row &r : rows) {
    std::printf("  %-12s setup %8.3f s  apply %8.4f s  minres %5d its %s %8.3f s  %s\n",
                r.method.c_str(), r.setup, r.apply, r.its,
                r.converged ? "(conv)" : "(NOT) ", r.minres_s, r.note.c_str());
    if (!out) continue;
    // One timed run: median = min = setup + MINRES solve of H s = -g.
    const double t = r.setup + r.minres_s;
    std::string note = r.note; // one CSV field: no quotes or line breaks
    std::replace(note.begin(), note.end(), '"', '\'');
    std::replace(note.begin(), note.end(), '\n', ' ');
    std::fprintf(out,
                 "\"%s\",\"%s\",\"%s\",1,precond,%s,%zu,1,%.6e,%.6e,%s,%s,%.6f,%.6f,"
                 "%d,%d,%.6f,\"%s\"\n",
                 RN_STUDY_COMMIT, RN_STUDY_COMPILER, RN_STUDY_FLAGS, r.method.c_str(), n,
                 t, t, base, r.method.c_str(), r.setup, r.apply, r.its,
                 r.converged ? 1 : 0, r.minres_s, note.c_str());
  }
  if (out) std::fclose(out);
  return 0;
}

} // namespace

int main(int argc, char **argv) {
  const char *system = nullptr, *csv = nullptr;
  bool trilinos = true, tacho = true;
  int max_its = 3000;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--csv") && i + 1 < argc)
      csv = argv[++i];
    else if (!std::strcmp(argv[i], "--skip-trilinos"))
      trilinos = false;
    else if (!std::strcmp(argv[i], "--skip-tacho"))
      tacho = false;
    else if (!std::strcmp(argv[i], "--max-its") && i + 1 < argc)
      max_its = std::atoi(argv[++i]);
    else
      system = argv[i];
  }
  if (!system) {
    std::fprintf(stderr, "usage: rodnet_precond_study SYSTEM.bin [--csv FILE] "
                         "[--skip-trilinos] [--skip-tacho] [--max-its N]\n");
    return 2;
  }
  Tpetra::ScopeGuard guard(&argc, &argv);
  try {
    return study(system, csv, trilinos, tacho, max_its);
  } catch (const std::exception &e) {
    std::fprintf(stderr, "precond_study: %s\n", e.what());
    return 1;
  }
}

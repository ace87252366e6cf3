// cell_path.cpp - strain paths and Bloch-Floquet stability of periodic cells
// (rn_cell_relax, rn_cell_bloch, rn_cell_bloch_eigen; docs/homogenization.md,
// "Strain paths and stability").  Dense LAPACK or the sparse route
// (bloch_sparse.hpp) for the Bloch eigenproblems; no Trilinos here.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <complex>
#include <limits>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "base/lapack.hpp"
#include "periodic/acoustic.hpp"
#include "periodic/bloch_sparse.hpp"
#include "periodic/cell_part.hpp"
#include "periodic/homogenize.hpp"
#include "base/nonconservative.hpp"
#include "system/problem.hpp"
#include "rodnet_solve.h"
#include "base/shim_error.hpp"
#include "factor/cholmod_factor.hpp"
#include "factor/sparse_cholesky.hpp"
#include "krylov/minres_local.hpp"

extern "C" {
// LAPACK (Fortran) with the hidden character-length arguments of gfortran.
void zheevr_(const char *jobz, const char *range, const char *uplo, const int *n,
             std::complex<double> *a, const int *lda, const double *vl, const double *vu,
             const int *il, const int *iu, const double *abstol, int *m, double *w,
             std::complex<double> *z, const int *ldz, int *isuppz,
             std::complex<double> *work, const int *lwork, double *rwork,
             const int *lrwork, int *iwork, const int *liwork, int *info, size_t, size_t,
             size_t);
void dsysv_(const char *uplo, const int *n, const int *nrhs, double *a, const int *lda,
            int *ipiv, double *b, const int *ldb, double *work, const int *lwork,
            int *info, size_t);
}

namespace rodnet {
namespace {

using cplx = std::complex<double>;
constexpr size_t kMaxDense = 4000; // dense Bloch / indefinite solves up to this size
// RN_BLOCH_AUTO: dense up to this many Bloch DOFs, sparse beyond (measured: a
// honeycomb path with 51 Bloch DOFs 0.15 s dense, 0.20 s sparse; 99 DOFs 0.32 s
// dense, 0.24 s sparse; 396 DOFs 4.4 s dense, 0.76 s sparse)
constexpr size_t kAutoSparse = 64;

double max_abs(size_t n, const double *a) {
  double m = 0.0;
  for (size_t i = 0; i < n; ++i) m = std::max(m, std::fabs(a[i]));
  return m;
}

// ---- rn_cell_relax -------------------------------------------------------------

// x_u <- x_u + alpha s (the first nu entries), into xt.
void trial(const std::vector<double> &x, const std::vector<double> &s, double alpha,
           size_t nu, std::vector<double> &xt) {
  xt = x;
  for (size_t i = 0; i < nu; ++i) xt[i] += alpha * s[i];
}

// Solves K_uu s = rhs densely (symmetric indefinite, LAPACK dsysv); false if singular.
bool dense_indefinite_solve(const CellBlocks &cb, std::vector<double> &rhs) {
  const int n = static_cast<int>(cb.nu), one = 1;
  std::vector<double> a(cb.nu * cb.nu, 0.0);
  for (size_t i = 0; i < cb.nu; ++i)
    for (int64_t q = cb.urp[i]; q < cb.urp[i + 1]; ++q)
      a[static_cast<size_t>(cb.ucol[static_cast<size_t>(q)]) * cb.nu + i] =
          cb.uval[static_cast<size_t>(q)];
  std::vector<int> ipiv(cb.nu);
  int info = 0, lwork = -1;
  double wq = 0.0;
  dsysv_("L", &n, &one, a.data(), &n, ipiv.data(), rhs.data(), &n, &wq, &lwork, &info, 1);
  lwork = std::max(1, static_cast<int>(wq));
  std::vector<double> work(static_cast<size_t>(lwork));
  dsysv_("L", &n, &one, a.data(), &n, ipiv.data(), rhs.data(), &n, work.data(), &lwork,
         &info, 1);
  if (info != 0) return false;
  for (double v : rhs)
    if (!std::isfinite(v)) return false;
  return true;
}

class Relax {
public:
  // descend: a minimisation that may leave the cell-periodic branch (rn_cell_minimize)
  // method (rn_bloch_method): the indefinite solves past an instability, dense
  // (LAPACK dsysv, up to kMaxDense DOFs), sparse (MINRES preconditioned by |LDL'|:
  // indefinite_solve) or auto (dense up to kMaxDense, sparse beyond)
  Relax(rn_network *net, bool descend, int method = RN_BLOCH_AUTO)
      : p_(net), cb_(p_, descend ? "rn_cell_minimize" : "rn_cell_relax", false),
        descend_(descend), method_(method) {
    x_.resize(cb_.n);
    g_.resize(cb_.n);
    check_status(rn_network_get_dofs(net, x_.data()), "rn_network_get_dofs");
    std::vector<int> kind(cb_.n);
    check_status(rn_network_dof_kinds(net, kind.data()), "rn_network_dof_kinds");
    double xpos = 0.0;
    for (size_t i = 0; i < cb_.nu; ++i)
      if (kind[i] == RN_DOF_POSITION) xpos = std::max(xpos, std::fabs(x_[i]));
    delta_.resize(cb_.nu);
    for (size_t i = 0; i < cb_.nu; ++i)
      delta_[i] = DBL_EPSILON * (kind[i] == RN_DOF_POSITION ? xpos : 1.0);
  }

  void run(const double *strain, rn_cell_relax_report &rep) {
    const size_t nu = cb_.nu;
    double E = 0.0;
    if (p_.gradient(x_.data(), &E, g_.data()) != RN_OK)
      throw Error(RN_ERR_GEOMETRY, "rn_cell_relax: the starting state is degenerate");
    factor_at(x_);
    std::vector<double> xs(x_);
    for (int v = 0; v < cb_.ns; ++v)
      xs[nu + static_cast<size_t>(v)] = strain[cb_.comp[v]];
    // the tangent predictor from the current (equilibrium) state; where K_uu is
    // indefinite (the principal branch past an instability, not minimising) with the
    // indefinite solve, kept if it lowers |g_u| (without it Newton starts from the
    // old fluctuations at the new strain and, in a supercell with many unstable
    // modes, may converge to a bifurcated equilibrium instead)
    std::vector<double> s(nu);
    for (size_t i = 0; i < nu; ++i) {
      double r = g_[i];
      for (int v = 0; v < cb_.ns; ++v)
        r += cb_.kue[static_cast<size_t>(v) * nu + i] *
             (strain[cb_.comp[v]] - x_[nu + static_cast<size_t>(v)]);
      s[i] = -r;
    }
    std::vector<double> xt;
    if (pd_) {
      chol_->solve(s.data());
      trial(xs, s, 1.0, nu, xt);
      double Et = 0.0, Es = 0.0;
      if (p_.energy(xt.data(), &Et) == RN_OK && p_.energy(xs.data(), &Es) == RN_OK &&
          Et <= Es) {
        xs = xt;
        rep.predictor = 1;
      }
    } else if (!descend_ && indefinite_solve(s, rep.sparse_solves)) {
      trial(xs, s, 1.0, nu, xt);
      std::vector<double> gs(cb_.n), gt(cb_.n);
      double Eg = 0.0;
      if (p_.gradient(xt.data(), &Eg, gt.data()) == RN_OK &&
          p_.gradient(xs.data(), &Eg, gs.data()) == RN_OK && unorm(gt) <= unorm(gs)) {
        xs = xt;
        rep.predictor = 1;
      }
    }
    x_ = xs;
    p_.accept(x_.data());
    if (descend_)
      descent(rep);
    else
      newton(rep);
  }

private:
  void factor_at(const std::vector<double> &x) {
    p_.assemble_hessian(x.data());
    cb_.extract(p_);
    if (!chol_) {
      rp_ = cb_.urp;
      col_ = cb_.ucol;
      chol_ = std::make_unique<SparseCholesky>(
          std::make_shared<SparseAnalysis>(cb_.nu, rp_.data(), col_.data()));
    }
    pd_ = chol_->factor(cb_.uval.data(), 0.0, nullptr);
  }

  // largest |g_u| and largest balancing force at x_
  void residual(double &res, double &scale) {
    const size_t nu = cb_.nu;
    std::vector<double> gabs(cb_.n);
    check_status(rn_network_gradient_magnitude(p_.network(), x_.data(), gabs.data()),
                 "rn_network_gradient_magnitude");
    res = max_abs(nu, g_.data());
    scale = max_abs(nu, gabs.data());
  }

  // Converged: |g_u| at most 1e-9 of the largest balancing force, or at the
  // round-off floor of the gradient: the largest |K_uu| delta, delta the last bit
  // of every coordinate (DBL_EPSILON times the largest |position| for positions, 1
  // for angles: as dist_system.cpp's floor; K_uu of the last factor_at).  The
  // balancing forces vanish where nothing loads the cell (the rest state, a zero
  // strain or stress step), and the relative test alone then asked round-off to
  // beat itself: a trivial path failed at its second step (issue 22).
  bool converged(double res, double scale) const {
    if (res <= 1e-9 * scale) return true;
    double floor = 0.0;
    for (size_t i = 0; i < cb_.nu; ++i) {
      double row = 0.0;
      for (int64_t q = cb_.urp[i]; q < cb_.urp[i + 1]; ++q)
        row += std::fabs(cb_.uval[static_cast<size_t>(q)]) *
               delta_[static_cast<size_t>(cb_.ucol[static_cast<size_t>(q)])];
      floor = std::max(floor, row);
    }
    return res <= floor;
  }

  double unorm(const std::vector<double> &g) const {
    double s = 0.0;
    for (size_t i = 0; i < cb_.nu; ++i) s += g[i] * g[i];
    return std::sqrt(s);
  }

  void newton(rn_cell_relax_report &rep) {
    const size_t nu = cb_.nu;
    std::vector<double> s(nu), xt, gt(cb_.n);
    for (int it = 0; it < 100; ++it) {
      double E = 0.0, res = 0.0, scale = 0.0;
      if (p_.gradient(x_.data(), &E, g_.data()) != RN_OK)
        throw Error(RN_ERR_GEOMETRY, "rn_cell_relax: degenerate state");
      residual(res, scale);
      rep.residual = res;
      rep.residual_scale = scale;
      factor_at(x_);
      rep.indefinite = !pd_;
      if (converged(res, scale)) {
        rep.converged = 1;
        return;
      }
      for (size_t i = 0; i < nu; ++i) s[i] = -g_[i];
      if (pd_)
        chol_->solve(s.data());
      else if (!indefinite_solve(s, rep.sparse_solves))
        return;
      const double gs = dot(nu, g_.data(), s.data()), g0 = unorm(g_);
      double alpha = 1.0;
      bool accepted = false;
      for (; alpha > 1e-10 && !accepted; alpha *= 0.5) {
        trial(x_, s, alpha, nu, xt);
        double Et = 0.0;
        if (pd_) {
          accepted = p_.energy(xt.data(), &Et) == RN_OK && Et <= E + 1e-4 * alpha * gs;
        } else {
          accepted = p_.gradient(xt.data(), &Et, gt.data()) == RN_OK &&
                     unorm(gt) <= (1.0 - 1e-4 * alpha) * g0;
        }
        if (accepted) break;
      }
      ++rep.iterations;
      if (!accepted) return;
      const double step = alpha * max_abs(nu, s.data());
      x_ = xt;
      p_.accept(x_.data());
      if (step <= 1e-14 * (1.0 + max_abs(cb_.n, x_.data()))) {
        p_.gradient(x_.data(), &E, g_.data());
        residual(rep.residual, rep.residual_scale);
        rep.converged = 1;
        return;
      }
    }
  }

  // s <- K_uu^-1 s where K_uu is indefinite (the Newton step on the principal branch
  // past an instability); false if it cannot be solved (singular, no convergence).
  // Sparse: MINRES on K_uu preconditioned by |LDL'| (CHOLMOD's LDL' of K_uu with
  // |D|: the preconditioned spectrum is +-1, two or three iterations), or where
  // that factorisation has a (nearly) zero pivot by the Cholesky factor of
  // K_uu + mu D, the smallest shift that factors (slower: many negative modes
  // spread its spectrum); solved to 1e-10 and accepted as an inexact Newton step if
  // the true residual is below 1e-4 of the gradient (the line search on |g| then
  // still descends).
  bool indefinite_solve(std::vector<double> &s, int &sparse_solves) {
    const size_t nu = cb_.nu;
    const bool sparse =
        method_ == RN_BLOCH_SPARSE || (method_ != RN_BLOCH_DENSE && nu > kMaxDense);
    if (!sparse) return nu <= kMaxDense && dense_indefinite_solve(cb_, s);
    if (!ldl_) ldl_ = std::make_unique<CholmodLdl>(nu, cb_.urp.data(), cb_.ucol.data());
    const bool have_ldl = ldl_->factor(cb_.uval.data());
    if (!have_ldl) {
      std::vector<double> d;
      diag_pattern(d);
      factor_shifted(d);
    }
    std::vector<double> b(s), r(nu);
    const LocalApply A = [this](const double *x, double *y) { kuu_apply(x, y); };
    const LocalApply M = [this, nu, have_ldl](const double *x, double *y) {
      std::copy(x, x + nu, y);
      if (have_ldl)
        ldl_->solve_abs(y);
      else
        chol_->solve(y);
    };
    const LocalMinresResult res = minres_local(nu, A, M, b.data(), s.data(), 1e-10, 1000);
    kuu_apply(s.data(), r.data());
    double rn = 0.0, bn = 0.0;
    for (size_t i = 0; i < nu; ++i) {
      rn = std::max(rn, std::fabs(r[i] - b[i]));
      bn = std::max(bn, std::fabs(b[i]));
      if (!std::isfinite(s[i])) return false;
    }
    ++sparse_solves;
    return res.iterations > 0 && rn <= 1e-4 * bn;
  }

  // y = K_uu x (the blocks of the last factor_at).
  void kuu_apply(const double *x, double *y) const {
    for (size_t i = 0; i < cb_.nu; ++i) {
      double t = 0.0;
      for (int64_t q = cb_.urp[i]; q < cb_.urp[i + 1]; ++q)
        t += cb_.uval[static_cast<size_t>(q)] * x[cb_.ucol[static_cast<size_t>(q)]];
      y[i] = t;
    }
  }

  // D = |diag K_uu| on the pattern of K_uu (floored at 1e-12 of its largest entry).
  void diag_pattern(std::vector<double> &d) const {
    d.assign(cb_.uval.size(), 0.0);
    double dmax = 0.0;
    for (size_t i = 0; i < cb_.nu; ++i)
      for (int64_t q = cb_.urp[i]; q < cb_.urp[i + 1]; ++q)
        if (static_cast<size_t>(cb_.ucol[static_cast<size_t>(q)]) == i)
          dmax = std::max(dmax, std::fabs(cb_.uval[static_cast<size_t>(q)]));
    for (size_t i = 0; i < cb_.nu; ++i)
      for (int64_t q = cb_.urp[i]; q < cb_.urp[i + 1]; ++q)
        if (static_cast<size_t>(cb_.ucol[static_cast<size_t>(q)]) == i)
          d[static_cast<size_t>(q)] =
              std::max(std::fabs(cb_.uval[static_cast<size_t>(q)]), 1e-12 * dmax);
  }

  // Factor K_uu + mu D with the smallest mu = 0 or 1e-10 * 4^k that is positive
  // definite; returns mu (the factor is in chol_).
  double factor_shifted(const std::vector<double> &d) {
    if (pd_) return 0.0;
    for (double mu = 1e-10; mu < 1e3; mu *= 4.0)
      if (chol_->factor(cb_.uval.data(), mu, d.data())) return mu;
    throw Error(RN_ERR_SOLVER, "rn_cell_minimize: no positive definite shift of K_uu");
  }

  // Lowest eigenvector of the pencil (K_uu, D) by inverse iteration with the
  // shifted factor (mu > 0: K_uu + mu D positive definite); returns the Rayleigh
  // quotient.
  double lowest_mode(const std::vector<double> &d, std::vector<double> &v) {
    const size_t nu = cb_.nu;
    std::vector<double> dv(nu), kv(nu);
    std::vector<double> dd(nu, 0.0);
    for (size_t i = 0; i < nu; ++i)
      for (int64_t q = cb_.urp[i]; q < cb_.urp[i + 1]; ++q)
        if (static_cast<size_t>(cb_.ucol[static_cast<size_t>(q)]) == i)
          dd[i] = d[static_cast<size_t>(q)];
    v.assign(nu, 0.0);
    for (size_t i = 0; i < nu; ++i)
      v[i] = 1.0 + 0.37 * std::sin(1.7 * static_cast<double>(i));
    double rq = 0.0;
    for (int it = 0; it < 60; ++it) {
      for (size_t i = 0; i < nu; ++i) dv[i] = dd[i] * v[i];
      chol_->solve(dv.data());
      const double m = max_abs(nu, dv.data());
      if (!(m > 0.0)) break;
      for (size_t i = 0; i < nu; ++i) v[i] = dv[i] / m;
      // Rayleigh quotient v'Kv / v'Dv
      kuu_apply(v.data(), kv.data());
      double vkv = 0.0, vdv = 0.0;
      for (size_t i = 0; i < nu; ++i) {
        vkv += v[i] * kv[i];
        vdv += v[i] * dd[i] * v[i];
      }
      const double rq_new = vkv / vdv;
      if (it > 5 && std::fabs(rq_new - rq) <= 1e-10 * std::fabs(rq_new)) {
        rq = rq_new;
        break;
      }
      rq = rq_new;
    }
    return rq;
  }

  // Minimisation of the energy over the fluctuations: Newton with the Cholesky
  // factor of K_uu + mu D (mu = 0 where K_uu is positive definite, else the smallest
  // shift that factors), an Armijo backtracking line search on the energy, and,
  // where the gradient vanishes but K_uu is indefinite (a saddle), a step along the
  // lowest mode of (K_uu, D).  Converged only at a state with K_uu positive definite.
  void descent(rn_cell_relax_report &rep) {
    const size_t nu = cb_.nu;
    std::vector<double> s(nu), xt, d, v;
    int saddle_steps = 0;
    for (int it = 0; it < 200; ++it) {
      double E = 0.0, res = 0.0, scale = 0.0;
      if (p_.gradient(x_.data(), &E, g_.data()) != RN_OK)
        throw Error(RN_ERR_GEOMETRY, "rn_cell_minimize: degenerate state");
      residual(res, scale);
      rep.residual = res;
      rep.residual_scale = scale;
      factor_at(x_);
      rep.indefinite = !pd_;
      diag_pattern(d);
      const bool small = converged(res, scale);
      if (small && pd_) {
        rep.converged = 1;
        return;
      }
      const double mu = factor_shifted(d);
      bool accepted = false;
      if (!small) {
        for (size_t i = 0; i < nu; ++i) s[i] = -g_[i];
        chol_->solve(s.data());
        const double gs = dot(nu, g_.data(), s.data());
        for (double alpha = 1.0; alpha > 1e-12 && !accepted; alpha *= 0.5) {
          trial(x_, s, alpha, nu, xt);
          double Et = 0.0;
          accepted = p_.energy(xt.data(), &Et) == RN_OK && Et <= E + 1e-4 * alpha * gs;
        }
      }
      if (!accepted && !pd_ && saddle_steps < 20) {
        // negative curvature: the lowest mode, both signs, from a step of 1e-3 of
        // the cell size up, backtracking
        ++saddle_steps;
        lowest_mode(d, v);
        const double gv = dot(nu, g_.data(), v.data());
        if (gv > 0.0)
          for (double &vi : v) vi = -vi;
        const double h = 1e-2 * std::pow(cb_.measure, 1.0 / cb_.dim);
        for (double alpha = h; alpha > 1e-8 * h && !accepted; alpha *= 0.5) {
          trial(x_, v, alpha, nu, xt);
          double Et = 0.0;
          accepted = p_.energy(xt.data(), &Et) == RN_OK && Et < E;
        }
      }
      ++rep.iterations;
      if (!accepted) return;
      double step = 0.0;
      for (size_t i = 0; i < nu; ++i) step = std::max(step, std::fabs(xt[i] - x_[i]));
      x_ = xt;
      p_.accept(x_.data());
      if (mu == 0.0 && step <= 1e-14 * (1.0 + max_abs(cb_.n, x_.data()))) {
        p_.gradient(x_.data(), &E, g_.data()); // stalled at round-off on a minimum
        residual(rep.residual, rep.residual_scale);
        rep.converged = 1;
        return;
      }
    }
  }

  Problem p_;
  CellBlocks cb_;
  std::vector<double> x_, g_;
  std::vector<double> delta_; // last bit of each fluctuation DOF (converged())
  std::vector<int64_t> rp_;
  std::vector<int32_t> col_;
  std::unique_ptr<SparseCholesky> chol_;
  bool pd_ = false;
  bool descend_ = false;
  int method_ = RN_BLOCH_AUTO;
  std::unique_ptr<CholmodLdl> ldl_; // the sparse indefinite solves' preconditioner
};

// ---- Bloch-Floquet analysis -----------------------------------------------------

class Bloch {
public:
  // sparse: 0 dense only (cells up to kMaxDense Bloch DOFs), 1 sparse beyond that,
  // 2 sparse at any size (SparseBloch), 3 sparse beyond kAutoSparse (RN_BLOCH_AUTO)
  Bloch(rn_network *net, rn_bloch_modes modes, int sparse = 0) : net_(net) {
    check_status(rn_network_cell_info(net, &dim_, nullptr, &measure_, nullptr),
                 "rn_network_cell_info");
    if (dim_ == 0) throw Error(RN_ERR_ARG, "rn_cell_bloch: the network is not periodic");
    check_status(rn_network_bloch_dofs(net, &n_, nullptr, nullptr),
                 "rn_network_bloch_dofs");
    if (n_ > kMaxDense && sparse == 0)
      throw Error(RN_ERR_ARG, "rn_cell_bloch: the cell has " + std::to_string(n_) +
                                  " Bloch DOFs; the dense Bloch analysis takes at most " +
                                  std::to_string(kMaxDense) +
                                  " (RN_BLOCH_SPARSE takes any size)");
    sparse_ = sparse == 2 || n_ > kMaxDense || (sparse == 3 && n_ > kAutoSparse);
    kind_.resize(n_);
    comp_.resize(n_);
    check_status(rn_network_bloch_dofs(net, &n_, kind_.data(), comp_.data()),
                 "rn_network_bloch_dofs");
    x_.resize(rn_network_num_dofs(net));
    check_status(rn_network_get_dofs(net, x_.data()), "rn_network_get_dofs");
    nfl_ = n_;
    int64_t sidx[6];
    int ns = 0;
    rodnet::check_status(rn_network_cell_info(net, nullptr, &ns, nullptr, nullptr),
                         "rn_network_cell_info");
    check_status(rn_network_cell_strain_dofs(net, sidx), "rn_network_cell_strain_dofs");
    size_t nfree = 0;
    for (int v = 0; v < ns; ++v) nfree += sidx[v] >= 0;
    nfl_ = x_.size() - nfree; // the anchor (if any) follows
    if (modes != RN_BLOCH_ALL && dim_ != 2)
      throw Error(RN_ERR_ARG,
                  "rn_cell_bloch: in-plane / out-of-plane modes need a 2D cell");
    mask_.assign(n_, 1);
    for (size_t i = 0; i < n_; ++i) {
      const bool in = (kind_[i] == RN_DOF_POSITION && comp_[i] < 2) ||
                      (kind_[i] == RN_DOF_ROTATION && comp_[i] == 2);
      if (modes == RN_BLOCH_IN_PLANE) mask_[i] = in;
      if (modes == RN_BLOCH_OUT_OF_PLANE) mask_[i] = !in;
    }
    for (size_t i = 0; i < n_; ++i)
      if (mask_[i]) {
        sel_.push_back(static_cast<int>(i));
        if (i < nfl_) sel0_.push_back(static_cast<int>(i));
      }
    if (sel0_.empty()) throw Error(RN_ERR_ARG, "rn_cell_bloch: no DOFs to examine");
    if (sparse_) {
      sb_.reset(new SparseBloch(net, x_.data(), n_));
    } else {
      re_.resize(n_ * n_);
      im_.resize(n_ * n_);
    }
    if (modes != RN_BLOCH_ALL) check_decoupled();
  }

  int dim() const { return dim_; }
  int evaluations() const { return evals_; }
  size_t size() const { return n_; }
  const SparseBloch *sparse() const { return sb_.get(); } // NULL: dense

  static bool is_zero(const double *xi, int d) {
    for (int i = 0; i < d; ++i)
      if (xi[i] != 0.0) return false;
    return true;
  }

  // The lowest nev eigenvalues (ascending) at xi; vec: eigenvector of the lowest
  // (2 n: re, im per Bloch DOF).  Returns the number found.
  int lowest(const double *xi, int nev, double *w, double *vec = nullptr) {
    if (sparse_) {
      const int k = sb_->lowest_k(xi, is_zero(xi, dim_) ? sel0_ : sel_, nev, w, vec);
      ++evals_;
      return k;
    }
    check_status(rn_network_bloch_hessian(net_, x_.data(), xi, re_.data(), im_.data()),
                 "rn_network_bloch_hessian");
    const std::vector<int> &sel = is_zero(xi, dim_) ? sel0_ : sel_;
    const int m = static_cast<int>(sel.size());
    std::vector<cplx> a(static_cast<size_t>(m) * static_cast<size_t>(m));
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const size_t at = static_cast<size_t>(sel[static_cast<size_t>(i)]) * n_ +
                          static_cast<size_t>(sel[static_cast<size_t>(j)]);
        a[static_cast<size_t>(i) + static_cast<size_t>(j) * static_cast<size_t>(m)] =
            cplx(re_[at], im_[at]);
      }
    const int il = 1, iu = std::min(nev, m);
    const double vl = 0.0, vu = 0.0, abstol = 0.0;
    int found = 0, info = 0, lwork = -1, lrwork = -1, liwork = -1, iwq = 0;
    std::vector<double> ev(static_cast<size_t>(m));
    std::vector<cplx> z(vec ? static_cast<size_t>(m) * static_cast<size_t>(iu) : 1);
    std::vector<int> isuppz(2 * static_cast<size_t>(std::max(1, iu)));
    cplx wq;
    double rwq = 0.0;
    const char *jobz = vec ? "V" : "N";
    const int ldz = vec ? m : 1;
    zheevr_(jobz, "I", "L", &m, a.data(), &m, &vl, &vu, &il, &iu, &abstol, &found,
            ev.data(), z.data(), &ldz, isuppz.data(), &wq, &lwork, &rwq, &lrwork, &iwq,
            &liwork, &info, 1, 1, 1);
    lwork = std::max(1, static_cast<int>(wq.real()));
    lrwork = std::max(1, static_cast<int>(rwq));
    liwork = std::max(1, iwq);
    std::vector<cplx> work(static_cast<size_t>(lwork));
    std::vector<double> rwork(static_cast<size_t>(lrwork));
    std::vector<int> iwork(static_cast<size_t>(liwork));
    zheevr_(jobz, "I", "L", &m, a.data(), &m, &vl, &vu, &il, &iu, &abstol, &found,
            ev.data(), z.data(), &ldz, isuppz.data(), work.data(), &lwork, rwork.data(),
            &lrwork, iwork.data(), &liwork, &info, 1, 1, 1);
    ++evals_;
    if (info != 0 || found < 1)
      throw Error(RN_ERR_SOLVER, "rn_cell_bloch: LAPACK zheevr failed (info " +
                                     std::to_string(info) + ")");
    for (int i = 0; i < found; ++i) w[i] = ev[static_cast<size_t>(i)];
    if (vec) {
      std::fill(vec, vec + 2 * n_, 0.0);
      for (int i = 0; i < m; ++i) {
        const size_t d = static_cast<size_t>(sel[static_cast<size_t>(i)]);
        vec[2 * d] = z[static_cast<size_t>(i)].real();
        vec[2 * d + 1] = z[static_cast<size_t>(i)].imag();
      }
    }
    return found;
  }

  double lowest1(const double *xi) {
    double w[1];
    lowest(xi, 1, w);
    return w[0];
  }

  // The lowest eigenvalue at xi and its gradient g[dim] in xi (Hellmann-Feynman from
  // its eigenvector and the terms of H; SparseBloch::gradient).
  double lowest_grad(const double *xi, double *g) {
    double w[1];
    std::vector<double> vec(2 * n_);
    lowest(xi, 1, w, vec.data());
    if (!sb_ && !terms_) terms_.reset(new SparseBloch(net_, x_.data(), n_));
    (sb_ ? sb_ : terms_)->gradient(xi, vec.data(), dim_, g);
    return w[0];
  }

  // Acoustic tensor data: fills res->acoustic_*.
  void acoustic(rn_bloch_result *res);

private:
  std::vector<int> amplitudes() const;
  // 1 where Bloch DOF i is the translation of amplitude component a of t.
  double translation(const AcousticTensor &t, size_t i, int a) const;
  void first_moments(const AcousticTensor &t, const std::vector<double> &K,
                     std::vector<double> &M, std::vector<std::vector<double>> &B,
                     std::vector<std::vector<double>> &X);
  void second_moments(AcousticTensor &t, std::vector<double> &M,
                      const std::vector<std::vector<double>> &B,
                      const std::vector<std::vector<double>> &X);
  void check_decoupled() {
    const double xi[3] = {0.1234, 0.3071, 0.0};
    double big = 0.0, cross = 0.0;
    if (sparse_) {
      sb_->coupling(xi, mask_, &big, &cross);
    } else {
      check_status(rn_network_bloch_hessian(net_, x_.data(), xi, re_.data(), im_.data()),
                   "rn_network_bloch_hessian");
      for (size_t i = 0; i < n_; ++i)
        for (size_t j = 0; j < n_; ++j) {
          const double v = std::hypot(re_[i * n_ + j], im_[i * n_ + j]);
          big = std::max(big, v);
          if (mask_[i] != mask_[j]) cross = std::max(cross, v);
        }
    }
    if (cross > 1e-9 * big)
      throw Error(RN_ERR_ARG,
                  "rn_cell_bloch: in-plane and out-of-plane modes do not decouple at "
                  "this state (coupling " +
                      std::to_string(cross / big) +
                      " of the largest entry): it is not planar; examine all modes");
  }

  rn_network *net_;
  int dim_ = 0;
  double measure_ = 0.0;
  size_t n_ = 0, nfl_ = 0;
  std::vector<int> kind_, comp_, sel_, sel0_;
  std::vector<char> mask_;
  bool sparse_ = false;
  std::unique_ptr<SparseBloch> terms_; // dense: the terms for lowest_grad only
  std::unique_ptr<SparseBloch> sb_;
  std::vector<double> x_, re_, im_;
  int evals_ = 0;
};

// The lowest eigenvalue of A(n) over unit directions n (best, at bn, its
// eigenvector bv over the Cartesian components) and the largest (top).
struct AcousticMin {
  const AcousticTensor &t;
  double best = std::numeric_limits<double>::infinity(), top = 0.0, bn[3] = {0, 0, 0},
         bv[3] = {0, 0, 0};
  explicit AcousticMin(const AcousticTensor &tensor) : t(tensor) {}

  double probe(const double *nv) {
    double A[9], v[3], w[3];
    const int na = t.na;
    t.at(nv, A);
    sym_eigen(na, A, w, v, "rn_cell_bloch");
    const double lo = w[0];
    top = std::max(top, w[na - 1]);
    if (lo < best) {
      best = lo;
      std::copy(nv, nv + 3, bn);
      std::fill(bv, bv + 3, 0.0);
      for (int a = 0; a < na; ++a) bv[t.amp[static_cast<size_t>(a)]] = v[a];
    }
    return lo;
  }

  // 2D: 720 directions of the half circle, then a golden-section refinement of
  // the angle around the best sample.
  void search_plane() {
    const int ndir = 720;
    double a0 = 0.0;
    for (int k = 0; k < ndir; ++k) {
      const double th = M_PI * k / ndir, nv[3] = {std::cos(th), std::sin(th), 0.0};
      const double before = best;
      probe(nv);
      if (best < before) a0 = th;
    }
    double lo = a0 - M_PI / ndir, hi = a0 + M_PI / ndir;
    const double gr = 0.5 * (std::sqrt(5.0) - 1.0);
    auto f = [&](double th) {
      const double nv[3] = {std::cos(th), std::sin(th), 0.0};
      return probe(nv);
    };
    double c1 = hi - gr * (hi - lo), c2 = lo + gr * (hi - lo), f1 = f(c1), f2 = f(c2);
    for (int it = 0; it < 40; ++it) {
      if (f1 < f2) {
        hi = c2;
        c2 = c1;
        f2 = f1;
        c1 = hi - gr * (hi - lo);
        f1 = f(c1);
      } else {
        lo = c1;
        c1 = c2;
        f1 = f2;
        c2 = lo + gr * (hi - lo);
        f2 = f(c2);
      }
    }
  }

  // 3D: 2000 Fibonacci points on the upper hemisphere (A(n) = A(-n)), then a
  // pattern search on the sphere around the best direction.
  void search_sphere() {
    const int ndir = 2000;
    for (int k = 0; k < ndir; ++k) {
      const double z = (k + 0.5) / ndir, r = std::sqrt(1.0 - z * z);
      const double ph = k * M_PI * (3.0 - std::sqrt(5.0));
      const double nv[3] = {r * std::cos(ph), r * std::sin(ph), z};
      probe(nv);
    }
    double h = 0.05;
    while (h > 1e-6) {
      bool moved = false;
      for (int ax = 0; ax < 3 && !moved; ++ax)
        for (int sg = -1; sg <= 1 && !moved; sg += 2) {
          double nv[3] = {bn[0], bn[1], bn[2]};
          nv[ax] += sg * h;
          const double nn = std::sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
          for (double &c : nv) c /= nn;
          const double before = best;
          probe(nv);
          moved = best < before;
        }
      if (!moved) h *= 0.5;
    }
  }
};

double Bloch::translation(const AcousticTensor &t, size_t i, int a) const {
  return kind_[i] == RN_DOF_POSITION && comp_[i] == t.amp[static_cast<size_t>(a)] ? 1.0
                                                                                  : 0.0;
}

// The amplitude components present in the modes examined.
std::vector<int> Bloch::amplitudes() const {
  std::vector<int> amp;
  for (int c = 0; c < 3; ++c)
    for (size_t i = 0; i < n_; ++i)
      if (mask_[i] && kind_[i] == RN_DOF_POSITION && comp_[i] == c) {
        amp.push_back(c);
        break;
      }
  return amp;
}

// B_J = (M1_J^T T) on the sel0 rows (m of them), na columns, and X_J = K^-1 B_J
// with the Cholesky factor K (m x m); M: scratch for the moments.
void Bloch::first_moments(const AcousticTensor &t, const std::vector<double> &K,
                          std::vector<double> &M, std::vector<std::vector<double>> &B,
                          std::vector<std::vector<double>> &X) {
  const size_t m = sel0_.size();
  const int mi = static_cast<int>(m), na = t.na;
  int info = 0;
  B.assign(static_cast<size_t>(t.d), {});
  X.assign(static_cast<size_t>(t.d), {});
  for (int J = 0; J < t.d; ++J) {
    double e[3] = {0.0, 0.0, 0.0};
    e[J] = 1.0;
    check_status(rn_network_bloch_moment(net_, x_.data(), e, nullptr, M.data()),
                 "rn_network_bloch_moment");
    std::vector<double> &b = B[static_cast<size_t>(J)];
    b.assign(m * static_cast<size_t>(na), 0.0);
    for (int a = 0; a < na; ++a)
      for (size_t r = 0; r < m; ++r) {
        double s = 0.0;
        const size_t w = static_cast<size_t>(sel0_[r]);
        for (size_t i = 0; i < n_; ++i)
          if (translation(t, i, a) != 0.0) s += M[i * n_ + w];
        b[r + static_cast<size_t>(a) * m] = s;
      }
    X[static_cast<size_t>(J)] = b;
    dpotrs_("L", &mi, &na, K.data(), &mi, X[static_cast<size_t>(J)].data(), &mi, &info,
            1);
  }
}

// Q_JL[a][b] = -1/2 T_a^T M2_JL T_b - B_J^T X_L, assembled per pair.
void Bloch::second_moments(AcousticTensor &t, std::vector<double> &M,
                           const std::vector<std::vector<double>> &B,
                           const std::vector<std::vector<double>> &X) {
  const int d = t.d, na = t.na;
  const size_t m = sel0_.size();
  t.Q.assign(static_cast<size_t>(d * d * na * na), 0.0);
  for (int J = 0; J < d; ++J)
    for (int L = J; L < d; ++L) {
      double e1[3] = {0.0, 0.0, 0.0}, e2[3] = {0.0, 0.0, 0.0};
      e1[J] = 1.0;
      e2[L] = 1.0;
      check_status(rn_network_bloch_moment(net_, x_.data(), e1, e2, M.data()),
                   "rn_network_bloch_moment");
      for (int a = 0; a < na; ++a)
        for (int b = 0; b < na; ++b) {
          double s = 0.0;
          for (size_t i = 0; i < n_; ++i) {
            if (translation(t, i, a) == 0.0) continue;
            for (size_t j = 0; j < n_; ++j)
              if (translation(t, j, b) != 0.0) s += M[i * n_ + j];
          }
          t.q(J, L, a, b) += -0.5 * s;
          if (L != J) t.q(L, J, a, b) += -0.5 * s;
        }
    }
  subtract_bx(d, na, m, B, X, t.Q);
}

// The acoustic tensor (AcousticTensor) and its lowest eigenvalue over the
// directions: fills res->acoustic_* (acoustic_valid 0 if K is not positive
// definite: no tangent).
void Bloch::acoustic(rn_bloch_result *res) {
  AcousticTensor t;
  t.amp = amplitudes();
  t.na = static_cast<int>(t.amp.size());
  t.d = dim_;
  t.measure = measure_;
  if (sparse_) {
    std::vector<int> amp_of(n_, -1);
    for (size_t i = 0; i < n_; ++i)
      for (int a = 0; a < t.na; ++a)
        if (translation(t, i, a) != 0.0) amp_of[i] = a;
    res->acoustic_valid =
        sparse_acoustic_brackets(net_, x_.data(), n_, t.d, t.na, sel0_, amp_of, t.Q);
    if (res->acoustic_valid && t.na > 0) acoustic_search(t, res);
    return;
  }
  const size_t m = sel0_.size();
  std::vector<double> M(n_ * n_);
  check_status(rn_network_bloch_moment(net_, x_.data(), nullptr, nullptr, M.data()),
               "rn_network_bloch_moment");
  std::vector<double> K(m * m);
  for (size_t j = 0; j < m; ++j)
    for (size_t i = 0; i < m; ++i)
      K[i + j * m] =
          M[static_cast<size_t>(sel0_[i]) * n_ + static_cast<size_t>(sel0_[j])];
  const int mi = static_cast<int>(m);
  int info = 0;
  dpotrf_("L", &mi, K.data(), &mi, &info, 1);
  res->acoustic_valid = info == 0;
  if (info != 0 || t.na == 0) return;
  std::vector<std::vector<double>> B, X;
  first_moments(t, K, M, B, X);
  second_moments(t, M, B, X);
  acoustic_search(t, res);
}

// Wraps xi_i into (-1/2, 1/2].
void wrap(double *xi, int d) {
  for (int i = 0; i < d; ++i) {
    xi[i] -= std::round(xi[i]);
    if (xi[i] <= -0.5) xi[i] += 1.0;
  }
}

// A wave vector and the lowest Bloch eigenvalue there.
struct Pt {
  double lam, xi[3];
};

// The lowest eigenvalue on the G^d grid of the Brillouin zone, half of it
// (H(-xi) = conj H(xi)): t <= -t (mod G) lexicographically (last index first);
// in grid order.
std::vector<Pt> grid_scan(Bloch &b, int G) {
  const int d = b.dim();
  std::vector<Pt> pts;
  int total = 1;
  for (int i = 0; i < d; ++i) total *= G;
  for (int code = 0; code < total; ++code) {
    int t[3] = {0, 0, 0}, u[3] = {0, 0, 0}, c = code;
    for (int i = 0; i < d; ++i) {
      t[i] = c % G;
      c /= G;
      u[i] = (G - t[i]) % G;
    }
    bool keep = true;
    for (int i = d - 1; i >= 0; --i)
      if (t[i] != u[i]) {
        keep = t[i] < u[i];
        break;
      }
    if (!keep) continue;
    Pt p{0.0, {0.0, 0.0, 0.0}};
    for (int i = 0; i < d; ++i) p.xi[i] = static_cast<double>(t[i]) / G;
    wrap(p.xi, d);
    p.lam = b.lowest1(p.xi);
    pts.push_back(p);
  }
  return pts;
}

// 0 < |xi|_inf < excl: left to the long-wavelength (acoustic) test.
bool excluded(const double *xi, int d, double excl) {
  double inf = 0.0;
  for (int i = 0; i < d; ++i) inf = std::max(inf, std::fabs(xi[i]));
  return inf > 0.0 && inf < excl;
}

// Probe: the lowest of cur's 2 d neighbours at distance h along the axes, if lower
// than cur by more than tol (skipping excluded ones); false if none is.
bool probe(Bloch &b, Pt &cur, double h, double excl, double tol) {
  const int d = b.dim();
  Pt best = cur;
  for (int ax = 0; ax < d; ++ax)
    for (int sg = -1; sg <= 1; sg += 2) {
      Pt c = cur;
      c.xi[ax] += sg * h;
      wrap(c.xi, d);
      if (excluded(c.xi, d, excl)) continue;
      c.lam = b.lowest1(c.xi);
      if (c.lam < best.lam) best = c;
    }
  if (!(best.lam < cur.lam - tol)) return false;
  cur = best;
  return true;
}

// Local minimum of the lowest eigenvalue from cur: quasi-Newton (BFGS) on xi with the
// Hellmann-Feynman gradient (Bloch::lowest_grad) and a backtracking line search,
// steps at most 1/(2G), until a step shorter than 1e-7 or no descent (none larger
// than tol predicted); then a probe of
// the axes at 1e-3 (a saddle where the gradient vanishes, e.g. a symmetric point of
// the grid, or a kink where two eigenvalues cross), and from a lower neighbour
// again (at most 4 restarts; lower by more than tol, the round-off of the
// eigenvalues).  Skips the wave vectors with 0 < |xi|_inf < excl.
Pt refine(Bloch &b, Pt cur, int G, double excl, double tol) {
  const int d = b.dim();
  const double hmax = 0.5 / G;
  for (int restart = 0; restart < 5; ++restart) {
    double g[3] = {0, 0, 0}, H[9] = {0}, x[3] = {cur.xi[0], cur.xi[1], cur.xi[2]};
    cur.lam = b.lowest_grad(cur.xi, g);
    double gn = 0.0;
    for (int a = 0; a < d; ++a) gn = std::max(gn, std::fabs(g[a]));
    for (int a = 0; a < d; ++a) H[a * 3 + a] = gn > 0.0 ? hmax / gn : 0.0;
    for (int it = 0; it < 50 && gn > 0.0; ++it) {
      double p[3] = {0, 0, 0}, plen = 0.0, slope = 0.0;
      for (int a = 0; a < d; ++a) {
        for (int c = 0; c < d; ++c) p[a] -= H[a * 3 + c] * g[c];
        plen = std::max(plen, std::fabs(p[a]));
        slope += p[a] * g[a];
      }
      if (!(slope < 0.0)) { // not a descent direction: back to steepest descent
        for (int a = 0; a < 9; ++a) H[a] = 0.0;
        for (int a = 0; a < d; ++a) H[a * 3 + a] = hmax / gn;
        continue;
      }
      double alpha = plen > hmax ? hmax / plen : 1.0;
      Pt t = cur;
      double gt[3] = {0, 0, 0}, xt[3] = {0, 0, 0};
      bool ok = false;
      // (a decrease below the eigenvalues' round-off tol is noise: stop there)
      while (alpha * plen >= 1e-7 && -alpha * slope > tol) {
        for (int a = 0; a < d; ++a) t.xi[a] = xt[a] = x[a] + alpha * p[a];
        wrap(t.xi, d);
        if (!excluded(t.xi, d, excl)) {
          t.lam = b.lowest_grad(t.xi, gt);
          if (t.lam <= cur.lam + 1e-4 * alpha * slope && t.lam < cur.lam) {
            ok = true;
            break;
          }
        }
        alpha *= 0.5;
      }
      if (!ok) break;
      // BFGS update of the inverse Hessian with s = xt - x, y = gt - g
      double sv[3], y[3], sy = 0.0, step = 0.0;
      for (int a = 0; a < d; ++a) {
        sv[a] = xt[a] - x[a];
        y[a] = gt[a] - g[a];
        sy += sv[a] * y[a];
        step = std::max(step, std::fabs(sv[a]));
      }
      if (sy > 0.0) {
        double Hy[3] = {0, 0, 0}, yHy = 0.0;
        for (int a = 0; a < d; ++a)
          for (int c = 0; c < d; ++c) Hy[a] += H[a * 3 + c] * y[c];
        for (int a = 0; a < d; ++a) yHy += y[a] * Hy[a];
        for (int a = 0; a < d; ++a)
          for (int c = 0; c < d; ++c)
            H[a * 3 + c] += (1.0 + yHy / sy) * sv[a] * sv[c] / sy -
                            (Hy[a] * sv[c] + sv[a] * Hy[c]) / sy;
      }
      cur = t;
      for (int a = 0; a < d; ++a) {
        x[a] = xt[a];
        g[a] = gt[a];
      }
      gn = 0.0;
      for (int a = 0; a < d; ++a) gn = std::max(gn, std::fabs(g[a]));
      if (step < 1e-7) break;
    }
    if (!probe(b, cur, 1e-3, excl, tol)) break;
  }
  return cur;
}

// Ties (symmetry-equivalent minima, equal up to round-off): the first in grid
// order becomes best, and all of them are reported in res->xi_equiv.
// The spread of the lowest eigenvalue over the grid (0 without one).
double spread(const std::vector<Pt> &grid_pts) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Pt &q : grid_pts) {
    lo = std::min(lo, q.lam);
    hi = std::max(hi, q.lam);
  }
  return grid_pts.empty() ? 0.0 : hi - lo;
}

void ties(const std::vector<Pt> &grid_pts, Pt &best, rn_bloch_result *res) {
  const double tie =
      grid_pts.empty() ? 0.0 : 1e-8 * std::max(spread(grid_pts), std::fabs(best.lam));
  res->nequiv = 0;
  for (const Pt &q : grid_pts)
    if (std::fabs(q.lam - best.lam) <= tie && res->nequiv < 12) {
      if (res->nequiv == 0) best = q;
      std::copy(q.xi, q.xi + 3, res->xi_equiv[res->nequiv++]);
    }
  if (res->nequiv == 0) {
    std::copy(best.xi, best.xi + 3, res->xi_equiv[0]);
    res->nequiv = 1;
  }
}

void local_search(Bloch &b, const rn_bloch_options &opt, int G, double excl,
                  const std::vector<Pt> &grid_pts, const std::vector<Pt> &starts,
                  rn_bloch_result *res);

void bloch_search(rn_network *net, const rn_bloch_options &opt, rn_bloch_result *res) {
  Bloch b(net, opt.modes,
          opt.method == RN_BLOCH_SPARSE  ? 2
          : opt.method == RN_BLOCH_DENSE ? 0
                                         : 3);
  const int d = b.dim();
  const int G = opt.grid > 0 ? opt.grid : (d == 2 ? 16 : 6);
  const double excl = 0.25 / G;
  std::vector<Pt> pts;
  if (!opt.no_scan) pts = grid_scan(b, G);
  const std::vector<Pt> grid_pts = pts; // in grid order
  std::sort(pts.begin(), pts.end(),
            [](const Pt &a, const Pt &c) { return a.lam < c.lam; });
  std::vector<Pt> starts(pts.begin(), pts.begin() + std::min<size_t>(3, pts.size()));
  if (opt.xi_hint) {
    Pt p{0.0, {0.0, 0.0, 0.0}};
    for (int i = 0; i < d; ++i) p.xi[i] = opt.xi_hint[i];
    wrap(p.xi, d);
    if (!excluded(p.xi, d, excl)) {
      p.lam = b.lowest1(p.xi);
      starts.push_back(p);
    }
  }
  res->bloch_dofs = b.size();
  if (starts.empty()) { // no_scan without a hint: no local test
    res->local_min = std::numeric_limits<double>::infinity();
    res->neig = 0;
    res->nequiv = 0;
  } else
    local_search(b, opt, G, excl, grid_pts, starts, res);
  if (opt.no_acoustic)
    res->acoustic_valid = -1;
  else
    b.acoustic(res);
  res->evaluations = b.evaluations();
}

void local_search(Bloch &b, const rn_bloch_options &opt, int G, double excl,
                  const std::vector<Pt> &grid_pts, const std::vector<Pt> &starts,
                  rn_bloch_result *res) {
  Pt best = starts.front();
  for (const Pt &s : starts)
    if (s.lam < best.lam) best = s;
  // the eigenvalues' round-off: 1e-10 of the spread over the grid (or of the start
  // without one)
  const double tol = 1e-10 * std::max(spread(grid_pts), std::fabs(best.lam));
  if (opt.refine)
    for (const Pt &start : starts) {
      Pt cur = refine(b, start, G, excl, tol);
      if (cur.lam < best.lam) best = cur;
    }
  ties(grid_pts, best, res);
  res->local_min = best.lam;
  std::copy(best.xi, best.xi + 3, res->xi);
  res->neig = b.lowest(best.xi, 8, res->eig);
  res->local_scale = 0.0;
  for (int i = 0; i < res->neig; ++i)
    res->local_scale = std::max(res->local_scale, std::fabs(res->eig[i]));
}

} // namespace

// The lowest eigenvalue of the acoustic tensor t over the directions into res.
void acoustic_search(const AcousticTensor &t, rn_bloch_result *res) {
  AcousticMin am(t);
  if (t.d == 2)
    am.search_plane();
  else
    am.search_sphere();
  res->acoustic_min = am.best;
  res->acoustic_scale = am.top;
  std::copy(am.bn, am.bn + 3, res->direction);
  std::copy(am.bv, am.bv + 3, res->amplitude);
}

} // namespace rodnet

namespace rodnet {
void sym_eigen(int m, const double *a, double *w, double *v, const char *where) {
  double A[36], work[64];
  const int lwork = 64;
  int info = 0;
  std::copy(a, a + m * m, A);
  dsyev_("V", "L", &m, A, &m, w, work, &lwork, &info, 1, 1);
  if (info != 0) throw Error(RN_ERR_SOLVER, std::string(where) + ": LAPACK dsyev failed");
  for (int i = 0; i < m; ++i) v[i] = A[i];
}

namespace {
rn_status cell_relax(rn_network *net, const double *strain, rn_cell_relax_report *rep,
                     bool descend, int method = RN_BLOCH_AUTO) {
  const char *where = descend ? "rn_cell_minimize" : "rn_cell_relax";
  if (!net) return RN_ERR_ARG;
  if (!strain)
    return rn_context_set_error(rn_network_context(net), RN_ERR_ARG, "%s: strain is NULL",
                                where);
  rn_cell_relax_report local{};
  rn_cell_relax_report &r = rep ? *rep : local;
  r = rn_cell_relax_report{};
  if (rn_status st = refuse_nonconservative(net, where, "the cell's relaxation"))
    return st;
  return guarded(net, where, [&] {
    int ns = 0;
    check_status(rn_network_cell_info(net, nullptr, &ns, nullptr, nullptr),
                 "rn_network_cell_info");
    for (int v = 0; v < ns; ++v)
      if (!std::isfinite(strain[v]))
        throw Error(RN_ERR_NOT_FINITE, std::string(where) + ": strain is not finite");
    if (method < RN_BLOCH_AUTO || method > RN_BLOCH_SPARSE)
      throw Error(RN_ERR_ARG, std::string(where) +
                                  ": method must be RN_BLOCH_AUTO, RN_BLOCH_DENSE or "
                                  "RN_BLOCH_SPARSE");
    if (rn_network_is_part(net)) {
      if (descend)
        throw Error(RN_ERR_ARG, std::string(where) +
                                    ": a part of a distributed cell relaxes on the "
                                    "principal branch only (rn_cell_relax)");
      relax_part(net, strain, r);
      return;
    }
    Relax(net, descend, method).run(strain, r);
  });
}
} // namespace
} // namespace rodnet

extern "C" rn_status rn_cell_relax(rn_network *net, const double *strain,
                                   rn_cell_relax_report *rep) {
  return rodnet::cell_relax(net, strain, rep, false);
}

extern "C" rn_status rn_cell_relax_method(rn_network *net, const double *strain,
                                          int method, rn_cell_relax_report *rep) {
  return rodnet::cell_relax(net, strain, rep, false, method);
}

extern "C" rn_status rn_cell_minimize(rn_network *net, const double *strain,
                                      rn_cell_relax_report *rep) {
  return rodnet::cell_relax(net, strain, rep, true);
}

extern "C" void rn_bloch_options_default(rn_bloch_options *opt) {
  if (!opt) return;
  *opt = rn_bloch_options{};
  opt->refine = 1;
  opt->modes = RN_BLOCH_ALL;
}

extern "C" rn_status rn_cell_bloch(rn_network *net, const rn_bloch_options *opt,
                                   rn_bloch_result *res) {
  if (!net) return RN_ERR_ARG;
  if (!res)
    return rn_context_set_error(rn_network_context(net), RN_ERR_ARG,
                                "rn_cell_bloch: res is NULL");
  rn_bloch_options def;
  rn_bloch_options_default(&def);
  const rn_bloch_options &o = opt ? *opt : def;
  *res = rn_bloch_result{};
  if (rn_status st =
          rodnet::refuse_nonconservative(net, "rn_cell_bloch", "the Bloch analysis"))
    return st;
  return rodnet::guarded(net, "rn_cell_bloch", [&] {
    if (o.grid < 0 || o.grid > 1000)
      throw rodnet::Error(RN_ERR_ARG, "rn_cell_bloch: grid must be in 0 .. 1000");
    if (o.method < RN_BLOCH_AUTO || o.method > RN_BLOCH_SPARSE)
      throw rodnet::Error(RN_ERR_ARG, "rn_cell_bloch: method must be RN_BLOCH_AUTO, "
                                      "RN_BLOCH_DENSE or RN_BLOCH_SPARSE");
    if (rn_network_is_part(net))
      rodnet::bloch_part(net, o, res);
    else
      rodnet::bloch_search(net, o, res);
  });
}

extern "C" rn_status rn_cell_acoustic_tangent(rn_network *net, rn_bloch_modes modes,
                                              rn_bloch_result *res) {
  if (!net) return RN_ERR_ARG;
  if (!res)
    return rn_context_set_error(rn_network_context(net), RN_ERR_ARG,
                                "rn_cell_acoustic_tangent: res is NULL");
  *res = rn_bloch_result{};
  if (rn_status st = rodnet::refuse_nonconservative(net, "rn_cell_acoustic_tangent",
                                                    "the acoustic test"))
    return st;
  return rodnet::guarded(net, "rn_cell_acoustic_tangent",
                         [&] { rodnet::acoustic_tangent(net, modes, res); });
}

extern "C" rn_status rn_cell_bloch_eigen(rn_network *net, const double *xi,
                                         rn_bloch_modes modes, int neig, double *eig,
                                         double *vec) {
  if (!net) return RN_ERR_ARG;
  if (!xi || !eig || neig < 1 || neig > 8)
    return rn_context_set_error(rn_network_context(net), RN_ERR_ARG,
                                "rn_cell_bloch_eigen: bad arguments");
  if (rn_status st = rodnet::refuse_nonconservative(net, "rn_cell_bloch_eigen",
                                                    "the Bloch analysis"))
    return st;
  return rodnet::guarded(net, "rn_cell_bloch_eigen", [&] {
    rodnet::Bloch b(net, modes, 1);
    b.lowest(xi, neig, eig, vec);
  });
}

extern "C" rn_status rn_cell_bloch_gradient(rn_network *net, const double *xi,
                                            rn_bloch_modes modes, int method, double *eig,
                                            double *grad) {
  if (!net) return RN_ERR_ARG;
  if (!xi || !eig || !grad || method < RN_BLOCH_AUTO || method > RN_BLOCH_SPARSE)
    return rn_context_set_error(rn_network_context(net), RN_ERR_ARG,
                                "rn_cell_bloch_gradient: bad arguments");
  if (rn_status st = rodnet::refuse_nonconservative(net, "rn_cell_bloch_gradient",
                                                    "the Bloch analysis"))
    return st;
  return rodnet::guarded(net, "rn_cell_bloch_gradient", [&] {
    rodnet::Bloch b(net, modes,
                    method == RN_BLOCH_SPARSE  ? 2
                    : method == RN_BLOCH_DENSE ? 0
                                               : 3);
    *eig = b.lowest_grad(xi, grad);
  });
}

extern "C" rn_status rn_cell_bloch_lowest_sparse(rn_network *net, const double *xi,
                                                 rn_bloch_modes modes, double *eig,
                                                 double *vec, int *steps, double *shift) {
  if (!net) return RN_ERR_ARG;
  if (!xi || !eig)
    return rn_context_set_error(rn_network_context(net), RN_ERR_ARG,
                                "rn_cell_bloch_lowest_sparse: bad arguments");
  if (rn_status st = rodnet::refuse_nonconservative(net, "rn_cell_bloch_lowest_sparse",
                                                    "the Bloch analysis"))
    return st;
  return rodnet::guarded(net, "rn_cell_bloch_lowest_sparse", [&] {
    rodnet::Bloch b(net, modes, 2);
    b.lowest(xi, 1, eig, vec);
    if (steps) *steps = b.sparse()->steps();
    if (shift) *shift = b.sparse()->shift();
  });
}

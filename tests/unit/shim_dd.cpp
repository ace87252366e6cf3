// shim_dd.cpp - the rod-level domain-decomposition preconditioner
// (shim_cxx/pc/impls/dd/dd_preconditioner.hpp) on a System over 1 or more ranks
// (shim_cxx/system/replicated_system.hpp; run under mpirun -np 2 too):
//  - exact static condensation: with the direct coarse solve and a positive definite
//    Hessian, M^-1 b equals the sparse Cholesky solution of H x = b to 1e-9
//    relative (backward error of M^-1 b below 1e-12), no shift is applied and
//    preconditioned MINRES converges in at most 2 iterations, on a honeycomb with
//    rigid joints, one with elastic joints, a single rod and an octet block (on
//    several ranks through the substructured coarse solve: an inter-rank separator
//    that is not empty, and in the indefinite cases below the shifted coarse matrix);
//  - M is SPD in every case: symmetry u'M^-1 v = v'M^-1 u to 1e-12 and positivity
//    v'M^-1 v > 0 on random vectors, also for the indefinite H - D/2 (shifted rod
//    blocks and coarse matrix; MINRES still converges) and with the AMG coarse
//    solve;
//  - a second setup with other values on the same structure gives that system's
//    solution (the coarse matrix is refilled, not rebuilt);
//  - with the AMG coarse solve, MINRES iterations on honeycombs of 12x12, 24x24 and
//    36x36 cells stay bounded (the largest at most 1.5x the smallest); the automatic
//    coarse solve is the direct one unless its factorisation costs too much.
//  - MueLu on the whole Hessian and Ifpack2 additive Schwarz: SPD, MINRES converges
//    with the true residual to match;
//  - the coarse pencil (S, A) of the AMG coarse solve (DdPreconditioner::
//    coarse_pencil), by which tr-krylov certifies that H is positive definite: H and
//    S have the same negative inertia (unshifted rod blocks), so its lowest Ritz
//    value is positive for H - c D with c = 0 and 0.5 mu (mu the lowest eigenvalue
//    of the pencil (H, D)) and, where the pencil is offered at all, negative for
//    c = 1.05 mu and 1.5 mu (an indefinite H).
// The results do not depend on the number of ranks (random vectors are functions of
// the global DOF index); every rank checks its own part and all must pass.
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Tpetra_Core.hpp>

#include "pc/impls/dd/dd_preconditioner.hpp"
#include "pc/impls/ifpack2/ifpack2.hpp"
#include "pc/impls/muelu/muelu.hpp"
#include "pc/registry.hpp"
#include "system/dof_blocks.hpp"
#include "krylov/minres.hpp"
#include "krylov/pencil_lanczos.hpp"
#include "system/replicated_system.hpp"
#include "factor/sparse_cholesky.hpp"
#include "factor/spd_factor.hpp"

extern "C" {
#include "shim_lattices.h"
}

namespace {

using namespace rodnet;
using Comm = Teuchos::Comm<int>;

int g_rank = 0;

// Deterministic pseudo-random value in [-1, 1) of a global index and a seed.
double rnd(GO g, unsigned seed) {
  unsigned long long h =
      static_cast<unsigned long long>(g) * 0x9E3779B97F4A7C15ull + seed;
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdull;
  h ^= h >> 33;
  return static_cast<double>(h >> 11) / 4503599627370496.0 - 1.0;
}

void random_vector(TMV &v, unsigned seed) {
  auto map = v.getMap();
  auto d = v.getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (size_t i = 0; i < d.extent(0); ++i)
    d(i, 0) = rnd(map->getGlobalElement(static_cast<LO>(i)), seed);
}

double dot(const TMV &a, const TMV &b) {
  Teuchos::Array<double> d(1);
  a.dot(b, d());
  return d[0];
}

double norm(const TMV &a) { return std::sqrt(dot(a, a)); }

// A lattice of `rodnet generate` under stretch along x (1e-3), 4 edges per rod.
rn_scene *lattice(rn_context *ctx, rn_lattice_kind kind, int cells, int model,
                  int edges = 4) {
  char path[256];
  std::snprintf(path, sizeof path, "shim_dd_scene_%d.json", g_rank);
  return shim_lattice(ctx, kind, cells, model, edges, path);
}

// A clamped cantilever of 40 edges with a tip force (single rod: no interface).
rn_network *single_rod(rn_context *ctx) {
  rn_network *net = nullptr;
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, f[3] = {0, 1e-3, 2e-3};
  rn_material m;
  rn_section sec;
  int rod = -1;
  std::vector<double> xyz;
  for (int i = 0; i <= 40; ++i)
    for (int k = 0; k < 3; ++k) xyz.push_back(a[k] + (b[k] - a[k]) * i / 40.0);
  CHECK_STATUS(rn_material_from_E_nu(1e7, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_section_circle(0.01, &sec), RN_OK);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "rod", 41, xyz.data(), nullptr, &rod), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &sec), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, 0, RN_START), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, 0, -1, f), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

class CrsOp : public VectorOperator {
public:
  explicit CrsOp(Teuchos::RCP<const Tpetra::Operator<>> A) : A_(std::move(A)) {}
  void apply(const MV &x, MV &y) const override { A_->apply(x, y); }

private:
  Teuchos::RCP<const Tpetra::Operator<>> A_;
};

// Replace H's values by H - c D (D = |diag H|) or, identity = true, by H - c I.
// mask (global DOF flags, may be null): on the flagged rows only.
void shift_hessian(ReplicatedSystem &sys, double c, bool identity = false,
                   const std::vector<bool> *mask = nullptr) {
  auto H = sys.hessian_nonconst();
  TMV d(H->getRowMap(), 1);
  H->getLocalDiagCopy(*d.getVectorNonConst(0));
  H->resumeFill();
  auto dv = d.getLocalViewHost(Tpetra::Access::ReadOnly);
  for (size_t i = 0; i < dv.extent(0); ++i) {
    const GO g = H->getRowMap()->getGlobalElement(static_cast<LO>(i));
    if (mask && !(*mask)[static_cast<size_t>(g)]) continue;
    const double add = -c * (identity ? 1.0 : std::fabs(dv(i, 0)));
    H->sumIntoGlobalValues(g, Teuchos::ArrayView<const GO>(&g, 1),
                           Teuchos::ArrayView<const double>(&add, 1));
  }
  H->fillComplete(H->getDomainMap(), H->getRangeMap());
}

// Lowest eigenvalue mu of the pencil (H, D), D = |diag H|, of the assembled Hessian
// (positive definite), by bisection on the inertia: H - s D factors iff s < mu.
// mask (global DOF flags, may be null): D only on the flagged rows (mu may then be
// infinite if H - s D stays positive definite: returns 1e300).
double pencil_min_eigenvalue(ReplicatedSystem &sys,
                             const std::vector<bool> *mask = nullptr) {
  Problem &p = sys.problem();
  const size_t n = p.size();
  std::vector<double> d(p.rowptr()[n], 0.0);
  for (size_t i = 0; i < n; ++i)
    for (int64_t q = p.rowptr()[i]; q < p.rowptr()[i + 1]; ++q)
      if (static_cast<size_t>(p.col()[q]) == i && (!mask || (*mask)[i]))
        d[q] = -std::fabs(p.values()[q]);
  auto an = std::make_shared<SparseAnalysis>(n, p.rowptr(), p.col());
  SparseCholesky chol(an);
  double lo = 0.0, hi = 1.0;
  while (chol.factor(p.values(), hi, d.data())) {
    lo = hi;
    hi *= 2.0;
    if (hi > 1e10) return 1e300;
  }
  for (int k = 0; k < 50; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (chol.factor(p.values(), mid, d.data()))
      lo = mid;
    else
      hi = mid;
  }
  return lo;
}

// x = H^-1 b by the sparse Cholesky of the whole (replicated) Hessian, owned part.
// c != 0: of H - c |diag H| (H the assembled Hessian).
void reference_solve(ReplicatedSystem &sys, double c, const TMV &b, TMV &x) {
  Problem &p = sys.problem();
  const size_t n = p.size();
  std::vector<double> vals(p.values(), p.values() + p.rowptr()[n]);
  for (size_t i = 0; i < n; ++i)
    for (int64_t q = p.rowptr()[i]; q < p.rowptr()[i + 1]; ++q)
      if (static_cast<size_t>(p.col()[q]) == i) vals[q] -= c * std::fabs(vals[q]);
  auto an = std::make_shared<SparseAnalysis>(n, p.rowptr(), p.col());
  SparseCholesky chol(an);
  CHECK(chol.factor(vals.data(), 0.0, nullptr));
  // gather b
  std::vector<double> full(n, 0.0), sum(n, 0.0);
  auto map = b.getMap();
  {
    auto bv = b.getLocalViewHost(Tpetra::Access::ReadOnly);
    for (size_t i = 0; i < bv.extent(0); ++i)
      full[static_cast<size_t>(map->getGlobalElement(static_cast<LO>(i)))] = bv(i, 0);
  }
  Teuchos::reduceAll(*map->getComm(), Teuchos::REDUCE_SUM, static_cast<int>(n),
                     full.data(), sum.data());
  chol.solve(sum.data());
  auto xv = x.getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (size_t i = 0; i < xv.extent(0); ++i)
    xv(i, 0) = sum[static_cast<size_t>(map->getGlobalElement(static_cast<LO>(i)))];
}

// Symmetry and positivity of M^-1 on random vectors.
// sym_tol: 1e-12 for the exact DD; 1e-10 with the AMG coarse solve, whose V-cycle
// (Chebyshev polynomials of the coarse matrix) is symmetric only up to round-off
// amplified by the coarse matrix's conditioning (measured 1e-13 .. 1.2e-12).
void check_spd(const Tpetra::Operator<> &Minv, const Teuchos::RCP<const TMap> &map,
               const char *name, double sym_tol = 1e-12) {
  TMV u(map, 1), v(map, 1), Mu(map, 1), Mv(map, 1);
  double worst_sym = 0.0, min_pos = 1.0;
  for (unsigned s = 0; s < 5; ++s) {
    random_vector(u, 100 + s);
    random_vector(v, 200 + s);
    Minv.apply(u, Mu);
    Minv.apply(v, Mv);
    const double a = dot(v, Mu), b = dot(u, Mv);
    const double scale = std::sqrt(dot(u, Mu) * dot(v, Mv));
    worst_sym = std::max(worst_sym, std::fabs(a - b) / scale);
    min_pos = std::min(min_pos, dot(u, Mu) / (norm(u) * norm(Mu)));
  }
  if (g_rank == 0)
    std::printf("  %s: symmetry %.2e, min v'M^-1 v / (|v| |M^-1 v|) %.2e\n", name,
                worst_sym, min_pos);
  CHECK(worst_sym <= sym_tol);
  CHECK(min_pos > 0.0);
}

// A block of 3 columns in one application (Preconditioner::takes_blocks: one halo
// exchange and one coarse solve for the block) against each column alone, with
// y = alpha M^-1 x + beta y: the same numbers (tol 0 for the exact DD: the same
// operations per column).
void check_block(const Tpetra::Operator<> &Minv, const Teuchos::RCP<const TMap> &map,
                 const char *name, double tol) {
  const size_t k = 3;
  TMV X(map, k), Y(map, k), Y0(map, k);
  for (size_t j = 0; j < k; ++j) {
    random_vector(*X.getVectorNonConst(j), 300 + static_cast<unsigned>(j));
    random_vector(*Y0.getVectorNonConst(j), 400 + static_cast<unsigned>(j));
  }
  Y.assign(Y0);
  Minv.apply(X, Y, Teuchos::NO_TRANS, 0.5, -2.0);
  double worst = 0.0;
  for (size_t j = 0; j < k; ++j) {
    TMV x(map, 1), y(map, 1);
    x.getVectorNonConst(0)->assign(*X.getVector(j));
    y.getVectorNonConst(0)->assign(*Y0.getVector(j));
    Minv.apply(x, y, Teuchos::NO_TRANS, 0.5, -2.0);
    const double ny = norm(y);
    y.getVectorNonConst(0)->update(-1.0, *Y.getVector(j), 1.0);
    worst = std::max(worst, norm(y) / ny);
  }
  if (g_rank == 0)
    std::printf("  %s: a block of %zu columns against each alone: %.2e\n", name, k,
                worst);
  CHECK(worst <= tol);
}

int minres_iterations(ReplicatedSystem &sys, const Tpetra::Operator<> &Minv, double tol) {
  auto map = sys.map();
  TMV b(map, 1), x(map, 1);
  random_vector(b, 7);
  MinresSolver solver(map, tol, 2000);
  CrsOp A(sys.hessian()), P(Teuchos::rcpFromRef(Minv));
  MinresResult r = solver.solve(A, P, b, x);
  // true residual
  TMV Hx(map, 1);
  sys.hessian()->apply(x, Hx);
  Hx.update(-1.0, b, 1.0);
  const double rel = norm(Hx) / norm(b); // collective: outside the rank-0 print
  if (g_rank == 0)
    std::printf("  MINRES: %d iterations, converged %d, |Hx - b| / |b| = %.2e\n",
                r.iterations, r.converged ? 1 : 0, rel);
  CHECK(r.converged);
  return r.iterations;
}

// The exact DD on a positive definite H and on H - D/2.
void check_exact(rn_network *net, const Teuchos::RCP<const Comm> &comm,
                 const char *name) {
  ReplicatedSystem sys(net, comm);
  auto map = sys.map();
  TMV x(map, 1);
  sys.get_state(x);
  sys.assemble_hessian(x);
  DdOptions opt;
  opt.coarse = DdOptions::Coarse::Direct;
  DdPreconditioner dd(opt);
  dd.setup(sys);
  if (g_rank == 0)
    std::printf("%s: %lld DOFs, %lld coarse rows, rods shifted %lld, coarse shift %g\n",
                name, static_cast<long long>(sys.global_size()), dd.coarse_rows(),
                dd.rods_shifted(), dd.coarse_shift());
  CHECK(dd.rods_shifted() == 0);
  CHECK(dd.coarse_shift() == 0.0);
  // On several ranks the direct coarse solve is substructured: an inter-rank separator
  // (the path these checks cover there); none on one rank.
  if (g_rank == 0)
    std::printf("  coarse separator rows %lld\n", dd.coarse_separator_rows());
  if (comm->getSize() > 1 && dd.coarse_rows() > 0)
    CHECK(dd.coarse_separator_rows() > 0);
  else
    CHECK(dd.coarse_separator_rows() == 0);
  auto Minv = dd.inverse();
  CHECK(dd.takes_blocks());
  check_block(*Minv, map, "exact DD", 0.0);
  for (int pass = 0; pass < 2; ++pass) {
    const double c = pass == 0 ? 0.0 : -1.0;
    if (pass == 1) { // a second setup on other values: H + D
      shift_hessian(sys, c);
      dd.setup(sys);
    }
    TMV b(map, 1), y(map, 1), yref(map, 1), Hy(map, 1);
    random_vector(b, 11);
    Minv->apply(b, y);
    reference_solve(sys, c, b, yref);
    sys.hessian()->apply(y, Hy);
    Hy.update(-1.0, b, 1.0);
    const double backward = norm(Hy) / (sys.hessian()->getFrobeniusNorm() * norm(y));
    yref.update(-1.0, y, 1.0);
    const double forward = norm(yref) / norm(y);
    if (g_rank == 0)
      std::printf(
          "  setup %d: |M^-1 b - H^-1 b| / |H^-1 b| = %.2e, backward error %.2e\n",
          pass + 1, forward, backward);
    CHECK(forward <= 1e-9);
    CHECK(backward <= 1e-12);
    CHECK(minres_iterations(sys, *Minv, 1e-10) <= 2);
    check_spd(*Minv, map, "exact DD");
  }
  // Indefinite: H - D/2 (hundreds of negative eigenvalues): M stays SPD.
  sys.assemble_hessian(x);
  shift_hessian(sys, 0.5);
  dd.setup(sys);
  if (g_rank == 0)
    std::printf("  H - D/2: rods shifted %lld, coarse shift %g, uniform shift %g\n",
                dd.rods_shifted(), dd.coarse_shift(), dd.uniform_shift());
  CHECK(dd.uniform_shift() > 0.0);
  check_spd(*Minv, map, "exact DD, H - D/2");
  // Indefinite (rod blocks or the coarse matrix): one shift for the whole DD, M^-1
  // is the exact inverse of H + sigma |diag H| (D of this, the first indefinite
  // set-up); the DD set up on that matrix (positive definite: no shift) gives the
  // same vectors.
  {
    const double sigma = dd.uniform_shift();
    CHECK(sigma > 0.0);
    TMV b1(map, 1), y1(map, 1), y2(map, 1);
    random_vector(b1, 12);
    Minv->apply(b1, y1);
    shift_hessian(sys, -sigma);
    dd.setup(sys);
    CHECK(dd.uniform_shift() == 0.0 && dd.rods_shifted() == 0 &&
          dd.coarse_shift() == 0.0);
    Minv->apply(b1, y2);
    y1.update(-1.0, y2, 1.0);
    const double diff = norm(y1) / norm(y2);
    if (g_rank == 0)
      std::printf("  DD of H - D/2 with shift %g against the DD of the shifted H: "
                  "%.2e\n",
                  sigma, diff);
    CHECK(diff <= 1e-9);
  }
  // Mildly indefinite: H - 1.5 mu D, mu the lowest eigenvalue of the pencil (H, D)
  // (a few negative eigenvalues, as past a buckling load): MINRES converges in a few
  // iterations.
  sys.assemble_hessian(x);
  const double mu = pencil_min_eigenvalue(sys);
  shift_hessian(sys, 1.5 * mu);
  dd.setup(sys);
  if (g_rank == 0)
    std::printf("  H - 1.5 mu D (mu %.3e): rods shifted %lld, coarse shift %g, uniform "
                "shift %g\n",
                mu, dd.rods_shifted(), dd.coarse_shift(), dd.uniform_shift());
  CHECK(dd.uniform_shift() > 0.0);
  check_spd(*Minv, map, "exact DD, H - 1.5 mu D");
  CHECK(minres_iterations(sys, *Minv, 1e-8) <= 60);
}

// The AMG coarse solve: SPD, and MINRES iterations for growing honeycombs (coarse
// matrices of more rows than MueLu's coarsest level, so that the V-cycle is not
// exact); the automatic choice.
void check_amg(rn_context *ctx, const Teuchos::RCP<const Comm> &comm) {
  std::vector<int> its;
  for (int cells : {12, 24, 36}) {
    rn_scene *scene = lattice(ctx, RN_LATTICE_HONEYCOMB, cells, RN_JOINT_RIGID);
    ReplicatedSystem sys(rn_scene_network(scene), comm);
    TMV x(sys.map(), 1);
    sys.get_state(x);
    sys.assemble_hessian(x);
    DdOptions opt;
    opt.coarse = DdOptions::Coarse::Amg;
    DdPreconditioner dd(opt);
    dd.setup(sys);
    if (g_rank == 0)
      std::printf(
          "honeycomb %dx%d rigid, AMG coarse: %lld DOFs, %lld coarse rows, shift %g\n",
          cells, cells, static_cast<long long>(sys.global_size()), dd.coarse_rows(),
          dd.coarse_shift());
    CHECK(dd.coarse_solver() == "amg");
    check_spd(*dd.inverse(), sys.map(), "AMG DD", 1e-10);
    check_block(*dd.inverse(), sys.map(), "AMG DD", 1e-12);
    its.push_back(minres_iterations(sys, *dd.inverse(), 1e-8));
    if (cells == 12) {
      shift_hessian(sys, 1.5 * pencil_min_eigenvalue(sys));
      dd.setup(sys);
      if (g_rank == 0)
        std::printf("  H - 1.5 mu D: rods shifted %lld, coarse shift %g\n",
                    dd.rods_shifted(), dd.coarse_shift());
      check_spd(*dd.inverse(), sys.map(), "AMG DD, H - 1.5 mu D", 1e-10);
      minres_iterations(sys, *dd.inverse(), 1e-8);
      // automatic choice: direct by default, AMG when the factorisation is too costly
      sys.assemble_hessian(x);
      DdPreconditioner autodd;
      autodd.setup(sys);
      CHECK(autodd.coarse_solver() == "direct");
      DdOptions cheap;
      cheap.direct_max_flops = 1e3;
      DdPreconditioner autoamg(cheap);
      autoamg.setup(sys);
      CHECK(autoamg.coarse_solver() == "amg");
      CHECK(minres_iterations(sys, *autoamg.inverse(), 1e-8) == its.back());
    }
    rn_scene_destroy(&scene);
  }
  CHECK(its.back() <= 1.5 * its.front());
}

// The coarse pencil's verdict against H's inertia (the top).  H - c D_G, D_G =
// |diag H| on the interface DOFs only: the rod blocks stay positive definite and
// unshifted, and c* (bisection on the sparse Cholesky of the whole matrix) is where
// H, hence S, stops being positive definite.
void check_coarse_pencil(rn_context *ctx, const Teuchos::RCP<const Comm> &comm) {
  rn_scene *scene = lattice(ctx, RN_LATTICE_HONEYCOMB, 12, RN_JOINT_RIGID);
  ReplicatedSystem sys(rn_scene_network(scene), comm);
  const NetworkDofs nd = network_dofs(rn_scene_network(scene));
  std::vector<bool> iface(nd.block.size());
  for (size_t i = 0; i < iface.size(); ++i) iface[i] = nd.block[i] < 0;
  TMV x(sys.map(), 1);
  sys.get_state(x);
  sys.assemble_hessian(x);
  const double cstar = pencil_min_eigenvalue(sys, &iface);
  CHECK(cstar < 1e300);
  for (double c : {0.0, 0.5, 0.99, 1.001, 1.01, 1.2}) {
    sys.assemble_hessian(x);
    if (c > 0.0) shift_hessian(sys, c * cstar, false, &iface);
    DdOptions opt;
    opt.coarse = DdOptions::Coarse::Amg;
    DdPreconditioner dd(opt);
    dd.setup(sys);
    Teuchos::RCP<const Tpetra::Operator<>> S, Ainv;
    const bool offered = dd.coarse_pencil(S, Ainv);
    double mu_s = 0.0;
    int steps = 0;
    if (offered) {
      TMV v(S->getDomainMap(), 1), Mv(S->getDomainMap(), 1);
      mu_s = pencil_lowest(*S, *Ainv, v, Mv, &steps);
    }
    if (g_rank == 0)
      std::printf("coarse pencil, H - %.2f c* D_G (c* = %.4e): rods shifted %lld, "
                  "coarse shift %g, offered %d, lowest Ritz value %.3e (%d steps)\n",
                  c, cstar, dd.rods_shifted(), dd.coarse_shift(), offered ? 1 : 0, mu_s,
                  steps);
    if (c < 1.0) { // H positive definite: offered, and certified
      CHECK(dd.rods_shifted() == 0);
      CHECK(offered);
      CHECK(mu_s > 1e-4);
    } else { // H indefinite: never certified (kCurvTol of tr_krylov.cpp)
      CHECK(!offered || !(mu_s > 1e3 * DBL_EPSILON));
    }
  }
  rn_scene_destroy(&scene);
}

// The alternatives measured against the DD (pc/impls/muelu, ifpack2): SPD, and
// MINRES reaches the tolerance with a true residual to match, on 1 and 2 ranks
// (Ifpack2's subdomain solves are rank-local Amesos2 KLU2 factorisations).
void check_alternatives(rn_context *ctx, const Teuchos::RCP<const Comm> &comm) {
  for (int model : {RN_JOINT_RIGID, RN_JOINT_ELASTIC}) {
    rn_scene *scene = lattice(ctx, RN_LATTICE_HONEYCOMB, 6, model);
    ReplicatedSystem sys(rn_scene_network(scene), comm);
    TMV x(sys.map(), 1);
    sys.get_state(x);
    sys.assemble_hessian(x);
    for (const char *name : {"muelu", "ifpack2"}) {
      std::unique_ptr<Preconditioner> P;
      if (std::string(name) == "muelu")
        P.reset(new MueluPreconditioner(sys.rigid_body_modes()));
      else
        P.reset(new SchwarzPreconditioner);
      CHECK(P != nullptr && P->name() == name);
      P->setup(sys);
      if (g_rank == 0)
        std::printf("%s, honeycomb 6x6 %s:\n", name,
                    model == RN_JOINT_RIGID ? "rigid" : "elastic");
      check_spd(*P->inverse(), sys.map(), name, 1e-10);
      CHECK(minres_iterations(sys, *P->inverse(), 1e-8) < 1000);
    }
    rn_scene_destroy(&scene);
  }
  // The registry (pc/registry.hpp): a row for every preconditioner of the enum, none
  // for auto or a value outside it.
  for (int k = RN_PRECOND_FACTOR; k <= RN_PRECOND_DD_AMG; ++k)
    CHECK(find_preconditioner(static_cast<rn_preconditioner>(k)) != nullptr &&
          find_preconditioner(static_cast<rn_preconditioner>(k))->kind == k);
  CHECK(find_preconditioner(RN_PRECOND_AUTO) == nullptr);
  CHECK(find_preconditioner(static_cast<rn_preconditioner>(RN_PRECOND_DD_AMG + 1)) ==
        nullptr);
}

} // namespace

int main(int argc, char **argv) {
  Tpetra::ScopeGuard guard(&argc, &argv);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  {
    auto comm = Tpetra::getDefaultComm();
    g_rank = comm->getRank();
    rn_context *ctx = nullptr;
    CHECK_STATUS(rn_context_create(&ctx), RN_OK);
    {
      rn_scene *s = lattice(ctx, RN_LATTICE_HONEYCOMB, 3, RN_JOINT_RIGID);
      check_exact(rn_scene_network(s), comm, "honeycomb 3x3 rigid");
      rn_scene_destroy(&s);
      s = lattice(ctx, RN_LATTICE_HONEYCOMB, 3, RN_JOINT_ELASTIC);
      check_exact(rn_scene_network(s), comm, "honeycomb 3x3 elastic");
      rn_scene_destroy(&s);
      s = lattice(ctx, RN_LATTICE_OCTET, 2, RN_JOINT_RIGID);
      check_exact(rn_scene_network(s), comm, "octet 2x2x2 rigid");
      rn_scene_destroy(&s);
      s = lattice(ctx, RN_LATTICE_OCTET, 2, RN_JOINT_ELASTIC, 2);
      check_exact(rn_scene_network(s), comm, "octet 2x2x2 elastic, 2 edges per rod");
      rn_scene_destroy(&s);
      rn_network *net = single_rod(ctx);
      check_exact(net, comm, "single rod");
      rn_network_destroy(&net);
    }
    check_amg(ctx, comm);
    check_coarse_pencil(ctx, comm);
    check_alternatives(ctx, comm);
    rn_context_destroy(&ctx);
    int failed = rn_test_failures > 0 ? 1 : 0, any = 0;
    Teuchos::reduceAll(*comm, Teuchos::REDUCE_MAX, failed, Teuchos::outArg(any));
    if (any && !failed) rn_test_failures = 1; // another rank failed
  }
  return rn_test_finish("shim_dd");
}

// multigrid.cpp - algebraic multigrid (MueLu) for the rod-level domain
// decomposition's coarse problem (dd_preconditioner.hpp) and for the alternative
// preconditioners measured against it (alt_preconditioners.hpp).  The only
// translation unit with MueLu / Ifpack2 headers (they compile slowly).
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <utility>

#include <Amesos2_Details_registerLinearSolverFactory.hpp>
#include <Ifpack2_Factory.hpp>
#include <MueLu_CreateTpetraPreconditioner.hpp>
#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_ParameterList.hpp>
#include <Teuchos_XMLParameterListHelpers.hpp>

#include "pc/alt_preconditioners.hpp"
#include "pc/spd_guard.hpp"
#include "base/shim_error.hpp"

namespace rodnet {

namespace {

using MueluOp = MueLu::TpetraOperator<double, LO, GO, Tpetra::Map<>::node_type>;

// Chebyshev polynomial of the given degree over [lambda_max / ratio, lambda_max],
// lambda_max of D^-1 A estimated safely (see below).
void chebyshev(Teuchos::ParameterList &c, int degree, double ratio) {
  c.set("chebyshev: degree", degree);
  c.set("chebyshev: ratio eigenvalue", ratio);
  c.set("chebyshev: eigenvalue max iterations", 50);
  c.set("chebyshev: boost factor", 1.3);
}

// Smoothed aggregation, Chebyshev smoothing of degree 3 (symmetric: the V-cycle is an SPD
// operator for an SPD matrix), rigid-body near-null space.  Coarsest level: KLU2 on
// one rank; on several ranks Jacobi relaxation (an Amesos2 solve of a matrix
// distributed over ranks is wrong in Trilinos 13.2, TRILINOS.md).
Teuchos::ParameterList
amg_parameters(int nranks, const Teuchos::RCP<const TMV> &nullspace, int block) {
  Teuchos::ParameterList p;
  p.set("verbosity", "none");
  p.set("multigrid algorithm", "sa");
  p.set("max levels", 10);
  p.set("coarse: max size", 1000);
  p.set("aggregation: type", "uncoupled");
  // Chebyshev needs an upper bound of the spectrum of D^-1 A: with MueLu's default
  // estimate (10 power iterations, boost 1.1) the V-cycle was indefinite for a
  // positive definite coarse matrix of a 36x36 honeycomb (the SPD probe then shifted
  // it by 100 |diag|: 2353 MINRES iterations); 50 iterations and a boost of 1.3 were
  // safe on every lattice measured (docs/solvers.md).
  p.set("smoother: type", "CHEBYSHEV");
  chebyshev(p.sublist("smoother: params"), 3, 20.0);
  if (nranks > 1) {
    // No direct solve of a distributed matrix: a coarsest level of at most 200 rows
    // smoothed by Chebyshev of degree 10 (Jacobi relaxation there: 137 MINRES
    // iterations on a 48x48 honeycomb on 2 ranks instead of 68).
    p.set("coarse: max size", 200);
    p.set("coarse: type", "CHEBYSHEV");
    chebyshev(p.sublist("coarse: params"), 10, 100.0);
  } else {
    p.set("coarse: type", "KLU2");
  }
  p.set("repartition: enable", false);
  p.set("number of equations", block);
  if (!nullspace.is_null())
    p.sublist("user data").set("Nullspace", Teuchos::rcp_const_cast<TMV>(nullspace));
  return p;
}

class AmgCoarse : public CoarseSolver {
public:
  // block: DOFs per node (rows 6 n .. 6 n + 5 for the DD's coarse matrix), 1 for a
  // matrix without node structure.
  explicit AmgCoarse(int block, std::string xml = std::string())
      : block_(block), xml_(std::move(xml)) {}
  void setup(const Teuchos::RCP<const TCrs> &S,
             const Teuchos::RCP<const TMV> &nullspace) override {
    if (!mpi_backed(*S->getComm()))
      throw Error(
          RN_ERR_TRILINOS,
          "algebraic multigrid (MueLu) needs the MPI runtime in Trilinos 13.2: run "
          "under mpirun or with RODNET_MPI=1 (docs/solvers.md)");
    const int nranks = S->getComm()->getSize();
    guard_.setup(
        *S,
        [&](const Teuchos::RCP<TCrs> &A) -> Teuchos::RCP<Tpetra::Operator<>> {
          Teuchos::ParameterList params = amg_parameters(nranks, nullspace, block_);
          if (!xml_.empty())
            Teuchos::updateParametersFromXmlFile(xml_, Teuchos::inOutArg(params));
          return MueLu::CreateTpetraPreconditioner(Teuchos::RCP<Tpetra::Operator<>>(A),
                                                   params);
        },
        "AMG");
    // matrix and hierarchy (operator complexity of smoothed aggregation ~1.5): estimate
    bytes_ = 2.5 * 12.0 * static_cast<double>(guard_.A->getNodeNumEntries());
  }
  void solve(const TMV &b, TMV &y) const override { guard_.P->apply(b, y); }
  double shift() const override { return guard_.shift; }
  double bytes() const override { return bytes_; }
  std::string name() const override { return "amg"; }

private:
  int block_;
  std::string xml_;
  SpdGuard guard_;
  double bytes_ = 0.0;
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

} // namespace

// A copy of S with t D added to the diagonal (D = |diag S| floored at 1e-8 max).
Teuchos::RCP<TCrs> shifted_copy(const TCrs &S, double t) {
  auto A = Teuchos::rcp(new TCrs(S, Teuchos::Copy));
  if (t == 0.0) return A;
  TMV d(S.getRowMap(), 1);
  auto dv = d.getVectorNonConst(0);
  S.getLocalDiagCopy(*dv);
  auto v = d.getLocalViewHost(Tpetra::Access::ReadWrite);
  double mx = 0.0, gmx = 0.0;
  for (size_t i = 0; i < v.extent(0); ++i) mx = std::max(mx, std::fabs(v(i, 0)));
  Teuchos::reduceAll(*S.getComm(), Teuchos::REDUCE_MAX, mx, Teuchos::outArg(gmx));
  A->resumeFill();
  auto rowmap = A->getRowMap();
  for (size_t i = 0; i < v.extent(0); ++i) {
    const double di = gmx > 0.0 ? std::max(std::fabs(v(i, 0)), 1e-8 * gmx) : 1.0;
    const GO g = rowmap->getGlobalElement(static_cast<LO>(i));
    const double add = t * di;
    A->sumIntoGlobalValues(g, Teuchos::ArrayView<const GO>(&g, 1),
                           Teuchos::ArrayView<const double>(&add, 1));
  }
  A->fillComplete(S.getDomainMap(), S.getRangeMap());
  return A;
}

// Positive definiteness probe of A with the SPD preconditioner P: preconditioned CG
// from a random right-hand side for `its` iterations; false if it meets
// nonpositive curvature (p'Ap <= 0) or a nonpositive r'P r.  Every eigenvector of
// P^-1 A is in the random start, and CG's Ritz values reach the ends of the
// spectrum first, so a negative eigenvalue of A shows up in a few iterations unless
// it is tiny against the spectrum's spread (then the coarse matrix is nearly
// singular there, and the outer MINRES, not this probe, meets it).
bool probe_positive(const TCrs &A, const Tpetra::Operator<> &P, int its) {
  auto map = A.getRowMap();
  TMV x(map, 1), r(map, 1), z(map, 1), p(map, 1), q(map, 1);
  {
    std::mt19937_64 gen(12345u + static_cast<unsigned>(map->getComm()->getRank()));
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    auto v = r.getLocalViewHost(Tpetra::Access::OverwriteAll);
    for (size_t i = 0; i < v.extent(0); ++i) v(i, 0) = u(gen);
  }
  Teuchos::Array<double> dots(1);
  P.apply(r, z);
  r.dot(z, dots());
  double rz = dots[0];
  if (!(rz > 0.0)) return false;
  p.assign(z);
  for (int k = 0; k < its; ++k) {
    A.apply(p, q);
    p.dot(q, dots());
    const double pq = dots[0];
    if (!(pq > 0.0)) return false;
    const double alpha = rz / pq;
    r.update(-alpha, q, 1.0);
    P.apply(r, z);
    r.dot(z, dots());
    const double rz1 = dots[0];
    if (!(rz1 > 0.0)) return rz1 == 0.0;
    p.update(1.0, z, rz1 / rz);
    rz = rz1;
  }
  return true;
}

std::unique_ptr<CoarseSolver> make_amg_coarse_solver(const std::string &xml) {
  return std::unique_ptr<CoarseSolver>(new AmgCoarse(6, xml));
}

// ---- MueLu on the whole Hessian ------------------------------------------------------
MueluPreconditioner::MueluPreconditioner(const Teuchos::RCP<const TMV> &nullspace)
    : nullspace_(nullspace), amg_(new AmgCoarse(1)) {}
MueluPreconditioner::~MueluPreconditioner() = default;

void MueluPreconditioner::setup(System &sys) {
  const auto t0 = std::chrono::steady_clock::now();
  map_ = sys.map();
  amg_->setup(sys.hessian(), nullspace_);
  stats_.setups++;
  stats_.setup_seconds += seconds_since(t0);
  stats_.bytes = amg_->bytes();
  stats_.shifted = amg_->shift() > 0.0;
}

Teuchos::RCP<const Tpetra::Operator<>> MueluPreconditioner::inverse() const {
  if (op_.is_null()) { // one operator for the preconditioner's life (callers keep it)
    std::shared_ptr<CoarseSolver> amg = amg_;
    op_ = stats_operator(
        map_, [amg](const TMV &x, TMV &y) { amg->solve(x, y); }, &stats_);
  }
  return op_;
}

double MueluPreconditioner::shift() const { return amg_->shift(); }

// ---- Ifpack2 additive Schwarz with a local sparse LU ---------------------------------
struct SchwarzPreconditioner::Impl {
  SpdGuard guard;
  Teuchos::RCP<const TMap> map;
};

SchwarzPreconditioner::SchwarzPreconditioner() : impl_(new Impl) {}
SchwarzPreconditioner::~SchwarzPreconditioner() = default;

void SchwarzPreconditioner::setup(System &sys) {
  const auto t0 = std::chrono::steady_clock::now();
  static const bool registered = [] {
    Amesos2::Details::registerLinearSolverFactory();
    return true;
  }();
  (void)registered;
  if (!mpi_backed(*sys.map()->getComm()))
    throw Error(
        RN_ERR_TRILINOS,
        "Ifpack2 additive Schwarz needs the MPI runtime in Trilinos 13.2: run under "
        "mpirun or with RODNET_MPI=1 (docs/solvers.md)");
  impl_->map = sys.map();
  impl_->guard.setup(
      *sys.hessian(),
      [](const Teuchos::RCP<TCrs> &A) -> Teuchos::RCP<Tpetra::Operator<>> {
        using RowMatrix = Tpetra::RowMatrix<>;
        Ifpack2::Factory factory;
        auto prec =
            factory.create<RowMatrix>("SCHWARZ", Teuchos::RCP<const RowMatrix>(A));
        Teuchos::ParameterList p;
        p.set("schwarz: overlap level", 1);
        p.set("schwarz: combine mode", "ADD");
        p.set("inner preconditioner name", "AMESOS2");
        Teuchos::ParameterList &inner = p.sublist("inner preconditioner parameters");
        inner.sublist("Amesos2");
        inner.set("Amesos2 solver name", "klu2");
        prec->setParameters(p);
        prec->initialize();
        prec->compute();
        return prec;
      },
      "ifpack2 preconditioner");
  stats_.setups++;
  stats_.setup_seconds += seconds_since(t0);
  stats_.bytes = 12.0 * static_cast<double>(impl_->guard.A->getNodeNumEntries()) * 2.0;
  stats_.shifted = impl_->guard.shift > 0.0;
}

Teuchos::RCP<const Tpetra::Operator<>> SchwarzPreconditioner::inverse() const {
  if (op_.is_null()) { // one operator for the preconditioner's life (callers keep it)
    std::shared_ptr<Impl> impl = impl_;
    op_ = stats_operator(
        impl_->map, [impl](const TMV &x, TMV &y) { impl->guard.P->apply(x, y); },
        &stats_);
  }
  return op_;
}

double SchwarzPreconditioner::shift() const { return impl_->guard.shift; }

// ---- by name
// ---------------------------------------------------------------------------
std::unique_ptr<Preconditioner>
make_preconditioner(const std::string &name, const Teuchos::RCP<const TMV> &nullspace) {
  if (name == "dd" || name == "dd-direct" || name == "dd-amg") {
    DdOptions o;
    o.coarse = name == "dd" ? DdOptions::Coarse::Auto
                            : (name == "dd-amg" ? DdOptions::Coarse::Amg
                                                : DdOptions::Coarse::Direct);
    return std::unique_ptr<Preconditioner>(new DdPreconditioner(o));
  }
  if (name == "muelu")
    return std::unique_ptr<Preconditioner>(new MueluPreconditioner(nullspace));
  if (name == "ifpack2")
    return std::unique_ptr<Preconditioner>(new SchwarzPreconditioner);
  if (name == "frosch")
    return std::unique_ptr<Preconditioner>(new FroschPreconditioner(nullspace));
  return nullptr;
}

} // namespace rodnet

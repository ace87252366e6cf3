// spd_guard.cpp - the diagonal shift, the positive definiteness probe and the MPI
// runtime test of the Trilinos preconditioners (spd_guard.hpp).
#include "pc/spd_guard.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include <Teuchos_CommHelpers.hpp>
#include <Teuchos_DefaultMpiComm.hpp>

namespace rodnet {

bool mpi_backed(const Teuchos::Comm<int> &comm) {
  return dynamic_cast<const Teuchos::MpiComm<int> *>(&comm) != nullptr;
}

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

} // namespace rodnet

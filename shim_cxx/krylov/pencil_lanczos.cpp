// pencil_lanczos.cpp - preconditioned Lanczos for the lowest eigenpair of a pencil
// (H, M) on Tpetra operators (see pencil_lanczos.hpp).
#include "krylov/pencil_lanczos.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Teuchos_Array.hpp>

#include "base/shim_error.hpp"

extern "C" void dstev_(const char *jobz, const int *n, double *d, double *e, double *z,
                       const int *ldz, double *work, int *info, size_t jobz_len);

namespace rodnet {

namespace {

using TMap = Tpetra::Map<>;
using GO = TMap::global_ordinal_type;
using Vec = Tpetra::MultiVector<>; // one column

constexpr int kSteps = 30; // at most this many Lanczos steps

double dot(const Vec &a, const Vec &b) {
  Teuchos::Array<double> r(1);
  a.dot(b, r());
  return r[0];
}

// Lowest eigenpair of the pencil (H, M) by preconditioned Lanczos (M-orthonormal
// basis, full reorthogonalisation) from a fixed pseudo-random start; v is returned
// M-normalised with M v in Mv, mu = v' H v.  H and M^{-1} are operators on map (the
// System's Hessian and the preconditioner, or the DD's coarse pencil).
class PencilLanczos {
public:
  PencilLanczos(const Tpetra::Operator<> &H, const Tpetra::Operator<> &Minv,
                const Teuchos::RCP<const TMap> &map)
      : H_(H), Minv_(Minv), map_(map), z_(map_, 1), y_(map_, 1) {}

  double lowest(Vec &v, Vec &Mv, int *steps) {
    std::vector<Vec> V, Z; // Lanczos vectors and M times them
    std::vector<double> alpha, beta;
    // start: z = pseudo-random (unpreconditioned space), y = M^{-1} z
    const size_t nloc = z_.getLocalLength();
    const GO base = map_->getMinGlobalIndex();
    {
      auto zv = z_.getLocalViewHost(Tpetra::Access::OverwriteAll);
      for (size_t i = 0; i < nloc; ++i)
        zv(i, 0) =
            1.0 +
            0.5 * std::sin(0.7 * static_cast<double>(base + static_cast<GO>(i)) + 0.3);
    }
    Minv_.apply(z_, y_);
    double b = std::sqrt(std::max(dot(z_, y_), 0.0));
    for (int k = 0; k < kSteps && b > 0.0; ++k) {
      V.emplace_back(map_, 1);
      Z.emplace_back(map_, 1);
      V.back().update(1.0 / b, y_, 0.0);
      Z.back().update(1.0 / b, z_, 0.0);
      if (k > 0) beta.push_back(b);
      H_.apply(V.back(), z_); // z = H v_k (unpreconditioned)
      const double a = dot(V.back(), z_);
      alpha.push_back(a);
      // z -= a M v_k + b M v_{k-1}; then full reorthogonalisation in the M-inner
      // product: z -= sum (v_j' z) M v_j
      z_.update(-a, Z.back(), 1.0);
      if (k > 0) z_.update(-b, Z[Z.size() - 2], 1.0);
      for (size_t j = 0; j < V.size(); ++j) z_.update(-dot(V[j], z_), Z[j], 1.0);
      Minv_.apply(z_, y_);
      b = std::sqrt(std::max(dot(z_, y_), 0.0));
      if (b <= 1e-12 * std::fabs(a)) break;
    }
    const int m = static_cast<int>(alpha.size());
    *steps = m;
    std::vector<double> d(alpha), e(beta), zz(static_cast<size_t>(m) * m),
        work(static_cast<size_t>(std::max(1, 2 * m - 2)));
    e.resize(static_cast<size_t>(std::max(m - 1, 1)));
    int info = 0;
    dstev_("V", &m, d.data(), e.data(), zz.data(), &m, work.data(), &info, 1);
    if (info != 0) throw Error(RN_ERR_LAPACK, "rn_solve: Lanczos eigenvalues (dstev)");
    v.putScalar(0.0);
    Mv.putScalar(0.0);
    for (int j = 0; j < m; ++j) { // eigenvector of the lowest Ritz value (column 0)
      v.update(zz[static_cast<size_t>(j)], V[static_cast<size_t>(j)], 1.0);
      Mv.update(zz[static_cast<size_t>(j)], Z[static_cast<size_t>(j)], 1.0);
    }
    H_.apply(v, y_);
    const double vv = dot(v, Mv);
    return vv > 0.0 ? dot(v, y_) / vv : d[0];
  }

private:
  const Tpetra::Operator<> &H_;
  const Tpetra::Operator<> &Minv_;
  Teuchos::RCP<const TMap> map_;
  Vec z_, y_;
};

} // namespace

double pencil_lowest(const Tpetra::Operator<> &H, const Tpetra::Operator<> &Minv,
                     const Teuchos::RCP<const Tpetra::Map<>> &map,
                     Tpetra::MultiVector<> &v, Tpetra::MultiVector<> &Mv, int *steps) {
  return PencilLanczos(H, Minv, map).lowest(v, Mv, steps);
}

double pencil_lowest(const Tpetra::Operator<> &H, const Tpetra::Operator<> &Minv,
                     Tpetra::MultiVector<> &v, Tpetra::MultiVector<> &Mv, int *steps) {
  return PencilLanczos(H, Minv, H.getDomainMap()).lowest(v, Mv, steps);
}

} // namespace rodnet

// banded.cpp - banded Cholesky (dpbtrf/dpbtrs) and banded eigenvalues (dsbevx).
#include "factor/banded.hpp"

#include <climits>
#include <cmath>
#include <string>

#include "base/lapack.hpp"
#include "base/shim_error.hpp"

extern "C" {
// LAPACK (Fortran) with the hidden character-length arguments of gfortran.
void dsbevx_(const char *jobz, const char *range, const char *uplo, const int *n,
             const int *kd, double *ab, const int *ldab, double *q, const int *ldq,
             const double *vl, const double *vu, const int *il, const int *iu,
             const double *abstol, int *m, double *w, double *z, const int *ldz,
             double *work, int *iwork, int *ifail, int *info, size_t jobz_len,
             size_t range_len, size_t uplo_len);
double dlamch_(const char *cmach, size_t cmach_len);
}

namespace rodnet {

namespace {

int lapack_int(size_t v, const char *what) {
  if (v > static_cast<size_t>(INT_MAX))
    throw Error(RN_ERR_LAPACK,
                std::string("rn_solve: ") + what + " exceeds LAPACK's int");
  return static_cast<int>(v);
}

// Lower band storage: A(i, j), j <= i <= j + kd, at ab[(i - j) + j * (kd + 1)].
// A = H + shift M with M given by CSR values m on the Hessian's pattern (or NULL).
void load_band(const CsrMatrix &p, double shift, const double *m, size_t kd,
               std::vector<double> &ab) {
  const size_t n = p.size(), ld = kd + 1;
  ab.assign(n * ld, 0.0);
  for (size_t i = 0; i < n; ++i) {
    for (int64_t k = p.rowptr()[i]; k < p.rowptr()[i + 1]; ++k) {
      const size_t j = static_cast<size_t>(p.col()[k]);
      if (j > i || i - j > kd) continue; // upper triangle (or outside the band)
      ab[(i - j) + j * ld] += m ? p.values()[k] + shift * m[k] : p.values()[k];
    }
  }
}

} // namespace

BandedSpd::BandedSpd(size_t n, size_t kd) : n_(n), kd_(kd) {
  lapack_int(n, "number of DOFs");
  lapack_int((kd + 1) * (n > 0 ? n : 1), "band storage");
  ab_.assign(n * (kd + 1), 0.0);
}

bool BandedSpd::factor(const CsrMatrix &p, double shift, const double *m) {
  if (p.bandwidth() != kd_) { // a new pattern (contact, CsrMatrix::pattern_version)
    lapack_int((p.bandwidth() + 1) * (n_ > 0 ? n_ : 1), "band storage");
    kd_ = p.bandwidth();
    ab_.assign(n_ * (kd_ + 1), 0.0);
  }
  p.count_factorization();
  load_band(p, shift, m, kd_, ab_);
  const int n = static_cast<int>(n_), kd = static_cast<int>(kd_), ld = kd + 1;
  int info = 0;
  if (n > 0) dpbtrf_("L", &n, &kd, ab_.data(), &ld, &info, 1);
  factored_ = (info == 0);
  return factored_;
}

void BandedSpd::solve(double *x) const {
  if (!factored_) throw Error(RN_ERR_INTERNAL, "rn_solve: banded solve before factor");
  const int n = static_cast<int>(n_), kd = static_cast<int>(kd_), ld = kd + 1, one = 1;
  int info = 0;
  if (n > 0) dpbtrs_("L", &n, &kd, &one, ab_.data(), &ld, x, &n, &info, 1);
  if (info != 0) throw Error(RN_ERR_LAPACK, "rn_solve: dpbtrs failed");
}

double banded_min_eigenvalue(const CsrMatrix &p) {
  const size_t n = p.size(), kd = p.bandwidth();
  if (n == 0) throw Error(RN_ERR_ARG, "rn_hessian_min_eigenvalue: no free DOFs");
  const int ni = lapack_int(n, "number of DOFs"), kdi = lapack_int(kd, "bandwidth");
  lapack_int((kd + 1) * n, "band storage");
  std::vector<double> ab;
  load_band(p, 0.0, nullptr, kd, ab);
  const int ld = kdi + 1, ldq = 1, ldz = 1, il = 1, iu = 1;
  const double vl = 0.0, vu = 0.0, abstol = 2.0 * dlamch_("S", 1);
  int m = 0, info = 0;
  double q = 0.0, z = 0.0;
  std::vector<double> w(n), work(7 * n);
  std::vector<int> iwork(5 * n), ifail(n);
  dsbevx_("N", "I", "L", &ni, &kdi, ab.data(), &ld, &q, &ldq, &vl, &vu, &il, &iu, &abstol,
          &m, w.data(), &z, &ldz, work.data(), iwork.data(), ifail.data(), &info, 1, 1,
          1);
  if (info != 0 || m != 1 || !std::isfinite(w[0]))
    throw Error(RN_ERR_LAPACK, "rn_hessian_min_eigenvalue: dsbevx failed (info " +
                                   std::to_string(info) + ")");
  return w[0];
}

} // namespace rodnet

// stability.cpp - lowest eigenvalues and zero modes of the reduced Hessian (see
// stability.hpp).
#include "eigen/stability.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <vector>

#include "base/lapack.hpp"
#include "krylov/lanczos.hpp"
#include "rodnet.h"
#include "base/shim_error.hpp"
#include "factor/spd_factor.hpp"

namespace rodnet {

namespace {

constexpr int kMaxSweeps = 200;        // subspace iterations
constexpr int kLanczosSteps = 20;      // certified case: Lanczos steps (memory 20 n)
constexpr double kResidualRel = 1e-8;  // Ritz pair converged: ||H x - mu x|| below
constexpr double kResidualAbs = 1e-13; // max(kResidualRel |mu|, kResidualAbs scale)
constexpr double kMetricFloor = 1e-20; // D_i >= kMetricFloor max_j D_j
constexpr double kSymmetryTol = 1e-8;  // a symmetry: ||H v|| <= kSymmetryTol scale
constexpr int kMaxSpinRods = 64;       // frame spins tried on networks up to this size

// ||D^{-1/2} H D^{-1/2}||_inf of the assembled Hessian.
double row_sum_norm(const Problem &p, const std::vector<double> &d) {
  double s = 0.0;
  for (size_t i = 0; i < p.size(); ++i) {
    double r = 0.0;
    for (int64_t k = p.rowptr()[i]; k < p.rowptr()[i + 1]; ++k)
      r +=
          std::fabs(p.values()[k]) / std::sqrt(d[i] * d[static_cast<size_t>(p.col()[k])]);
    s = std::max(s, r);
  }
  return s;
}

// <a, b>_D
double ddot(const std::vector<double> &d, const double *a, const double *b) {
  double s = 0.0;
  for (size_t i = 0; i < d.size(); ++i) s += d[i] * a[i] * b[i];
  return s;
}

// A deterministic pseudo-random vector (entries in [-1, 1]).
void fill_start(size_t n, uint64_t seed, double *x) {
  uint64_t s = seed * 0x9E3779B97F4A7C15ULL + 1;
  for (size_t i = 0; i < n; ++i) {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    x[i] = static_cast<double>(s >> 11) * (2.0 / 9007199254740992.0) - 1.0;
  }
}

// D-orthonormalise the k columns of X (n x k, column-major) by modified
// Gram-Schmidt, twice; a column that loses its information (a multiple of the
// previous ones) is replaced by a fresh start vector.
void orthonormalize(const std::vector<double> &d, int k, std::vector<double> &X,
                    uint64_t &seed) {
  const size_t n = d.size();
  for (int j = 0; j < k; ++j) {
    double *xj = X.data() + static_cast<size_t>(j) * n;
    for (int attempt = 0; attempt < 3; ++attempt) {
      const double before = std::sqrt(ddot(d, xj, xj));
      for (int pass = 0; pass < 2; ++pass)
        for (int i = 0; i < j; ++i) {
          const double *xi = X.data() + static_cast<size_t>(i) * n;
          const double c = ddot(d, xi, xj);
          for (size_t r = 0; r < n; ++r) xj[r] -= c * xi[r];
        }
      const double after = std::sqrt(ddot(d, xj, xj));
      if (after > 1e-10 * before && after > 0.0) {
        for (size_t r = 0; r < n; ++r) xj[r] /= after;
        break;
      }
      if (attempt == 2)
        throw Error(RN_ERR_INTERNAL, "stability: orthonormalisation failed");
      fill_start(n, ++seed, xj);
    }
  }
}

// The k x k symmetric eigenproblem G y = mu y (G overwritten by the eigenvectors,
// column-major; mu ascending).
void small_eigen(int k, std::vector<double> &G, std::vector<double> &mu) {
  mu.assign(static_cast<size_t>(k), 0.0);
  int lwork = std::max(1, 3 * k - 1), info = 0;
  std::vector<double> work(static_cast<size_t>(lwork));
  dsyev_("V", "U", &k, G.data(), &k, mu.data(), work.data(), &lwork, &info, 1, 1);
  if (info != 0) throw Error(RN_ERR_LAPACK, "stability: dsyev failed");
}

// Y <- Y C for an n x k block Y and a k x k matrix C (column-major).
void rotate(size_t n, int k, std::vector<double> &Y, const std::vector<double> &C) {
  std::vector<double> row(static_cast<size_t>(k));
  for (size_t r = 0; r < n; ++r) {
    for (int j = 0; j < k; ++j) {
      double s = 0.0;
      for (int i = 0; i < k; ++i)
        s += Y[static_cast<size_t>(i) * n + r] * C[static_cast<size_t>(j * k + i)];
      row[static_cast<size_t>(j)] = s;
    }
    for (int j = 0; j < k; ++j)
      Y[static_cast<size_t>(j) * n + r] = row[static_cast<size_t>(j)];
  }
}

// D-orthonormalise the columns of V (n x k, column-major) by modified Gram-Schmidt,
// twice, dropping the columns that are (to 1e-8) combinations of the earlier ones;
// returns the number kept (the first columns of V).
int orthonormalize_drop(const std::vector<double> &d, int k, std::vector<double> &V) {
  const size_t n = d.size();
  int kept = 0;
  for (int j = 0; j < k; ++j) {
    double *v = V.data() + static_cast<size_t>(j) * n;
    const double before = std::sqrt(ddot(d, v, v));
    if (!(before > 0.0)) continue;
    for (int pass = 0; pass < 2; ++pass)
      for (int i = 0; i < kept; ++i) {
        const double *q = V.data() + static_cast<size_t>(i) * n;
        const double c = ddot(d, q, v);
        for (size_t r = 0; r < n; ++r) v[r] -= c * q[r];
      }
    const double after = std::sqrt(ddot(d, v, v));
    if (!(after > 1e-8 * before)) continue;
    double *q = V.data() + static_cast<size_t>(kept) * n;
    for (size_t r = 0; r < n; ++r) q[r] = v[r] / after;
    ++kept;
  }
  V.resize(static_cast<size_t>(kept) * n);
  return kept;
}

// The exact symmetries of the energy at the state (docs/solvers.md "Stability"):
// the candidates are the rigid motions (the three translations, the rotations about
// the axes rn_network_free_motions finds unblocked, about the centroid: a position
// moves by w x (x - c), a material angle by w . t, a joint rotation by w) and, for
// networks of at most kMaxSpinRods rods, the spin of each rod's material frame (its free
// material angles all by 1) and each component of the rotation of each rigid joint
// (at most kMaxSpinRods of them: a spin of the rods through a rigid joint turns it
// about their tangent, as when a ring of two rods rolls about its centre line); the
// symmetries are the combinations of them that the Hessian
// maps to zero: eigenvectors of the projected pencil with |mu| <= kZeroModeTol scale (the
// zero band) and
// ||H v - mu D v||_{D^-1} <= kSymmetryTol scale (the gradient left at the state
// tilts a rigid motion's image by about its size; a rigid motion that a support
// blocks, or that turns a loaded structure, is not one).
// Returns a D-orthonormal basis (n x m, column-major); m = columns.
// The vertices of every rod (xyz[r], 3 per vertex) and their centroid c; false if
// the network does not give them.
bool rod_points(rn_network *net, std::vector<std::vector<double>> &xyz, double c[3]) {
  const int nrods = rn_network_num_rods(net);
  xyz.assign(static_cast<size_t>(nrods), {});
  size_t count = 0;
  for (int r = 0; r < nrods; ++r) {
    const int nv = rn_network_rod_num_vertices(net, r);
    xyz[static_cast<size_t>(r)].resize(3 * static_cast<size_t>(nv > 0 ? nv : 0));
    if (nv <= 0 || rn_network_rod_vertices(net, r, xyz[static_cast<size_t>(r)].data()))
      return false;
    for (int v = 0; v < nv; ++v, ++count)
      for (int k = 0; k < 3; ++k) c[k] += xyz[static_cast<size_t>(r)][3 * v + k];
  }
  for (int k = 0; k < 3; ++k) c[k] /= static_cast<double>(count ? count : 1);
  return true;
}

// The candidate motions' columns of V (n x k, column-major): the translations (0-2),
// the free rotations fm about c (3 ..), the spins of the first `spins` rods' material
// frames, and the rotation components of the joints with a slot in jslot (njrot of
// them); false if a joint's position is not known.
bool candidate_motions(rn_network *net, const std::vector<rn_dof_info> &info,
                       const std::vector<std::vector<double>> &xyz, const double c[3],
                       const rn_free_motions &fm, int spins,
                       const std::vector<int> &jslot, int njrot, std::vector<double> &V) {
  const size_t n = info.size();
  const int nrot = fm.num_rotations;
  auto col = [&](int j) { return V.data() + static_cast<size_t>(j) * n; };
  for (size_t i = 0; i < n; ++i) {
    const rn_dof_info &f = info[i];
    double pos[3] = {0.0, 0.0, 0.0}, t[3] = {0.0, 0.0, 0.0};
    if (f.kind == RN_DOF_POSITION) {
      if (f.rod >= 0) {
        for (int a = 0; a < 3; ++a)
          pos[a] = xyz[static_cast<size_t>(f.rod)][3 * static_cast<size_t>(f.index) + a];
      } else if (rn_network_joint_position(net, f.joint, pos) != RN_OK) {
        return false;
      }
      const double r[3] = {pos[0] - c[0], pos[1] - c[1], pos[2] - c[2]};
      col(f.component)[i] = 1.0;
      for (int b = 0; b < nrot; ++b) { // (a x r)_component
        const double *e = fm.rotation[b];
        const double w[3] = {e[1] * r[2] - e[2] * r[1], e[2] * r[0] - e[0] * r[2],
                             e[0] * r[1] - e[1] * r[0]};
        col(3 + b)[i] = w[f.component];
      }
    } else if (f.kind == RN_DOF_THETA) {
      const double *x0 =
          &xyz[static_cast<size_t>(f.rod)][3 * static_cast<size_t>(f.index)];
      double len = 0.0;
      for (int a = 0; a < 3; ++a) {
        t[a] = x0[3 + a] - x0[a];
        len += t[a] * t[a];
      }
      len = std::sqrt(len);
      for (int b = 0; b < nrot; ++b) {
        const double *e = fm.rotation[b];
        col(3 + b)[i] = len > 0.0 ? (e[0] * t[0] + e[1] * t[1] + e[2] * t[2]) / len : 0.0;
      }
      if (f.rod < spins) col(3 + nrot + f.rod)[i] = 1.0;
    } else if (f.kind == RN_DOF_ROTATION) {
      for (int b = 0; b < nrot; ++b) col(3 + b)[i] = fm.rotation[b][f.component];
      if (njrot && f.joint >= 0 && jslot[static_cast<size_t>(f.joint)] >= 0)
        col(3 + nrot + spins + 3 * jslot[static_cast<size_t>(f.joint)] + f.component)[i] =
            1.0;
    }
  }
  return true;
}

// Rayleigh-Ritz on the k D-orthonormal columns of V: keeps (first in V) the Ritz
// vectors in the zero band whose residual ||H v - mu D v||_{D^-1} is at most
// kSymmetryTol scale; returns their number.
int keep_symmetries(Problem &p, const std::vector<double> &d, double scale, int k,
                    std::vector<double> &V) {
  const size_t n = p.size();
  auto col = [&](int j) { return V.data() + static_cast<size_t>(j) * n; };
  std::vector<double> W(V.size()), G(static_cast<size_t>(k * k)), mu;
  for (int j = 0; j < k; ++j)
    p.hessian_apply(col(j), W.data() + static_cast<size_t>(j) * n);
  for (int j = 0; j < k; ++j)
    for (int i = 0; i <= j; ++i) {
      const double g = 0.5 * (dot(n, col(i), W.data() + static_cast<size_t>(j) * n) +
                              dot(n, col(j), W.data() + static_cast<size_t>(i) * n));
      G[static_cast<size_t>(j * k + i)] = G[static_cast<size_t>(i * k + j)] = g;
    }
  small_eigen(k, G, mu);
  rotate(n, k, V, G);
  rotate(n, k, W, G);
  int m = 0;
  for (int j = 0; j < k; ++j) {
    const double *v = col(j), *w = W.data() + static_cast<size_t>(j) * n;
    double res = 0.0;
    for (size_t r = 0; r < n; ++r) {
      const double e = w[r] - mu[static_cast<size_t>(j)] * d[r] * v[r];
      res += e * e / d[r];
    }
    if (std::sqrt(res) > kSymmetryTol * scale ||
        std::fabs(mu[static_cast<size_t>(j)]) > kZeroModeTol * scale)
      continue;
    if (m != j) std::copy(v, v + n, col(m));
    ++m;
  }
  return m;
}

std::vector<double> symmetry_basis(Problem &p, const std::vector<double> &d, double scale,
                                   int *m_out) {
  const size_t n = p.size();
  rn_network *net = p.network();
  *m_out = 0;
  std::vector<rn_dof_info> info(n);
  if (n == 0 || rn_network_dof_info(net, info.data()) != RN_OK) return {};
  const int nrods = rn_network_num_rods(net);
  std::vector<std::vector<double>> xyz;
  double c[3] = {0.0, 0.0, 0.0};
  if (!rod_points(net, xyz, c)) return {};
  // the rotations no constraint blocks (rn_network_free_motions: a rotation blocked
  // at one end of a long rod, restricted to the free DOFs, is nearly a null vector:
  // its Rayleigh quotient falls like N^-3), about the centroid: Rayleigh-Ritz with
  // the translations finds the axis through the supports
  rn_free_motions fm{};
  if (rn_network_free_motions(net, &fm) != RN_OK) return {};
  const int nrot = fm.num_rotations;
  const int spins = nrods <= kMaxSpinRods ? nrods : 0;
  // the joints with a rotation (rigid joints): a spin of the rods meeting at one
  // turns it about their common tangent (a ring rolling about its centre line), so
  // each rotation component is a candidate too, for as many joints as spins
  std::vector<int> jslot(static_cast<size_t>(std::max(rn_network_num_joints(net), 0)),
                         -1);
  int njrot = 0;
  for (size_t i = 0; i < n && spins; ++i)
    if (info[i].kind == RN_DOF_ROTATION && info[i].joint >= 0 &&
        static_cast<size_t>(info[i].joint) < jslot.size() &&
        jslot[static_cast<size_t>(info[i].joint)] < 0)
      jslot[static_cast<size_t>(info[i].joint)] = njrot++;
  if (njrot > kMaxSpinRods) njrot = 0;
  int k = 3 + nrot + spins + 3 * njrot;
  std::vector<double> V(n * static_cast<size_t>(k), 0.0);
  if (!candidate_motions(net, info, xyz, c, fm, spins, jslot, njrot, V)) return {};
  k = orthonormalize_drop(d, k, V);
  if (k == 0) return {};
  const int m = keep_symmetries(p, d, scale, k, V);
  V.resize(static_cast<size_t>(m) * n);
  *m_out = m;
  return V;
}

// x <- x - S S' D x: D-orthogonal to the symmetries S (n x m).
void deflate(const std::vector<double> &d, const std::vector<double> &S, int m,
             double *x) {
  const size_t n = d.size();
  for (int pass = 0; pass < 2; ++pass)
    for (int j = 0; j < m; ++j) {
      const double *s = S.data() + static_cast<size_t>(j) * n;
      const double c = ddot(d, s, x);
      for (size_t r = 0; r < n; ++r) x[r] -= c * s[r];
    }
}

struct RitzPairs {
  std::vector<double> mu, residual; // ascending Ritz values, ||H x - mu x||
  bool converged = false;           // every pair the verdict needs has converged
};

// rp.residual: ||H x - mu D x|| in the D^{-1} norm of the k Ritz pairs (mu in rp,
// x in X, H x in W).
void ritz_residuals(const std::vector<double> &d, int k, const std::vector<double> &X,
                    const std::vector<double> &W, RitzPairs &rp) {
  const size_t n = d.size();
  rp.residual.assign(static_cast<size_t>(k), 0.0);
  for (int j = 0; j < k; ++j) {
    const double *x = X.data() + static_cast<size_t>(j) * n,
                 *w = W.data() + static_cast<size_t>(j) * n;
    double s = 0.0;
    for (size_t r = 0; r < n; ++r) {
      const double e = w[r] - rp.mu[static_cast<size_t>(j)] * d[r] * x[r];
      s += e * e / d[r];
    }
    rp.residual[static_cast<size_t>(j)] = std::sqrt(s);
  }
}

// Whether the pairs the verdict needs have converged: through the first Ritz value
// outside the zero band [-delta, delta] (only the first if it is below -delta).
bool ritz_converged(const RitzPairs &rp, int k, double delta, double scale) {
  int need = 0;
  while (need < k && std::fabs(rp.mu[static_cast<size_t>(need)]) <= delta) ++need;
  need = std::min(need + 1, k);
  if (rp.mu[0] < -delta) need = 1;
  for (int j = 0; j < need; ++j)
    if (rp.residual[static_cast<size_t>(j)] >
        std::max(kResidualRel * std::fabs(rp.mu[static_cast<size_t>(j)]),
                 kResidualAbs * scale))
      return false;
  return true;
}

// Subspace iteration with the factorisation f of H + s D (positive definite): the
// lowest Ritz pairs of the pencil (H, D).  Stops once the pairs up to the first one
// outside the zero band [-delta, delta] have converged (only the first if it is
// below -delta).
RitzPairs subspace_iteration(Problem &p, const SpdFactor &f, const std::vector<double> &d,
                             double delta, double scale, const std::vector<double> &S,
                             int m) {
  const size_t n = p.size();
  const int k =
      static_cast<int>(std::min<size_t>(n - static_cast<size_t>(m), kStabilityBlock));
  std::vector<double> X(n * static_cast<size_t>(k)), W(X.size()),
      G(static_cast<size_t>(k * k));
  uint64_t seed = 1;
  for (int j = 0; j < k; ++j)
    fill_start(n, seed++, X.data() + static_cast<size_t>(j) * n);
  RitzPairs rp;
  for (int sweep = 0; sweep < kMaxSweeps && !rp.converged; ++sweep) {
    for (int j = 0; j < k; ++j) {
      double *x = X.data() + static_cast<size_t>(j) * n;
      for (size_t r = 0; r < n; ++r) x[r] *= d[r];
      f.solve(x);
      deflate(d, S, m, x); // the complement of the symmetries
    }
    orthonormalize(d, k, X, seed);
    if (m > 0) { // again: a column orthonormalize restarted is not deflated yet
      for (int j = 0; j < k; ++j) deflate(d, S, m, X.data() + static_cast<size_t>(j) * n);
      orthonormalize(d, k, X, seed);
    }
    for (int j = 0; j < k; ++j)
      p.hessian_apply(X.data() + static_cast<size_t>(j) * n,
                      W.data() + static_cast<size_t>(j) * n);
    for (int j = 0; j < k; ++j)
      for (int i = 0; i <= j; ++i) {
        const double g = 0.5 * (dot(n, X.data() + static_cast<size_t>(i) * n,
                                    W.data() + static_cast<size_t>(j) * n) +
                                dot(n, X.data() + static_cast<size_t>(j) * n,
                                    W.data() + static_cast<size_t>(i) * n));
        G[static_cast<size_t>(j * k + i)] = G[static_cast<size_t>(i * k + j)] = g;
      }
    small_eigen(k, G, rp.mu);
    rotate(n, k, X, G);
    rotate(n, k, W, G);
    ritz_residuals(d, k, X, W, rp);
    rp.converged = static_cast<size_t>(k + m) == n || // the whole space: exact
                   ritz_converged(rp, k, delta, scale);
  }
  return rp;
}

// The largest Ritz value theta of A^{-1} D by Lanczos, A factored in f (from the
// fixed start 7): 1 / theta bounds the lowest eigenvalue of the pencil (A, D) from
// above.
double inverse_lanczos(const SpdFactor &f, const std::vector<double> &d) {
  std::vector<double> v(d.size());
  fill_start(d.size(), 7, v.data());
  const LanczosResult lr =
      lanczos_largest([&f](double *x) { f.solve(x); }, d, kLanczosSteps, 1e-6, v);
  return lr.theta;
}

// The verdict from the Ritz pairs rp of subspace_iteration (m symmetries): the
// lowest eigenvalue, the soft modes (|mu| <= delta outside the symmetries), whether
// they are positive (inertia of H itself, f refactored, when there are no
// symmetries; otherwise each soft Ritz value beyond its residual) and whether the
// state is a verified minimum.
void classify_soft_modes(Problem &p, SpdFactor &f, const std::vector<double> &d,
                         const std::vector<double> &dvals, double delta, int m,
                         const RitzPairs &rp, rn_stability &st) {
  size_t j = 0;
  while (j < rp.mu.size() && std::fabs(rp.mu[j]) <= delta) ++j;
  st.lowest_eigenvalue = rp.mu[0];
  if (rp.mu[0] < -delta) { // unstable
    for (double mu : rp.mu) st.soft_modes += std::fabs(mu) <= delta;
    return;
  }
  st.soft_modes = static_cast<int>(j);
  bool positive = j == 0;
  if (!positive && m == 0 && rp.mu[0] > 0.0 && f.factor(p, 0.0, dvals.data())) {
    // H itself factors: the soft modes are positive eigenvalues below delta
    // (inertia); the lowest by shift-and-invert Lanczos on H^{-1} D
    st.lowest_eigenvalue = 1.0 / inverse_lanczos(f, d);
    positive = true;
  } else if (!positive && m > 0) {
    // on the complement of the symmetries: every soft Ritz value positive
    // beyond its residual (an eigenvalue within the residual of each)
    positive = true;
    for (size_t i = 0; i < j; ++i) positive = positive && rp.mu[i] > rp.residual[i];
  }
  if (positive) st.soft_positive = st.soft_modes;
  st.verified_minimum =
      rp.converged && positive && (j < rp.mu.size() ? rp.mu[j] > delta : true);
}

} // namespace

rn_stability hessian_stability(Problem &p, rn_factorization kind) {
  const auto start = std::chrono::steady_clock::now();
  const long factorizations0 = p.counters.factorizations;
  rn_stability st{};
  st.checked = 1;
  st.method = RN_STABILITY_CHOLESKY;
  const size_t n = p.size();
  const std::vector<double> d = hessian_metric(p, kMetricFloor);
  st.scale = row_sum_norm(p, d);
  if (!std::isfinite(st.scale))
    throw Error(RN_ERR_NOT_FINITE, "stability: non-finite Hessian");
  if (n == 0) { // nothing free: trivially a minimum
    st.verified_minimum = 1;
  } else if (!(st.scale > 0.0)) { // H = 0: every mode is a zero mode
    st.zero_modes = static_cast<int>(std::min<size_t>(n, kStabilityBlock));
    st.soft_modes = st.zero_modes;
  } else {
    const double delta = kZeroModeTol * st.scale;
    const std::vector<double> dvals = diagonal_on_pattern(p, d);
    int m = 0;
    const std::vector<double> S = symmetry_basis(p, d, st.scale, &m);
    st.symmetries = m;
    auto f = make_spd_factor(p, kind);
    if (m == 0 && f->factor(p, -delta, dvals.data())) {
      // every eigenvalue above delta: the lowest by shift-and-invert Lanczos on
      // (H - delta D)^{-1} D, whose Ritz value bounds 1 / (lambda_min - delta) from
      // below
      st.lowest_eigenvalue = 1.0 / inverse_lanczos(*f, d) + delta;
      st.verified_minimum = 1;
    } else if (static_cast<size_t>(m) >= n) { // every mode a symmetry
      st.verified_minimum = 1;
    } else {
      // an eigenvalue <= delta: the smallest shift s with H + s D positive definite
      // (delta, or 10^k scale, k >= -10), for which f then holds the factorisation;
      // subspace iteration on the complement of the symmetries
      if (!f->factor(p, delta, dvals.data())) {
        std::vector<double> scaled(dvals);
        for (double &e : scaled) e *= st.scale;
        factor_shifted(*f, p, 0.0, scaled.data(), false);
      }
      const RitzPairs rp = subspace_iteration(p, *f, d, delta, st.scale, S, m);
      classify_soft_modes(p, *f, d, dvals, delta, m, rp, st);
    }
    st.zero_modes = st.symmetries + st.soft_modes - st.soft_positive;
  }
  st.factorizations = p.counters.factorizations - factorizations0;
  st.time_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return st;
}

int count_symmetries(Problem &p) {
  if (p.size() == 0) return 0;
  const std::vector<double> d = hessian_metric(p, kMetricFloor);
  const double scale = row_sum_norm(p, d);
  if (!std::isfinite(scale) || !(scale > 0.0)) return 0;
  int m = 0;
  symmetry_basis(p, d, scale, &m);
  return m;
}

} // namespace rodnet

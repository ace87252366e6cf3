// cell_part.cpp - the cell's relaxation and stability tests on a part of a
// distributed periodic cell (rn_cell_relax and rn_cell_bloch on a part;
// docs/homogenization.md, "Paths under mpirun"), through the distributed solver,
// and the acoustic tensor from the homogenised tangent (rn_cell_acoustic_tangent).
// The C API only (rn_solve, rn_network_stability, rn_homogenize) and LAPACK; no
// Trilinos here.  Every function is collective over the ranks on a part.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "base/lapack.hpp"
#include "base/shim_error.hpp"
#include "periodic/acoustic.hpp"
#include "periodic/cell_part.hpp"
#include "rodnet_model.h"
#include "rodnet_solve.h"

namespace rodnet {

namespace {

// Holds the strain DOFs for its lifetime (rn_network_cell_hold_strain).
class HoldStrain {
public:
  explicit HoldStrain(rn_network *net) : net_(net) {
    check_status(rn_network_cell_hold_strain(net_, 1), "rn_network_cell_hold_strain");
  }
  ~HoldStrain() { rn_network_cell_hold_strain(net_, 0); }
  HoldStrain(const HoldStrain &) = delete;
  HoldStrain &operator=(const HoldStrain &) = delete;

private:
  rn_network *net_;
};

// The index pairs (i, j) of the Voigt components (engineering shear), as the
// strain basis of c_api/periodic/periodic.c.
const int kPairs2[3][2] = {{0, 0}, {1, 1}, {0, 1}};
const int kPairs3[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};

struct Voigt {
  int d, ns;
  const int (*pairs)[2];
  explicit Voigt(int dim)
      : d(dim), ns(dim == 2 ? 3 : 6), pairs(dim == 2 ? kPairs2 : kPairs3) {}
  // Component of the index pair (i, j) (either order).
  int of(int i, int j) const {
    for (int v = 0; v < ns; ++v)
      if ((pairs[v][0] == i && pairs[v][1] == j) ||
          (pairs[v][0] == j && pairs[v][1] == i))
        return v;
    return -1;
  }
  // Basis tensor B_v (d x d, row-major 3 x 3 storage).
  void basis(int v, double *B) const {
    std::fill(B, B + 9, 0.0);
    B[3 * pairs[v][0] + pairs[v][1]] += 0.5;
    B[3 * pairs[v][1] + pairs[v][0]] += 0.5;
  }
};

// C = A B (3 x 3, the leading d x d block).
void mul(int d, const double *A, const double *B, double *C) {
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j) {
      double s = 0.0;
      for (int k = 0; k < d; ++k) s += A[3 * i + k] * B[3 * k + j];
      C[3 * i + j] = s;
    }
}

} // namespace

rn_status cell_state(rn_network *net, double *strain, double *stress, double *energy) {
  double E[RN_TERM_COUNT];
  size_t n = rn_network_num_dofs(net);
  std::vector<double> x(n ? n : 1);
  rn_status st = rn_network_get_dofs(net, x.data());
  if (!st) st = rn_network_cell_strain(net, x.data(), strain);
  if (!st) st = rn_network_cell_stress(net, x.data(), stress);
  if (!st && energy) st = rn_network_energy_terms(net, x.data(), E);
  if (!st && energy) *energy = E[RN_TERM_STRETCH] + E[RN_TERM_BEND] + E[RN_TERM_TWIST];
  if (!st && rn_network_is_part(net)) { // the parts' shares (collective)
    int ns = 0;
    st = rn_network_cell_info(net, nullptr, &ns, nullptr, nullptr);
    if (!st) st = rn_dist_allreduce_double(stress, ns, RN_DIST_SUM);
    if (!st && energy) st = rn_dist_allreduce_double(energy, 1, RN_DIST_SUM);
  }
  return st;
}

void acoustic_from_tangent(int dim, double measure, const double *strain,
                           const double *stress, const double *C,
                           const std::vector<int> &amp, AcousticTensor &t) {
  const Voigt vg(dim);
  const int d = dim, ns = vg.ns;
  // F = I + H (symmetric), H = sum_v eps_v B_v; sigma: sigma : B_v = stress_v
  double F[9] = {0.0}, sig[9] = {0.0}, B[6][9];
  for (int v = 0; v < ns; ++v) vg.basis(v, B[v]);
  for (int i = 0; i < d; ++i) F[3 * i + i] = 1.0;
  for (int v = 0; v < ns; ++v)
    for (int k = 0; k < 9; ++k) F[k] += strain[v] * B[v][k];
  for (int v = 0; v < ns; ++v) {
    sig[3 * vg.pairs[v][0] + vg.pairs[v][1]] = stress[v];
    sig[3 * vg.pairs[v][1] + vg.pairs[v][0]] = stress[v];
  }
  // The second Piola-Kirchhoff stress S (of the Green-Lagrange strain
  // E = H + H^2 / 2): sigma = (F S + S F) / 2, solved in F's eigenbasis.
  double Q[9] = {0.0}, f[3] = {0.0}, work[64];
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j) Q[i * d + j] = F[3 * i + j]; // packed d x d
  int n = d, lwork = 64, info = 0;
  dsyev_("V", "L", &n, Q, &n, f, work, &lwork, &info, 1, 1);
  if (info != 0) throw Error(RN_ERR_SOLVER, "rn_cell_acoustic_tangent: dsyev failed");
  // column m of the eigenvectors: Q[m * d + i] (column-major)
  double S[9] = {0.0};
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j) {
      double s = 0.0;
      for (int a = 0; a < d; ++a)
        for (int b = 0; b < d; ++b) {
          double sp = 0.0; // sigma in the eigenbasis
          for (int k = 0; k < d; ++k)
            for (int l = 0; l < d; ++l)
              sp += Q[a * d + k] * sig[3 * k + l] * Q[b * d + l];
          s += Q[a * d + i] * 2.0 * sp / (f[a] + f[b]) * Q[b * d + j];
        }
      S[3 * i + j] = s;
    }
  // T: eps -> the Voigt components of dE = (F dH + dH F) / 2; Qm_vw = S : sym(B_v B_w)
  double T[36] = {0.0}, Qm[36] = {0.0};
  for (int v = 0; v < ns; ++v) {
    double FB[9], BF[9];
    mul(d, F, B[v], FB);
    mul(d, B[v], F, BF);
    for (int w = 0; w < ns; ++w) {
      const int i = vg.pairs[w][0], j = vg.pairs[w][1];
      const double m = 0.5 * (FB[3 * i + j] + BF[3 * i + j]);
      T[w * ns + v] = i == j ? m : 2.0 * m;
    }
    for (int w = 0; w < ns; ++w) {
      double BB[9], WB[9], s = 0.0;
      mul(d, B[v], B[w], BB);
      mul(d, B[w], B[v], WB);
      for (int i = 0; i < d; ++i)
        for (int j = 0; j < d; ++j)
          s += S[3 * i + j] * 0.5 * (BB[3 * j + i] + WB[3 * j + i]);
      Qm[v * ns + w] = s;
    }
  }
  // C = T' CE T + Qm: CE = T^-T (C - Qm) T^-1, by two solves with T' (column-major
  // T' is row-major T)
  double M[36], Tt[36];
  int ipiv[6], nn = ns;
  for (int v = 0; v < ns; ++v)
    for (int w = 0; w < ns; ++w) M[v * ns + w] = C[v * ns + w] - Qm[v * ns + w];
  // X = T^-T M: solve T' X = M (column-major: the matrix T' has entries T'[i][j] =
  // T[j][i], stored column-major as Tt[i + j ns] = T[j][i] = T[j * ns + i])
  for (int k = 0; k < ns * ns; ++k) Tt[k] = T[k];
  dgesv_(&nn, &nn, Tt, &nn, ipiv, M, &nn, &info); // M symmetric: row = column major
  if (info != 0)
    throw Error(RN_ERR_SOLVER, "rn_cell_acoustic_tangent: the strain map is singular");
  // CE = X T^-1, i.e. CE' = T^-T X': solve T' Y = X' (X column-major in M)
  double Xt[36];
  for (int i = 0; i < ns; ++i)
    for (int j = 0; j < ns; ++j) Xt[i + j * ns] = M[j + i * ns];
  for (int k = 0; k < ns * ns; ++k) Tt[k] = T[k];
  dgesv_(&nn, &nn, Tt, &nn, ipiv, Xt, &nn, &info);
  if (info != 0)
    throw Error(RN_ERR_SOLVER, "rn_cell_acoustic_tangent: the strain map is singular");
  // Xt column-major holds CE' ; CE[v][w] = Xt[w + v ns]
  double CE[36];
  for (int v = 0; v < ns; ++v)
    for (int w = 0; w < ns; ++w) CE[v * ns + w] = 0.5 * (Xt[w + v * ns] + Xt[v + w * ns]);
  // Q_JL[a][b] = V (sum_IK F_aI F_bK CE_IJKL + delta_ab S_JL): the first elasticity
  // tensor L_aJbL = F_aI F_bK CE_IJKL + delta_ab S_JL times the cell's measure
  t.d = d;
  t.measure = measure;
  t.amp = amp;
  t.na = static_cast<int>(amp.size());
  t.Q.assign(static_cast<size_t>(d * d * t.na * t.na), 0.0);
  for (int J = 0; J < d; ++J)
    for (int L = 0; L < d; ++L)
      for (int a = 0; a < t.na; ++a)
        for (int b = 0; b < t.na; ++b) {
          const int ca = amp[static_cast<size_t>(a)], cb = amp[static_cast<size_t>(b)];
          double s = ca == cb ? S[3 * J + L] : 0.0;
          if (ca < d && cb < d)
            for (int I = 0; I < d; ++I)
              for (int K = 0; K < d; ++K)
                s += F[3 * ca + I] * F[3 * cb + K] * CE[vg.of(I, J) * ns + vg.of(K, L)];
          t.q(J, L, a, b) = measure * s;
        }
}

void acoustic_tangent(rn_network *net, rn_bloch_modes modes, rn_bloch_result *res) {
  int dim = 0, ns = 0;
  double measure = 0.0;
  check_status(rn_network_cell_info(net, &dim, &ns, &measure, nullptr),
               "rn_network_cell_info");
  if (dim == 0)
    throw Error(RN_ERR_ARG, "rn_cell_acoustic_tangent: the network is not periodic");
  if (modes != RN_BLOCH_ALL && dim != 2)
    throw Error(RN_ERR_ARG,
                "rn_cell_acoustic_tangent: in-plane / out-of-plane modes need a 2D cell");
  rn_homogenization h;
  const rn_status st = rn_homogenize(net, &h);
  if (st == RN_ERR_SOLVER) { // K not positive definite: no tangent
    res->acoustic_valid = 0;
    return;
  }
  check_status(st, "rn_homogenize");
  double strain[6] = {0.0}, stress[6] = {0.0};
  check_status(cell_state(net, strain, stress, nullptr), "rn_cell_acoustic_tangent");
  std::vector<int> amp;
  if (dim == 3 || modes == RN_BLOCH_ALL || modes == RN_BLOCH_IN_PLANE) amp = {0, 1};
  if (dim == 3) amp.push_back(2);
  if (dim == 2 && modes != RN_BLOCH_IN_PLANE && rn_network_is_planar(net) != 1)
    amp.push_back(2);
  AcousticTensor t;
  acoustic_from_tangent(dim, measure, strain, stress, h.C, amp, t);
  res->acoustic_valid = 1;
  acoustic_search(t, res);
}

void relax_part(rn_network *net, const double *strain, rn_cell_relax_report &r) {
  int ns = 0;
  int64_t sidx[6];
  check_status(rn_network_cell_info(net, nullptr, &ns, nullptr, nullptr),
               "rn_network_cell_info");
  check_status(rn_network_cell_strain_dofs(net, sidx), "rn_network_cell_strain_dofs");
  const size_t n = rn_network_num_dofs(net);
  std::vector<double> x(n ? n : 1);
  check_status(rn_network_get_dofs(net, x.data()), "rn_network_get_dofs");
  for (int v = 0; v < ns; ++v) // every part holds the strain DOFs
    if (sidx[v] >= 0) x[static_cast<size_t>(sidx[v])] = strain[v];
  check_status(rn_network_set_dofs(net, x.data()), "rn_network_set_dofs");
  HoldStrain hold(net);
  rn_solve_options o;
  rn_solve_options_default(&o);
  o.solver = RN_SOLVER_NOX; // Newton on grad E = 0: stays on the principal branch
  o.stability = 0;          // rn_cell_bloch examines the state
  // Every Newton step solved to 1e-6: past an instability the principal branch is a
  // saddle, and a step with Eisenstat-Walker's 0.1 error along its soft mode led
  // Newton to a buckled state (the regular 20 x 20 honeycomb on 2 ranks: at the
  // step past its critical strain, whose bracket then located it 1.5e-4 low).
  o.forcing = 1e-6;
  // At a singular Jacobian (a trial at the critical strain itself) Newton does not
  // converge: as the one-process relaxation, 100 iterations and no load cuts (the
  // strain is held: a cut would repeat the same problem).
  o.max_iterations = 100;
  o.max_load_cuts = 0;
  rn_solve_report rep;
  check_status(rn_solve(net, &o, &rep), "rn_cell_relax");
  r.converged = rep.converged;
  r.iterations = rep.iterations;
  r.residual = rep.force_residual;
  r.residual_scale = rep.force_tolerance;
}

void bloch_part(rn_network *net, const rn_bloch_options &o, rn_bloch_result *res) {
  int dim = 0;
  check_status(rn_network_cell_info(net, &dim, nullptr, nullptr, nullptr),
               "rn_network_cell_info");
  if (dim == 0) throw Error(RN_ERR_ARG, "rn_cell_bloch: the network is not periodic");
  if (o.modes != RN_BLOCH_ALL)
    throw Error(RN_ERR_ARG,
                "rn_cell_bloch: on a part of a distributed cell every mode is examined "
                "(RN_BLOCH_ALL; the planar model, rn_network_set_model, has the in-plane "
                "ones alone)");
  rn_stability s{};
  {
    HoldStrain hold(net);
    check_status(rn_network_stability(net, &s), "rn_network_stability");
  }
  if (!s.checked)
    throw Error(RN_ERR_SOLVER, "rn_cell_bloch: the stability check of the cell-periodic "
                               "fluctuations (LOBPCG) gave no converged eigenvalue");
  res->local_min = s.lowest_eigenvalue;
  res->eig[0] = s.lowest_eigenvalue;
  res->neig = 1;
  res->local_scale = s.scale;
  res->nequiv = 1;
  res->evaluations = 1;
  res->acoustic_valid = -1;
  if (!o.no_acoustic) acoustic_tangent(net, RN_BLOCH_ALL, res);
}

} // namespace rodnet

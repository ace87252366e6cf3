// homogenize.cpp - linear effective elasticity of a periodic cell (rn_homogenize):
// the Schur complement of the assembled Hessian onto the macroscopic strain DOFs.
//
// The strain DOFs are the last nstrain reduced DOFs (they follow the joints in the
// full layout); the leading block K_uu (fluctuations: positions, angles, joint
// rotations) is copied into its own CSR pattern, analysed once (METIS nested
// dissection) and factored by the supernodal sparse Cholesky; the nstrain right-hand
// sides K_ue are solved with that one factorisation, and
//   C = (K_ee - K_eu K_uu^-1 K_ue) / measure.
// No Trilinos here.
#include <cmath>
#include <memory>
#include <new>
#include <string>
#include <vector>

#include "periodic/homogenize.hpp"
#include "base/nonconservative.hpp"
#include "system/problem.hpp"
#include "rodnet_solve.h"
#include "base/shim_error.hpp"
#include "factor/sparse_cholesky.hpp"

namespace rodnet {

CellBlocks::CellBlocks(Problem &p, const std::string &where, bool all_free) {
  rn_network *net = p.network();
  int nstrain = 0;
  check_status(rn_network_cell_info(net, &dim, &nstrain, &measure, nullptr),
               "rn_network_cell_info");
  if (dim == 0) throw Error(RN_ERR_ARG, where + ": the network is not periodic");
  int64_t sidx[6];
  check_status(rn_network_cell_strain_dofs(net, sidx), "rn_network_cell_strain_dofs");
  n = p.size();
  ns = 0;
  for (int v = 0; v < nstrain; ++v) {
    if (sidx[v] < 0 && all_free)
      throw Error(RN_ERR_ARG,
                  where + ": every strain component must be a DOF (strain component " +
                      std::to_string(v) + " is prescribed)");
    if (sidx[v] >= 0) comp[ns++] = v;
  }
  nu = n - static_cast<size_t>(ns);
  for (int k = 0; k < ns; ++k) // the free strain DOFs are the last reduced DOFs
    if (sidx[comp[k]] != static_cast<int64_t>(nu) + k)
      throw Error(RN_ERR_STATE, where + ": unexpected strain DOF layout");
}

void CellBlocks::extract(const Problem &p) {
  const int64_t *rp = p.rowptr();
  const int32_t *col = p.col();
  const double *val = p.values();
  urp.assign(nu + 1, 0);
  ucol.clear();
  uval.clear();
  kue.assign(nu * static_cast<size_t>(ns), 0.0);
  kee.assign(36, 0.0);
  for (size_t i = 0; i < n; ++i) {
    for (int64_t q = rp[i]; q < rp[i + 1]; ++q) {
      const size_t j = static_cast<size_t>(col[q]);
      if (i < nu && j < nu) {
        ucol.push_back(col[q]);
        uval.push_back(val[q]);
      } else if (i < nu)
        kue[(j - nu) * nu + i] = val[q];
      else if (j >= nu)
        kee[(i - nu) * static_cast<size_t>(ns) + (j - nu)] = val[q];
    }
    if (i < nu) urp[i + 1] = static_cast<int64_t>(ucol.size());
  }
  for (double v : uval)
    if (!std::isfinite(v)) throw Error(RN_ERR_NOT_FINITE, "non-finite Hessian");
}

namespace {

void homogenize(rn_network *net, rn_homogenization *h) {
  Problem p(net);
  CellBlocks cb(p, "rn_homogenize");
  const int dim = cb.dim, ns = cb.ns;
  const double measure = cb.measure;
  const size_t nu = cb.nu;
  std::vector<double> x(cb.n);
  check_status(rn_network_get_dofs(net, x.data()), "rn_network_get_dofs");
  p.assemble_hessian(x.data());
  cb.extract(p);
  const std::vector<double> &kue = cb.kue, &kee = cb.kee;
  auto analysis = std::make_shared<SparseAnalysis>(nu, cb.urp.data(), cb.ucol.data());
  SparseCholesky chol(analysis);
  if (!chol.factor(cb.uval.data(), 0.0, nullptr))
    throw Error(RN_ERR_SOLVER,
                "rn_homogenize: the fluctuation block of the Hessian is not positive "
                "definite: the cell has a mechanism (a periodic fluctuation of zero "
                "energy, e.g. a joint or rod end that nothing holds) or is unstable "
                "at this state");
  std::vector<double> sol(kue);
  for (int v = 0; v < ns; ++v) chol.solve(sol.data() + static_cast<size_t>(v) * nu);
  for (int a = 0; a < ns; ++a)
    for (int b = 0; b < ns; ++b) {
      double s = 0.0;
      const double *ka = kue.data() + static_cast<size_t>(a) * nu;
      const double *xb = sol.data() + static_cast<size_t>(b) * nu;
      for (size_t i = 0; i < nu; ++i) s += ka[i] * xb[i];
      h->C[a * ns + b] = (kee[static_cast<size_t>(a * ns + b)] - s) / measure;
    }
  for (int a = 0; a < ns; ++a) // exact symmetry (the two products differ by round-off)
    for (int b = a + 1; b < ns; ++b)
      h->C[a * ns + b] = h->C[b * ns + a] = 0.5 * (h->C[a * ns + b] + h->C[b * ns + a]);
  h->dim = dim;
  h->nstrain = ns;
  h->measure = measure;
  h->fluctuation_dofs = nu;
  check_status(rn_network_cell_relative_density(net, &h->relative_density),
               "rn_network_cell_relative_density");
}

} // namespace
} // namespace rodnet

extern "C" rn_status rn_homogenize(rn_network *net, rn_homogenization *h) {
  if (!net) return RN_ERR_ARG;
  rn_context *ctx = rn_network_context(net);
  if (!h) return rn_context_set_error(ctx, RN_ERR_ARG, "rn_homogenize: h is NULL");
  *h = rn_homogenization{};
  if (rn_status st =
          rodnet::refuse_nonconservative(net, "rn_homogenize", "homogenisation"))
    return st;
  try {
    *h = rn_homogenization{};
    if (rn_network_is_part(net))
      rodnet::homogenize_dist(net, h);
    else
      rodnet::homogenize(net, h);
    return RN_OK;
  } catch (const rodnet::Error &e) {
    return e.recorded() ? e.status()
                        : rn_context_set_error(ctx, e.status(), "%s", e.what());
  } catch (const std::bad_alloc &) {
    return rn_context_set_error(ctx, RN_ERR_ALLOC, "rn_homogenize: out of memory");
  } catch (const std::exception &e) {
    return rn_context_set_error(ctx, RN_ERR_SOLVER, "rn_homogenize: %s", e.what());
  }
}

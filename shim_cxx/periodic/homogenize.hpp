// homogenize.hpp - the blocks of a periodic cell's Hessian (shared by rn_homogenize
// and the strain path, cell_path.cpp): fluctuations u (every reduced DOF but the
// strain components, which are the last ns) and strain e; the small dense
// eigen-solve and the exception guard of the periodic entries (cell_path.cpp,
// stress_path.cpp).  No Trilinos here.
#ifndef RODNET_SHIM_HOMOGENIZE_HPP
#define RODNET_SHIM_HOMOGENIZE_HPP

#include <cstddef>
#include <cstdint>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "base/shim_error.hpp"
#include "rodnet_solve.h"
#include "system/problem.hpp"

namespace rodnet {

struct CellBlocks {
  int dim = 0, ns = 0;              // ns: the strain components that are DOFs
  int comp[6] = {0, 0, 0, 0, 0, 0}; // their components (Voigt index) [ns]
  double measure = 0.0;
  size_t n = 0, nu = 0;         // reduced DOFs, fluctuation DOFs (n - ns)
  std::vector<int64_t> urp;     // K_uu in CSR [nu + 1]
  std::vector<int32_t> ucol;    //
  std::vector<double> uval;     //
  std::vector<double> kue, kee; // K_ue as ns dense columns of nu; K_ee ns x ns
  // Checks that net is periodic with every strain component a DOF (throws Error);
  // all_free false: prescribed components are allowed (ns counts the free ones).
  CellBlocks(Problem &p, const std::string &where, bool all_free = true);
  // Extracts the blocks from the Hessian p assembled last (throws on non-finite).
  void extract(const Problem &p);
};

// Eigenvalues (ascending, w[m]) of the symmetric m x m (m <= 6, row-major) matrix a
// and the eigenvector of the lowest (v[m]) by LAPACK dsyev; throws Error (where:
// the entry point, for the message) if dsyev fails.
void sym_eigen(int m, const double *a, double *w, double *v, const char *where);

// rn_homogenize on a part of a distributed cell (homogenize_dist.cpp; collective,
// throws Error).
void homogenize_dist(rn_network *net, rn_homogenization *h);

// Runs f; converts any exception to a status with the message in net's context.
template <class F>
rn_status guarded(rn_network *net, const char *where, F &&f) {
  rn_context *ctx = rn_network_context(net);
  try {
    f();
    return RN_OK;
  } catch (const Error &e) {
    return e.recorded() ? e.status()
                        : rn_context_set_error(ctx, e.status(), "%s", e.what());
  } catch (const std::bad_alloc &) {
    return rn_context_set_error(ctx, RN_ERR_ALLOC, "%s: out of memory", where);
  } catch (const std::exception &e) {
    return rn_context_set_error(ctx, RN_ERR_SOLVER, "%s: %s", where, e.what());
  }
}

} // namespace rodnet
#endif

// homogenize.hpp - the blocks of a periodic cell's Hessian (shared by rn_homogenize
// and the strain path, cell_path.cpp): fluctuations u (every reduced DOF but the
// strain components, which are the last ns) and strain e.  No Trilinos here.
#ifndef RODNET_SHIM_HOMOGENIZE_HPP
#define RODNET_SHIM_HOMOGENIZE_HPP

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

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

} // namespace rodnet
#endif

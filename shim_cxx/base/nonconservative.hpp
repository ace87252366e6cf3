// nonconservative.hpp - the refusal of couples fixed in space (rodnet_couple.h,
// RN_COUPLE_FIXED) by the entry points that need an energy: the minimisers, path
// following, the stability check, the lowest Hessian eigenvalue, homogenisation and
// the periodic cell's relaxation and Bloch analysis.  Such a couple has no potential
// in 3D: the network's "Hessian" then holds its nonsymmetric Jacobian, which none
// of them may read as a symmetric matrix.
#ifndef RODNET_SHIM_NONCONSERVATIVE_HPP
#define RODNET_SHIM_NONCONSERVATIVE_HPP

#include "rodnet.h"
#include "rodnet_couple.h"

namespace rodnet {

// RN_ERR_ARG naming the first couple fixed in space if the network has one (`what`:
// the method that needs a conservative problem, for the message; where: the entry
// point), recorded in the network's context.  RN_OK otherwise.
inline rn_status refuse_nonconservative(rn_network *net, const char *where,
                                        const char *what) {
  char which[160];
  if (rn_network_fixed_couples(net, nullptr, nullptr) == 0) return RN_OK;
  return rn_context_set_error(
      rn_network_context(net), RN_ERR_ARG,
      "%s: the moment on %s is a couple fixed in space (\"model\": \"fixed\"), a "
      "nonconservative load with no energy: %s does not apply; solve it with the nox "
      "solver (--solver nox), Newton on the residual",
      where, rn_network_fixed_couple_where(net, which, sizeof which), what);
}

} // namespace rodnet

#endif

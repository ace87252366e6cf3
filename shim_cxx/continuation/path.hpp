// path.hpp - pseudo-arclength continuation of equilibria behind rn_path_follow
// (path.cpp; rodnet_solve.h, docs/path-following.md).
#ifndef RODNET_SHIM_PATH_HPP
#define RODNET_SHIM_PATH_HPP

#include "rodnet_solve.h"

namespace rodnet {

// Follows the path with options opt (validated here: Error RN_ERR_ARG) and fills rep
// (zeroed by the caller, NaN event fields).  Throws Error.
void follow_path(rn_network *net, const rn_path_options &opt, rn_path_report &rep);

} // namespace rodnet

#endif

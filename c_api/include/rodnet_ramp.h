/* rodnet_ramp.h - where the free DOFs of a network belong in the load factor
 * (public; docs/solvers.md "Prescribed motions of any size").  Declared apart
 * from rodnet.h so that the solver shim does not depend on it. */
#ifndef RODNET_RAMP_H
#define RODNET_RAMP_H

#include "rodnet.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The load factor at which the network's free DOFs were last set: 0 after
 * rn_network_finalize (the initial geometry belongs to load factor 0, whatever
 * load factor finalize then moves the prescribed motions to), else the load
 * factor of the last rn_network_set_dofs or successful rn_network_update_reference
 * (the solvers' accepted iterates); rn_network_state_restore restores it.  rn_solve
 * measures the jump of a load step's prescribed motions from there.  NaN for NULL
 * or before finalize.  Not collective. */
double rn_network_dofs_load_factor(const rn_network *net);

#ifdef __cplusplus
}
#endif

#endif

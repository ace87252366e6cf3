/* rodnet_model.h - the planar model of rodnet (public; docs/model.md "The
 * planar model").  Declared apart from rodnet.h so that the solver shim does
 * not depend on it. */
#ifndef RODNET_MODEL_H
#define RODNET_MODEL_H

#include "rodnet.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the planar model (docs/model.md "The planar model") ------------------
 * A network whose rods, rest data, sections, loads, constraints and lattice
 * vectors all lie in (or act in) one plane z = const and whose sections have a
 * principal axis along z can be solved with the planar model: only the in-plane
 * DOFs are free (x, y of every vertex and joint, the rotation about z of rigid
 * joints); z, the material angles and the rotations about x and y are held at
 * their initial values.  Its in-plane equilibria equal the 3D model's; it
 * cannot see out-of-plane buckling.  Default RN_MODEL_AUTO: the 3D model, and
 * finalize records whether the network qualifies (rn_network_planar). */
typedef enum { RN_MODEL_AUTO = 0, RN_MODEL_3D = 1, RN_MODEL_PLANAR = 2 } rn_model;
/* Ask for a model before finalize; with RN_MODEL_PLANAR finalize fails with
 * RN_ERR_ARG naming what leaves the plane if the network does not qualify.
 * RN_ERR_STATE after finalize, RN_ERR_ARG for another value. */
rn_status rn_network_set_model(rn_network *net, rn_model model);
/* After finalize: 1 if the planar model is in use, 0 for 3D (-1: not
 * finalized or NULL). */
int rn_network_is_planar(const rn_network *net);
/* After finalize: 1 if the network qualifies for the planar model, 0 if not
 * (*why, if why is not NULL, then names what leaves the plane; a string the
 * network owns), -1 if not finalized.  Local to a part in a partition. */
int rn_network_planar(const rn_network *net, const char **why);

#ifdef __cplusplus
}
#endif

#endif

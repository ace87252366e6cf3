/* bcs.h - boundary conditions and loads (boundary.c, loads.c, planar.c): the
 * load factor that moves the fixed DOFs, lumped forces, the planar model. */
#ifndef RN_BCS_MODULE_H
#define RN_BCS_MODULE_H

#include "core/network_internal.h"

/* ---- the planar model (planar.c; docs/model.md) ----------------------------
 * Finalize: whether the network qualifies (planar_ok, planar_why; before the
 * DOF map, on the input data), and, with the planar model, marks the
 * out-of-plane full DOFs fixed (z of every position, material angles, joint
 * rotations about x and y; after the rods' and joints' own marks, before the
 * joint ends alias their joints).  rn_planar_assess_built completes the
 * assessment once the joints are built (their rest frames, stored twist and
 * rest strains; the rods' rest twist a ring's total twist lowered); finalize
 * fails with the planar model if it clears planar_ok. */
void rn_planar_assess(rn_network *net);
void rn_planar_assess_built(rn_network *net);
void rn_planar_mark(rn_network *net);

/* ---- finalize / load factor ------------------------------------------------ */
/* Writes the fixed entries of net->xfull for the current load factor and the
 * reference frames of clamped ends with a prescribed rotation. */
rn_status rn_apply_load_factor(rn_network *net);
/* The largest prescribed rotation per unit load factor (rad): clamped rod ends
 * with a prescribed motion and clamped joints. */
double rn_prescribed_rotation_rate(const rn_network *net);
/* Largest turn of a prescribed rotation per step of rn_ramp_load_factor (rad). */
#define RN_RAMP_ANGLE 0.7853981633974483
/* Moves the applied load factor from net->lambda to lambda in steps that turn no
 * prescribed rotation by more than RN_RAMP_ANGLE, each rn_apply_load_factor, so the
 * reference twists next to turned clamps keep their winding. */
void rn_ramp_load_factor(rn_network *net, double lambda);
/* Steps of at most RN_RAMP_ANGLE for a turn (rad): 1 for a turn up to RN_RAMP_ANGLE,
 * or beyond RN_RAMP_MAX_STEPS steps (or not finite: such a turn is applied at once
 * and its winding is not followed). */
#define RN_RAMP_MAX_STEPS 16384
int rn_ramp_steps(double turn);
/* Vertex forces r->fvert from point forces, line load and gravity (loads.c). */
void rn_rod_lump_forces(const rn_network *net, rn_rod *r);
/* Edge of the material frame a moment at vertex acts on. */
int rn_moment_edge(int nv, int vertex);

#endif

/* rodnet.h - public C API of rodnet: static equilibria of discrete elastic
 * rods (DER).
 *
 * Conventions (after libCEED / SUNDIALS / PETSc):
 *  - Every function returns rn_status: 0 ok, < 0 error (object unchanged),
 *    > 0 recoverable at a trial point (e.g. a degenerate configuration: the
 *    solver rejects the step).  The context keeps "where: what" of the last
 *    error, see rn_context_last_error().
 *  - Opaque handles; rn_X_destroy(&x) accepts NULL and sets *x to NULL.
 *  - Inputs are copied; outputs go to caller arrays of documented length.
 *  - Library code never aborts, exits or prints.
 *  - Nothing here is collective over MPI unless it says so.
 *
 * Lifecycle of a network: create -> add rods, set properties, rest shape,
 * boundary conditions and loads -> rn_network_finalize() (validates, builds
 * the DOF map; the topology is frozen from then on) -> evaluate / solve ->
 * read results -> destroy.
 *
 * Degrees of freedom.  A rod with n vertices has 4n-1 full DOFs in the order
 * (x_0[3], theta^0, x_1[3], theta^1, ..., x_{n-1}[3]); rods are concatenated.
 * Joints follow all rods: position (3) and, for rigid (or clamped) joints, a
 * rotation vector (3).  A rod end vertex attached to a joint is the joint's
 * position (one reduced DOF, not two).  Boundary conditions fix DOFs; the
 * *reduced* DOF vector holds the free ones in the same order.  All
 * evaluation functions work on reduced vectors.
 */
#ifndef RODNET_H
#define RODNET_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define RODNET_VERSION_MAJOR 0
#define RODNET_VERSION_MINOR 1
#define RODNET_VERSION_PATCH 0
#define RODNET_VERSION_STRING "0.1.0"

/* ---- status codes (one list: codes, names and messages) ----------------- */
#define RN_STATUS_LIST(X)                                                        \
  X(RN_OK, 0, "ok")                                                              \
  X(RN_DEGENERATE, 1, "degenerate configuration at a trial point")               \
  X(RN_OVERFLOW, 2, "energy or derivatives overflow (not finite) at this state") \
  X(RN_ERR_ALLOC, -1, "out of memory")                                           \
  X(RN_ERR_ARG, -2, "invalid argument")                                          \
  X(RN_ERR_STATE, -3, "operation not allowed in the object's current state")     \
  X(RN_ERR_RANGE, -4, "index out of range")                                      \
  X(RN_ERR_GEOMETRY, -5, "degenerate geometry")                                  \
  X(RN_ERR_BC, -6, "inconsistent boundary conditions")                           \
  X(RN_ERR_NOT_FINITE, -7, "value is not finite")                                \
  X(RN_ERR_LAPACK, -8, "dense/banded factorisation failed")                      \
  X(RN_ERR_SOLVER, -9, "solver failure")                                         \
  X(RN_ERR_TRILINOS, -10, "Trilinos error")                                      \
  X(RN_ERR_IO, -11, "input/output error")                                        \
  X(RN_ERR_PARSE, -12, "malformed input")                                        \
  X(RN_ERR_CHECK, -13, "derivative self-test failed")                            \
  X(RN_ERR_INTERNAL, -14, "internal error")

typedef enum rn_status {
#define RN_STATUS_ENUM_(name, code, msg) name = code,
  RN_STATUS_LIST(RN_STATUS_ENUM_)
#undef RN_STATUS_ENUM_
} rn_status;

/* Stable name ("RN_ERR_ARG") and message of a status; never NULL. */
const char *rn_status_name(rn_status s);
const char *rn_status_message(rn_status s);

/* Run-time version; compile-time version in RODNET_VERSION_*. */
const char *rn_version_string(void);
void rn_version(int *major, int *minor, int *patch);

/* Layout of the public structs for bindings that mirror them without a
 * compiler (c_api/abi/abi.c; the Python package checks its ctypes structures
 * against these at import, docs/python.md): sizeof(type) (0 for a type not in
 * the table), offsetof(type, field) (-1 for an unknown type or field) and the
 * number of fields the table lists for type.  The types: rn_material,
 * rn_section, rn_reaction, and in rodnet_solve.h rn_iteration_info,
 * rn_solve_options, rn_stability, rn_solve_report, rn_homogenization and the
 * rn_cell_path_* structs. */
size_t rn_abi_sizeof(const char *type);
long rn_abi_offsetof(const char *type, const char *field);
int rn_abi_num_fields(const char *type);

/* ---- context ------------------------------------------------------------ */
typedef struct rn_context rn_context;

/* Create a context (holds the last error message).  Returns RN_ERR_ALLOC. */
rn_status rn_context_create(rn_context **ctx);
/* Destroy a context; accepts NULL and *ctx == NULL; sets *ctx to NULL. */
void rn_context_destroy(rn_context **ctx);
/* "where: what" of the last error recorded in ctx ("" if none); borrowed. */
const char *rn_context_last_error(const rn_context *ctx);
/* Record an error (used by layers above the library, e.g. readers). */
rn_status rn_context_set_error(rn_context *ctx, rn_status s, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;
void rn_context_clear_error(rn_context *ctx);

/* ---- materials and sections --------------------------------------------- */
typedef struct rn_material {
  double E;       /* Young's modulus, > 0 */
  double G;       /* shear modulus, > 0 */
  double density; /* mass per unit volume, >= 0 (gravity only) */
} rn_material;

/* Material from (E, nu): G = E / (2 (1 + nu)); needs E > 0, -1 < nu < 0.5+.
 * (nu = 0.5 is allowed: incompressible.)  RN_ERR_ARG otherwise. */
rn_status rn_material_from_E_nu(double E, double nu, double density, rn_material *m);

/* Cross-section: area A, second moments in the material frame and torsion
 * constant J.  The bending stiffness B = E [[I11, I12], [I12, I22]] acts on
 * the material curvature (kappa1, kappa2) of seed 000 (2.2), where kappa1 is
 * the component of the curvature normal along d1 (bending in the plane of t
 * and d1); hence I11 = int (r . d1)^2 dA, I22 = int (r . d2)^2 dA,
 * I12 = int (r . d1)(r . d2) dA.  Twisting stiffness is G J. */
typedef struct rn_section {
  double A, I11, I22, I12, J;
} rn_section;

/* Solid circle of radius r. */
rn_status rn_section_circle(double r, rn_section *s);
/* Hollow circle, outer radius ro > inner radius ri >= 0. */
rn_status rn_section_hollow_circle(double ro, double ri, rn_section *s);
/* Ellipse with semi-axis a along d1 and b along d2;
 * J = pi a^3 b^3 / (a^2 + b^2). */
rn_status rn_section_ellipse(double a, double b, rn_section *s);
/* Rectangle of width w along d1 and height h along d2; J from the
 * Saint-Venant series (not the thin-strip limit). */
rn_status rn_section_rectangle(double w, double h, rn_section *s);
/* Checks A > 0, I11 > 0, I22 > 0, I11 I22 - I12^2 > 0, J > 0, all finite. */
rn_status rn_section_validate(const rn_section *s);

/* ---- networks (rods, BCs, loads) ---------------------------------------- */
typedef struct rn_network rn_network;

enum { RN_START = 0, RN_END = 1 };

/* Create an empty network bound to ctx (errors are recorded there). */
rn_status rn_network_create(rn_context *ctx, rn_network **net);
/* Destroy; accepts NULL; sets *net to NULL. */
void rn_network_destroy(rn_network **net);

/* Add a rod through nv >= 2 vertices xyz[3*nv] (copied).  d1: initial
 * material axis of the first edge (3 values, need not be unit or exactly
 * perpendicular: it is projected; NULL derives one, see docs/model.md); the
 * other edges get its parallel transport along the polyline.  The rest shape
 * is the initial shape until rest_* below override it.  name may be NULL.
 * *rod receives the rod index.  RN_ERR_GEOMETRY for zero-length edges or
 * opposite consecutive tangents; RN_ERR_NOT_FINITE for NaN/Inf. */
rn_status rn_network_add_rod(rn_network *net, const char *name, int nv, const double *xyz,
                             const double *d1, int *rod);

/* Add a closed rod (a ring) through nv >= 3 distinct vertices xyz[3*nv]; the
 * first vertex is not repeated: edge nv-1 joins the last vertex to the first.
 * It is stored as a rod of nv + 1 vertices whose last vertex is the first one
 * (both alias one position) and nv edges, closed by a smooth joint
 * (RN_JOINT_SMOOTH, named after the rod) at vertex 0 = vertex nv: every
 * stencil is periodic (stretching of the closing edge, bending and twisting at
 * every vertex including vertex 0, which is the joint's).  The other calls
 * on the rod use the stored rod's indices (vertices 0 .. nv, edges 0 .. nv-1;
 * rest curvature and twist of vertices 1 .. nv-1 by rn_network_set_rest_*, of
 * vertex 0 by rn_network_set_joint_rest_* on the joint; vertex 0 is
 * constrained and loaded through the joint).  d1 as for rn_network_add_rod.
 * *rod and *joint (either may be NULL) receive the indices.  The twist the
 * ring carries is set by rn_network_set_joint_link. */
rn_status rn_network_add_closed_rod(rn_network *net, const char *name, int nv,
                                    const double *xyz, const double *d1, int *rod,
                                    int *joint);
/* 1 if rod was added by rn_network_add_closed_rod (0 otherwise or invalid). */
int rn_network_rod_is_closed(const rn_network *net, int rod);

/* Material and section of a rod's edges: edge = -1 for all edges. */
rn_status rn_network_set_material(rn_network *net, int rod, int edge,
                                  const rn_material *m);
rn_status rn_network_set_section(rn_network *net, int rod, int edge, const rn_section *s);

/* Rest shape overrides: kappa[2*(nv-2)] integrated material curvature per
 * interior vertex (seed 000 (2.2)); tau[nv-2] integrated twist per interior
 * vertex; len[nv-1] rest length per edge (> 0). */
rn_status rn_network_set_rest_curvature(rn_network *net, int rod, const double *kappa);
rn_status rn_network_set_rest_twist(rn_network *net, int rod, const double *tau);
rn_status rn_network_set_rest_lengths(rn_network *net, int rod, const double *len);

/* Boundary conditions.  Vertex and edge indices may be negative (-1 = last).
 * clamp: fixes the end edge (its two vertices and its material angle).
 * pin: fixes one vertex position.  fix_theta: fixes one material angle. */
rn_status rn_network_clamp(rn_network *net, int rod, int end);
rn_status rn_network_pin(rn_network *net, int rod, int vertex);
rn_status rn_network_fix_theta(rn_network *net, int rod, int edge);
/* Position components, as a bitmask, of a component pin. */
enum { RN_FIX_X = 1, RN_FIX_Y = 2, RN_FIX_Z = 4, RN_FIX_XYZ = 7 };
/* Component pin: fixes the global coordinates of one vertex named by the
 * bitmask components (RN_FIX_X | RN_FIX_Z: x and z fixed, y free; a roller
 * or a frictionless grip).  Repeated pins of a vertex, and pins of a vertex
 * that a clamp or rn_network_pin also fixes, add up (union of the fixed
 * components); rn_network_pin is the same as components = RN_FIX_XYZ.  The
 * fixed DOFs leave the reduced vector.  RN_ERR_ARG unless components is in
 * 1 .. RN_FIX_XYZ. */
rn_status rn_network_pin_components(rn_network *net, int rod, int vertex, int components);
/* Prescribed motion of a clamped end: translation disp[3] and rotation
 * rotvec[3] (rotation vector, about the midpoint of the clamped edge, which
 * is where the continuum clamp sits).  Either may be NULL.  Scaled by the
 * load factor.  RN_ERR_BC if that end is not clamped (checked at finalize). */
rn_status rn_network_displace_end(rn_network *net, int rod, int end, const double disp[3],
                                  const double rotvec[3]);
/* Prescribed displacement of a pinned (or clamped) vertex; it acts on the
 * fixed components only.  For a vertex pinned in some components, every
 * non-zero component of disp must be a fixed one: RN_ERR_BC otherwise (e.g.
 * disp = (0, 0.1, 0) on a vertex pinned in x only), checked at finalize. */
rn_status rn_network_displace_vertex(rn_network *net, int rod, int vertex,
                                     const double disp[3]);

/* Loads (dead, scaled by the load factor).  Their potential is measured from the
 * initial state: -lambda f . (x - x0) for forces (x0 the input position of the
 * vertex or joint), the rotation since the initial state for couples; the load
 * energy is 0 at the initial state and independent of the origin. */
rn_status rn_network_add_force(rn_network *net, int rod, int vertex, const double f[3]);
/* Couple on the material frame of the edge at a vertex (edge i for vertex i,
 * the last edge for the last vertex); see rnk_moment_* for the model. */
rn_status rn_network_add_moment(rn_network *net, int rod, int vertex, const double m[3]);
/* Uniform load per unit rest length on a rod, lumped to vertices with their
 * Voronoi rest lengths. */
rn_status rn_network_add_line_load(rn_network *net, int rod, const double w[3]);
/* Gravity acceleration g[3] on every rod with density > 0 (rho A per unit
 * rest length). */
rn_status rn_network_add_gravity(rn_network *net, const double g[3]);

/* Validate and freeze: builds rest quantities and the DOF map.  RN_ERR_BC
 * for inconsistent boundary conditions (e.g. displace on a free end),
 * RN_ERR_ARG for missing materials/sections. */
rn_status rn_network_finalize(rn_network *net);

/* Load factor lambda in [0, 1] (continuation): scales loads and prescribed
 * motions; moves the fixed DOFs accordingly.  Default 1. */
rn_status rn_network_set_load_factor(rn_network *net, double lambda);
double rn_network_load_factor(const rn_network *net);
/* How far the prescribed motions move between load factors t0 and t1 with the
 * free DOFs held: *stretch = the largest change of a rod edge's vector over its
 * length at t0 (HUGE_VAL for a zero-length edge; 0 if no prescribed motion
 * reaches an edge), *angle = the largest prescribed rotation turned (rad).
 * rn_solve splits load steps by them (docs/solvers.md, "Prescribed motions of
 * any size").  Prescribed rotations are followed in turns of at most pi/4 here
 * and in rn_network_set_load_factor, so windings beyond pi are kept.  The
 * network's state is left as it was.  A part of a distributed network: its own
 * rods (not collective).  RN_ERR_ARG for t0, t1 outside [0, 1] or NULL outputs,
 * RN_ERR_NOT_FINITE, RN_ERR_STATE before finalize. */
rn_status rn_network_load_step_size(rn_network *net, double t0, double t1,
                                    double *stretch, double *angle);

/* ---- sizes and state ----------------------------------------------------- */
size_t rn_network_num_dofs(const rn_network *net); /* reduced */
size_t rn_network_num_full_dofs(const rn_network *net);
int rn_network_num_rods(const rn_network *net);
int rn_network_rod_num_vertices(const rn_network *net, int rod);
const char *rn_network_rod_name(const rn_network *net, int rod); /* borrowed */
rn_context *rn_network_context(const rn_network *net);

/* Current state (reduced DOFs): copy out / set (x[num_dofs]). */
rn_status rn_network_get_dofs(const rn_network *net, double *x);
rn_status rn_network_set_dofs(rn_network *net, const double *x);

/* ---- evaluation on a reduced DOF vector x (pure: no state changes) ------ */
/* Total energy.  > 0 (RN_DEGENERATE) at a degenerate trial point. */
rn_status rn_network_energy(const rn_network *net, const double *x, double *E);
/* Energy (E may be NULL) and gradient g[num_dofs]. */
rn_status rn_network_gradient(const rn_network *net, const double *x, double *E,
                              double *g);
/* Hessian-vector product Hv = H(x) v, matrix-free from the stencil blocks. */
rn_status rn_network_hvp(const rn_network *net, const double *x, const double *v,
                         double *Hv);
/* Linearised load increment: dg[num_dofs] = the first-order change of the
 * gradient at fixed free DOFs x when the load factor goes from t_prev to t,
 *   dg = H_{free,fixed}(x; t_prev) [X_c(t) - X_c(t_prev)]
 *        + (t - t_prev) d/dlambda (gradient of the loads),
 * X_c the prescribed (fixed) DOFs: pinned and clamped positions, the material
 * angles of clamped edges (the angle that turns the reference frame at t_prev
 * into the prescribed one) and the rotations of clamped joints.  Exact for
 * prescribed translations and loads; the chord for prescribed rotations.
 * g(x; t) ~ g(x; t_prev) + dg (the load-step predictor of rn_solve).
 * Evaluated at t_prev; the network's load factor and state are left as they
 * were.  t_prev, t in [0, 1] (RN_ERR_ARG), finite (RN_ERR_NOT_FINITE);
 * RN_DEGENERATE at a degenerate x. */
rn_status rn_network_load_increment(rn_network *net, const double *x, double t_prev,
                                    double t, double *dg);
/* Second-order stretching error of a step s (a reduced direction) from x:
 * for every rod edge j, with L_j its length and a_j = dL_j/dx at x,
 *   r_j = L_j(x + s) - L_j(x) - a_j . s   (the stretch a step gives beyond its
 *                                          linearisation, O(|s|^2)),
 *   f = sum_j (E A_j / lbar_j) r_j a_j    (f[num_dofs], reduced DOFs).
 * -f is the stretching force a quadratic model at x misses at x + s; a
 * trust-region solver corrects the step with -(H + lambda D)^{-1} f (a
 * second-order correction, docs/solvers.md).  In a part: the part's own rods.
 * Pure.  RN_ERR_NOT_FINITE for NaN or infinite x or s, RN_DEGENERATE if an
 * edge has zero length at x or x + s. */
rn_status rn_network_stretch_correction(const rn_network *net, const double *x,
                                        const double *s, double *f);
/* Energy split by term: E[RN_TERM_COUNT].  The bending and twisting energy
 * of rigid and elastic joints (between terminal and connection edges) counts as
 * RN_TERM_BEND, a smooth joint's vertex as RN_TERM_BEND and RN_TERM_TWIST;
 * forces and couples on joints as RN_TERM_LOAD. */
enum { RN_TERM_STRETCH = 0, RN_TERM_BEND, RN_TERM_TWIST, RN_TERM_LOAD, RN_TERM_COUNT };
rn_status rn_network_energy_terms(const rn_network *net, const double *x, double *E);

/* Sparse Hessian in CSR, both triangles, on the reduced DOFs.  The pattern is
 * fixed at finalize (borrowed arrays valid until destroy), except with contact,
 * where a new accepted state may rebuild it (rn_network_pattern_version in
 * rodnet_contact.h; the arrays are then valid until the version changes):
 * rowptr[num_dofs+1], col[nnz] sorted per row. */
rn_status rn_network_hessian_pattern(const rn_network *net, size_t *nnz,
                                     const int64_t **rowptr, const int32_t **col);
/* Values vals[nnz] of H(x) in that pattern (same blocks as rn_network_hvp). */
rn_status rn_network_hessian_values(const rn_network *net, const double *x, double *vals);
/* Half bandwidth of the pattern: max |i - j| over nonzeros. */
size_t rn_network_hessian_bandwidth(const rn_network *net);

/* ---- domain decomposition: rods and interface ----------------------------
 * Classification of the reduced DOFs for rod-level domain decomposition
 * (docs/solvers.md).  block[i] is the rod whose interior DOF i is, or
 * RN_DOF_INTERFACE: joint positions and rotations, and every rod DOF that a
 * stencil couples with another rod (with elastic joints the vertex next to the
 * joint and the terminal edge's angle of every end, which the joint's rotation
 * fit couples; with rigid joints, whose energy is a sum of one term per end,
 * those stay rod-interior; with contact, the vertices of both edges of every
 * pair in the Hessian pattern that joins two rods or two edges of one rod at
 * least 3 apart, so the classification changes with
 * rn_network_pattern_version).  No Hessian entry couples the interiors of two
 * different rods (the pattern of a rigid joint's stencil is dense, its values
 * between two ends are zero).  point[3 i]: the point DOF i moves at the
 * current state (vertex or joint position; for a material angle the midpoint
 * of its edge); axis[3 i]: the unit tangent of the edge of a material angle,
 * zero otherwise.  With the DOF kinds (rn_network_dof_info), an infinitesimal
 * rigid motion (translation t, rotation w about the origin) changes a position
 * DOF by t + w x point, a joint rotation DOF by w and a material angle by
 * w . axis (the rigid-body modes, e.g. the near-null space of algebraic
 * multigrid).  point and axis may be NULL; arrays have num_dofs (times 3)
 * entries.  RN_ERR_STATE before finalize. */
#define RN_DOF_INTERFACE (-1)
rn_status rn_network_dof_blocks(const rn_network *net, int32_t *block, double *point,
                                double *axis);

/* Accept x as the new state: x becomes current, reference frames are moved by
 * time-parallel transport, reference twists and moment angles are continued.
 * x is updated in place: the rotation DOFs of rigid joints are reset to 0 as
 * their rotation moves into the joint's reference rotation (nothing else in
 * x changes).  The energy at x is unchanged by the update.  On error (e.g.
 * RN_DEGENERATE) neither the network nor x changes. */
rn_status rn_network_update_reference(rn_network *net, double *x);

/* ---- state snapshots (continuation, line searches, what-if studies) ------ */
/* An opaque copy of a finalized network's whole mutable state: the current
 * state (all DOFs, fixed ones included), the load factor, the rods' reference
 * frames and reference twists, the couples' reference frames and angles, and
 * the joints' reference rotations, couple frames and angles and stored end
 * twists.  Restoring it makes every evaluation (energy, gradient, HVP,
 * Hessian, results) bit-identical to what it was when the state was saved,
 * whatever happened in between (solves, reference updates, load factor
 * changes).  Topology, properties, BCs and loads are not part of it. */
typedef struct rn_state rn_state;

/* Save the state of a finalized network into a new snapshot *s (owned by the
 * caller: rn_state_destroy).  RN_ERR_STATE before finalize, RN_ERR_ALLOC;
 * *s is NULL on error. */
rn_status rn_network_state_save(const rn_network *net, rn_state **s);
/* Make s the network's state.  s must have been saved from this network
 * (RN_ERR_ARG otherwise); it stays valid and can be restored again. */
rn_status rn_network_state_restore(rn_network *net, const rn_state *s);
/* Destroy a snapshot; accepts NULL and *s == NULL; sets *s to NULL. */
void rn_state_destroy(rn_state **s);

/* ---- results ------------------------------------------------------------- */
/* Current vertex positions xyz[3*nv] and material angles theta[nv-1]
 * (relative to the reference directors; see rn_network_rod_frames). */
rn_status rn_network_rod_vertices(const rn_network *net, int rod, double *xyz);
rn_status rn_network_rod_theta(const rn_network *net, int rod, double *theta);
/* Initial (input) vertex positions of a rod. */
rn_status rn_network_rod_initial_vertices(const rn_network *net, int rod, double *xyz);
/* Current material directors d1[3*(nv-1)], d2[3*(nv-1)] (either may be NULL). */
rn_status rn_network_rod_frames(const rn_network *net, int rod, double *d1, double *d2);
/* Per-edge stretching strain l/lbar - 1 and per-interior-vertex material
 * curvature kappa[2*(nv-2)] and twist tau[nv-2] (integrated), current state.
 * Any pointer may be NULL. */
rn_status rn_network_rod_strains(const rn_network *net, int rod, double *strain,
                                 double *kappa, double *tau);
/* Rest length of each edge, len[nv-1] (the input edge lengths unless
 * rn_network_set_rest_lengths overrode them).  Works before finalize too. */
rn_status rn_network_rod_rest_lengths(const rn_network *net, int rod, double *len);
/* Stress resultants and energies of the interior vertex stencils at the
 * current state; entry i-1 belongs to interior vertex i (1 .. nv-2), and vlen
 * is its Voronoi rest length (lbar^{i-1} + lbar^i) / 2:
 *   moment[2*(nv-2)]      bending moment (m1, m2) = B (kappa - kbar) / vlen, in
 *                         the material components of rn_network_rod_strains
 *                         (kappa1 = kb . (d2^{i-1} + d2^i) / 2, kappa2 =
 *                         -kb . (d1^{i-1} + d1^i) / 2), B the vertex's averaged
 *                         bending stiffness; |M| = hypot(m1, m2) (= E I |kb| /
 *                         vlen for an isotropic section and a straight rest
 *                         shape);
 *   twist_moment[nv-2]    twisting moment G J (tau - taubar) / vlen;
 *   bend_energy[nv-2],    bending and twisting energy of the stencil (their
 *   twist_energy[nv-2]    sums are the rod's RN_TERM_BEND and RN_TERM_TWIST).
 * Any pointer may be NULL.  RN_DEGENERATE (> 0) for a degenerate stencil,
 * RN_ERR_STATE before finalize, RN_ERR_RANGE for a bad rod. */
rn_status rn_network_rod_vertex_fields(const rn_network *net, int rod, double *moment,
                                       double *twist_moment, double *bend_energy,
                                       double *twist_energy);
/* Per edge at the current state: axial_force[nv-1] = E A (l / lbar - 1) and
 * stretch_energy[nv-1] = 1/2 E A (l - lbar)^2 / lbar (its sum is the rod's
 * RN_TERM_STRETCH).  Either pointer may be NULL. */
rn_status rn_network_rod_edge_fields(const rn_network *net, int rod, double *axial_force,
                                     double *stretch_energy);

/* ---- joints (rod networks; docs/joints.md) ------------------------------- */
typedef enum rn_joint_model {
  /* Perez et al. 2015 / seed 001: the joint's rotation is the least-squares
   * fit (polar decomposition) of the incident terminal edges' material frames
   * to their rest frames; no rotation DOFs. */
  RN_JOINT_ELASTIC = 0,
  /* The joint's rotation is a DOF (rotation vector about a reference rotation
   * that moves on accepted steps); rigid connections (frame theory). */
  RN_JOINT_RIGID = 1,
  /* Valence 2, one rod ending and one starting at the joint: the joint vertex
   * is an ordinary DER vertex between the two terminal edges (bending and
   * twisting with the stiffness averaged over the two edges, Voronoi length
   * half their rest lengths), exactly as inside a rod; no rotation DOFs, no
   * connection edges.  Rest curvature and twist: those of the input shape
   * unless rn_network_set_joint_rest_* override them.  It closes the ring of
   * rn_network_add_closed_rod.  Cannot be clamped or carry a couple (pin it). */
  RN_JOINT_SMOOTH = 2
} rn_joint_model;

/* Add a joint where n_ends >= 1 rod ends meet: end k is end ends[k]
 * (RN_START or RN_END) of rod rods[k].  The end vertices must coincide (to
 * 1e-9 of the shortest incident edge); they become one vertex, the joint,
 * whose position is a DOF.  Each rod end gets a connection edge that
 * continues its terminal edge straight across the joint, rigidly attached to
 * the joint's rotation; the bending and twisting between terminal and
 * connection edge is the joint's energy.  A rod end belongs to at most one
 * joint and cannot itself be clamped or pinned (constrain the joint).  name
 * may be NULL.  *joint receives the joint index. */
rn_status rn_network_add_joint(rn_network *net, const char *name, rn_joint_model model,
                               int n_ends, const int *rods, const int *ends, int *joint);
int rn_network_num_joints(const rn_network *net);
const char *rn_network_joint_name(const rn_network *net, int joint); /* borrowed */
int rn_network_joint_model(const rn_network *net, int joint);        /* -1 if invalid */
int rn_network_joint_valence(const rn_network *net, int joint);      /* -1 if invalid */

/* Boundary conditions on joints: clamp fixes position and rotation (an elastic
 * joint then holds its connection edges in their rest orientation); pin
 * fixes the position; pin_joint_components fixes the position components
 * named by the bitmask components (RN_FIX_X, RN_FIX_Y, RN_FIX_Z; RN_ERR_ARG
 * unless in 1 .. RN_FIX_XYZ), the others stay free.  Pins add up (union of
 * the fixed components; a clamp fixes all).  Prescribed motion (scaled by the
 * load factor): disp of a pinned or clamped joint, acting on its fixed
 * components only (a non-zero component of disp on a free one is RN_ERR_BC
 * at finalize), and rotvec (about the joint) of a clamped one. */
rn_status rn_network_clamp_joint(rn_network *net, int joint);
rn_status rn_network_pin_joint(rn_network *net, int joint);
rn_status rn_network_pin_joint_components(rn_network *net, int joint, int components);
rn_status rn_network_displace_joint(rn_network *net, int joint, const double disp[3],
                                    const double rotvec[3]);
/* Dead force on a joint, and a couple on its rotation (model as for rods:
 * rotation about the couple's axis). */
rn_status rn_network_add_joint_force(rn_network *net, int joint, const double f[3]);
rn_status rn_network_add_joint_moment(rn_network *net, int joint, const double m[3]);

/* Rest shape of a joint (before finalize; docs/joints.md "Rest shapes").  By
 * default a joint's rest shape is its input geometry.
 * straight: valence 2 only; the two rods continue each other straight and
 * untwisted at rest (rigid and elastic joints: the rest frame of the second
 * end's terminal edge becomes the first's, turned by pi about its d1 if both
 * rods end or both start there; smooth joints: rest curvature and twist 0).
 * frames: rigid and elastic joints; frames[9 valence] the rest frame (rows t,
 * d1, d2, orthonormal and right-handed to 1e-9) of each end's terminal edge,
 * t along the edge as the rod runs (the frames of the input shape are the
 * default; only their relative orientation matters).
 * strains: smooth joints; the rest material curvature kappa[2] (integrated)
 * and twist tau of the joint vertex.  RN_ERR_ARG for a model or valence the
 * form does not apply to or frames that are not rotations. */
rn_status rn_network_set_joint_rest_straight(rn_network *net, int joint);
rn_status rn_network_set_joint_rest_frames(rn_network *net, int joint,
                                           const double *frames);
rn_status rn_network_set_joint_rest_strains(rn_network *net, int joint,
                                            const double kappa[2], double tau);
/* Twist carried through a smooth joint (before finalize): the reference twist
 * at the joint vertex starts at h + 2 pi link instead of h, h in (-pi, pi] the
 * angle between the two terminal edges' input frames (for a closed rod the
 * holonomy of its parallel-transported frame; 0 for a planar ring).  The rest
 * twist is unchanged, so link full turns of twist are stored in the loop: the
 * total twist of a ring (the sum over its vertices) starts at
 * h + 2 pi link + the rods' own input twist; for a planar ring link is its
 * linking number.  The twist is continued on every reference update (never
 * reduced modulo 2 pi), so the link of a loop is conserved. */
rn_status rn_network_set_joint_link(rn_network *net, int joint, int link);
/* Twist at a smooth joint's vertex at the current state (integrated; the
 * total twist of a closed rod is this plus the sum of its rod's tau of
 * rn_network_rod_strains).  RN_ERR_ARG for other models. */
rn_status rn_network_joint_twist(const rn_network *net, int joint, double *twist);

/* Current joint position x[3] and rotation R[9] (row-major, rest = identity).
 * RN_ERR_STATE before finalize, RN_ERR_RANGE for a bad joint, RN_DEGENERATE
 * if an elastic joint's fit is singular at the current state. */
rn_status rn_network_joint_position(const rn_network *net, int joint, double x[3]);
rn_status rn_network_joint_rotation(const rn_network *net, int joint, double R[9]);

/* ---- periodic cells (docs/homogenization.md) -----------------------------
 * A periodic network is an infinite lattice given by one cell: lattice vectors
 * a_1, a_2 (a 2D cell: both in the xy plane) or a_1, a_2, a_3 (3D), rods and
 * joints of the cell, and rod ends attached to periodic images of joints (the
 * copy of joint J shifted by i a_1 + j a_2 + k a_3).  The cell deforms with the
 * macroscopic deformation gradient F = I + eps, eps the symmetric strain tensor
 * of the strain DOFs (Voigt with engineering shear: 2D (e11, e22, g12), 3D
 * (e11, e22, e33, g23, g13, g12)), applied to the lattice vectors, plus the
 * periodic fluctuation of every DOF: a rod end at image n of joint J is at
 * x_J + F (sum n_m a_m).  The strain DOFs follow the joints in the full layout
 * and are reduced DOFs unless prescribed.  Symmetric F removes the rigid
 * rotations (a 2D cell also keeps F_31 = F_32 = 0: no rotation out of plane);
 * finalize pins joint 0 (rod 0's first vertex without joints), the anchor, if
 * no boundary condition fixes a position.  A part of a partition
 * (rn_network_set_part, docs/parallel.md) may be periodic: the strain DOFs are
 * owned by part 0 and held by every part, the applied stress's work is part 0's,
 * and the cell's stress and relative density below are the part's contributions
 * (they sum over the parts to the network's); the Bloch-Floquet calls need a
 * whole network. */

/* Make the empty network periodic with dim = 2 or 3 lattice vectors
 * vectors[3 dim] (rows).  RN_ERR_GEOMETRY for a degenerate cell, RN_ERR_ARG for
 * a 2D cell out of the xy plane, RN_ERR_STATE after rods were added. */
rn_status rn_network_set_periodic(rn_network *net, int dim, const double *vectors);
/* rn_network_add_joint where end k attaches to the image images[3 k .. 3 k + 2]
 * (lattice shifts, components beyond the cell's dimension 0) of the joint: the
 * end vertex must be at the joint's position plus the shift (the joint's
 * position is the first end's vertex minus its shift).  images NULL: none.
 * RN_ERR_STATE for a non-zero image in a network that is not periodic. */
rn_status rn_network_add_joint_images(rn_network *net, const char *name,
                                      rn_joint_model model, int n_ends, const int *rods,
                                      const int *ends, const int *images, int *joint);
/* Strain control before finalize: component v is prescribed (fixed[v] != 0,
 * value strain[v] scaled by the load factor; strain may be NULL: 0) or a DOF
 * (default: every component free).  nstrain entries each.  RN_ERR_ARG if a
 * component to prescribe carries a non-zero applied stress (contradictory
 * control; rn_network_set_cell_stress). */
rn_status rn_network_set_cell_strain(rn_network *net, const int *fixed,
                                     const double *strain);
/* Applied macroscopic stress (Voigt, work conjugate to the strain DOFs, per unit
 * cell area / volume, scaled by the load factor): the energy gains
 * -lambda measure sigma . eps (mixed control: stress on the free components).
 * RN_ERR_ARG for a non-zero stress on a prescribed strain component
 * (contradictory control: its work would be a constant, the stress ignored). */
rn_status rn_network_set_cell_stress(rn_network *net, const double *stress);
/* After finalize (or before): new values of the prescribed strain components
 * (strain[nstrain]: the entries of components that are DOFs are ignored; NULL
 * keeps them) and of the applied stress (stress[nstrain]; NULL keeps it), both
 * scaled by the load factor; which components are prescribed does not change.
 * Moves the prescribed strain DOFs accordingly (general strain / stress paths).
 * RN_ERR_ARG (nothing changed) for a non-zero stress on a prescribed component. */
rn_status rn_network_set_cell_load(rn_network *net, const double *strain,
                                   const double *stress);
/* Hold the strain DOFs (hold != 0; after finalize) or release them (0).  While
 * held they are fixed at their values as if prescribed, with the DOF layout
 * unchanged: the reduced gradient's and load increment's strain entries are 0,
 * the Hessian's strain rows and columns (values and HVP) those of the identity
 * (its 1 on part 0 of a partition); the energy is unchanged.  A solve then
 * relaxes the fluctuations at the current strain, and the stability check
 * examines them alone (rn_cell_relax and rn_cell_bloch on a part). */
rn_status rn_network_cell_hold_strain(rn_network *net, int hold);
/* Dimension (0 if not periodic), number of strain components, cell area (2D)
 * or volume (3D), lattice vectors vectors[9] (rows; unused rows 0).  Any
 * pointer may be NULL. */
rn_status rn_network_cell_info(const rn_network *net, int *dim, int *nstrain,
                               double *measure, double vectors[9]);
/* Reduced index of each strain component (-1 if prescribed); idx[nstrain]. */
rn_status rn_network_cell_strain_dofs(const rn_network *net, int64_t *idx);
/* Strain at the reduced state x (NULL: the current state); strain[nstrain]. */
rn_status rn_network_cell_strain(const rn_network *net, const double *x, double *strain);
/* Macroscopic stress at x: (1 / measure) dE_elastic / d eps (the derivative of
 * the energy without the applied stress, at fixed fluctuations; at an
 * equilibrium of the fluctuations this is the homogenised stress).  Force per
 * length in 2D, per area in 3D.  stress[nstrain]. */
rn_status rn_network_cell_stress(const rn_network *net, const double *x, double *stress);
/* Relative density of the cell: 3D, the solid volume sum A l (rest lengths) over
 * the cell volume; 2D, the in-plane solid area sum t l over the cell area, t =
 * sqrt(12 I_n / A) the in-plane thickness of the section's equivalent
 * rectangle (I_n its second moment about the in-plane normal of the edge;
 * exact for rectangles, sqrt(3) r for a circle of radius r). */
rn_status rn_network_cell_relative_density(const rn_network *net, double *rho);

/* Bloch-Floquet analysis (docs/homogenization.md, "Stability").  The Bloch DOFs
 * of a periodic network are its free fluctuation DOFs (the reduced DOFs but the
 * strain components, in the same order) followed, if finalize pinned an anchor,
 * by the anchor's 3 position components.  *n receives their number; kind[n]
 * (RN_DOF_*) and component[n] (as rn_dof_info) may be NULL.  RN_ERR_STATE if
 * the network is not periodic or not finalized. */
rn_status rn_network_bloch_dofs(const rn_network *net, size_t *n, int *kind,
                                int *component);
/* The Bloch-Floquet Hessian at the reduced state x for the wave vector
 * k = sum_i xi_i b_i (xi[dim], reciprocal-lattice coordinates of the lattice
 * vectors, b_i . a_j = 2 pi delta_ij): the second variation of the energy of the
 * infinite lattice per cell for perturbations u(copy n) = u exp(2 pi i xi . n)
 * at fixed macroscopic strain, a complex Hermitian n x n matrix H = re + i im
 * (row-major, caller arrays of n * n).  H(0) restricted to the reduced
 * fluctuation DOFs is the reduced Hessian's fluctuation block; H(-xi) =
 * conj(H(xi)).  Dense: memory 16 n^2 bytes. */
rn_status rn_network_bloch_hessian(const rn_network *net, const double *x,
                                   const double *xi, double *re, double *im);
/* The same matrix in compressed sparse rows (memory linear in the cell, for cells
 * beyond the dense one's reach): the entries the stencils give at x (an entry
 * whose phases cancel may be kept as a zero), columns ascending in each row, both
 * triangles; the values those of rn_network_bloch_hessian (summed in the same
 * order).  With col NULL: *nnz (and rowptr[n + 1] if not NULL) only; with col:
 * caller arrays rowptr[n + 1], col, re, im of *nnz entries on entry (RN_ERR_RANGE
 * and the count needed in *nnz if that is short).  Each call assembles the
 * stencils' Hessians (linear in the cell). */
rn_status rn_network_bloch_hessian_csr(const rn_network *net, const double *x,
                                       const double *xi, size_t *nnz, int64_t *rowptr,
                                       int64_t *col, double *re, double *im);
/* Real moments of the phase expansion of the Bloch Hessian for Cartesian wave
 * vectors: out[n * n] = sum over stencils s and entries k, l of
 * H_s,kl d1 (k2 NULL) or H_s,kl d1 d2, d = q . (s_l - s_k) the phase difference
 * of the entries' lattice shifts for q = k1 (d1) or k2 (d2); both NULL: the
 * plain sum H(0).  So H(t k) = H0 + i t M1(k) - t^2/2 M2(k, k) + O(t^3); they
 * give the acoustic tensor of the long-wavelength limit. */
rn_status rn_network_bloch_moment(const rn_network *net, const double *x,
                                  const double *k1, const double *k2, double *out);
/* The Bloch Hessian at x as a sum over lattice shifts, for many wave vectors at one
 * state: H(xi) = sum_t exp(2 pi i xi . n_t) T_t, n_t = shift[3 t ..] the integer
 * lattice coordinates of term t (of nterms; unused ones 0) and T_t real, all on one
 * pattern in compressed sparse rows (the union; both triangles, columns ascending):
 * T_t's entry q is val[t * nnz + q].  With col NULL: *nterms, *nnz (and rowptr[n + 1]
 * if not NULL) only; with col: caller arrays rowptr[n + 1], col[*nnz], shift[3 *
 * *nterms], val[*nterms * *nnz] (RN_ERR_RANGE and the count needed if short).  The
 * values agree with rn_network_bloch_hessian_csr to round-off (summed per term). */
rn_status rn_network_bloch_terms(const rn_network *net, const double *x, int *nterms,
                                 int *shift, size_t *nnz, int64_t *rowptr, int64_t *col,
                                 double *val);
/* The same moments in compressed sparse rows, as rn_network_bloch_hessian_csr
 * gives H (both triangles, columns ascending, the values of
 * rn_network_bloch_moment summed in the same order; col NULL: the count only;
 * caller arrays rowptr[n + 1], col, val of *nnz entries, RN_ERR_RANGE if short). */
rn_status rn_network_bloch_moment_csr(const rn_network *net, const double *x,
                                      const double *k1, const double *k2, size_t *nnz,
                                      int64_t *rowptr, int64_t *col, double *val);

/* ---- parts of a network (distributed solves; docs/parallel.md) -----------
 * A distributed solve gives every rod to one part (rank) and builds on each
 * rank only what its part needs.  The scene is built twice through the same
 * calls: first into a network in graph-only mode, which records the rod graph
 * (vertices per rod, the rod ends of each joint) and nothing else; the graph is
 * partitioned (rn_partition_rods in rodnet_solve.h); then into a network made a
 * part of that partition by rn_network_set_part before anything is added.
 *
 * A part holds its owned rods and joints (a joint is owned by the part holding
 * most of its rod ends, ties to the smallest part), whose stencils it alone
 * evaluates, and ghost rods and joints that those stencils read (a ghost rod is
 * held with its geometry and properties, but only the DOFs next to owned
 * joints are in the part's DOF vector).  Every call keeps its meaning with
 * WHOLE-network rod and joint indices: a call about a rod or joint the part
 * does not hold is checked as far as possible (index ranges, vertex ranges,
 * finite values) and then accepted without effect; results of such a rod or
 * joint are RN_ERR_RANGE.  rn_network_num_rods / _num_joints give the whole
 * network's counts.  The part's reduced DOF vector (rn_network_num_dofs
 * entries) holds its owned DOFs first (owned rods in order, each contiguous,
 * then owned joints), then its ghost DOFs; evaluation functions return the
 * energy, gradient, Hessian-vector product and Hessian of the owned stencils
 * only, at a full local vector (owned and ghost values), so that summing over
 * the parts by global DOF gives the whole network's.  Validation at finalize
 * sees only the part's rods and joints.  Nothing here is collective. */

/* Make the empty network record the rod graph only (RN_ERR_STATE if not empty).
 * Building calls are checked as far as the graph allows and store nothing;
 * rn_network_finalize then only freezes it. */
rn_status rn_network_set_graph_only(rn_network *net);
/* The graph recorded in graph-only mode (borrowed, valid until destroy):
 * rod_nv[nrods], joint j's rods joint_rods[joint_ptr[j] .. joint_ptr[j+1]-1]
 * in the order of its ends.  RN_ERR_STATE for other networks. */
rn_status rn_network_rod_graph(const rn_network *net, int *nrods, const int **rod_nv,
                               int *njoints, const int **joint_ptr,
                               const int **joint_rods);
/* Make the empty network part `part` of nparts: rod r is owned by part
 * rod_part[r]; the graph (rod_nv, joint_ptr, joint_rods, as recorded by
 * rn_network_rod_graph) must be the one the building calls then describe
 * (RN_ERR_ARG at the first rod that differs).  Arrays are copied. */
rn_status rn_network_set_part(rn_network *net, int nparts, int part, int nrods,
                              const int *rod_nv, const int *rod_part, int njoints,
                              const int *joint_ptr, const int *joint_rods);
/* 1 if the network is a part / in graph-only mode. */
int rn_network_is_part(const rn_network *net);
int rn_network_is_graph_only(const rn_network *net);
/* 1 if the rod's data is held here (owned or ghost; always in a whole
 * network); the part owning a rod / joint (0 in a whole network, -1 if out of
 * range or in graph-only mode). */
int rn_network_rod_is_local(const rn_network *net, int rod);
int rn_network_rod_owner(const rn_network *net, int rod);
int rn_network_joint_owner(const rn_network *net, int joint);

/* Sizes and work of a finalized part (of a whole network: one part owning
 * everything).  owned_stencils counts the stencils evaluated here: stretched
 * edges, bend-twist vertices, couples on rods, joints. */
typedef struct rn_part_info {
  int nparts, part;
  int owned_rods, ghost_rods, owned_joints, ghost_joints;
  size_t owned_dofs, ghost_dofs; /* owned_dofs + ghost_dofs = num_dofs */
  long owned_stencils;
} rn_part_info;
rn_status rn_network_part_info(const rn_network *net, rn_part_info *info);
/* The part's reduced DOFs: the first *n_owned are owned; keys[num_dofs] gives
 * each DOF's key (its canonical index in the whole network's full DOF layout:
 * rods concatenated in order, 4 nv - 1 entries each, then 6 entries per joint;
 * equal keys on different parts are the same DOF) and owners[num_dofs] the
 * part that owns it.  Borrowed; RN_ERR_STATE unless a finalized part. */
rn_status rn_network_part_dofs(const rn_network *net, size_t *n_owned,
                               const int64_t **keys, const int **owners);
/* The state of the rods, joints and couples a finalized part owns (current
 * positions and angles, reference frames and twists, joint rotations and
 * reference data, couple frames and angles) packed into buf[*n] doubles (buf
 * NULL: only *n), for another process; part 0 adds the macroscopic strain of a
 * periodic cell. */
rn_status rn_network_part_state_pack(const rn_network *net, double *buf, size_t *n);
/* Installs such a packed state into a finalized network holding those rods,
 * joints and couples (a whole network built from the same scene, at the same
 * load factor): afterwards its results (rn_network_rod_*, rn_network_joint_*,
 * energies) are those of the part's owner.  RN_ERR_ARG if a record does not match
 * the network. */
rn_status rn_network_part_state_unpack(rn_network *net, const double *buf, size_t n);

/* ---- equilibrium: DOF kinds, applied loads, reactions --------------------
 * The gradient of the energy is the out-of-balance generalised force: a force
 * at a position DOF, a moment at a material angle (about the edge tangent) or
 * at a joint rotation component (global frame).  At a fixed DOF it is the
 * reaction of the support on the structure, dE/dq (R = dE/dq balances the
 * internal and applied forces there).  Used by rn_solve's stopping test and by
 * result writers. */
enum {
  RN_DOF_POSITION = 0, /* a vertex or joint coordinate: the gradient is a force */
  RN_DOF_THETA = 1,    /* a material angle: a moment about the edge tangent */
  RN_DOF_ROTATION = 2, /* a joint rotation-vector component: a moment (global) */
  RN_DOF_STRAIN = 3    /* a macroscopic strain component of a periodic cell: the
                          gradient is an energy (stress times cell measure) */
};
/* kind[num_dofs]: the RN_DOF_* kind of every reduced DOF. */
rn_status rn_network_dof_kinds(const rn_network *net, int *kind);
/* What a reduced DOF is: its kind, its owner (a rod, or a joint: a rod end
 * vertex at a joint is the joint's position) and where in it. */
typedef struct rn_dof_info {
  int kind;      /* RN_DOF_* */
  int rod;       /* owning rod, -1 for a joint's DOF */
  int joint;     /* owning joint, -1 for a rod's DOF */
  int index;     /* rod vertex (position) or edge (angle); 0 for joints */
  int component; /* coordinate or rotation component 0, 1, 2; 0 for angles */
} rn_dof_info;
/* info[num_dofs] for every reduced DOF. */
rn_status rn_network_dof_info(const rn_network *net, rn_dof_info *info);
/* gfull[num_full_dofs]: the gradient with respect to every DOF of the full
 * layout (free and fixed) at the reduced state x.  A rod end vertex at a joint
 * aliases the joint position: its slot holds its rod's contributions and the
 * joint's slot the joint's; their sum is the gradient with respect to the
 * joint position.  RN_DEGENERATE at a degenerate x. */
rn_status rn_network_gradient_full(const rn_network *net, const double *x, double *gfull);
/* gabs[num_dofs]: at each reduced DOF the sum over the energy's stencils and
 * the loads of the magnitude of their gradient there, |dE_s/dq_i| summed over
 * stencils s: the size of the forces (moments) that balance at that DOF, whose
 * round-off bounds how small the gradient can be computed. */
rn_status rn_network_gradient_magnitude(const rn_network *net, const double *x,
                                        double *gabs);
/* The largest applied force (Euclidean norm per vertex or joint: point
 * forces, lumped line loads and gravity) and the largest applied couple, at
 * the current load factor. */
rn_status rn_network_applied_load_max(const rn_network *net, double *force,
                                      double *moment);

/* A support: a group of fixed DOFs that act together. */
typedef enum rn_support_kind {
  RN_SUPPORT_CLAMP = 0,  /* clamped rod end: its end edge (2 vertices, angle) */
  RN_SUPPORT_VERTEX = 1, /* pinned rod vertex (some or all components) */
  RN_SUPPORT_THETA = 2,  /* fixed material angle of a rod edge (fix_theta) */
  RN_SUPPORT_JOINT = 3   /* pinned or clamped joint */
} rn_support_kind;

/* The reaction of one support on the structure, in the global frame. */
typedef struct rn_reaction {
  rn_support_kind kind;
  int rod;            /* rod index (-1 for a joint) */
  int index;          /* clamp: end (0 start, 1 end); vertex; edge; joint */
  int fixed;          /* fixed position components (RN_FIX_* bitmask; 0 for
                         RN_SUPPORT_THETA) */
  int fixed_rotation; /* 1 if the support fixes rotations (clamps) */
  double point[3];    /* where it acts: the vertex, the joint, the midpoint of
                         the clamped (or angle-fixed) edge; current state */
  double force[3];    /* reaction force; 0 on free components */
  double moment[3];   /* reaction moment about point: the moments of the two
                         vertex forces of a clamp plus dE/dtheta along the
                         edge tangent; dE/dw of a clamped joint; the
                         dE/dtheta moment of a fixed angle */
} rn_reaction;

/* Number of supports of a finalized network (0 otherwise).  Order: per rod,
 * the start clamp, pinned vertices (not in a clamp) by vertex, fixed angles
 * (not of a clamped edge) by edge, the end clamp; then pinned or clamped
 * joints by index. */
int rn_network_num_supports(const rn_network *net);
/* Reactions r[n] (n = rn_network_num_supports) at the reduced state x
 * (usually an equilibrium: the current state after rn_solve).  At equilibrium
 * they balance the applied loads: sum of forces and of moments (about any
 * point) is zero.  RN_ERR_ARG if n is not the number of supports,
 * RN_DEGENERATE at a degenerate x, RN_ERR_ALLOC. */
rn_status rn_network_reactions(const rn_network *net, const double *x, rn_reaction *r,
                               int n);

/* The resultant of the applied loads at the current state and load factor:
 * force[3] (point forces, lumped line loads and gravity, joint forces) and
 * moment[3] about the origin (their moments x x f at the current positions,
 * plus the spatial moment each couple applies at the current state: M for a
 * couple fixed in space, m = f x (M x f) / |n x f|^2 for a conservative one,
 * on a rod edge or a joint; rodnet_couple.h, docs/model.md "Loads").  At
 * equilibrium it balances the resultant of the reactions
 * (rn_network_reactions): their sum is zero.  RN_ERR_ARG. */
rn_status rn_network_applied_resultant(const rn_network *net, double force[3],
                                       double moment[3]);

/* Internal force and moment per edge of rod (whole-network index of a whole
 * network; a part's local index) at the current state: force[3 ne] and
 * moment[3 ne], global frame, the force and the moment about the edge's
 * midpoint that the part of the rod after the midpoint (towards its last
 * vertex) exerts on the part before it; force . tangent > 0 in tension.  They
 * are the stencil forces of the rod's own elastic energy at the vertices
 * before the cut, summed and negated (and their moments, with the twisting
 * moments dE/dtheta t/|t| of the edges before the cut and half of the cut
 * edge's): exact statics of the cut part at equilibrium, so at the first free
 * edge after a clamp they equal minus the clamp's reaction carried to that
 * point.  RN_ERR_RANGE, RN_ERR_ARG, RN_DEGENERATE, RN_ERR_ALLOC. */
rn_status rn_network_rod_internal_forces(const rn_network *net, int rod, double *force,
                                         double *moment);
/* The same for every rod at once: force and moment [3 * total edges], the rods'
 * edges in rod order.  One evaluation of the network's state; the per-rod call
 * costs a copy of the whole state each time, so loops over rods use this one.
 * RN_ERR_ARG, RN_DEGENERATE, RN_ERR_ALLOC. */
rn_status rn_network_internal_forces(const rn_network *net, double *force,
                                     double *moment);

/* The rigid-body motions that no constraint blocks at the current state, and
 * the applied loads on them (c_api/bcs/supports.c). */
typedef struct rn_free_motions {
  int num_translations; /* free translations: orthonormal directions */
  double translation[3][3];
  int num_rotations; /* free rotations: orthonormal axes (of a free
                        rotation or screw motion) */
  double rotation[3][3];
  double center[3];      /* centroid of the vertices */
  double force[3];       /* applied force resultant */
  double moment[3];      /* applied moment resultant about center */
  int unbalanced_force;  /* the force has a component along a free
                            translation: no configuration balances it */
  int unbalanced_moment; /* no net force, but the couple turns a free
                            rotation (a dead couple stays unbalanced however
                            the structure turns) */
} rn_free_motions;

/* Fills fm for a finalized (whole) network: a rigid motion is free if it
 * changes no fixed DOF (clamps, pins, component pins, prescribed motions,
 * fixed angles, clamped joints).  A net force with only a free rotation is
 * not flagged: the structure can turn until the force passes through the
 * axis (a pendulum).  RN_OK, RN_ERR_ARG, RN_ERR_STATE. */
rn_status rn_network_free_motions(const rn_network *net, rn_free_motions *fm);

/* RN_OK unless the loads are unbalanced on a free rigid motion
 * (rn_free_motions.unbalanced_force or unbalanced_moment), then RN_ERR_BC with
 * a message naming the free motions and the unbalanced resultant.  Call it
 * before rn_solve: such a scene has no equilibrium and the solver would run to
 * its iteration limit.  Free motions under balanced loads are accepted (the
 * solvers' shifted factorisations and trust regions handle the singular
 * Hessian: docs/solvers.md). */
rn_status rn_network_check_supports(const rn_network *net);

/* ---- derivative self-test ------------------------------------------------ */
typedef struct rn_check_report {
  double grad_rel_err; /* worst relative FD error of the gradient */
  double hvp_rel_err;  /* worst relative FD error of the HVP */
  double hess_sym_err; /* relative asymmetry of the assembled Hessian */
  double hess_hvp_err; /* relative mismatch between CSR Hessian and HVP */
  double grad_order;   /* observed order of the FD error over the h-sweep */
  double hvp_order;
  int n_points; /* points tested */
  /* worst over the cases of the error extrapolated to h -> 0 (Richardson's
   * extrapolation of neighbouring steps removes the h^2 truncation term; the
   * smallest over the pairs of the sweep): round-off for a correct derivative
   * even where the error itself is large truncation, the derivative's error for
   * a wrong one (c_api/eval/check.c) */
  double grad_extrapolated_err;
  double hvp_extrapolated_err;
} rn_check_report;

/* The verdict on one finite-difference test of rn_check_report: 1 (pass) if
 * the error rel_err or the error extrapolated to h -> 0 is at most tol, 0
 * otherwise (also for NaN).  A correct derivative whose differences are still
 * dominated by truncation over the sweep (order 2) passes; a wrong one does
 * not, whatever its observed order. */
int rn_check_fd_passes(double rel_err, double extrapolated_err, double tol);

/* Check gradient and HVP against central differences at x (NULL = current
 * state) and at n_random random perturbations of it (seeded, relative size
 * perturb), over an h-sweep.  Fills rep; returns RN_OK (the caller compares
 * the errors with its tolerance). */
rn_status rn_network_check_derivatives(const rn_network *net, const double *x,
                                       int n_random, double perturb, uint64_t seed,
                                       rn_check_report *rep);

/* A smooth objective of n variables given by callbacks (user first), for the
 * derivative self-test of your own energies.  Callbacks return RN_OK, a
 * positive status at a degenerate trial point (that step is skipped) or a
 * negative one on error. */
typedef struct rn_objective {
  size_t n;
  const double *scale; /* [n] typical size of each variable (steps and
                          perturbations are relative to it); NULL: all 1 */
  /* energy *E and gradient g[n] at x[n] */
  rn_status (*gradient)(void *user, const double *x, double *E, double *g);
  /* Hessian-vector product hv[n] = H(x) v */
  rn_status (*hvp)(void *user, const double *x, const double *v, double *hv);
  /* optional: the size of the energy's terms at x (sum of their absolute
   * values), which sets the round-off level of the differences; NULL: |E| */
  double (*energy_size)(void *user, const double *x);
  void *user;
} rn_objective;

/* The gradient and HVP sweeps of rn_network_check_derivatives on obj at x
 * (not NULL) and n_random perturbations of it (relative size perturb, seeded);
 * fills rep (hess_sym_err and hess_hvp_err 0: no assembled Hessian).  RN_OK,
 * RN_ERR_ARG, RN_ERR_NOT_FINITE (x), RN_ERR_ALLOC, a callback's negative
 * status, or its positive status at x; the message in ctx. */
rn_status rn_objective_check_derivatives(rn_context *ctx, const rn_objective *obj,
                                         const double *x, int n_random, double perturb,
                                         uint64_t seed, rn_check_report *rep);

#ifdef __cplusplus
}
#endif
#endif

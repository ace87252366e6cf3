/* network_internal.h - the private layout of rn_network (its rods, joints,
 * couples, DOF map, Hessian pattern, periodic cell) and the core functions every
 * c_api module uses: errors and argument checks, the partition's index
 * translation (partition.c), the gathers and scatters of the stencils
 * (gather.c, with the periodic image entries), frames, fixed components, state.
 * Not installed.
 *
 * The modules of c_api/ (one folder each) depend in ONE direction; a module
 * includes the headers of the modules below it only:
 *
 *   core < periodic < joints < contact < bcs < eval < parts < reactions < homog
 *        < lifecycle
 *
 *   core       the network object, its rods, partition index, DOF gathers,
 *              state, frames, results (this header; partition.h)
 *   periodic   the periodic cell: strain DOFs, image records, its Hessian rows,
 *              the Bloch accumulator (periodic/periodic.h)
 *   joints     joints: building calls, stencils, placement (joints/joints.h)
 *   contact    contact edges, candidate pairs, pattern pairs (contact/contact.h)
 *   bcs        boundary conditions, loads, the load factor, the planar model
 *              (bcs/bcs.h)
 *   eval       energy, gradient, Hessian (pattern and CSR), load increments,
 *              derivative checks (eval/eval.h)
 *   parts      making a part of a partition, its state exchange, DOF blocks
 *   reactions  reactions, internal forces, free rigid motions
 *   homog      cell stress and Bloch-Floquet Hessians of periodic cells
 *   lifecycle  finalize, reference update, destroy: the calls that drive
 *              every module
 *
 * Where a lower module must reach a higher one, it calls a hook of the
 * network that finalize sets (accept_state, rebuild_pattern below). */
#ifndef RODNET_NETWORK_INTERNAL_H
#define RODNET_NETWORK_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "core/dof_layout.h"
#include "rnk.h"
#include "rodnet.h"
#include "rodnet_model.h"
#include "rodnet_contact.h"

/* One rod: input geometry, properties, BCs and its part of the reference
 * state.  ne = nv - 1 edges, nv - 2 interior vertices. */
typedef struct rn_rod {
  char *name;
  int gid;   /* index in the whole network (= the local index unless a part) */
  int owner; /* part that owns it (part.c; 0 in a whole network) */
  int ghost; /* 1: held for the joint stencils of this part only; its own
                stencils are evaluated by its owner */
  int nv, ne;
  size_t off;             /* first full DOF (set at finalize) */
  double *x0;             /* initial vertices [3 nv] */
  rn_material *mat;       /* per edge [ne] */
  rn_section *sec;        /* per edge [ne] */
  unsigned char *has_mat; /* [ne] */
  unsigned char *has_sec; /* [ne] */
  double *lbar;           /* rest lengths [ne] */
  double *kbar;           /* rest material curvature [2 (nv-2)] */
  double *taubar;         /* rest twist [nv-2] */
  rnk_frame *ref_base;    /* reference frames of the input shape [ne] */
  rnk_frame *ref;         /* current reference frames [ne] */
  double *ref_twist;      /* reference twist at the last update [nv-2] */
  /* boundary conditions */
  unsigned char *pinned;      /* [nv] fixed components, RN_FIX_* bitmask */
  unsigned char *has_vdisp;   /* [nv] */
  double *vdisp;              /* prescribed vertex displacements [3 nv] */
  unsigned char *theta_fixed; /* [ne] */
  int clamped[2];             /* RN_START, RN_END */
  int has_end_motion[2];
  double end_disp[2][3];
  double end_rot[2][3];
  /* loads (unscaled) */
  double *fpoint; /* point forces [3 nv] */
  double line_load[3];
  /* built at finalize */
  double *fvert;         /* lumped dead forces [3 nv] */
  rnk_stretch_param *sp; /* [ne] */
  rnk_bend_param *bp;    /* [nv-2] */
  rnk_twist_param *tp;   /* [nv-2], ref_twist taken from ref_twist[] */
  int joint[2];          /* joint at RN_START / RN_END, -1: none */
  int closed;            /* 1: a closed rod (rn_network_add_closed_rod): vertex
                            nv - 1 is vertex 0, joint[] its smooth joint */
} rn_rod;

/* Rest shape of a joint (rn_network_set_joint_rest_*). */
enum { RN_REST_INPUT = 0, RN_REST_STRAIGHT, RN_REST_FRAMES, RN_REST_STRAINS };

/* A dead couple on the material frame of one edge. */
typedef struct rn_moment {
  int gid; /* index among all couples added to the whole network */
  int rod, vertex, edge;
  double M[3];
  double f0[9];  /* (t, d1, d2) at the last reference update */
  double angle0; /* accumulated angle up to that update */
  double b[3];   /* body vector the couple turns (rnk_moment_param.b) */
  int model;     /* rn_couple_model (rodnet_couple.h): conservative or fixed */
} rn_moment;

/* A joint: the end vertices of its rods become one vertex whose position is
 * a DOF; rotation DOFs for rigid joints (docs/joints.md).  The rod end
 * vertices alias the joint position (their full entries map to the joint's
 * reduced indices, and xfull keeps them equal to it). */
typedef struct rn_joint {
  char *name;
  int gid;        /* index in the whole network (= the local index unless a part) */
  int owner;      /* part that owns it (part.c) */
  int ghost;      /* 1: only its position is used here (aliased by the ends of
                     local rods); its stencil belongs to its owner, and only
                     the ends at local rods are listed */
  int model;      /* rn_joint_model */
  int valence;    /* >= 1 */
  int *rod, *end; /* incident rod ends [valence] */
  double x0[3];   /* initial position (the first end's vertex) */
  double lmin;    /* shortest incident terminal edge (input) */
  size_t off;     /* first full DOF (set at finalize) */
  int pinned;     /* fixed position components, RN_FIX_* bitmask */
  int clamped;    /* position and rotation fixed */
  int has_motion;
  double disp[3], rot[3]; /* prescribed motion (unscaled) */
  double force[3], M[3];  /* loads (unscaled); M: the conservative couple */
  double Mfix[3];         /* the couple fixed in space (RN_COUPLE_FIXED) */
  /* reference state */
  double Qhat[9];      /* rigid: reference rotation; clamped: prescribed rotation */
  double f0[9];        /* rotation at the last reference update (couple) */
  double angle0;       /* couple angle accumulated up to that update */
  double couple_p[3];  /* vector the couple turns (rnk_joint.couple_p) */
  int rest;            /* RN_REST_*: where the rest shape comes from */
  double *rest_frames; /* RN_REST_FRAMES: [9 valence] */
  double rest_kbar[2], rest_taubar; /* RN_REST_STRAINS (smooth joints) */
  int link;                         /* smooth joints: full turns of twist added */
  int has_total_twist;              /* ring joints: total twist given */
  double total_twist;               /* (rn_network_set_ring_total_twist) */
  double turns; /* smooth joints: whole turns in the reference twist (finalize) */
  int *image;   /* periodic cells: lattice shift (3 ints) of each end's
                   joint copy [3 valence]; NULL: no image ends */
  int32_t *img; /* built at finalize: image record of each kernel stencil
                   entry (periodic.c, read by gather.c), -1 none; NULL:
                   no image ends */
  /* built at finalize */
  rnk_joint_end *ends; /* kernel parameters [valence]; twist.ref_twist is the
                          reference twist stored at the last update */
  size_t *idx;         /* full index of each kernel stencil entry */
} rn_joint;

/* Where row a of the full layout, restricted to the rod stencils' columns
 * [a + lo, a + hi], goes in the CSR values: at pos.. pos + hi - lo if those
 * columns are free, distinct and consecutive in the row (pos >= 0), by a
 * search per entry otherwise (pos == RN_BAND_SEARCH); RN_BAND_NONE for fixed
 * rows and joint DOFs.  Built with the pattern (hessian.c). */
enum { RN_BAND_SEARCH = -1, RN_BAND_NONE = -2 };
typedef struct rn_band_row {
  int64_t pos;
  signed char lo, hi;
  signed char assign; /* the row's run is only this row's rod band, complete in
                         one assembly segment: stored, not added (no zeroing) */
} rn_band_row;

/* Edges per rod segment of the Hessian assembly (assembly.c); consecutive
 * segments share one edge.  hessian.c mirrors the segmentation to know which
 * rows a single segment completes. */
enum { RN_ROD_SEGMENT = 33 };

struct rn_network {
  rn_context *ctx;
  rn_rod *rods;
  int nrods, cap_rods;
  rn_moment *moments;
  int nmom, cap_mom;
  /* couples fixed in space added to the whole network (also those another
   * part holds), and where the first is: on joint fixed_joint if
   * fixed_on_joint, else on rod fixed_rod, vertex fixed_vertex
   * (rodnet_couple.h) */
  int nfixed_couples, fixed_rod, fixed_vertex, fixed_on_joint, fixed_joint;
  int couple_tilt_off; /* 1: no tilt check of conservative couples (reference.c) */
  rn_joint *joints;
  int njoints, cap_joints;
  double gravity[3];
  int finalized;
  double lambda;   /* load factor */
  double lambda_x; /* load factor at which the free DOFs were last set */
  size_t nfull, nred;
  int64_t *map;      /* full -> reduced index, -1 if fixed [nfull] */
  int64_t *red2full; /* reduced -> full [nred] */
  double *xfull;     /* current state; fixed entries at lambda [nfull] */
  int64_t *rowptr;   /* Hessian pattern [nred + 1] */
  int32_t *col;      /* [nnz] */
  rn_band_row *band; /* rod rows of the full layout into the CSR values [nfull] */
  int *rod_direct;   /* [2 nrods]: rod edges [lo, hi) whose stencils' DOFs are free,
                        distinct and consecutive in the reduced vector */
  int64_t *hzero;    /* [2 nhzero]: (first, count) of the CSR values no rod band
                        stores: zeroed before each assembly */
  size_t nhzero;
  size_t nnz;
  size_t bandwidth;
  unsigned long pattern_version; /* + 1 at each rebuild (rodnet_contact.h) */
  size_t pattern_work;           /* entries the pattern build's candidate loops
                                    looked at (hessian.c; a test asserts that it grows
                                    linearly with a periodic supercell) */
  struct rn_part_data *part;     /* NULL: a whole network (part.c) */
  struct rn_cell *cell;          /* NULL: not periodic (periodic.c) */
  int positions_fixed;           /* a clamp or pin of a position was asked for,
                                    also one another part holds (the periodic
                                    anchor: periodic.c) */
  int model;                     /* rn_model asked for (planar.c) */
  int planar;                    /* 1: the planar model is in use (set at finalize) */
  int planar_ok;                 /* 1: the network qualifies for it (set at finalize) */
  char planar_why[240];          /* if not: what leaves the plane */
  struct rn_contact *contact;    /* NULL: no contact (contact.c) */
  /* hooks set by finalize (lifecycle/finalize.c): a lower module's calls into a
   * higher one.  accept_state: the accepted state changed (core's state calls
   * -> contact's pattern pairs, rn_contact_pattern_update); rebuild_pattern:
   * the Hessian pattern again (contact -> eval, rn_rebuild_hessian_pattern). */
  rn_status (*accept_state)(rn_network *net, int force, const char *where);
  rn_status (*rebuild_pattern)(rn_network *net);
};

/* The accepted state changed (set_dofs, state restore, load factor): the
 * contact pattern follows it (RN_OK before finalize: nothing to follow). */
static inline rn_status rn_net_accept_state(rn_network *net, const char *where) {
  return net->accept_state ? net->accept_state(net, 0, where) : RN_OK;
}

/* ---- parts of a network (partition.c, parts/part.c) -------------------------
 * A network built in graph-only mode records the rod graph and nothing else; a
 * part holds the rods and joints that one part of a partition needs (owned and
 * ghost ones, in increasing whole-network index) under their whole-network
 * indices at the API.  Internally rods and joints are indexed locally; gid
 * gives the whole-network index (used in every message). */
typedef struct rn_part_data rn_part_data;
/* Map entry of a full DOF that a part does not hold (a ghost rod's DOF that no
 * stencil of the part reads, a ghost joint's rotation). */
enum { RN_DOF_ABSENT = -3 };
/* Internal status of an API call that concerns a rod or joint another part
 * holds: the call is accepted and has no effect here. */
#define RN_NOT_HERE ((rn_status)1000)
static inline rn_status rn_not_here_ok(rn_status st) {
  return st == RN_NOT_HERE ? RN_OK : st;
}
/* Whole-network number of rods / joints added so far (or of the partition). */
int rn_net_num_rods_g(const rn_network *net);
int rn_net_num_joints_g(const rn_network *net);
/* Rods / joints added so far (whole-network count). */
int rn_net_rods_added(const rn_network *net);
int rn_net_joints_added(const rn_network *net);
/* Vertices of rod gid (also of rods another part holds); 0 if out of range. */
int rn_net_rod_nv(const rn_network *net, int gid);
/* Translates the whole-network rod index *rod into the local index: RN_OK, an
 * RN_ERR_RANGE error (recorded; where names the caller) if it is out of range,
 * or RN_NOT_HERE if another part holds it.  The same for joints. */
rn_status rn_net_rod(const rn_network *net, const char *where, int *rod);
rn_status rn_net_joint(const rn_network *net, const char *where, int *joint);
/* Hooks of the building calls: add_rod asks whether rod gid is held here (1)
 * and records its vertex count; add_joint whether the joint is held and which
 * of its ends are (keep[k]; ghost joints list only the ends at local rods;
 * images: the ends' periodic images or NULL, for the graph's joint point);
 * add_moment numbers the couples. */
rn_status rn_part_add_rod(rn_network *net, int nv, const double *xyz, int *keep);
rn_status rn_part_add_joint(rn_network *net, const char *name, int n_ends,
                            const int *rods, const int *ends, const int *images,
                            int *keep, int *keep_end);
int rn_part_next_moment(rn_network *net);
/* Sets gid/owner/ghost of the rod or joint just added locally. */
void rn_part_tag_rod(const rn_network *net, rn_rod *r);
void rn_part_tag_joint(const rn_network *net, rn_joint *J);
/* 1 if the stencils of rod ir / joint ij / moment im are evaluated here. */
static inline int rn_rod_evaluated(const rn_rod *r) { return !r->ghost; }
static inline int rn_joint_evaluated(const rn_joint *J) { return !J->ghost; }

/* ---- periodic cells (periodic/, gather.c; docs/homogenization.md) -------------
 * A periodic network has lattice vectors a_m (2 or 3) and macroscopic strain
 * DOFs (Voigt, engineering shear: 3 in 2D, 6 in 3D) after the joints in the full
 * layout; the cell deforms with F = I + sum_v eps_v B_v (symmetric).  A rod end
 * at the image n of a joint (lattice shift s = sum n_m a_m) is the joint's
 * position plus F s: its full slot aliases the joint position like any joint
 * end, and every gather adds the shift s + T eps (T[c][v] = (B_v s)_c), every
 * scatter adds T^T onto the strain DOFs.  The joint's own stencil sees the
 * neighbour vertex of that end shifted by -F s. */
typedef struct rn_image {
  size_t base;    /* full index of the unshifted position (joint or vertex) */
  double s[3];    /* shift at zero strain (sign included) */
  double T[3][6]; /* d shift / d eps */
} rn_image;
typedef struct rn_cell {
  int dim, nstrain;
  double a[3][3];   /* lattice vectors (rows) */
  double measure;   /* area (2D) or volume (3D) */
  double B[6][9];   /* strain basis tensors (row-major) */
  size_t off;       /* full index of the first strain DOF */
  int fixed[6];     /* prescribed strain components */
  double strain[6]; /* their prescribed values (unscaled by the load factor) */
  double stress[6]; /* applied macroscopic stress (work conjugate, unscaled) */
  int anchored;     /* 1: finalize pinned joint 0 (or rod 0's vertex 0) */
  int held;         /* rn_network_cell_hold_strain: the strain DOFs are held */
  rn_image *img;    /* image records */
  int nimg, cap_img;
  int32_t *slot; /* [nfull]: 3 r + c for component c of record r, -1 */
} rn_cell;
/* In a part of a partition, the macroscopic strain DOFs are owned by part 0 and
 * held by every part (a ghost elsewhere); the stress work is evaluated there. */
int rn_cell_owned_here(const rn_network *net);
/* rn_network_cell_hold_strain: while the strain DOFs are held, the reduced
 * gradient, HVP and Hessian see them as fixed (their entries of the gradient 0,
 * their rows and columns those of the identity, the 1 on part 0).  Zeroes the
 * strain entries of a reduced vector v[nred]; no-op when not held. */
void rn_cell_hold_zero(const rn_network *net, double *v);
/* The strain rows of a held HVP Hv = H [v_u; 0]: v's strain entries on part 0, 0
 * elsewhere (the identity rows, summed once over the parts). */
void rn_cell_hold_hvp(const rn_network *net, const double *v, double *Hv);
/* The Hessian values vals[nnz] with the held strain rows and columns replaced. */
void rn_cell_hold_hessian(const rn_network *net, double *vals);
static inline int rn_cell_held(const rn_network *net) {
  return net->cell && net->cell->held;
}
/* Number of full strain DOFs (0 if not periodic). */
static inline size_t rn_cell_full_count(const rn_network *net) {
  return net->cell ? (size_t)net->cell->nstrain : 0;
}
/* Record slot (3 r + c) of entry k of a stencil (contiguous at full index s, or
 * by the image list img), -1 if none. */
static inline int32_t rn_cell_entry_slot(const rn_cell *c, size_t s, const int32_t *img,
                                         int k) {
  return img ? img[k] : c->slot[s + (size_t)k];
}
/* Shift of record r at the strain of the full state full. */
void rn_cell_shift(const rn_network *net, const rn_image *im, const double *full,
                   double out[3]);
/* Gather / scatter corrections of a contiguous slice [s, s + n) (rod stencils)
 * or of an index list with its image list img (joint stencils; img NULL: none). */
void rn_cell_gather(const rn_network *net, const double *x, size_t s, const size_t *idx,
                    const int32_t *img, int n, double *q);
void rn_cell_gather_dir(const rn_network *net, const double *v, size_t s,
                        const size_t *idx, const int32_t *img, int n, double *q);
void rn_cell_gather_fixed_dir(const rn_network *net, const double *vfull, size_t s,
                              const size_t *idx, const int32_t *img, int n, double *q);
void rn_cell_scatter(const rn_network *net, const double *gl, size_t s, const size_t *idx,
                     const int32_t *img, int n, double *g);
void rn_cell_scatter_full(const rn_network *net, const double *gl, size_t s,
                          const size_t *idx, const int32_t *img, int n, double *gfull);
void rn_cell_expand(const rn_network *net, double *full);
/* ---- errors -------------------------------------------------------------- */
/* Record "where: what" in ctx (ctx may be NULL) and return s. */
rn_status rn_fail(rn_context *ctx, rn_status s, const char *where, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;

/* Checks shared by the API entry points; each records an error on failure. */
/* Range check and translation of a whole-network rod index into the local one;
 * RN_ERR_RANGE also for a rod held by another part. */
rn_status rn_net_check_rod(const rn_network *net, const char *where, int *rod);
rn_status rn_net_check_building(const rn_network *net, const char *where);
rn_status rn_net_check_final(const rn_network *net, const char *where);
int rn_all_finite(size_t n, const double *v);
/* 1 if every |v[i]| <= RN_HESS_BOUND (finite): a sum of fewer than 1e7 such
 * values cannot overflow. */
#define RN_HESS_BOUND 1e300
int rn_all_bounded(size_t n, const double *v);
/* Resolves a possibly negative index (-1 = last) into [0, n); -1 if out of
 * range. */
int rn_wrap_index(int i, int n);

/* ---- fixed components (fixed.c) --------------------------------------------- */
/* Fixed position components (RN_FIX_* bitmask) of rod vertex v: its pins and
 * the clamps of the rod's ends; of a joint: its pins, all if clamped. */
int rn_rod_fixed_components(const rn_rod *r, int v);
/* 1 if rod vertex v belongs to a clamped end edge. */
int rn_rod_in_clamp(const rn_rod *r, int v);
static inline int rn_joint_fixed_components(const rn_joint *J) {
  return J->clamped ? RN_FIX_XYZ : J->pinned;
}
/* 1 if component k (0 x, 1 y, 2 z) is in the bitmask. */
static inline int rn_component_fixed(int mask, int k) { return (mask >> k) & 1; }
/* The first component k with disp[k] != 0 that mask leaves free, -1 if none. */
int rn_free_displaced_component(int mask, const double disp[3]);
/* "x", "xz", ... (the components of mask) into buf[4]; returns buf. */
const char *rn_components_name(int mask, char buf[4]);

/* ---- state and stencils (gather.c) ----------------------------------------- */
/* Local stencil of n DOFs starting at full index s: q[k] = x[map] if free,
 * else the fixed value in net->xfull. */
void rn_gather(const rn_network *net, const double *x, size_t s, int n, double *q);
/* Local direction: v[map] if free, else 0. */
void rn_gather_dir(const rn_network *net, const double *v, size_t s, int n, double *q);
/* Local direction from a full-layout vector: vfull[s+k] if fixed, else 0. */
void rn_gather_fixed_dir(const rn_network *net, const double *vfull, size_t s, int n,
                         double *q);
/* g[map[s+k]] += gl[k] for free DOFs. */
void rn_scatter_add(const rn_network *net, const double *gl, size_t s, int n, double *g);
/* Full state from a reduced vector: free entries from x, fixed from xfull. */
void rn_expand_state(const rn_network *net, const double *x, double *full);
/* The same over an index list: q[k] from full index idx[k]. */
void rn_gather_idx(const rn_network *net, const double *x, const size_t *idx, int n,
                   double *q);
void rn_gather_dir_idx(const rn_network *net, const double *v, const size_t *idx, int n,
                       double *q);
void rn_gather_fixed_dir_idx(const rn_network *net, const double *vfull,
                             const size_t *idx, int n, double *q);
void rn_scatter_add_idx(const rn_network *net, const double *gl, const size_t *idx, int n,
                        double *g);

/* ---- frames (frames.c) ----------------------------------------------------- */
/* Reference frames of a new rod from its vertices and optional d1, reference
 * twists (prev 0) and rest quantities at the input shape (theta = 0). */
rn_status rn_rod_init_frames(rn_context *ctx, rn_rod *r, int rod_index, const double *d1);
/* Rotation matrix of the rotation vector w (Rodrigues). */
void rn_rotation_matrix(const double w[3], double R[9]);
void rn_mat_vec3(const double R[9], const double v[3], double out[3]);

/* ---- joints (the rest: joints/joints.h) -------------------------------------- */
/* End vertices of a joint coincide, and two joints are coincident, within
 * this fraction of the shortest incident terminal edge. */
#define RN_JOINT_COINCIDE_TOL 1e-9
/* 1 if the joint has rotation DOFs in the full vector: rigid joints, and
 * clamped joints of either model (rotation held at the prescribed value). */
static inline int rn_joint_has_rotation(const rn_joint *J) {
  return J->model == RN_JOINT_RIGID || J->clamped;
}
/* Number of full DOFs of all joints. */
size_t rn_joints_full_count(const rn_network *net);
/* Initial position, shortest incident terminal edge, index and name of a joint;
 * the coincidence check (the first pair closer than RN_JOINT_COINCIDE_TOL of
 * their shorter lmin is an RN_ERR_GEOMETRY error naming both). */
typedef struct rn_joint_point {
  double x0[3], lmin;
  int gid;
  const char *name;
} rn_joint_point;
/* ---- rods ---------------------------------------------------------------- */
void rn_rod_free(rn_rod *r);
/* The vector a couple m works on, in the coordinates of the frame f (rows
 * f[3k..3k+2], orthonormal): the frame vector most perpendicular to m,
 * projected onto the plane normal to m and normalised (zero if m = 0). */
void rn_couple_vector(const double f[9], const double m[3], double b[3]);
#endif

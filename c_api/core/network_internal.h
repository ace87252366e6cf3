/* network_internal.h - private layout of rn_network and helpers shared by the
 * c_api source files.  Not installed. */
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
  int *image;   /* periodic cells: lattice shift (3 ints) of each end's
                   joint copy [3 valence]; NULL: no image ends */
  int32_t *img; /* built at finalize: image record of each kernel stencil
                   entry (periodic.c), -1 none; NULL: no image ends */
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
  int model;                     /* rn_model asked for (planar.c) */
  int planar;                    /* 1: the planar model is in use (set at finalize) */
  int planar_ok;                 /* 1: the network qualifies for it (set at finalize) */
  char planar_why[240];          /* if not: what leaves the plane */
  struct rn_contact *contact;    /* NULL: no contact (contact.c) */
};

/* ---- parts of a network (part.c) ------------------------------------------
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
 * of its ends are (keep[k]; ghost joints list only the ends at local rods);
 * add_moment numbers the couples. */
rn_status rn_part_add_rod(rn_network *net, int nv, const double *xyz, int *keep);
rn_status rn_part_add_joint(rn_network *net, const char *name, int n_ends,
                            const int *rods, const int *ends, int *keep, int *keep_end);
/* Graph-only finalize: coincident joints (the check every part cannot make). */
rn_status rn_part_graph_validate(const rn_network *net, const char *where);
int rn_part_next_moment(rn_network *net);
/* Sets gid/owner/ghost of the rod or joint just added locally. */
void rn_part_tag_rod(const rn_network *net, rn_rod *r);
void rn_part_tag_joint(const rn_network *net, rn_joint *J);
/* Finalize of a part: marks the full DOFs no evaluated stencil reads with
 * RN_DOF_ABSENT in net->map (called after fixed and aliased entries are
 * marked, before numbering) and returns 1 if full entry a (canonical) is owned
 * by this part (numbering order: owned first). */
void rn_part_mark_absent(rn_network *net);
int rn_part_entry_owned(const rn_network *net, size_t a);
/* Global keys of the reduced DOFs (after numbering); RN_ERR_ALLOC. */
rn_status rn_part_begin_numbering(rn_network *net);
rn_status rn_part_build_keys(rn_network *net);
void rn_part_free(rn_part_data **p);
/* 1 if the stencils of rod ir / joint ij / moment im are evaluated here. */
static inline int rn_rod_evaluated(const rn_rod *r) { return !r->ghost; }
static inline int rn_joint_evaluated(const rn_joint *J) { return !J->ghost; }

/* ---- periodic cells (periodic.c; docs/homogenization.md) ---------------------
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
  rn_image *img;    /* image records */
  int nimg, cap_img;
  int32_t *slot; /* [nfull]: 3 r + c for component c of record r, -1 */
} rn_cell;
void rn_cell_free(struct rn_cell **c);
/* Number of full strain DOFs (0 if not periodic). */
static inline size_t rn_cell_full_count(const rn_network *net) {
  return net->cell ? (size_t)net->cell->nstrain : 0;
}
/* Finalize: marks the strain DOFs (map), after the joints' offsets are set. */
void rn_cell_mark(rn_network *net);
/* Finalize: image records and slots (after build_dof_map's numbering and
 * rn_joints_build); anchor (before the DOF map). */
rn_status rn_cell_build(rn_network *net);
void rn_cell_anchor(rn_network *net);
/* Fixed strain components of xfull at the load factor. */
void rn_cell_place(rn_network *net);
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
/* Hessian: the strain rows and columns of a stencil's dense block H[n n]
 * (contiguous at s, or by idx/img), or of rod band rows (rnk.h band storage). */
void rn_cell_hess_block(const rn_network *net, size_t s, const size_t *idx,
                        const int32_t *img, int n, const double *H, double *vals);
void rn_cell_hess_band(const rn_network *net, size_t s, int n, const double *band,
                       double *vals);
/* Pattern: 1 if reduced column list of row r must include the strain DOFs;
 * the extra candidates of a strain row (appends to buf via push). */
int rn_cell_pattern_flags(const rn_network *net, const size_t *lo, const size_t *hi,
                          unsigned char *touch);
/* Energy and gradient of the applied macroscopic stress at x (load scale lambda):
 * E -= lambda V sigma . eps. */
double rn_cell_load(const rn_network *net, const double *x, double lambda, double *g,
                    double *gfull);
/* F s of the lattice shift n[3] at the strain of the full state (the offset of
 * an image end from its joint), and the image slots of a full state set from
 * their joints (after the other entries). */
void rn_cell_image_offset(const rn_network *net, const int *n, const double *full,
                          double out[3]);
void rn_cell_expand(const rn_network *net, double *full);
/* Joint stencil from a full state: q[k] = full[idx[k]] plus image shifts. */
void rn_joint_gather_full(const rn_network *net, const rn_joint *J, const double *full,
                          double *q);

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

/* ---- fixed components (boundary.c) ------------------------------------------ */
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

/* ---- state and stencils --------------------------------------------------- */
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

/* ---- load increment (assembly.c) -------------------------------------------- */
/* Hv[nred] = H_{free,fixed}(x) vfull: every stencil's Hessian block applied to
 * the fixed entries of the full-layout direction vfull[nfull], free rows only.
 * No argument checks (where names the caller in messages). */
rn_status rn_eval_fixed_hvp(const rn_network *net, const double *x, const double *vfull,
                            double *Hv, const char *where);
/* g[nred] = gradient of the load terms (forces, couples) at load factor 1: their
 * derivative with respect to the load factor (loads are linear in it). */
rn_status rn_eval_load_rate(const rn_network *net, const double *x, double *g,
                            const char *where);

/* gfull[nfull] = gradient of the energy with respect to every full DOF (free and
 * fixed; an aliased rod end slot gets its rod's stencils, the joint's slot the
 * joint stencil and the joint force) at the reduced state x (reactions.c). */
rn_status rn_eval_gradient_full(const rn_network *net, const double *x, double *gfull,
                                const char *where);

/* gfull[nfull] += gradient of rod ir's own stretching, bending and twisting
 * energy (no loads, no joints) at the reduced state x, on its full-layout slots
 * (reactions.c: internal forces). */
rn_status rn_eval_rod_gradient_full(const rn_network *net, int ir, const double *x,
                                    double *gfull, const char *where);

/* gabs[nred] = sum over the stencils (and loads) of |their gradient| at each reduced
 * DOF: the magnitude of the forces that balance there (reactions.c). */
rn_status rn_eval_gradient_magnitude(const rn_network *net, const double *x, double *gabs,
                                     const char *where);

/* ---- Bloch-Floquet Hessians of periodic cells (bloch.c) ----------------------
 * An accumulator of stencil Hessian blocks onto the dense n x n Bloch matrix
 * (row-major): entry (k, l) of a stencil, at the Bloch DOFs bk, bl of its entries
 * with image phases phi_k, phi_l (phi = k . s of the entry's lattice shift s),
 * adds H_kl w(phi_l - phi_k): complex mode (im != NULL) w = exp(i d); real moment
 * mode w = d1 (order 1) or d1 d2 (order 2), d1, d2 the differences under the two
 * phase sets ph1, ph2. */
typedef struct rn_bloch_acc {
  size_t n;
  const int64_t *bidx; /* [nfull] Bloch DOF of each full entry (aliases resolved), -1 */
  const double *ph1;   /* [nimg] phase of each image record */
  const double *ph2;   /* [nimg] second phase set (order 2), or NULL */
  double k1[3], k2[3]; /* the Cartesian wave vectors of ph1, ph2 */
  int order;           /* real mode: 0, 1 or 2 */
  double *re, *im;     /* output; im NULL: real mode */
} rn_bloch_acc;
/* A block of n entries at full index s, or by index list idx (a joint stencil:
 * J given, whose ends at images carry their rod's DOFs from another cell). */
void rn_bloch_add_block(const rn_network *net, rn_bloch_acc *b, size_t s,
                        const size_t *idx, const int32_t *img, int n, const double *H,
                        const struct rn_joint *J);
void rn_bloch_add_band(const rn_network *net, rn_bloch_acc *b, size_t s, int n,
                       const double *band);
/* Every stencil's Hessian block at x into b (assembly.c). */
rn_status rn_eval_bloch(const rn_network *net, const double *x, rn_bloch_acc *b,
                        const char *where);

/* ---- frames (frames.c) ----------------------------------------------------- */
/* Reference frames of a new rod from its vertices and optional d1, reference
 * twists (prev 0) and rest quantities at the input shape (theta = 0). */
rn_status rn_rod_init_frames(rn_context *ctx, rn_rod *r, int rod_index, const double *d1);
/* Rotation matrix of the rotation vector w (Rodrigues). */
void rn_rotation_matrix(const double w[3], double R[9]);
void rn_mat_vec3(const double R[9], const double v[3], double out[3]);

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
/* Builds the Hessian pattern (hessian.c). */
rn_status rn_build_hessian_pattern(rn_network *net);
/* Builds the pattern again (contact pairs changed); keeps the old one and
 * returns RN_ERR_ALLOC on failure. */
rn_status rn_rebuild_hessian_pattern(rn_network *net);
/* Adds the free-free entries of a dense n x n stencil block at full index s
 * into CSR values (hessian.c). */
void rn_csr_add_block(const rn_network *net, size_t s, int n, const double *H,
                      double *vals);
/* Adds rows s .. s + n - 1 of the full layout given in rnk.h band storage
 * (band[i * RNK_BAND + c - (s + i) + RNK_BAND_HALF] = entry (s + i, c); rod
 * stencils only) into CSR values.  Returns 1 if every value it added was at
 * most RN_HESS_BOUND in magnitude (rn_all_bounded). */
int rn_csr_add_band(const rn_network *net, size_t s, int n, const double *band,
                    double *vals);
/* Zeroes the CSR values that the rod bands do not store (net->hzero). */
void rn_hessian_zero(const rn_network *net, double *vals);
/* Frees the Hessian pattern (rowptr, col, band, rod_direct, hzero) and sets
 * the pointers NULL. */
void rn_hessian_pattern_free(rn_network *net);
/* The same for a stencil gathered by the full index list idx[n]. */
void rn_csr_add_block_idx(const rn_network *net, const size_t *idx, int n,
                          const double *H, double *vals);

/* ---- joints (joints.c, joint_stencil.c) ------------------------------------ */
/* End vertices of a joint coincide, and two joints are coincident, within
 * this fraction of the shortest incident terminal edge. */
#define RN_JOINT_COINCIDE_TOL 1e-9
/* 1 if the joint has rotation DOFs in the full vector: rigid joints, and
 * clamped joints of either model (rotation held at the prescribed value). */
static inline int rn_joint_has_rotation(const rn_joint *J) {
  return J->model == RN_JOINT_RIGID || J->clamped;
}
void rn_joint_free(rn_joint *J);

/* ---- contact (contact.c) ---------------------------------------------------- */
typedef struct rn_contact rn_contact;
/* Pairs of contact edges (indices into the contact edge list), a < b. */
typedef struct rn_contact_list {
  int *pair; /* [2 n] */
  size_t n, cap;
} rn_contact_list;
/* At finalize after the DOF map: the contact edges (RN_OK without contact). */
rn_status rn_contact_build(rn_network *net, const char *where);
void rn_contact_unbuild(rn_network *net);
void rn_contact_free(rn_network *net);
/* The Hessian pattern's contact pairs (docs/contact.md, "Hessian pattern"):
 * the pairs whose boxes, inflated by the radius, dhat / 2 and margin / 2,
 * overlap at the accepted state.  rn_contact_pattern_update keeps them (force
 * 0) if every pair within half the margin at the accepted state is one of
 * them, else rebuilds them there and the CSR pattern with them
 * (pattern_version + 1); the old pattern stays on failure.  Called at
 * finalize and wherever the accepted state changes. */
rn_status rn_contact_pattern_update(rn_network *net, int force, const char *where);
int rn_contact_in_pattern(const rn_network *net, int a, int b);
size_t rn_contact_pattern_count(const rn_network *net);
/* The two contact edges (a < b, indices into the contact's edge list) of pattern
 * pair i: the one decoding of the pattern's keys. */
void rn_contact_pattern_pair(const rn_network *net, size_t i, int *a, int *b);
/* The 12 full indices of pattern pair i. */
void rn_contact_pattern_idx(const rn_network *net, size_t i, size_t idx[12]);
/* 1 if pattern pair i joins two rods or two edges of one rod at least 3 apart
 * (edges j and j + 2, close on every straight rod, stay inside its band). */
int rn_contact_pattern_far(const rn_network *net, size_t i);
/* RN_ERR_GEOMETRY if the initial state interpenetrates. */
rn_status rn_contact_check_initial(const rn_network *net, const char *where);
/* The pairs within the barrier's reach at x (x NULL: the accepted state); with
 * ccd, first the continuous check of the motion from the accepted state to x
 * (RN_DEGENERATE naming the pair if it would cross).  L is freed on error. */
rn_status rn_contact_candidates(const rn_network *net, const double *x, int ccd,
                                const char *where, rn_contact_list *L);
void rn_contact_list_free(rn_contact_list *L);
/* The 12 full indices of pair (a, b): (p0, p1) of edge a, then of edge b. */
void rn_contact_pair_idx(const rn_network *net, int a, int b, size_t idx[12]);
/* The kernel parameters of pair (a, b): radius the sum of the rods' radii. */
rnk_contact_param rn_contact_pair_param(const rn_network *net, int a, int b);
/* rn_fail with a message naming the pair's rods and edges. */
rn_status rn_contact_pair_fail(const rn_network *net, rn_status st, const char *where,
                               int a, int b, const char *what);
/* Number of full DOFs of all joints. */
size_t rn_joints_full_count(const rn_network *net);
/* Finalize steps: BC conflicts with rod vertices, coincident joints
 * (validate); kernel parameters and stencil index lists (build, after the
 * DOF offsets are set); the fit at the initial state (check_initial). */
rn_status rn_joints_validate(const rn_network *net, const char *where);
/* Initial position, shortest incident terminal edge, index and name of a joint;
 * the coincidence check (the first pair closer than RN_JOINT_COINCIDE_TOL of
 * their shorter lmin is an RN_ERR_GEOMETRY error naming both). */
typedef struct rn_joint_point {
  double x0[3], lmin;
  int gid;
  const char *name;
} rn_joint_point;
rn_status rn_joint_points_check(rn_context *ctx, const char *where, int n,
                                const rn_joint_point *p);
rn_status rn_joints_build(rn_network *net);
rn_status rn_joints_check_initial(const rn_network *net, const char *where);
void rn_joints_unbuild(rn_network *net);
/* Fixed joint DOFs (positions, prescribed rotations Qhat) for the current
 * load factor, copied to the aliased rod end vertices of net->xfull (place);
 * then, once every fixed DOF is placed, the stored twists of clamped joints
 * with a prescribed motion are continued (continue_twists). */
void rn_joints_place(rn_network *net);
void rn_joints_continue_twists(rn_network *net);
/* Copies each joint position in net->xfull to its rod end vertices. */
void rn_joints_sync(rn_network *net);

/* Kernel parameters of joint ij: copies the terminal edges' current
 * reference frames to refs[valence] and fills kj, the couple scaled by
 * load_scale (the network's load factor, or 1 for the load rate). */
void rn_joint_kernel(const rn_network *net, int ij, double load_scale, rnk_frame *refs,
                     rnk_joint *kj);
/* Scratch of one joint evaluation (declared by the caller, on its stack:
 * evaluation stays reentrant): q[n], v[n], loc[n n] (gradient or Hessian
 * block), the kernel workspace and the reference frames; in the embedded
 * buffers up to valence 8, on the heap beyond. */
enum { RN_JOINT_STACK = 5120, RN_JOINT_STACK_ENDS = 8 };
typedef struct rn_joint_scratch {
  int n; /* stencil size */
  double *q, *v, *loc, *work;
  double *fix; /* a fixed couple's force and Jacobian (n + n n), NULL if the
                  joint has none */
  rnk_frame *refs;
  double *heap; /* NULL if the buffers below suffice */
  rnk_frame *heap_refs;
  double buf[RN_JOINT_STACK];
  rnk_frame frames[RN_JOINT_STACK_ENDS];
} rn_joint_scratch;
/* RN_ERR_ALLOC if the heap fallback fails. */
rn_status rn_joint_scratch_init(const rn_joint *J, rn_joint_scratch *s);
void rn_joint_scratch_free(rn_joint_scratch *s);

/* ---- rods ---------------------------------------------------------------- */
void rn_rod_free(rn_rod *r);
/* Vertex forces r->fvert from point forces, line load and gravity (loads.c). */
void rn_rod_lump_forces(const rn_network *net, rn_rod *r);
/* The vector a couple m works on, in the coordinates of the frame f (rows
 * f[3k..3k+2], orthonormal): the frame vector most perpendicular to m,
 * projected onto the plane normal to m and normalised (zero if m = 0). */
void rn_couple_vector(const double f[9], const double m[3], double b[3]);
/* Edge of the material frame a moment at vertex acts on. */
int rn_moment_edge(int nv, int vertex);

#endif

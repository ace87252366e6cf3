/* periodic.h - periodic cells (periodic.c, bloch_acc.c; docs/homogenization.md):
 * the cell's finalize steps, its strain rows in the Hessian, the applied
 * macroscopic stress, image offsets of joint ends, and the accumulator of the
 * Bloch matrix.  The gathers of image entries are core's (core/gather.c). */
#ifndef RN_PERIODIC_MODULE_H
#define RN_PERIODIC_MODULE_H

#include "core/network_internal.h"

void rn_cell_free(struct rn_cell **c);
/* Finalize: marks the strain DOFs (map), after the joints' offsets are set. */
void rn_cell_mark(rn_network *net);
/* Finalize: image records and slots (after build_dof_map's numbering and
 * rn_joints_build); anchor (before the DOF map). */
rn_status rn_cell_build(rn_network *net);
void rn_cell_anchor(rn_network *net);
/* Fixed strain components of xfull at the load factor. */
void rn_cell_place(rn_network *net);
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
/* Joint stencil from a full state: q[k] = full[idx[k]] plus image shifts. */
void rn_joint_gather_full(const rn_network *net, const rn_joint *J, const double *full,
                          double *q);

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
  /* sparse mode (re NULL): every entry appended as a triplet (row, column, re, im)
   * in assembly order (moment set: the real moment of order `order` as re, im 0);
   * trip_failed set if the array could not grow */
  int moment;
  int raw; /* sparse mode: re the entry h, im its phase difference d1 (terms) */
  struct rn_bloch_trip *trip;
  size_t ntrip, cap_trip;
  int trip_failed;
} rn_bloch_acc;
typedef struct rn_bloch_trip {
  int64_t r, c;
  double re, im;
} rn_bloch_trip;
/* A block of n entries at full index s, or by index list idx (a joint stencil:
 * J given, whose ends at images carry their rod's DOFs from another cell). */
void rn_bloch_add_block(const rn_network *net, rn_bloch_acc *b, size_t s,
                        const size_t *idx, const int32_t *img, int n, const double *H,
                        const struct rn_joint *J);
void rn_bloch_add_band(const rn_network *net, rn_bloch_acc *b, size_t s, int n,
                       const double *band);

/* Argument checks of the cell calls: a periodic network, still building
 * (building) or finalized; records an error. */
rn_status rn_cell_check(const rn_network *net, const char *where, int building);

#endif

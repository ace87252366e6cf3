/* rnk.h - rodnet energy kernels (energy layer).
 *
 * Pure math per stencil: energy, gradient, Hessian block and Hessian-vector
 * product of each energy term of a discrete elastic rod (DER).  No allocation,
 * no I/O, no globals; libm only.  Every function returns an int status:
 *   RNK_OK (0)          success;
 *   RNK_DEGENERATE (1)  the configuration is degenerate at this trial point
 *                       (zero-length edge, exactly opposite tangents, a kink of
 *                       180 degrees): recoverable, the caller should reject the
 *                       step.  Outputs are then unspecified (but finite).
 *
 * Local DOF layout of the stencils (the seed 000 ordering):
 *   edge stencil   q[7]  = (x_j[3], theta^j, x_{j+1}[3])
 *   vertex stencil q[11] = (x_{i-1}[3], theta^{i-1}, x_i[3], theta^i, x_{i+1}[3])
 * Hessian blocks are dense, row-major, n x n, symmetric.
 *
 * Frames.  Each edge carries a reference frame (t_hat, a1_hat) stored by the
 * caller (the reference state).  The reference director of the current edge is
 * the parallel transport of a1_hat from t_hat to the current tangent t, and the
 * material directors are d1 = cos(theta) a1 + sin(theta) a2, d2 = -sin(theta) a1
 * + cos(theta) a2 with a2 = t x a1.  The energy is therefore a smooth, pure
 * function of (DOFs, reference state); all derivatives here are exact
 * derivatives of that function (not the "frozen frame" approximation), at any
 * configuration, not only at an up-to-date reference.
 */
#ifndef RODNET_RNK_H
#define RODNET_RNK_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

enum { RNK_OK = 0, RNK_DEGENERATE = 1 };

/* Smallest admissible 1 + t_a . t_b (parallel transport, curvature binormal). */
#define RNK_OPPOSITE_TOL 1e-12

/* Reference frame of an edge: unit tangent and unit first director, a1 . t = 0. */
typedef struct rnk_frame {
  double t[3];
  double a1[3];
} rnk_frame;

/* ---- frames -------------------------------------------------------------- */

/* Parallel transport of v from unit tangent ta to unit tangent tb (rotation
 * about ta x tb taking ta to tb).  Accurate for nearly parallel tangents;
 * RNK_DEGENERATE if 1 + ta.tb < RNK_OPPOSITE_TOL. */
int rnk_transport(const double ta[3], const double tb[3], const double v[3],
                  double out[3]);

/* Material frame of an edge with edge vector e, reference frame ref, angle
 * theta: unit tangent t, directors d1, d2.  Any output may be NULL. */
int rnk_material_frame(const double e[3], const rnk_frame *ref, double theta, double t[3],
                       double d1[3], double d2[3]);

/* Time-parallel update of a reference frame to the current edge vector e:
 * ref->a1 becomes the transported director (re-orthonormalised), ref->t the
 * current unit tangent.  The energy does not change. */
int rnk_frame_update(const double e[3], rnk_frame *ref);

/* Reference twist at a vertex stencil q[11] with edge reference frames
 * ref[0], ref[1]: the signed angle from the parallel transport of the first
 * edge's reference director to the second's, continued from ref_twist_prev
 * (the value stored at the last reference update) so that it does not alias
 * modulo 2 pi. */
int rnk_reference_twist(const double q[11], const rnk_frame ref[2], double ref_twist_prev,
                        double *m);

/* Material curvature (kappa1, kappa2) (integrated, seed 000 (2.2)) and twist
 * (theta^i - theta^{i-1} + reference twist) at a vertex stencil. */
int rnk_strains(const double q[11], const rnk_frame ref[2], double ref_twist_prev,
                double kappa[2], double *twist);

/* ---- stretching: E = 1/2 k (l - lbar)^2 / lbar on an edge stencil q[7] ---- */
typedef struct rnk_stretch_param {
  double k;    /* axial stiffness E A */
  double lbar; /* rest length */
} rnk_stretch_param;

int rnk_stretch_energy(const double q[7], const rnk_stretch_param *p, double *E);
int rnk_stretch_grad(const double q[7], const rnk_stretch_param *p, double *E,
                     double g[7]);
int rnk_stretch_hess(const double q[7], const rnk_stretch_param *p, double H[49]);
int rnk_stretch_hvp(const double q[7], const rnk_stretch_param *p, const double v[7],
                    double Hv[7]);

/* ---- bending: E = 1/2 (k - kbar)^T B (k - kbar) / vlen on q[11] ---------- */
typedef struct rnk_bend_param {
  double B[3];    /* B11, B12, B22: bending stiffness E I in (d1, d2) */
  double kbar[2]; /* rest material curvature (integrated) */
  double vlen;    /* Voronoi rest length (lbar^{i-1} + lbar^i) / 2 */
} rnk_bend_param;

int rnk_bend_energy(const double q[11], const rnk_frame ref[2], const rnk_bend_param *p,
                    double *E);
int rnk_bend_grad(const double q[11], const rnk_frame ref[2], const rnk_bend_param *p,
                  double *E, double g[11]);
int rnk_bend_hess(const double q[11], const rnk_frame ref[2], const rnk_bend_param *p,
                  double H[121]);
int rnk_bend_hvp(const double q[11], const rnk_frame ref[2], const rnk_bend_param *p,
                 const double v[11], double Hv[11]);

/* ---- twist: E = 1/2 beta (tau - taubar)^2 / vlen on q[11] --------------- */
typedef struct rnk_twist_param {
  double beta;      /* twisting stiffness G J */
  double taubar;    /* rest twist (integrated) */
  double vlen;      /* Voronoi rest length */
  double ref_twist; /* reference twist stored at the last reference update */
} rnk_twist_param;

int rnk_twist_energy(const double q[11], const rnk_frame ref[2], const rnk_twist_param *p,
                     double *E);
int rnk_twist_grad(const double q[11], const rnk_frame ref[2], const rnk_twist_param *p,
                   double *E, double g[11]);
int rnk_twist_hess(const double q[11], const rnk_frame ref[2], const rnk_twist_param *p,
                   double H[121]);
int rnk_twist_hvp(const double q[11], const rnk_frame ref[2], const rnk_twist_param *p,
                  const double v[11], double Hv[11]);

/* ---- bending + twisting at one vertex, sharing the edge frames ----------
 * Same values as rnk_bend_* + rnk_twist_* (E, g and H are the sums); closed
 * forms (rod.c, docs/energy.md): the bending-only and twisting-only kernels
 * above are these with the other stiffness zero.  The HVP never forms the
 * block. */
int rnk_bendtwist_energy(const double q[11], const rnk_frame ref[2],
                         const rnk_bend_param *bp, const rnk_twist_param *tp, double *Eb,
                         double *Et);
int rnk_bendtwist_grad(const double q[11], const rnk_frame ref[2],
                       const rnk_bend_param *bp, const rnk_twist_param *tp, double *E,
                       double g[11]);
int rnk_bendtwist_hess(const double q[11], const rnk_frame ref[2],
                       const rnk_bend_param *bp, const rnk_twist_param *tp,
                       double H[121]);
int rnk_bendtwist_hvp(const double q[11], const rnk_frame ref[2],
                      const rnk_bend_param *bp, const rnk_twist_param *tp,
                      const double v[11], double Hv[11]);

/* Test oracle: the same four functions evaluated with second-order jets
 * (generic forward differentiation of the composition, bendtwist.c).  Slow;
 * kept so that the tests can compare the closed forms with an independent
 * implementation at any configuration. */
int rnk_jet_bendtwist_energy(const double q[11], const rnk_frame ref[2],
                             const rnk_bend_param *bp, const rnk_twist_param *tp,
                             double *Eb, double *Et);
int rnk_jet_bendtwist_grad(const double q[11], const rnk_frame ref[2],
                           const rnk_bend_param *bp, const rnk_twist_param *tp, double *E,
                           double g[11]);
int rnk_jet_bendtwist_hess(const double q[11], const rnk_frame ref[2],
                           const rnk_bend_param *bp, const rnk_twist_param *tp,
                           double H[121]);
int rnk_jet_bendtwist_hvp(const double q[11], const rnk_frame ref[2],
                          const rnk_bend_param *bp, const rnk_twist_param *tp,
                          const double v[11], double Hv[11]);

/* ---- whole rods: stretching + bending + twisting in one pass -------------
 * A segment of a rod: ne >= 1 consecutive edges, their ne + 1 vertices and
 * the ne - 1 interior vertices between them.  x is the segment's slice of the
 * rod's DOF vector, (x_0[3], theta^0, x_1[3], ..., theta^{ne-1}, x_ne[3]),
 * n = 4 ne + 3 doubles; the vertex stencil of interior vertex k (1 <= k <
 * ne) is x[4 (k-1) .. 4 (k-1) + 10], the edge stencil of edge j x[4 j ..
 * 4 j + 6].  Values are those of rnk_stretch_* (edges stretch_lo <= j <
 * stretch_hi only: so that overlapping segments count each edge once) and
 * rnk_bendtwist_* (every interior vertex, parameters bp[k-1], tp[k-1] with
 * the stored reference twist ref_twist[k-1] in place of tp[k-1].ref_twist).
 * Each edge's frame is computed once for both of its vertices.  The loops
 * have no early exit: on RNK_DEGENERATE, bad[0] is the first degenerate
 * stretched edge and bad[1] the first degenerate interior vertex (-1 if
 * none) and the outputs are unspecified. */
typedef struct rnk_rod_seg {
  int ne;
  const double *x;             /* [4 ne + 3] */
  const rnk_frame *ref;        /* [ne] reference frames */
  const rnk_stretch_param *sp; /* [ne] */
  int stretch_lo, stretch_hi;  /* edges whose stretching counts */
  const rnk_bend_param *bp;    /* [ne - 1] */
  const rnk_twist_param *tp;   /* [ne - 1] */
  const double *ref_twist;     /* [ne - 1] */
} rnk_rod_seg;

/* Half bandwidth of a rod's Hessian in its DOF vector (a vertex stencil spans
 * 11 consecutive DOFs) and the row length of the band storage below. */
enum { RNK_BAND_HALF = 10, RNK_BAND = 2 * RNK_BAND_HALF + 1 };

/* E[0..2] = stretching, bending, twisting energy of the segment. */
int rnk_rod_energy(const rnk_rod_seg *s, double E[3], int bad[2]);
/* Also adds the gradient to g[4 ne + 3]. */
int rnk_rod_grad(const rnk_rod_seg *s, double E[3], double *g, int bad[2]);
/* Adds H v to Hv[4 ne + 3] (matrix-free: no block is formed). */
int rnk_rod_hvp(const rnk_rod_seg *s, const double *v, double *Hv, int bad[2]);
/* Adds the Hessian to the band storage: entry (a, c), |a - c| <= 10, at
 * band[a * RNK_BAND + c - a + RNK_BAND_HALF], a, c in [0, 4 ne + 3). */
int rnk_rod_hess(const rnk_rod_seg *s, double *band, int bad[2]);

/* ---- couple on an edge's material frame, edge stencil q[7] ---------------
 * E = -|M| (angle0 + alpha): alpha is the rotation about the fixed axis
 * n = M/|M|, since the last reference update, of a vector f = b1 t + b2 d1 +
 * b3 d2 fixed in the edge's material frame (the caller picks b once, so that
 * f is perpendicular to n at the start): the signed angle between the
 * projections of f0 and f onto the plane normal to n; angle0 accumulates it
 * over updates.  The energy is a function of the configuration (a continuous
 * lift of a planar angle), hence conservative; for rotations about n it is
 * exactly the work of a dead couple (planar end-moment problems are
 * reproduced), and at the start its virtual work is M . (rotation).  (A
 * constant couple in 3D is not conservative: no energy matches it for all
 * finite rotations.) */
typedef struct rnk_moment_param {
  double M[3];   /* applied moment */
  double f0[9];  /* material frame (t, d1, d2) at the last update */
  double angle0; /* accumulated angle at the last update */
  double b[3];   /* body coordinates (t, d1, d2) of the turned vector */
} rnk_moment_param;

int rnk_moment_energy(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                      double *E);
int rnk_moment_grad(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                    double *E, double g[7]);
int rnk_moment_hess(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                    double H[49]);
int rnk_moment_hvp(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                   const double v[7], double Hv[7]);
/* Rotation angle alpha of the current frame about M's axis since f0. */
int rnk_moment_angle(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                     double *alpha);
/* Closed forms above (moment.c); the jet oracle of the tests: */
int rnk_jet_moment_energy(const double q[7], const rnk_frame *ref,
                          const rnk_moment_param *p, double *E);
int rnk_jet_moment_grad(const double q[7], const rnk_frame *ref,
                        const rnk_moment_param *p, double *E, double g[7]);
int rnk_jet_moment_hess(const double q[7], const rnk_frame *ref,
                        const rnk_moment_param *p, double H[49]);
int rnk_jet_moment_hvp(const double q[7], const rnk_frame *ref, const rnk_moment_param *p,
                       const double v[7], double Hv[7]);
int rnk_jet_moment_angle(const double q[7], const rnk_frame *ref,
                         const rnk_moment_param *p, double *alpha);

/* ---- joint stencil: a rod end meeting a joint (connection edge) ----------
 * The rod's terminal edge (between the joint position x_J and the rod vertex
 * next to it, x_n) meets a fictitious connection edge that is rigidly
 * attached to the joint's rotation Q = exp([w]) Q_hat (seed 001; Perez et al.
 * 2015): its frame is Q applied to the rest frame of the terminal edge.  The
 * energy is the bending + twisting at the joint vertex between the two edges.
 * Stencil q[10] = (x_n[3], theta of the terminal edge, x_J[3], w[3]);
 * ref is the terminal edge's reference frame.  Twist is measured between the
 * material frames, continued from the stored value twist.ref_twist. */
typedef struct rnk_joint_end_param {
  double c[9];           /* connection frame (t, d1, d2) at w = 0, i.e. Q_hat
                            applied to the rest frame of the terminal edge */
  int side;              /* 0: the rod ends at the joint (terminal edge first,
                            from x_n to x_J); 1: the rod starts at it
                            (connection edge first, terminal edge x_J -> x_n) */
  rnk_bend_param bend;   /* B, kbar (0: straight continuation), vlen */
  rnk_twist_param twist; /* beta, taubar, vlen, ref_twist */
} rnk_joint_end_param;

int rnk_joint_end_energy(const double q[10], const rnk_frame *ref,
                         const rnk_joint_end_param *p, double *E);
int rnk_joint_end_grad(const double q[10], const rnk_frame *ref,
                       const rnk_joint_end_param *p, double *E, double g[10]);
int rnk_joint_end_hess(const double q[10], const rnk_frame *ref,
                       const rnk_joint_end_param *p, double H[100]);
int rnk_joint_end_hvp(const double q[10], const rnk_frame *ref,
                      const rnk_joint_end_param *p, const double v[10], double Hv[10]);
/* Current curvature and twist at the joint vertex (for reference updates and
 * output). */
int rnk_joint_end_strains(const double q[10], const rnk_frame *ref,
                          const rnk_joint_end_param *p, double kappa[2], double *twist);

/* ---- a whole joint: every incident rod end, both models -------------------
 * Stencil layout (the caller gathers it by index lists):
 *   q = (x_J[3], w[3] if rigid, then per end k: x_n[3] of end k, theta_k)
 * of size rnk_joint_stencil_size(): 3 (+3 rigid) + 4 valence.  End k's
 * terminal edge runs from x_n to x_J (side 0) or from x_J to x_n (side 1).
 * Rotation of the joint (rest = identity):
 *   rigid:   Q = exp([w]) Qhat;
 *   elastic: Q = polar(sum_k F_k Fbar_k^T), F_k = (t, d1, d2) of terminal edge k
 *            as columns, Fbar_k its rest frame (the least-squares fit of the
 *            rest frames to the current ones, Perez et al. 2015 eq. 4);
 *            exact first and second derivatives through the polar factor.
 * Energy: sum over ends of the end stencil (connection frame Q cbar_k) plus an
 * optional couple on Q (as rnk_moment_*: rotation about the couple's axis of
 * the vector Q couple_p). */
typedef struct rnk_joint_end {
  int side;              /* 0: the rod ends at the joint, 1: it starts there */
  double cbar[9];        /* rest frame (t, d1, d2) of the terminal edge */
  rnk_bend_param bend;   /* B, kbar (0), vlen (half the terminal rest length) */
  rnk_twist_param twist; /* beta, taubar (0), vlen, ref_twist (last update) */
} rnk_joint_end;

typedef struct rnk_joint {
  int rigid;                 /* 1: rigid (rotation DOFs), 0: elastic */
  int smooth;                /* 1: a smooth joint (below; rigid = 0, valence 2) */
  int valence;               /* >= 1 */
  const rnk_joint_end *ends; /* [valence] */
  const rnk_frame *refs;     /* reference frames of the terminal edges [valence] */
  double Qhat[9];            /* rigid: reference rotation */
  double M[3];               /* couple on the joint rotation (zero: none) */
  double f0[9];              /* joint rotation at the last update (couple) */
  double angle0;             /* couple angle accumulated up to that update */
  double couple_p[3];        /* vector turned by the couple: Q couple_p (rest
                                coordinates; perpendicular to M at rest) */
} rnk_joint;

size_t rnk_joint_stencil_size(const rnk_joint *j);
/* Doubles of workspace the functions below need (caller allocates). */
size_t rnk_joint_work_size(const rnk_joint *j);
/* Closed forms (jointq.c, docs/energy.md): cost a small multiple of the
 * energy's, linear in the valence except the Hessian block of elastic joints
 * (dense: quadratic).  The HVP never forms the block. */
int rnk_joint_energy(const double *q, const rnk_joint *j, double *work, double *E);
/* g[n], H[n*n], v[n], Hv[n] with n = rnk_joint_stencil_size(j). */
int rnk_joint_grad(const double *q, const rnk_joint *j, double *work, double *E,
                   double *g);
int rnk_joint_hess(const double *q, const rnk_joint *j, double *work, double *H);
int rnk_joint_hvp(const double *q, const rnk_joint *j, double *work, const double *v,
                  double *Hv);
/* Current rotation Q (row-major), the twists at the joint vertex of every
 * end (for the reference update: ends[k].twist.ref_twist <- twist[k]) and the
 * couple's rotation angle since f0. */
int rnk_joint_rotation(const double *q, const rnk_joint *j, double R[9]);
int rnk_joint_twists(const double *q, const rnk_joint *j, double *twist);
int rnk_joint_couple_angle(const double *q, const rnk_joint *j, double *alpha);

/* Smooth joint (j->smooth = 1, rigid = 0, valence 2): the joint vertex is an
 * ordinary DER vertex between the two terminal edges, the closing vertex of a
 * closed rod or a smooth valence-2 connection.  ends[0] has side 0 (its rod
 * ends at the joint), ends[1] side 1 (its rod starts there); the energy is
 * rnk_bendtwist_* on the vertex stencil (x_n of end 0, theta_0, x_J, theta_1,
 * x_n of end 1) with frames (refs[0], refs[1]) and the vertex parameters
 * ends[0].bend, ends[0].twist (stiffness, rest curvature and twist, Voronoi
 * length, stored reference twist); ends[1]'s are unused.  rnk_joint_* above
 * dispatch to these (the same values): the twists are the reference twist at
 * the vertex continued from ends[0].twist.ref_twist (both entries), the
 * rotation is F_1 Fbar_1^T (end 1's material frame against its rest frame),
 * a couple is not modelled (alpha = 0).  Eb and Et split the energy. */
int rnk_smooth_joint_energy(const double *q, const rnk_joint *j, double *Eb, double *Et);
int rnk_smooth_joint_grad(const double *q, const rnk_joint *j, double *E, double *g);
int rnk_smooth_joint_hess(const double *q, const rnk_joint *j, double *H);
int rnk_smooth_joint_hvp(const double *q, const rnk_joint *j, const double *v,
                         double *Hv);
int rnk_smooth_joint_twists(const double *q, const rnk_joint *j, double *twist);
int rnk_smooth_joint_rotation(const double *q, const rnk_joint *j, double R[9]);
/* The vertex stencil q11 of a smooth joint's stencil q. */
void rnk_smooth_joint_vertex(const double *q, double q11[11]);

/* Test oracle: the same functions evaluated with second-order jets
 * (joint.c, joint_net.c; slow).  rnk_jet_joint_work_size doubles of work. */
size_t rnk_jet_joint_work_size(const rnk_joint *j);
int rnk_jet_joint_energy(const double *q, const rnk_joint *j, double *work, double *E);
int rnk_jet_joint_grad(const double *q, const rnk_joint *j, double *work, double *E,
                       double *g);
int rnk_jet_joint_hess(const double *q, const rnk_joint *j, double *work, double *H);
int rnk_jet_joint_twists(const double *q, const rnk_joint *j, double *twist);
int rnk_jet_joint_couple_angle(const double *q, const rnk_joint *j, double *alpha);
int rnk_jet_joint_end_energy(const double q[10], const rnk_frame *ref,
                             const rnk_joint_end_param *p, double *E);
int rnk_jet_joint_end_grad(const double q[10], const rnk_frame *ref,
                           const rnk_joint_end_param *p, double *E, double g[10]);
int rnk_jet_joint_end_hess(const double q[10], const rnk_frame *ref,
                           const rnk_joint_end_param *p, double H[100]);
int rnk_jet_joint_end_hvp(const double q[10], const rnk_frame *ref,
                          const rnk_joint_end_param *p, const double v[10],
                          double Hv[10]);
int rnk_jet_joint_end_strains(const double q[10], const rnk_frame *ref,
                              const rnk_joint_end_param *p, double kappa[2],
                              double *twist);

/* Polar factor R of M (M = R U, U symmetric positive definite), by Newton
 * iteration; RNK_DEGENERATE if M is (nearly) singular or det M <= 0. */
int rnk_polar(const double M[9], double R[9]);

/* Derivatives of the elastic joint's rotation vector: phi(M') is defined by
 * exp([phi]) R0 = polar(M') with R0 = polar(M), so phi(M) = 0.  Returns R0,
 * dphi[9 a + m] = d phi_a / d M_m and d2phi[81 a + 9 m + n] =
 * d2 phi_a / d M_m d M_n at M (M row-major, m = 3 i + j). */
int rnk_polar_rotvec_derivs(const double M[9], double R0[9], double dphi[27],
                            double d2phi[243]);

/* Rotation matrix exp([w]) (row-major) of a rotation vector w, accurate for
 * small |w| (series for the Rodrigues coefficients). */
void rnk_rotation_exp(const double w[3], double R[9]);

/* ---- dead force on a vertex: E = -f . x (linear; Hessian zero) ----------- */
double rnk_force_energy(const double x[3], const double f[3]);
void rnk_force_grad(const double f[3], double g[3]);

/* ---- contact between two segments (contact.c) ------------------------------
 * Pair stencil x[12] = (p0, p1, q0, q1): the ends of two edges.  The gap is
 * the distance between the segments minus radius (the sum of the two rods'
 * radii); the energy is the barrier of incremental potential contact,
 * b(y) = -kappa (y - dhat)^2 log(y / dhat) for 0 < y < dhat, 0 beyond.
 * RNK_DEGENERATE for a zero-length edge or a gap <= 0 (interpenetration). */
typedef struct rnk_contact_param {
  double radius; /* sum of the two radii */
  double dhat;   /* activation distance of the barrier (> 0) */
  double kappa;  /* stiffness of the barrier (> 0) */
} rnk_contact_param;

/* Edge-edge regime only when sin^2 of the edges' angle exceeds this. */
#define RNK_CONTACT_PARALLEL 1e-10

/* Squared distance d2 between the segments (p0, p1) and (q0, q1), with its
 * gradient g[12] and Hessian H[144] (either may be NULL). */
int rnk_segment_distance2(const double x[12], double *d2, double *g, double *H);
/* Gap: distance minus radius. */
int rnk_contact_gap(const double x[12], double radius, double *gap);
int rnk_contact_energy(const double x[12], const rnk_contact_param *p, double *E);
int rnk_contact_grad(const double x[12], const rnk_contact_param *p, double *E,
                     double g[12]);
int rnk_contact_hess(const double x[12], const rnk_contact_param *p, double H[144]);
/* Continuous collision check of the linear motion x0 -> x1 of a pair by
 * conservative advancement: hit = 0 certifies that the gap stays above
 * thr = 0.1 min(gap(x0), dhat) all along; hit = 1 if it falls below 2 thr at
 * some point of the motion (or cannot be certified in 256 advancements, or
 * the pair starts interpenetrating). */
int rnk_contact_ccd(const double x0[12], const double x1[12], double radius, double dhat,
                    int *hit);

/* Dense helper: y = H v for an n x n row-major block. */
void rnk_block_mv(int n, const double *H, const double *v, double *y);

#ifdef __cplusplus
}
#endif
#endif

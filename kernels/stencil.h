/* stencil.h - internal helpers shared by the kernels: edge-frame jets and the
 * map from jet variables (edge vectors and angles) to stencil DOFs. */
#ifndef RODNET_STENCIL_H
#define RODNET_STENCIL_H

#include "jet.h"
#include "rnk.h"

/* Frame of one edge as jets over the 4 variables (e[0..2], theta):
 * t = e/|e|, reference director a1 = transport of ref->a1 from ref->t to t,
 * a2 = t x a1, material directors d1, d2.  RNK_DEGENERATE for a zero edge or
 * a tangent opposite to the reference tangent. */
typedef struct rnk_edge_jet {
  jvec t, a1, a2, d1, d2;
} rnk_edge_jet;

int rnk_edge_jet_eval(const double e[3], double theta, const rnk_frame *ref, int ord,
                      rnk_edge_jet *f);
/* Both edge frames of a vertex stencil q[11], each as a jet over its own
 * 4 variables; products of the two are formed with jvec_dot_mixed, giving
 * jets over the 8 variables (e0[3], theta0, e1[3], theta1). */
int rnk_vertex_frames(const double q[11], const rnk_frame ref[2], int ord,
                      rnk_edge_jet f[2]);

/* Scatter a scalar jet over the 8 variables (e0, theta0, e1, theta1) into the
 * gradient g[11] and Hessian H[121] of a vertex stencil (either may be NULL). */
void rnk_scatter_vertex(const jet *E, double *g, double *H);
/* Same for a jet over (e, theta) into an edge stencil g[7], H[49]. */
void rnk_scatter_edge(const jet *E, double *g, double *H);

/* Material curvature (kappa1, kappa2) at a vertex (8-variable jets). */
int rnk_curvature_jet(const rnk_edge_jet f[2], jet kappa[2]);
/* Twist tau = theta1 - theta0 + m_prev + increment (8-variable jet). */
void rnk_twist_jet(const rnk_edge_jet f[2], const double q[11], double m_prev, jet *tau);

/* Energies from the frames (bendtwist.c). */
int rnk_bend_from_frames(const rnk_edge_jet f[2], const rnk_bend_param *p, jet *E);
void rnk_twist_from_frames(const rnk_edge_jet f[2], const double q[11],
                           const rnk_twist_param *p, jet *E);

/* exp([w]) v_i for nvec vectors v[3 nvec], as jets over the 3 variables w. */
void rnk_rotate_jet(const double w[3], int ord, int nvec, const double *v, jvec *out);

/* Signed rotation about n of the frame vector f (jets) since it was f0: the
 * angle between the projections onto the plane normal to n (moment.c). */
int rnk_projected_angle(const jvec *f, const double f0[3], const double n[3], jet *alpha);

/* Reference-twist increment relative to m_prev: angle from the transported
 * first reference director to the second, minus m_prev, in (-pi, pi). */
void rnk_twist_increment(const rnk_edge_jet f[2], double m_prev, jet *dm);

#endif

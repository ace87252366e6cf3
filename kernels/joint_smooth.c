/* joint_smooth.c - the smooth joint of rnk.h: the joint vertex as an ordinary
 * DER vertex between the two terminal edges (the closing vertex of a closed
 * rod, a smooth valence-2 connection).  The joint stencil (x_J, x_n0, theta_0,
 * x_n1, theta_1) is permuted onto the vertex stencil of rnk_bendtwist_*. */
#include <string.h>

#include "rnk.h"

/* Joint stencil index of vertex stencil entry k. */
static const int perm[11] = {3, 4, 5, 6, 0, 1, 2, 10, 7, 8, 9};

void rnk_smooth_joint_vertex(const double *q, double q11[11]) {
  for (int k = 0; k < 11; ++k) q11[k] = q[perm[k]];
}

int rnk_smooth_joint_energy(const double *q, const rnk_joint *j, double *Eb, double *Et) {
  double q11[11];
  rnk_smooth_joint_vertex(q, q11);
  return rnk_bendtwist_energy(q11, j->refs, &j->ends[0].bend, &j->ends[0].twist, Eb, Et);
}

int rnk_smooth_joint_grad(const double *q, const rnk_joint *j, double *E, double *g) {
  double q11[11], g11[11];
  int st;
  rnk_smooth_joint_vertex(q, q11);
  st = rnk_bendtwist_grad(q11, j->refs, &j->ends[0].bend, &j->ends[0].twist, E, g11);
  if (st) return st;
  for (int k = 0; k < 11; ++k) g[perm[k]] = g11[k];
  return RNK_OK;
}

int rnk_smooth_joint_hess(const double *q, const rnk_joint *j, double *H) {
  double q11[11], H11[121];
  int st;
  rnk_smooth_joint_vertex(q, q11);
  st = rnk_bendtwist_hess(q11, j->refs, &j->ends[0].bend, &j->ends[0].twist, H11);
  if (st) return st;
  for (int a = 0; a < 11; ++a)
    for (int b = 0; b < 11; ++b) H[11 * perm[a] + perm[b]] = H11[11 * a + b];
  return RNK_OK;
}

int rnk_smooth_joint_hvp(const double *q, const rnk_joint *j, const double *v,
                         double *Hv) {
  double q11[11], v11[11], h11[11];
  int st;
  rnk_smooth_joint_vertex(q, q11);
  rnk_smooth_joint_vertex(v, v11);
  st = rnk_bendtwist_hvp(q11, j->refs, &j->ends[0].bend, &j->ends[0].twist, v11, h11);
  if (st) return st;
  for (int k = 0; k < 11; ++k) Hv[perm[k]] = h11[k];
  return RNK_OK;
}

int rnk_smooth_joint_twists(const double *q, const rnk_joint *j, double *twist) {
  double q11[11], m;
  int st;
  rnk_smooth_joint_vertex(q, q11);
  if ((st = rnk_reference_twist(q11, j->refs, j->ends[0].twist.ref_twist, &m))) return st;
  twist[0] = twist[1] = m;
  return RNK_OK;
}

int rnk_smooth_joint_rotation(const double *q, const rnk_joint *j, double R[9]) {
  double e[3], F[9];
  const double *Fb = j->ends[1].cbar;
  int st;
  for (int c = 0; c < 3; ++c) e[c] = q[7 + c] - q[c]; /* x_J -> x_n1 */
  if ((st = rnk_material_frame(e, &j->refs[1], q[10], F, F + 3, F + 6))) return st;
  for (int a = 0; a < 3; ++a) /* sum_c F_c Fbar_c^T, rows F[3c..] */
    for (int b = 0; b < 3; ++b) {
      double s = 0.0;
      for (int c = 0; c < 3; ++c) s += F[3 * c + a] * Fb[3 * c + b];
      R[3 * a + b] = s;
    }
  return RNK_OK;
}

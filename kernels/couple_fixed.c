/* couple_fixed.c - a couple fixed in space acting on one edge's material
 * frame: the generalised force of the virtual work M . omega and its
 * Jacobian, from second-order jets of the frame (jet.h, stencil.h).
 *
 * omega = 1/2 sum_k d_k x d_k' over the orthonormal frame (d_0, d_1, d_2) =
 * (t, d1, d2), so with y = (e, theta), e = x1 - x0,
 *   Q_i = 1/2 sum_k (M x d_k) . d_k,i
 *   J_ij = 1/2 sum_k [(M x d_k,j) . d_k,i + (M x d_k) . d_k,ij]. */
#include <math.h>

#include "jet.h"
#include "rnk_couple.h"
#include "stencil.h"

static double hess_entry(const jet *a, int i, int j) {
  return i <= j ? a->h[i][j] : a->h[j][i];
}

int rnk_couple_fixed_force(const double q[7], const rnk_frame *ref, const double M[3],
                           double Q[7], double *J) {
  double e[3] = {q[4] - q[0], q[5] - q[1], q[6] - q[2]};
  int ord = J ? 2 : 1;
  rnk_edge_jet f;
  int st = rnk_edge_jet_eval(e, q[3], ref, ord, &f);
  if (st) return st;
  const jvec *d[3] = {&f.t, &f.d1, &f.d2};
  double Qy[4] = {0, 0, 0, 0}, Jy[4][4] = {{0}};
  for (int k = 0; k < 3; ++k) {
    const jet *c = d[k]->c;
    double dv[3] = {c[0].v, c[1].v, c[2].v}, Md[3];
    Md[0] = M[1] * dv[2] - M[2] * dv[1];
    Md[1] = M[2] * dv[0] - M[0] * dv[2];
    Md[2] = M[0] * dv[1] - M[1] * dv[0];
    for (int i = 0; i < 4; ++i)
      Qy[i] += 0.5 * (Md[0] * c[0].g[i] + Md[1] * c[1].g[i] + Md[2] * c[2].g[i]);
    if (!J) continue;
    for (int j = 0; j < 4; ++j) {
      double dj[3] = {c[0].g[j], c[1].g[j], c[2].g[j]}, Mdj[3];
      Mdj[0] = M[1] * dj[2] - M[2] * dj[1];
      Mdj[1] = M[2] * dj[0] - M[0] * dj[2];
      Mdj[2] = M[0] * dj[1] - M[1] * dj[0];
      for (int i = 0; i < 4; ++i) {
        double s = 0.0;
        for (int a = 0; a < 3; ++a)
          s += Mdj[a] * c[a].g[i] + Md[a] * hess_entry(&c[a], i, j);
        Jy[i][j] += 0.5 * s;
      }
    }
  }
  /* (e, theta) -> stencil (x0, theta, x1): e = x1 - x0 */
  static const int idx[4][2] = {{0, 4}, {1, 5}, {2, 6}, {3, 3}};
  for (int a = 0; a < 4; ++a) {
    if (a < 3) {
      Q[idx[a][0]] = -Qy[a];
      Q[idx[a][1]] = Qy[a];
    } else {
      Q[3] = Qy[3];
    }
  }
  if (!J) return RNK_OK;
  for (int i = 0; i < 49; ++i) J[i] = 0.0;
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      for (int x = 0; x < (a < 3 ? 2 : 1); ++x)
        for (int y = 0; y < (b < 3 ? 2 : 1); ++y) {
          double sa = a < 3 ? (x ? 1.0 : -1.0) : 1.0, sb = b < 3 ? (y ? 1.0 : -1.0) : 1.0;
          J[7 * idx[a][x] + idx[b][y]] += sa * sb * Jy[a][b];
        }
  return RNK_OK;
}

int rnk_moment_spatial(const double F[9], const double b[3], const double M[3],
                       double m[3]) {
  double fv[3], mm = sqrt(M[0] * M[0] + M[1] * M[1] + M[2] * M[2]);
  for (int a = 0; a < 3; ++a) fv[a] = b[0] * F[a] + b[1] * F[3 + a] + b[2] * F[6 + a];
  double ff = fv[0] * fv[0] + fv[1] * fv[1] + fv[2] * fv[2];
  if (!(mm > 0.0)) {
    m[0] = m[1] = m[2] = 0.0;
    return RNK_OK;
  }
  if (!(ff > 0.0)) return RNK_DEGENERATE;
  double il = 1.0 / sqrt(ff), fn = 0.0, Mf = 0.0;
  for (int a = 0; a < 3; ++a) {
    fv[a] *= il;
    fn += fv[a] * M[a] / mm;
    Mf += fv[a] * M[a];
  }
  double s2 = 1.0 - fn * fn; /* |n x f|^2 */
  if (!(s2 > 1e-12)) return RNK_DEGENERATE;
  for (int a = 0; a < 3; ++a) m[a] = (M[a] - Mf * fv[a]) / s2;
  return RNK_OK;
}

/* joint_net.c - a whole joint: every incident rod end through its connection
 * edge, the joint's rotation (rigid: a DOF; elastic: the polar-decomposition
 * fit of Perez et al. 2015) and an optional couple on that rotation.
 *
 * Elastic joints: with Q(Y) = polar(M(Y)), M = sum_k F_k Fbar_k^T, write
 * Q = exp([phi(Y)]) Q0 with Q0 = Q at the evaluation point (phi = 0 there).
 * Each end's energy is the end kernel with connection frame Q0 cbar_k and
 * rotation vector phi; the chain rule (seed 001 section 4.1)
 *   g = g_direct + Phi^T G_w,
 *   H = H_direct + C Phi + Phi^T C^T + Phi^T H_ww Phi + sum_a G_w,a Phi2_a
 * needs dphi/dY and d2phi/dY2, obtained from phi(M) as second-order jets in
 * the 9 entries of M (Newton iteration for the polar factor, then
 * phi = f(u) axial(P - P^T), P = Q Q0^T, u = (3 - tr P)/2,
 * f(u) = theta / (2 sin theta) = 1/2 + u/6 + u^2/15 + ...) and from the
 * terminal edges' frame jets.
 *
 * Production code: the stencil size, the polar factor rnk_polar (the elastic
 * fit of jointq.c) and the joint rotation rnk_joint_rotation (the rotation the C
 * API reports and takes as a rigid joint's reference).  The jet evaluations
 * rnk_jet_joint_* are slow: the tests (kernels_joint_closed) and bench_joints
 * hold the closed forms (jointq.c) to them. */
#include <math.h>
#include <string.h>

#include "rnk.h"
#include "stencil.h"

size_t rnk_joint_stencil_size(const rnk_joint *j) {
  return (size_t)(3 + (j->rigid ? 3 : 0) + 4 * j->valence);
}

size_t rnk_jet_joint_work_size(const rnk_joint *j) {
  size_t ny = 4 * (size_t)j->valence, n = rnk_joint_stencil_size(j);
  /* dphi/dY [3 ny], d2phi/dY2 [3 ny ny], Phi [3 n], cross C [n 3] */
  return 3 * ny + 3 * ny * ny + 3 * n + 3 * n + 16;
}

/* ---- 3x3 helpers (row-major) ---- */
static void mat_mul(const double A[9], const double B[9], double C[9]) {
  double T[9];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      T[3 * i + k] = A[3 * i] * B[k] + A[3 * i + 1] * B[3 + k] + A[3 * i + 2] * B[6 + k];
  memcpy(C, T, sizeof T);
}

static double det3(const double A[9]) {
  return A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
         A[2] * (A[3] * A[7] - A[4] * A[6]);
}

static double fro(const double A[9]) {
  double s = 0;
  for (int i = 0; i < 9; ++i) s += A[i] * A[i];
  return sqrt(s);
}

int rnk_polar(const double M[9], double R[9]) {
  double X[9], Y[9];
  double nm = fro(M), d = det3(M);
  if (!(nm > 0.0) || !isfinite(nm) || !(d > 1e-10 * nm * nm * nm)) return RNK_DEGENERATE;
  memcpy(X, M, sizeof X);
  for (int it = 0; it < 100; ++it) {
    /* scaled Newton: X <- (g X + X^{-T} / g) / 2, g = (|X^-1| / |X|)^(1/2) */
    double dx = det3(X), C[9];
    C[0] = X[4] * X[8] - X[5] * X[7], C[1] = X[5] * X[6] - X[3] * X[8];
    C[2] = X[3] * X[7] - X[4] * X[6], C[3] = X[2] * X[7] - X[1] * X[8];
    C[4] = X[0] * X[8] - X[2] * X[6], C[5] = X[1] * X[6] - X[0] * X[7];
    C[6] = X[1] * X[5] - X[2] * X[4], C[7] = X[2] * X[3] - X[0] * X[5];
    C[8] = X[0] * X[4] - X[1] * X[3];
    /* X^{-T} = C / det (C = cofactor matrix) */
    double g = sqrt(fro(C) / fabs(dx) / fro(X)), diff = 0;
    if (it > 6) g = 1.0;
    for (int i = 0; i < 9; ++i) {
      Y[i] = 0.5 * (g * X[i] + C[i] / (dx * g));
      diff += (Y[i] - X[i]) * (Y[i] - X[i]);
    }
    memcpy(X, Y, sizeof X);
    if (sqrt(diff) <= 1e-15) break;
  }
  memcpy(R, X, sizeof X);
  return RNK_OK;
}

/* phi(M) as jets over the 9 entries of M, at the point M (phi = 0 there);
 * Q0 = polar(M) on output. */
static int phi_jets(const double M[9], int ord, jet phi[3], double Q0[9]) {
  int st = rnk_polar(M, Q0);
  if (st) return st;
  jet X[9], C[9], t, p, det, idet;
  for (int i = 0; i < 9; ++i) jet_var(&X[i], 9, ord, M[i], i);
  /* unscaled Newton in jets (derivatives of the iterates converge with the
   * values); stop 2 iterations after the values have converged */
  int extra = -1;
  for (int it = 0; it < 200 && extra != 0; ++it) {
    static const int cof[9][4] = {{4, 8, 5, 7}, {5, 6, 3, 8}, {3, 7, 4, 6},
                                  {2, 7, 1, 8}, {0, 8, 2, 6}, {1, 6, 0, 7},
                                  {1, 5, 2, 4}, {2, 3, 0, 5}, {0, 4, 1, 3}};
    for (int i = 0; i < 9; ++i) {
      jet_mul(&C[i], &X[cof[i][0]], &X[cof[i][1]]);
      jet_mul(&p, &X[cof[i][2]], &X[cof[i][3]]);
      jet_sub(&C[i], &C[i], &p);
    }
    jet_mul(&det, &X[0], &C[0]);
    jet_fma(&det, &X[1], &C[1]);
    jet_fma(&det, &X[2], &C[2]);
    jet_inv(&idet, &det);
    double diff = 0;
    for (int i = 0; i < 9; ++i) {
      jet_mul(&t, &C[i], &idet);
      jet_lin(&t, 0.5, &X[i], 0.5, &t);
      diff += (t.v - X[i].v) * (t.v - X[i].v);
      X[i] = t;
    }
    if (extra > 0)
      --extra;
    else if (extra < 0 && sqrt(diff) <= 1e-14)
      extra = 2;
  }
  if (extra != 0) return RNK_DEGENERATE;
  /* P = X Q0^T, u = (3 - tr P)/2, phi = f(u) axial(P - P^T) */
  jet P[9];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) {
      jet_scale(&P[3 * i + k], Q0[3 * k], &X[3 * i]);
      for (int l = 1; l < 3; ++l) {
        jet_scale(&t, Q0[3 * k + l], &X[3 * i + l]);
        jet_add(&P[3 * i + k], &P[3 * i + k], &t);
      }
    }
  jet u, f;
  jet_add(&u, &P[0], &P[4]);
  jet_add(&u, &u, &P[8]);
  jet_scale(&u, -0.5, &u);
  jet_add_const(&u, &u, 1.5);
  jet_chain(&f, &u, 0.5 + u.v / 6.0, 1.0 / 6.0, 2.0 / 15.0);
  jet_sub(&phi[0], &P[7], &P[5]);
  jet_sub(&phi[1], &P[2], &P[6]);
  jet_sub(&phi[2], &P[3], &P[1]);
  for (int a = 0; a < 3; ++a) jet_mul(&phi[a], &f, &phi[a]);
  return RNK_OK;
}

int rnk_polar_rotvec_derivs(const double M[9], double R0[9], double dphi[27],
                            double d2phi[243]) {
  jet phi[3];
  int st = phi_jets(M, 2, phi, R0);
  if (st) return st;
  for (int a = 0; a < 3; ++a)
    for (int m = 0; m < 9; ++m) {
      dphi[9 * a + m] = phi[a].g[m];
      for (int n = 0; n < 9; ++n)
        d2phi[81 * a + 9 * m + n] = m <= n ? phi[a].h[m][n] : phi[a].h[n][m];
    }
  return RNK_OK;
}

/* End k's terminal edge vector and the sign s with e = s (x_J - x_n). */
static double end_edge(const double *q, int base, int side, double e[3]) {
  double s = side == 0 ? 1.0 : -1.0;
  for (int c = 0; c < 3; ++c) e[c] = s * (q[c] - q[base + c]);
  return s;
}

/* Current rotation of the joint and, for elastic joints, its M. */
static int joint_rotation(const double *q, const rnk_joint *j, double Q[9], double M[9]) {
  if (j->rigid) {
    double Rw[9];
    rnk_rotation_exp(q + 3, Rw);
    mat_mul(Rw, j->Qhat, Q);
    return RNK_OK;
  }
  double Mloc[9] = {0};
  for (int k = 0; k < j->valence; ++k) {
    int base = 3 + 4 * k;
    double e[3], F[9];
    end_edge(q, base, j->ends[k].side, e);
    int st = rnk_material_frame(e, &j->refs[k], q[base + 3], F, F + 3, F + 6);
    if (st) return st;
    const double *Fb = j->ends[k].cbar;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int c = 0; c < 3; ++c) Mloc[3 * a + b] += F[3 * c + a] * Fb[3 * c + b];
  }
  if (M) memcpy(M, Mloc, sizeof Mloc);
  return rnk_polar(Mloc, Q);
}

int rnk_joint_rotation(const double *q, const rnk_joint *j, double R[9]) {
  if (j->smooth) return rnk_smooth_joint_rotation(q, j, R);
  return joint_rotation(q, j, R, NULL);
}

/* End stencil q10 = (x_n, theta, x_J, w) and its parameters for rotation Qref. */
static void end_setup(const double *q, const rnk_joint *j, int k, const double Qref[9],
                      const double w[3], double q10[10], rnk_joint_end_param *p) {
  int base = 3 + (j->rigid ? 3 : 0) + 4 * k;
  const rnk_joint_end *en = &j->ends[k];
  for (int c = 0; c < 3; ++c) {
    q10[c] = q[base + c];
    q10[4 + c] = q[c];
    q10[7 + c] = w[c];
  }
  q10[3] = q[base + 3];
  for (int v = 0; v < 3; ++v)
    for (int a = 0; a < 3; ++a)
      p->c[3 * v + a] = Qref[3 * a] * en->cbar[3 * v] +
                        Qref[3 * a + 1] * en->cbar[3 * v + 1] +
                        Qref[3 * a + 2] * en->cbar[3 * v + 2];
  p->side = en->side;
  p->bend = en->bend;
  p->twist = en->twist;
}

int rnk_jet_joint_twists(const double *q, const rnk_joint *j, double *twist) {
  double Q[9], w0[3] = {0, 0, 0}, q10[10];
  rnk_joint_end_param p;
  if (j->smooth) return rnk_smooth_joint_twists(q, j, twist);
  int st = joint_rotation(q, j, Q, NULL);
  if (st) return st;
  for (int k = 0; k < j->valence; ++k) {
    end_setup(q, j, k, Q, w0, q10, &p);
    st = rnk_jet_joint_end_strains(q10, &j->refs[k], &p, NULL, &twist[k]);
    if (st) return st;
  }
  return RNK_OK;
}

/* Couple: E = -|M| (angle0 + alpha(w)), Q = exp([w]) Qref, jets over w. */
static int couple_jet(const rnk_joint *j, const double Qref[9], const double w[3],
                      int ord, jet *E) {
  double m = sqrt(j->M[0] * j->M[0] + j->M[1] * j->M[1] + j->M[2] * j->M[2]);
  jet_const(E, 3, ord, 0.0);
  if (!(m > 0.0)) return RNK_OK;
  double n[3] = {j->M[0] / m, j->M[1] / m, j->M[2] / m}, col[3], f0c[3];
  const double *cp = j->couple_p;
  for (int a = 0; a < 3; ++a) {
    col[a] = Qref[3 * a] * cp[0] + Qref[3 * a + 1] * cp[1] + Qref[3 * a + 2] * cp[2];
    f0c[a] = j->f0[3 * a] * cp[0] + j->f0[3 * a + 1] * cp[1] + j->f0[3 * a + 2] * cp[2];
  }
  jvec f;
  rnk_rotate_jet(w, ord, 1, col, &f);
  int st = rnk_projected_angle(&f, f0c, n, E);
  if (st) return st;
  jet_add_const(E, E, j->angle0);
  jet_scale(E, -m, E);
  return RNK_OK;
}

int rnk_jet_joint_couple_angle(const double *q, const rnk_joint *j, double *alpha) {
  double Q[9], w0[3] = {0, 0, 0};
  if (j->smooth) return rnk_joint_couple_angle(q, j, alpha);
  int st = joint_rotation(q, j, Q, NULL);
  if (st) return st;
  rnk_joint jj = *j;
  jj.angle0 = 0.0;
  jet E;
  st = couple_jet(&jj, Q, w0, 0, &E);
  if (st) return st;
  double m = sqrt(j->M[0] * j->M[0] + j->M[1] * j->M[1] + j->M[2] * j->M[2]);
  *alpha = m > 0.0 ? -E.v / m : 0.0;
  return RNK_OK;
}

/* Index of end-local DOF l (x_n 0..2, theta 3, x_J 4..6, w 7..9) in the joint
 * stencil; -1 for w of an elastic joint (no DOF: goes through phi). */
static int end_index(const rnk_joint *j, int k, int l) {
  int base = 3 + (j->rigid ? 3 : 0) + 4 * k;
  if (l < 4) return base + l;
  if (l < 7) return l - 4;
  return j->rigid ? 3 + (l - 7) : -1;
}

/* M = sum_k F_k Fbar_k^T, F_k the material frame of end k's terminal edge. */
static int fit_matrix(const double *q, const rnk_joint *j, double M[9]) {
  for (int k = 0; k < j->valence; ++k) {
    int base = 3 + 4 * k;
    double e[3], F[9];
    end_edge(q, base, j->ends[k].side, e);
    int st = rnk_material_frame(e, &j->refs[k], q[base + 3], F, F + 3, F + 6);
    if (st) return st;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        for (int c = 0; c < 3; ++c)
          M[3 * a + b] += F[3 * c + a] * j->ends[k].cbar[3 * c + b];
  }
  return RNK_OK;
}

/* End k's part of M as 4-jets in Y_k = (e_k, theta_k): its columns of dM/dY
 * (dM [9][ny]) and the term sum_m phi_M_m d2M_m/dY_k2 of d2phi. */
static int end_fit_jets(const double *q, const rnk_joint *j, int k, const jet phi[3],
                        double dM[9][4 * 64], double *d2phi) {
  int ny = 4 * j->valence, base = 3 + 4 * k;
  double e[3];
  rnk_edge_jet fk;
  end_edge(q, base, j->ends[k].side, e);
  int st = rnk_edge_jet_eval(e, q[base + 3], &j->refs[k], 2, &fk);
  if (st) return st;
  const jvec *fr[3] = {&fk.t, &fk.d1, &fk.d2};
  const double *Fb = j->ends[k].cbar;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      /* M_ab contribution of end k: sum_c F[c][a] Fbar[c][b], as a 4-jet */
      double g4[4] = {0, 0, 0, 0}, h4[4][4] = {{0}};
      for (int c = 0; c < 3; ++c) {
        const jet *x = &fr[c]->c[a];
        double w = Fb[3 * c + b];
        for (int i = 0; i < 4; ++i) {
          g4[i] += w * x->g[i];
          for (int jj = i; jj < 4; ++jj) h4[i][jj] += w * x->h[i][jj];
        }
      }
      int m = 3 * a + b;
      for (int i = 0; i < 4; ++i) dM[m][4 * k + i] = g4[i];
      /* second-derivative term: sum_a phi_a,M_m d2M_m/dY_k2 */
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < 4; ++i)
          for (int jj = 0; jj < 4; ++jj) {
            double h = i <= jj ? h4[i][jj] : h4[jj][i];
            d2phi[((size_t)c * ny + 4 * k + i) * ny + 4 * k + jj] += phi[c].g[m] * h;
          }
    }
  return RNK_OK;
}

/* dphi/dY [3][ny] and d2phi/dY2 [3][ny][ny], Y = (e_k, theta_k) per end. */
static int elastic_phi_derivs(const double *q, const rnk_joint *j, double Q0[9],
                              double *dphi, double *d2phi) {
  int v = j->valence, ny = 4 * v;
  double M[9] = {0};
  /* frames of the terminal edges: a first pass for M's value */
  int st = fit_matrix(q, j, M);
  if (st) return st;
  jet phi[3];
  st = phi_jets(M, 2, phi, Q0);
  if (st) return st;
  memset(dphi, 0, sizeof(double) * 3 * (size_t)ny);
  memset(d2phi, 0, sizeof(double) * 3 * (size_t)ny * (size_t)ny);
  /* dM/dY for all ends: 9 x ny (small) */
  double dM[9][4 * 64];
  if (v > 64) return RNK_DEGENERATE;
  for (int k = 0; k < v; ++k)
    if ((st = end_fit_jets(q, j, k, phi, dM, d2phi))) return st;
  for (int c = 0; c < 3; ++c)
    for (int y = 0; y < ny; ++y) {
      double s = 0;
      for (int m = 0; m < 9; ++m) s += phi[c].g[m] * dM[m][y];
      dphi[(size_t)c * ny + y] = s;
    }
  /* first-derivative term: dM^T phi_MM dM */
  for (int c = 0; c < 3; ++c)
    for (int m = 0; m < 9; ++m)
      for (int n = 0; n < 9; ++n) {
        double h = m <= n ? phi[c].h[m][n] : phi[c].h[n][m];
        if (h == 0.0) continue;
        for (int y = 0; y < ny; ++y) {
          double a = h * dM[m][y];
          if (a == 0.0) continue;
          double *row = d2phi + ((size_t)c * ny + y) * ny;
          for (int z = 0; z < ny; ++z) row[z] += a * dM[n][z];
        }
      }
  return RNK_OK;
}

/* The ends' energies with their direct derivatives: g and H on the stencil's DOFs,
 * and for the rotation w (elastic joints: through phi) its gradient Gw, Hessian
 * Hww [3][3] and the cross terms C [n][3]. */
static int ends_direct(const double *q, const rnk_joint *j, int ord, const double *Qref,
                       const double w[3], double *Etot, double *g, double *H, double *C,
                       double Gw[3], double Hww[9]) {
  int n = (int)rnk_joint_stencil_size(j), st;
  for (int k = 0; k < j->valence; ++k) {
    double q10[10], g10[10], H10[100], Ek;
    rnk_joint_end_param p;
    end_setup(q, j, k, Qref, w, q10, &p);
    if (ord == 0)
      st = rnk_jet_joint_end_energy(q10, &j->refs[k], &p, &Ek);
    else
      st = rnk_jet_joint_end_grad(q10, &j->refs[k], &p, &Ek, g10);
    if (st) return st;
    *Etot += Ek;
    if (ord >= 2) {
      st = rnk_jet_joint_end_hess(q10, &j->refs[k], &p, H10);
      if (st) return st;
    }
    for (int l = 0; l < 10 && ord >= 1; ++l) {
      int I = end_index(j, k, l);
      if (I >= 0) {
        if (g) g[I] += g10[l];
      } else {
        Gw[l - 7] += g10[l];
      }
      if (ord < 2) continue;
      for (int m = 0; m < 10; ++m) {
        int J = end_index(j, k, m);
        double h = H10[10 * l + m];
        if (I >= 0 && J >= 0)
          H[(size_t)I * n + J] += h;
        else if (I >= 0)
          C[3 * I + (m - 7)] += h;
        else if (J < 0)
          Hww[3 * (l - 7) + (m - 7)] += h;
      }
    }
  }
  return RNK_OK;
}

/* The couple on the rotation: added to the energy, and to the rotation DOFs'
 * derivatives (rigid) or Gw and Hww (elastic). */
static int couple_direct(const rnk_joint *j, int ord, const double *Qref,
                         const double w[3], double *Etot, double *g, double *H,
                         double Gw[3], double Hww[9]) {
  int n = (int)rnk_joint_stencil_size(j);
  jet Ec;
  int st = couple_jet(j, Qref, w, ord, &Ec);
  if (st) return st;
  *Etot += Ec.v;
  if (ord >= 1)
    for (int a = 0; a < 3; ++a) {
      if (j->rigid) {
        if (g) g[3 + a] += Ec.g[a];
      } else {
        Gw[a] += Ec.g[a];
      }
      if (ord < 2) continue;
      for (int b = 0; b < 3; ++b) {
        double h = a <= b ? Ec.h[a][b] : Ec.h[b][a];
        if (j->rigid)
          H[(size_t)(3 + a) * n + 3 + b] += h;
        else
          Hww[3 * a + b] += h;
      }
    }
  return RNK_OK;
}

/* Phi = dphi/dz [3][n] from dphi/dY: e_k = s_k (x_J - x_n,k): Y index 4k+c <- z
 * index c (+s), 3+4k+c (-s); theta_k: Y index 4k+3 <- z index 3+4k+3. */
static void phi_on_stencil(const rnk_joint *j, int n, const double *dphi, double *Phi) {
  int v = j->valence, ny = 4 * v;
  memset(Phi, 0, sizeof(double) * 3 * (size_t)n);
  for (int a = 0; a < 3; ++a)
    for (int k = 0; k < v; ++k) {
      double s = j->ends[k].side == 0 ? 1.0 : -1.0;
      for (int c = 0; c < 3; ++c) {
        double d = dphi[(size_t)a * ny + 4 * k + c];
        Phi[(size_t)a * n + c] += s * d;
        Phi[(size_t)a * n + 3 + 4 * k + c] -= s * d;
      }
      Phi[(size_t)a * n + 3 + 4 * k + 3] += dphi[(size_t)a * ny + 4 * k + 3];
    }
}

/* sum_a G_w,a d2phi_a/dz2 = dY/dz^T (sum_a G_a d2phi_a/dY2) dY/dz, added to H. */
static void add_phi_curvature(const rnk_joint *j, int n, const double Gw[3],
                              const double *d2phi, double *H) {
  int v = j->valence, ny = 4 * v;
  for (int k = 0; k < v; ++k)
    for (int i = 0; i < 4; ++i)
      for (int l = 0; l < v; ++l)
        for (int jj = 0; jj < 4; ++jj) {
          int y1 = 4 * k + i, y2 = 4 * l + jj;
          double h = 0;
          for (int a = 0; a < 3; ++a) h += Gw[a] * d2phi[((size_t)a * ny + y1) * ny + y2];
          if (h == 0.0) continue;
          /* z images of y1 and y2 with coefficients */
          int z1[2], z2[2], n1, n2;
          double c1[2], c2[2];
          double s1 = j->ends[k].side == 0 ? 1.0 : -1.0,
                 s2 = j->ends[l].side == 0 ? 1.0 : -1.0;
          if (i < 3)
            n1 = 2, z1[0] = i, c1[0] = s1, z1[1] = 3 + 4 * k + i, c1[1] = -s1;
          else
            n1 = 1, z1[0] = 3 + 4 * k + 3, c1[0] = 1.0;
          if (jj < 3)
            n2 = 2, z2[0] = jj, c2[0] = s2, z2[1] = 3 + 4 * l + jj, c2[1] = -s2;
          else
            n2 = 1, z2[0] = 3 + 4 * l + 3, c2[0] = 1.0;
          for (int r = 0; r < n1; ++r)
            for (int t = 0; t < n2; ++t)
              H[(size_t)z1[r] * n + z2[t]] += c1[r] * c2[t] * h;
        }
}

static int joint_eval(const double *q, const rnk_joint *j, int ord, double *work,
                      double *E, double *g, double *H) {
  int n = (int)rnk_joint_stencil_size(j), v = j->valence;
  double Q0[9], w[3] = {0, 0, 0};
  int st;
  const double *Qref = j->Qhat;
  if (j->rigid) {
    memcpy(w, q + 3, sizeof w);
  } else {
    st = joint_rotation(q, j, Q0, NULL);
    if (st) return st;
    Qref = Q0;
  }
  if (g) memset(g, 0, sizeof(double) * (size_t)n);
  if (H) memset(H, 0, sizeof(double) * (size_t)n * (size_t)n);
  double Etot = 0.0, Gw[3] = {0, 0, 0}, Hww[9] = {0};
  double *C = work; /* cross terms [n][3] for elastic joints */
  if (!j->rigid && ord >= 2) memset(C, 0, sizeof(double) * 3 * (size_t)n);
  if ((st = ends_direct(q, j, ord, Qref, w, &Etot, g, H, C, Gw, Hww))) return st;
  if ((st = couple_direct(j, ord, Qref, w, &Etot, g, H, Gw, Hww))) return st;
  if (E) *E = Etot;
  if (j->rigid || ord == 0) return RNK_OK;

  /* elastic: chain rule through phi(Y(z)) */
  int ny = 4 * v;
  double *dphi = work + 3 * (size_t)n, *d2phi = dphi + 3 * (size_t)ny;
  double *Phi = d2phi + 3 * (size_t)ny * ny; /* [3][n] */
  double Qc[9];
  st = elastic_phi_derivs(q, j, Qc, dphi, d2phi);
  if (st) return st;
  phi_on_stencil(j, n, dphi, Phi);
  if (g)
    for (int a = 0; a < 3; ++a)
      for (int z = 0; z < n; ++z) g[z] += Gw[a] * Phi[(size_t)a * n + z];
  if (ord < 2) return RNK_OK;
  /* C Phi + Phi^T C^T + Phi^T Hww Phi */
  for (int z1 = 0; z1 < n; ++z1)
    for (int z2 = 0; z2 < n; ++z2) {
      double h = 0;
      for (int a = 0; a < 3; ++a) {
        h += C[3 * z1 + a] * Phi[(size_t)a * n + z2] +
             Phi[(size_t)a * n + z1] * C[3 * z2 + a];
        for (int b = 0; b < 3; ++b)
          h += Phi[(size_t)a * n + z1] * Hww[3 * a + b] * Phi[(size_t)b * n + z2];
      }
      H[(size_t)z1 * n + z2] += h;
    }
  add_phi_curvature(j, n, Gw, d2phi, H);
  return RNK_OK;
}

/* A smooth joint's oracle is the vertex stencil's (rnk_bendtwist_*, whose own
 * oracle tests cover it). */
int rnk_jet_joint_energy(const double *q, const rnk_joint *j, double *work, double *E) {
  if (j->smooth) return rnk_joint_energy(q, j, work, E);
  return joint_eval(q, j, 0, work, E, NULL, NULL);
}

int rnk_jet_joint_grad(const double *q, const rnk_joint *j, double *work, double *E,
                       double *g) {
  if (j->smooth) return rnk_joint_grad(q, j, work, E, g);
  return joint_eval(q, j, 1, work, E, g, NULL);
}

int rnk_jet_joint_hess(const double *q, const rnk_joint *j, double *work, double *H) {
  if (j->smooth) return rnk_joint_hess(q, j, work, H);
  return joint_eval(q, j, 2, work, NULL, NULL, H);
}

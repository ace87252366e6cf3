/* supports.c - rigid-body motions that no constraint blocks, and whether the
 * applied loads can be balanced on them (rn_network_free_motions,
 * rn_network_check_supports).
 *
 * An infinitesimal rigid motion, translation t and rotation w about the
 * centroid c of the current positions, moves a position DOF at x by
 * t + w x (x - c), a joint rotation by w and a material angle by w . tangent.
 * A constraint blocks it if it changes a fixed DOF: one row of C v per fixed
 * DOF (v = (t, w L), L the size of the structure, so both parts are lengths).
 * The free motions are the null space of C^T C (6 x 6, Jacobi eigenvalues);
 * the free translations that of its translation block.  The loads are
 * unbalanced when the applied force has a component along a free
 * translation (no configuration can balance it), or when there is no net force
 * but the net couple turns a free rotation (a dead couple stays unbalanced
 * however the structure turns).  A net force with a free rotation is not an
 * error: the structure can turn until the force passes through the axis (a
 * pendulum). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "core/network_internal.h"
#include "rodq.h"

typedef struct motion_rows {
  double A[6][6]; /* C^T C */
  double c[3], L; /* centroid and size */
} motion_rows;

static void add_row(motion_rows *m, const double row[6]) {
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b) m->A[a][b] += row[a] * row[b];
}

/* Fixed position component k at x. */
static void add_position_row(motion_rows *m, const double *x, int k) {
  double row[6] = {0, 0, 0, 0, 0, 0}, d[3], e[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i) d[i] = (x[i] - m->c[i]) / m->L;
  e[k] = 1.0;
  row[k] = 1.0;
  /* e_k . (w x d) = w . (d x e_k) */
  row[3] = d[1] * e[2] - d[2] * e[1];
  row[4] = d[2] * e[0] - d[0] * e[2];
  row[5] = d[0] * e[1] - d[1] * e[0];
  add_row(m, row);
}

/* A fixed rotation about the unit axis a. */
static void add_rotation_row(motion_rows *m, const double a[3]) {
  double row[6] = {0, 0, 0, a[0], a[1], a[2]};
  add_row(m, row);
}

static int is_fixed(const rn_network *net, size_t i) { return net->map[i] == -1; }

static void centroid(const rn_network *net, motion_rows *m) {
  double lo[3] = {INFINITY, INFINITY, INFINITY},
         hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  long n = 0;
  memset(m, 0, sizeof *m);
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    for (int v = 0; v < r->nv; ++v, ++n) {
      const double *x = &net->xfull[rn_dof_vertex(r->off, v)];
      for (int k = 0; k < 3; ++k) {
        m->c[k] += x[k];
        lo[k] = fmin(lo[k], x[k]);
        hi[k] = fmax(hi[k], x[k]);
      }
    }
  }
  m->L = 0.0;
  for (int k = 0; k < 3; ++k) {
    m->c[k] = n ? m->c[k] / (double)n : 0.0;
    if (n) m->L = fmax(m->L, hi[k] - lo[k]);
  }
  if (!(m->L > 0.0)) m->L = 1.0;
}

static void constraint_rows(const rn_network *net, motion_rows *m) {
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    for (int v = 0; v < r->nv; ++v)
      for (int k = 0; k < 3; ++k)
        if (is_fixed(net, rn_dof_vertex(r->off, v) + (size_t)k))
          add_position_row(m, &net->xfull[rn_dof_vertex(r->off, v)], k);
    for (int j = 0; j < r->ne; ++j) {
      if (!is_fixed(net, rn_dof_theta(r->off, j))) continue;
      const double *a = &net->xfull[rn_dof_vertex(r->off, j)];
      const double *b = &net->xfull[rn_dof_vertex(r->off, j + 1)];
      double t[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
      double l = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
      if (!(l > 0.0)) continue;
      for (int k = 0; k < 3; ++k) t[k] /= l;
      add_rotation_row(m, t);
    }
  }
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    for (int k = 0; k < 3; ++k) {
      if (is_fixed(net, rn_dof_joint_position(J->off) + (size_t)k))
        add_position_row(m, &net->xfull[rn_dof_joint_position(J->off)], k);
      if (rn_joint_has_rotation(J) &&
          is_fixed(net, rn_dof_joint_rotation(J->off) + (size_t)k)) {
        double e[3] = {0, 0, 0};
        e[k] = 1.0;
        add_rotation_row(m, e);
      }
    }
  }
}

/* Eigen-decomposition of the symmetric n x n matrix a (destroyed) by cyclic
 * Jacobi rotations: eigenvalues in ev, eigenvectors in the columns of V. */
static void jacobi(int n, double a[6][6], double ev[6], double V[6][6]) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) V[i][j] = i == j;
  for (int sweep = 0; sweep < 60; ++sweep) {
    double off = 0.0, diag = 0.0;
    for (int i = 0; i < n; ++i) {
      diag += a[i][i] * a[i][i];
      for (int j = i + 1; j < n; ++j) off += a[i][j] * a[i][j];
    }
    if (off <= 1e-36 * diag || off == 0.0) break;
    for (int p = 0; p < n; ++p)
      for (int q = p + 1; q < n; ++q) {
        if (a[p][q] == 0.0) continue;
        double th = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
        double t = (th >= 0 ? 1.0 : -1.0) / (fabs(th) + sqrt(th * th + 1.0));
        double c = 1.0 / sqrt(t * t + 1.0), s = t * c;
        for (int k = 0; k < n; ++k) { /* columns p, q */
          double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < n; ++k) { /* rows p, q */
          double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < n; ++k) {
          double vkp = V[k][p], vkq = V[k][q];
          V[k][p] = c * vkp - s * vkq;
          V[k][q] = s * vkp + c * vkq;
        }
      }
  }
  for (int i = 0; i < n; ++i) ev[i] = a[i][i];
}

/* Null vectors of the leading n x n block of m->A: their count; vectors in
 * out[k][0..n-1].  Null: eigenvalue <= 1e-20 times the trace (the rows are
 * of unit size, so a blocked motion has an eigenvalue of order 1). */
static int null_space(const motion_rows *m, int n, double out[6][6]) {
  double a[6][6], ev[6], V[6][6], tr = 0.0;
  int cnt = 0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) a[i][j] = m->A[i][j];
    tr += m->A[i][i];
  }
  jacobi(n, a, ev, V);
  for (int i = 0; i < n; ++i)
    if (ev[i] <= 1e-12 * fmax(tr, 1.0)) { /* Jacobi: ev to ~1e-16 tr */
      for (int k = 0; k < n; ++k) out[cnt][k] = V[k][i];
      cnt++;
    }
  return cnt;
}

/* Orthonormal basis (Gram-Schmidt, dropping dependent vectors) of the k
 * vectors v[i][off..off+2]; returns its size. */
static int basis3(double v[6][6], int k, int off, double out[3][3]) {
  int n = 0;
  for (int i = 0; i < k && n < 3; ++i) {
    double u[3] = {v[i][off], v[i][off + 1], v[i][off + 2]};
    for (int j = 0; j < n; ++j) {
      double d = rq_dot3(u, out[j]);
      for (int c = 0; c < 3; ++c) u[c] -= d * out[j][c];
    }
    double l = sqrt(rq_dot3(u, u));
    if (l < 1e-8) continue;
    for (int c = 0; c < 3; ++c) out[n][c] = u[c] / l;
    n++;
  }
  return n;
}

rn_status rn_network_free_motions(const rn_network *net, rn_free_motions *fm) {
  static const char *where = "rn_network_free_motions";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!fm) return rn_fail(net->ctx, RN_ERR_ARG, where, "fm is NULL");
  memset(fm, 0, sizeof *fm);
  motion_rows m;
  centroid(net, &m);
  constraint_rows(net, &m);
  memcpy(fm->center, m.c, sizeof m.c);
  double nt[6][6], nall[6][6];
  int kt = null_space(&m, 3, nt), k = null_space(&m, 6, nall);
  fm->num_translations = basis3(nt, kt, 0, fm->translation);
  /* rotation axes: the w parts of the free motions (a free screw about an
   * axis away from the centroid has a translation part too) */
  fm->num_rotations = basis3(nall, k, 3, fm->rotation);
  if ((st = rn_network_applied_resultant(net, fm->force, fm->moment))) return st;
  /* the moment about the centroid */
  double *M = fm->moment, *F = fm->force, *c = m.c;
  M[0] -= c[1] * F[2] - c[2] * F[1];
  M[1] -= c[2] * F[0] - c[0] * F[2];
  M[2] -= c[0] * F[1] - c[1] * F[0];
  /* scales: sums of the magnitudes of the applied forces and couples */
  double fsum = 0.0, msum = 0.0;
  for (int ir = 0; ir < net->nrods; ++ir)
    for (int v = 0; v < net->rods[ir].nv; ++v)
      fsum += fabs(net->lambda) *
              sqrt(rq_dot3(&net->rods[ir].fvert[3 * v], &net->rods[ir].fvert[3 * v]));
  for (int ij = 0; ij < net->njoints; ++ij) {
    fsum +=
        fabs(net->lambda) * sqrt(rq_dot3(net->joints[ij].force, net->joints[ij].force));
    msum += fabs(net->lambda) * sqrt(rq_dot3(net->joints[ij].M, net->joints[ij].M));
  }
  for (int im = 0; im < net->nmom; ++im)
    msum += fabs(net->lambda) * sqrt(rq_dot3(net->moments[im].M, net->moments[im].M));
  const double ftol = 1e-10 * fsum, mtol = 1e-10 * (msum + fsum * m.L);
  for (int i = 0; i < fm->num_translations; ++i)
    if (fabs(rq_dot3(F, fm->translation[i])) > ftol) fm->unbalanced_force = 1;
  if (sqrt(rq_dot3(F, F)) <= ftol)
    for (int i = 0; i < k; ++i) /* (t, w L): power F.t + M.w = M.w here */
      if (fabs(rq_dot3(M, &nall[i][3])) / m.L > mtol) fm->unbalanced_moment = 1;
  return RN_OK;
}

/* "x", "-y" for an axis-aligned unit vector, else "(a, b, c)". */
static void axis_name(const double v[3], char *buf, size_t n) {
  for (int k = 0; k < 3; ++k)
    if (fabs(fabs(v[k]) - 1.0) < 1e-9) {
      snprintf(buf, n, "%s%c", v[k] < 0 ? "-" : "", "xyz"[k]);
      return;
    }
  snprintf(buf, n, "(%.3g, %.3g, %.3g)", v[0], v[1], v[2]);
}

static void list_axes(char *buf, size_t n, const char *what, int cnt, double ax[3][3]) {
  size_t len = strlen(buf);
  if (!cnt || len >= n) return;
  snprintf(buf + len, n - len, "%s%s%s", len ? "; " : "", what,
           cnt == 1 ? "" : " each of");
  for (int i = 0; i < cnt; ++i) {
    char a[64];
    axis_name(ax[i], a, sizeof a);
    len = strlen(buf);
    if (len < n) snprintf(buf + len, n - len, "%s %s", i ? "," : "", a);
  }
}

rn_status rn_network_check_supports(const rn_network *net) {
  static const char *where = "rn_network_check_supports";
  rn_free_motions fm;
  rn_status st = rn_network_free_motions(net, &fm);
  if (st) return st;
  if (!fm.unbalanced_force && !fm.unbalanced_moment) return RN_OK;
  char motions[512] = "";
  list_axes(motions, sizeof motions, "translation along", fm.num_translations,
            fm.translation);
  list_axes(motions, sizeof motions, "rotation about", fm.num_rotations, fm.rotation);
  return rn_fail(net->ctx, RN_ERR_BC, where,
                 "the constraints leave rigid-body motions free (%s) and the applied "
                 "loads are not balanced on them (%s (%.6g, %.6g, %.6g)): no "
                 "equilibrium exists; add constraints that block these motions",
                 motions, fm.unbalanced_force ? "net force" : "net couple, no net force:",
                 fm.unbalanced_force ? fm.force[0] : fm.moment[0],
                 fm.unbalanced_force ? fm.force[1] : fm.moment[1],
                 fm.unbalanced_force ? fm.force[2] : fm.moment[2]);
}

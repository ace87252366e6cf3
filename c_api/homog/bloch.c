/* bloch.c - Bloch-Floquet Hessians of periodic cells (docs/homogenization.md,
 * "Stability"): the second variation of the infinite lattice for perturbations
 * u(cell n) = u_0 exp(i k . s_n), s_n = sum n_m a_m, assembled on one cell.
 *
 * A stencil entry at an image record (a rod end at an image of a joint, or the
 * neighbour of an image end seen from the joint) carries the phase k . s of the
 * record's lattice shift s; every stencil block H_s adds P^H H_s P to the Bloch
 * matrix, P = diag(exp(i phi)) over its entries.  The Bloch DOFs are the free
 * fluctuation DOFs (every reduced DOF but the strain components) and, if
 * finalize pinned an anchor, its three position components: a Bloch wave moves
 * every copy of the anchor (only k = 0 has rigid translations).  The macroscopic
 * strain stays fixed.  The same assembly gives the real "moments" of the phase
 * expansion, sum_s sum_kl (phi_l - phi_k)^p H_s,kl, for the long-wavelength limit. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "eval/eval.h"
#include "periodic/periodic.h"

static const char *const where_dofs = "rn_network_bloch_dofs";

/* Bloch DOF of every full entry (-1: none; aliases resolved like the reduced map),
 * and the number of Bloch DOFs.  NULL on allocation failure. */
static int64_t *bloch_index(const rn_network *net, size_t *n) {
  const rn_cell *c = net->cell;
  int64_t *b = malloc((net->nfull ? net->nfull : 1) * sizeof(int64_t));
  size_t nfl = 0;
  if (!b) return NULL;
  for (size_t a = 0; a < net->nfull; ++a) {
    b[a] = (a >= c->off || net->map[a] < 0) ? -1 : net->map[a];
    if (b[a] >= 0 && (size_t)b[a] + 1 > nfl) nfl = (size_t)b[a] + 1;
  }
  *n = nfl;
  if (!c->anchored) return b;
  if (net->njoints > 0) {
    const rn_joint *J = &net->joints[0];
    size_t p = rn_dof_joint_position(J->off);
    for (int q = 0; q < 3; ++q) b[p + (size_t)q] = (int64_t)(nfl + (size_t)q);
    for (int k = 0; k < J->valence; ++k) { /* the rod end vertices aliasing it */
      const rn_rod *r = &net->rods[J->rod[k]];
      size_t v = rn_dof_vertex(r->off, rn_end_vertex(r->nv, J->end[k]));
      for (int q = 0; q < 3; ++q) b[v + (size_t)q] = (int64_t)(nfl + (size_t)q);
    }
  } else {
    size_t v = rn_dof_vertex(net->rods[0].off, 0);
    for (int q = 0; q < 3; ++q) b[v + (size_t)q] = (int64_t)(nfl + (size_t)q);
  }
  *n = nfl + 3;
  return b;
}

static rn_status check_periodic(const rn_network *net, const char *where) {
  rn_status st;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!net->cell)
    return rn_fail(net->ctx, RN_ERR_STATE, where,
                   "the network is not periodic (rn_network_set_periodic)");
  if (net->part)
    return rn_fail(net->ctx, RN_ERR_STATE, where,
                   "the Bloch-Floquet analysis needs the whole cell, not a part of a "
                   "partition");
  return RN_OK;
}

rn_status rn_network_bloch_dofs(const rn_network *net, size_t *n, int *kind,
                                int *component) {
  rn_status st;
  size_t nb = 0, nfl;
  int64_t *b;
  if (!net) return RN_ERR_ARG;
  if ((st = check_periodic(net, where_dofs))) return st;
  if (!n) return rn_fail(net->ctx, RN_ERR_ARG, where_dofs, "n is NULL");
  if (!(b = bloch_index(net, &nb)))
    return rn_fail(net->ctx, RN_ERR_ALLOC, where_dofs, "out of memory");
  free(b);
  *n = nb;
  if (!kind && !component) return RN_OK;
  nfl = net->cell->anchored ? nb - 3 : nb;
  rn_dof_info *info = malloc((net->nred ? net->nred : 1) * sizeof(*info));
  if (!info) return rn_fail(net->ctx, RN_ERR_ALLOC, where_dofs, "out of memory");
  if ((st = rn_network_dof_info(net, info))) {
    free(info);
    return st;
  }
  for (size_t i = 0; i < nb; ++i) {
    int kd = i < nfl ? info[i].kind : RN_DOF_POSITION;
    int cp = i < nfl ? info[i].component : (int)(i - nfl);
    if (kind) kind[i] = kd;
    if (component) component[i] = cp;
  }
  free(info);
  return RN_OK;
}

/* The Cartesian wave vector of k = sum xi_i b_i (b_i . a_j = 2 pi delta_ij):
 * b_i = 2 pi sum_j (G^-1)_ij a_j, G = a a^T the Gram matrix. */
static void cartesian_wave(const rn_cell *c, const double *xi, double *k) {
  double G[3][3] = {{0}}, Gi[3][3] = {{0}};
  int d = c->dim;
  for (int i = 0; i < d; ++i)
    for (int j = 0; j < d; ++j)
      for (int q = 0; q < 3; ++q) G[i][j] += c->a[i][q] * c->a[j][q];
  if (d == 2) {
    double det = G[0][0] * G[1][1] - G[0][1] * G[1][0];
    Gi[0][0] = G[1][1] / det, Gi[1][1] = G[0][0] / det;
    Gi[0][1] = -G[0][1] / det, Gi[1][0] = -G[1][0] / det;
  } else {
    double det = G[0][0] * (G[1][1] * G[2][2] - G[1][2] * G[2][1]) -
                 G[0][1] * (G[1][0] * G[2][2] - G[1][2] * G[2][0]) +
                 G[0][2] * (G[1][0] * G[2][1] - G[1][1] * G[2][0]);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
        Gi[i][j] = (G[i1][j1] * G[i2][j2] - G[i1][j2] * G[i2][j1]) / det;
      }
  }
  for (int q = 0; q < 3; ++q) {
    k[q] = 0.0;
    for (int i = 0; i < d; ++i)
      for (int j = 0; j < d; ++j)
        k[q] += 6.283185307179586477 * xi[i] * Gi[i][j] * c->a[j][q];
  }
}

/* Phase k . s of every image record. */
static void record_phases(const rn_cell *c, const double *k, double *ph) {
  for (int r = 0; r < c->nimg; ++r)
    ph[r] = k[0] * c->img[r].s[0] + k[1] * c->img[r].s[1] + k[2] * c->img[r].s[2];
}

/* The triplets of the sparse mode. */
typedef struct bloch_triplets {
  rn_bloch_trip *trip;
  size_t ntrip, n;
} bloch_triplets;

/* Assembles into b (re, im zeroed here) with the phase sets of k1, k2; re NULL: the
 * sparse mode, its triplets into *trip (the caller frees trip->trip). */
static rn_status bloch_assemble(const rn_network *net, const double *x, const double *k1,
                                const double *k2, int recip, double *re, double *im,
                                bloch_triplets *trip, const char *where) {
  const rn_cell *c = net->cell;
  rn_bloch_acc b;
  rn_status st;
  size_t n = 0;
  double *ph = malloc(2 * (size_t)(c->nimg ? c->nimg : 1) * sizeof(double));
  int64_t *bidx = bloch_index(net, &n);
  if (!ph || !bidx) {
    free(ph);
    free(bidx);
    return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  }
  memset(&b, 0, sizeof(b));
  b.n = n;
  b.bidx = bidx;
  if (k1 && recip) cartesian_wave(c, k1, b.k1);
  if (k1 && !recip) memcpy(b.k1, k1, sizeof(b.k1));
  if (k2) memcpy(b.k2, k2, sizeof(b.k2));
  if (k1) record_phases(c, b.k1, ph);
  if (k2) record_phases(c, b.k2, ph + (c->nimg ? c->nimg : 1));
  b.ph1 = k1 ? ph : NULL;
  b.ph2 = k2 ? ph + (c->nimg ? c->nimg : 1) : NULL;
  b.order = (k1 != NULL) + (k2 != NULL);
  b.re = re;
  b.im = im;
  b.moment = !re && !recip;
  b.raw = !re && recip == 2;
  if (re) memset(re, 0, n * n * sizeof(double));
  if (re && im) memset(im, 0, n * n * sizeof(double));
  st = rn_eval_bloch(net, x, &b, where);
  if (!st && b.trip_failed) st = rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  free(ph);
  free(bidx);
  if (trip && !st) {
    trip->trip = b.trip;
    trip->ntrip = b.ntrip;
    trip->n = n;
  } else {
    free(b.trip);
  }
  return st;
}

static rn_status check_bloch_args(const rn_network *net, const double *x, const void *a,
                                  const void *b, const char *where) {
  rn_status st;
  if ((st = check_periodic(net, where))) return st;
  if ((!x && net->nred) || !a || !b)
    return rn_fail(net->ctx, RN_ERR_ARG, where, "NULL array");
  if (!rn_all_finite(net->nred, x))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "x has NaN or infinite entries");
  return RN_OK;
}

/* A wave vector xi[dim]: given and finite. */
static rn_status check_wave(const rn_network *net, const double *xi, const char *where) {
  if (!xi) return rn_fail(net->ctx, RN_ERR_ARG, where, "xi is NULL");
  if (!rn_all_finite((size_t)net->cell->dim, xi))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "xi is not finite");
  return RN_OK;
}

rn_status rn_network_bloch_hessian(const rn_network *net, const double *x,
                                   const double *xi, double *re, double *im) {
  static const char *where = "rn_network_bloch_hessian";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = check_bloch_args(net, x, re, im, where)) || (st = check_wave(net, xi, where)))
    return st;
  return bloch_assemble(net, x, xi, NULL, 1, re, im, NULL, where);
}

rn_status rn_network_bloch_moment(const rn_network *net, const double *x,
                                  const double *k1, const double *k2, double *out) {
  static const char *where = "rn_network_bloch_moment";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = check_bloch_args(net, x, out, out, where))) return st;
  if (!k1 && k2) return rn_fail(net->ctx, RN_ERR_ARG, where, "k2 without k1");
  if ((k1 && !rn_all_finite(3, k1)) || (k2 && !rn_all_finite(3, k2)))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "k1 or k2 is not finite");
  return bloch_assemble(net, x, k1, k2, 0, out, NULL, NULL, where);
}

/* Stable merge sort of t[0 .. m - 1] by column (scratch w of m). */
static void sort_row(rn_bloch_trip *t, rn_bloch_trip *w, size_t m) {
  for (size_t width = 1; width < m; width *= 2) {
    for (size_t lo = 0; lo < m; lo += 2 * width) {
      size_t mid = lo + width < m ? lo + width : m;
      size_t hi = lo + 2 * width < m ? lo + 2 * width : m, i = lo, j = mid, k = lo;
      while (i < mid && j < hi) w[k++] = t[j].c < t[i].c ? t[j++] : t[i++];
      while (i < mid) w[k++] = t[i++];
      while (j < hi) w[k++] = t[j++];
    }
    memcpy(t, w, m * sizeof *t);
  }
}

/* Triplets to CSR: a counting sort by row, each row by column (both stable: the
 * duplicates of an entry stay in assembly order and are summed in it, as the dense
 * matrix sums them).  Fills rowptr[n + 1] and *nnz; with col (and re, im) the
 * entries (cap: the arrays' length; im may be NULL: real values; re and im NULL:
 * the pattern only; tr is not changed).  0, or -1 out of memory. */
static int triplets_to_csr(const bloch_triplets *tr, size_t cap, size_t *nnz,
                           int64_t *rowptr, int64_t *col, double *re, double *im) {
  const size_t n = tr->n, m = tr->ntrip;
  size_t *start = calloc(n + 1, sizeof(size_t));
  rn_bloch_trip *s = malloc((m ? m : 1) * sizeof *s),
                *w = malloc((m ? m : 1) * sizeof *w);
  if (!start || !s || !w) {
    free(start), free(s), free(w);
    return -1;
  }
  for (size_t q = 0; q < m; ++q) ++start[tr->trip[q].r + 1];
  for (size_t r = 0; r < n; ++r) start[r + 1] += start[r];
  for (size_t q = 0; q < m; ++q) s[start[tr->trip[q].r]++] = tr->trip[q];
  for (size_t r = n; r > 0; --r) start[r] = start[r - 1]; /* back to the row starts */
  start[0] = 0;
  size_t count = 0;
  for (size_t r = 0; r < n; ++r) {
    rn_bloch_trip *t = s + start[r];
    size_t len = start[r + 1] - start[r];
    sort_row(t, w, len);
    if (rowptr) rowptr[r] = (int64_t)count;
    for (size_t q = 0; q < len; ++q) {
      if (q > 0 && t[q].c == t[q - 1].c) {
        if (col && count <= cap) {
          if (re) re[count - 1] += t[q].re;
          if (im) im[count - 1] += t[q].im;
        }
        continue;
      }
      if (col && count < cap) {
        col[count] = t[q].c;
        if (re) re[count] = 0.0 + t[q].re;
        if (im) im[count] = 0.0 + t[q].im;
      }
      ++count;
    }
  }
  if (rowptr) rowptr[n] = (int64_t)count;
  *nnz = count;
  free(start), free(s), free(w);
  return 0;
}

/* The triplets of the sparse mode into CSR with the checks of the _csr entries. */
static rn_status csr_out(const rn_network *net, bloch_triplets *tr, size_t *nnz,
                         int64_t *rowptr, int64_t *col, double *re, double *im,
                         const char *where) {
  size_t cap = col ? *nnz : 0, count = 0;
  if (triplets_to_csr(tr, cap, &count, rowptr, col, re, im)) {
    free(tr->trip);
    return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  }
  free(tr->trip);
  *nnz = count;
  if (col && count > cap)
    return rn_fail(net->ctx, RN_ERR_RANGE, where,
                   "the arrays hold %zu entries, the matrix has %zu", cap, count);
  return RN_OK;
}

rn_status rn_network_bloch_hessian_csr(const rn_network *net, const double *x,
                                       const double *xi, size_t *nnz, int64_t *rowptr,
                                       int64_t *col, double *re, double *im) {
  static const char *where = "rn_network_bloch_hessian_csr";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = check_bloch_args(net, x, nnz, nnz, where)) ||
      (st = check_wave(net, xi, where)))
    return st;
  if (col && (!rowptr || !re || !im))
    return rn_fail(net->ctx, RN_ERR_ARG, where, "col without rowptr, re or im");
  bloch_triplets tr = {NULL, 0, 0};
  if ((st = bloch_assemble(net, x, xi, NULL, 1, NULL, NULL, &tr, where))) return st;
  return csr_out(net, &tr, nnz, rowptr, col, re, im, where);
}

rn_status rn_network_bloch_moment_csr(const rn_network *net, const double *x,
                                      const double *k1, const double *k2, size_t *nnz,
                                      int64_t *rowptr, int64_t *col, double *val) {
  static const char *where = "rn_network_bloch_moment_csr";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = check_bloch_args(net, x, nnz, nnz, where))) return st;
  if (!k1 && k2) return rn_fail(net->ctx, RN_ERR_ARG, where, "k2 without k1");
  if ((k1 && !rn_all_finite(3, k1)) || (k2 && !rn_all_finite(3, k2)))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "k1 or k2 is not finite");
  if (col && (!rowptr || !val))
    return rn_fail(net->ctx, RN_ERR_ARG, where, "col without rowptr or val");
  bloch_triplets tr = {NULL, 0, 0};
  if ((st = bloch_assemble(net, x, k1, k2, 0, NULL, NULL, &tr, where))) return st;
  return csr_out(net, &tr, nnz, rowptr, col, val, NULL, where);
}

/* The lattice shift of a phase difference d under the coded wave vector xi =
 * (1, 64, 4096): d = 2 pi (n1 + 64 n2 + 4096 n3), |n_i| < 32. */
static void decode_shift(double d, int *n) {
  long code = lround(d / 6.283185307179586477);
  for (int i = 0; i < 3; ++i) {
    long r = ((code % 64) + 64 + 32) % 64 - 32;
    n[i] = (int)r;
    code = (code - r) / 64;
  }
}

rn_status rn_network_bloch_terms(const rn_network *net, const double *x, int *nterms,
                                 int *shift, size_t *nnz, int64_t *rowptr, int64_t *col,
                                 double *val) {
  static const char *where = "rn_network_bloch_terms";
  enum { MAX_TERMS = 64 };
  const double code[3] = {1.0, 64.0, 4096.0};
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = check_bloch_args(net, x, nnz, nterms, where))) return st;
  if (col && (!rowptr || !val || !shift))
    return rn_fail(net->ctx, RN_ERR_ARG, where, "col without rowptr, val or shift");
  const int tcap = col ? *nterms : 0;
  bloch_triplets tr = {NULL, 0, 0};
  if ((st = bloch_assemble(net, x, code, NULL, 2, NULL, NULL, &tr, where))) return st;
  /* the distinct shifts, in order of first appearance; each triplet's term in its im */
  int sh[MAX_TERMS][3], nt = 0;
  for (size_t q = 0; q < tr.ntrip; ++q) {
    int n[3], t = 0;
    decode_shift(tr.trip[q].im, n);
    while (t < nt && (sh[t][0] != n[0] || sh[t][1] != n[1] || sh[t][2] != n[2])) ++t;
    if (t == nt) {
      if (nt == MAX_TERMS) {
        free(tr.trip);
        return rn_fail(net->ctx, RN_ERR_INTERNAL, where, "more than %d lattice shifts",
                       MAX_TERMS);
      }
      memcpy(sh[nt++], n, sizeof n);
    }
    tr.trip[q].im = (double)t;
  }
  /* the pattern (union over the terms), then each term's values on it */
  size_t count = 0, cap = col ? *nnz : 0;
  if (triplets_to_csr(&tr, cap, &count, rowptr, col, NULL, NULL)) {
    free(tr.trip);
    return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  }
  *nnz = count;
  *nterms = nt;
  if (col && (count > cap || nt > tcap)) {
    free(tr.trip);
    return rn_fail(net->ctx, RN_ERR_RANGE, where,
                   "the arrays hold %zu entries and %d terms, the matrix has %zu and %d",
                   cap, tcap, count, nt);
  }
  if (col) {
    memset(val, 0, (size_t)nt * count * sizeof(double));
    for (int t = 0; t < nt; ++t) memcpy(shift + 3 * t, sh[t], sizeof sh[t]);
    for (size_t q = 0; q < tr.ntrip; ++q) { /* each triplet's entry: search its row */
      const rn_bloch_trip *e = &tr.trip[q];
      int64_t lo = rowptr[e->r], hi = rowptr[e->r + 1] - 1;
      while (lo < hi) {
        int64_t mid = (lo + hi) / 2;
        if (col[mid] < e->c)
          lo = mid + 1;
        else
          hi = mid;
      }
      val[(size_t)e->im * count + (size_t)lo] += e->re;
    }
  }
  free(tr.trip);
  return RN_OK;
}

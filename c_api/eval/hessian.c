/* hessian.c - CSR pattern of the reduced Hessian (built at finalize; rebuilt
 * when the contact pattern pairs change, contact.c) and the
 * scatter of stencil blocks into it.  Rows collect the columns of every
 * stencil touching them: rod stencils as ranges of their rod's full vector,
 * joint stencils by their index lists, through the aliases of joint
 * positions. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact/contact.h"
#include "eval/eval.h"
#include "periodic/periodic.h"

/* Widens [lo, hi] of every DOF of a stencil slice [s, s + n) to the slice. */
static void cover(size_t *lo, size_t *hi, size_t s, int n) {
  for (size_t a = s; a < s + (size_t)n; ++a) {
    if (s < lo[a]) lo[a] = s;
    if (s + (size_t)n - 1 > hi[a]) hi[a] = s + (size_t)n - 1;
  }
}

/* Rod stencils are contiguous slices of their rod's full vector and stencils
 * that contain a DOF overlap, so the rod DOFs coupled to full index a are the
 * range [lo(a), hi(a)]. */
static void stencil_ranges(const rn_network *net, size_t *lo, size_t *hi) {
  for (size_t a = 0; a < net->nfull; ++a) {
    lo[a] = a;
    hi[a] = a;
  }
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    if (!rn_rod_evaluated(r)) continue; /* a ghost rod of a part */
    for (int j = 0; j < r->ne; ++j)
      cover(lo, hi, rn_dof_edge_stencil(r->off, j), RN_EDGE_STENCIL);
    for (int i = 1; i < r->nv - 1; ++i)
      cover(lo, hi, rn_dof_vertex_stencil(r->off, i), RN_VERTEX_STENCIL);
  }
}

/* Incidence lists in CSR form: for each reduced row, the full indices that
 * map to it (one, or a joint position and its aliased rod end vertices) and
 * the joints whose stencil contains it. */
typedef struct row_lists {
  size_t *fptr, *full; /* [nred + 1], [nfull] */
  size_t *jptr, *jnt;  /* [nred + 1], [sum of free joint stencil entries] */
} row_lists;

static void row_lists_free(row_lists *L) {
  free(L->fptr);
  free(L->full);
  free(L->jptr);
  free(L->jnt);
}

static int joint_stencil_n(const rn_joint *J) {
  return rn_joint_stencil_count(rn_joint_has_rotation(J), J->valence);
}

/* Counting sort of the full indices (pass 0: count, 1: fill). */
static void fill_full_lists(const rn_network *net, row_lists *L) {
  for (size_t a = 0; a < net->nfull; ++a)
    if (net->map[a] >= 0) L->fptr[net->map[a] + 1]++;
  for (size_t r = 0; r < net->nred; ++r) L->fptr[r + 1] += L->fptr[r];
  for (size_t a = 0; a < net->nfull; ++a)
    if (net->map[a] >= 0) L->full[L->fptr[net->map[a]]++] = a;
  for (size_t r = net->nred; r > 0; --r) L->fptr[r] = L->fptr[r - 1];
  L->fptr[0] = 0;
}

static rn_status row_lists_build(const rn_network *net, row_lists *L) {
  size_t nj = 0, n1 = net->nred + 1;
  for (int ij = 0; ij < net->njoints; ++ij)
    if (rn_joint_evaluated(&net->joints[ij]))
      nj += (size_t)joint_stencil_n(&net->joints[ij]);
  L->fptr = calloc(n1, sizeof(size_t));
  L->full = malloc((net->nfull + 1) * sizeof(size_t));
  L->jptr = calloc(n1, sizeof(size_t));
  L->jnt = malloc((nj + 1) * sizeof(size_t));
  if (!L->fptr || !L->full || !L->jptr || !L->jnt) return RN_ERR_ALLOC;
  fill_full_lists(net, L);
  for (int pass = 0; pass < 2; ++pass) {
    for (int ij = 0; ij < net->njoints; ++ij) {
      const rn_joint *J = &net->joints[ij];
      if (!rn_joint_evaluated(J)) continue; /* a ghost joint of a part */
      for (int k = 0; k < joint_stencil_n(J); ++k) {
        int64_t m = net->map[J->idx[k]];
        if (m < 0) continue;
        if (pass == 0)
          L->jptr[m + 1]++;
        else
          L->jnt[L->jptr[m]++] = (size_t)ij;
      }
    }
    if (pass == 0)
      for (size_t r = 0; r < net->nred; ++r) L->jptr[r + 1] += L->jptr[r];
  }
  for (size_t r = net->nred; r > 0; --r) L->jptr[r] = L->jptr[r - 1];
  L->jptr[0] = 0;
  return RN_OK;
}

static int cmp_i32(const void *a, const void *b) {
  int32_t x = *(const int32_t *)a, y = *(const int32_t *)b;
  return (x > y) - (x < y);
}

/* Sorts c[n] ascending: insertion sort for the short, nearly sorted candidate
 * lists of the rows next to joints (a few dozen entries; qsort's merge sort
 * costs ~20x more there), qsort beyond. */
static void sort_columns(int32_t *c, size_t n) {
  if (n > 64) {
    qsort(c, n, sizeof(int32_t), cmp_i32);
    return;
  }
  for (size_t i = 1; i < n; ++i) {
    int32_t v = c[i];
    size_t j = i;
    for (; j > 0 && c[j - 1] > v; --j) c[j] = c[j - 1];
    c[j] = v;
  }
}

static int increasing(const int32_t *c, size_t n) {
  for (size_t i = 1; i < n; ++i)
    if (c[i] <= c[i - 1]) return 0;
  return 1;
}

/* Growable column buffer. */
typedef struct col_buf {
  int32_t *c;
  size_t n, cap;
  size_t examined; /* entries the candidate loops of rods, joints and the
                      periodic cell looked at (pattern_work; not contact) */
} col_buf;

static int push(col_buf *b, int64_t c) {
  if (b->n == b->cap) {
    size_t cap = b->cap ? 2 * b->cap : 64;
    int32_t *p = realloc(b->c, cap * sizeof(int32_t));
    if (!p) return -1;
    b->c = p;
    b->cap = cap;
  }
  b->c[b->n++] = (int32_t)c;
  return 0;
}

/* Contact: for each reduced row, the reduced columns of the stencils of the
 * pattern's contact pairs (contact.c) that contain it (CSR, with duplicates). */
typedef struct contact_rows {
  size_t *ptr;  /* [nred + 1] */
  int32_t *col; /* [ptr[nred]] */
} contact_rows;

static int contact_rows_build(const rn_network *net, contact_rows *C) {
  const size_t np = rn_contact_pattern_count(net);
  C->ptr = calloc(net->nred + 1, sizeof(size_t));
  if (!C->ptr) return -1;
  for (int pass = 0; pass < 2; ++pass) {
    for (size_t i = 0; i < np; ++i) {
      size_t idx[12];
      int64_t m[12];
      int nm = 0;
      rn_contact_pattern_idx(net, i, idx);
      for (int k = 0; k < 12; ++k)
        if ((m[nm] = net->map[idx[k]]) >= 0) nm++;
      for (int k = 0; k < nm; ++k) {
        if (pass == 0) {
          C->ptr[m[k] + 1] += (size_t)nm;
          continue;
        }
        for (int l = 0; l < nm; ++l) C->col[C->ptr[m[k]]++] = (int32_t)m[l];
      }
    }
    if (pass == 0) {
      for (size_t r = 0; r < net->nred; ++r) C->ptr[r + 1] += C->ptr[r];
      if (!(C->col = malloc((C->ptr[net->nred] + 1) * sizeof(int32_t)))) return -1;
    }
  }
  for (size_t r = net->nred; r > 0; --r) C->ptr[r] = C->ptr[r - 1];
  C->ptr[0] = 0;
  return 0;
}

/* Periodic cells: the rows flagged by rn_cell_pattern_flags (1: a stencil at
 * a periodic image, 2: a strain DOF), listed once so that each row takes its
 * strain columns (and each strain row the flagged rows) without a pass over
 * every row: the pattern is built in time linear in its size. */
typedef struct cell_rows {
  const unsigned char *flag; /* [nred] */
  int32_t *all, *strain;     /* the flagged rows, the strain rows (ascending) */
  size_t nall, nstrain;
} cell_rows;

static int cell_rows_build(const rn_network *net, const unsigned char *touch,
                           cell_rows *T) {
  T->flag = touch;
  T->nall = T->nstrain = 0;
  T->all = malloc((net->nred ? net->nred : 1) * sizeof(int32_t));
  T->strain = malloc(6 * sizeof(int32_t));
  if (!T->all || !T->strain) return -1;
  for (size_t q = 0; q < net->nred; ++q) {
    if (touch[q]) T->all[T->nall++] = (int32_t)q;
    if (touch[q] == 2 && T->nstrain < 6) T->strain[T->nstrain++] = (int32_t)q;
  }
  return 0;
}

/* Candidate columns of row r appended to b (unsorted, with duplicates). */
static int row_candidates(const rn_network *net, const row_lists *L, const size_t *lo,
                          const size_t *hi, const cell_rows *T, const contact_rows *C,
                          size_t r, col_buf *b) {
  for (size_t p = L->fptr[r]; p < L->fptr[r + 1]; ++p) {
    size_t a = L->full[p];
    b->examined += hi[a] - lo[a] + 1;
    for (size_t c = lo[a]; c <= hi[a]; ++c)
      if (net->map[c] >= 0 && push(b, net->map[c])) return -1;
  }
  for (size_t p = L->jptr[r]; p < L->jptr[r + 1]; ++p) {
    const rn_joint *J = &net->joints[L->jnt[p]];
    b->examined += (size_t)joint_stencil_n(J);
    for (int k = 0; k < joint_stencil_n(J); ++k)
      if (net->map[J->idx[k]] >= 0 && push(b, net->map[J->idx[k]])) return -1;
  }
  if (T && T->flag[r]) { /* periodic: rows coupled to the strain DOFs */
    const int32_t *q = T->flag[r] == 2 ? T->all : T->strain;
    size_t nq = T->flag[r] == 2 ? T->nall : T->nstrain;
    b->examined += nq;
    for (size_t k = 0; k < nq; ++k)
      if (push(b, q[k])) return -1;
  }
  if (C->ptr) /* contact: the pattern pairs' stencils */
    for (size_t p = C->ptr[r]; p < C->ptr[r + 1]; ++p)
      if (push(b, C->col[p])) return -1;
  return 0;
}

/* Rows in order: candidates sorted and made unique in place at the end of
 * the column buffer (for plain rods they are already sorted and unique). */
static rn_status fill_rows(rn_network *net, const row_lists *L, const size_t *lo,
                           const size_t *hi, const cell_rows *T, const contact_rows *C,
                           col_buf *b) {
  for (size_t row = 0; row < net->nred; ++row) {
    size_t start = b->n, u = start;
    net->rowptr[row] = (int64_t)start;
    if (row_candidates(net, L, lo, hi, T, C, row, b)) return RN_ERR_ALLOC;
    if (!increasing(b->c + start, b->n - start)) /* rows away from joints are */
      sort_columns(b->c + start, b->n - start);
    for (size_t p = start; p < b->n; ++p) {
      size_t c = (size_t)b->c[p], d = c > row ? c - row : row - c;
      if (u > start && b->c[u - 1] == b->c[p]) continue;
      b->c[u++] = b->c[p];
      if (d > net->bandwidth) net->bandwidth = d;
    }
    b->n = u;
  }
  net->rowptr[net->nred] = (int64_t)b->n;
  return RN_OK;
}

static int64_t csr_find(const rn_network *net, int64_t r, int64_t c);

/* The band row descriptors (network_internal.h) from the pattern and the rod
 * stencil ranges [lo(a), hi(a)]. */
static rn_status build_band_rows(rn_network *net, const size_t *lo, const size_t *hi) {
  net->band = malloc((net->nfull ? net->nfull : 1) * sizeof(rn_band_row));
  if (!net->band) return RN_ERR_ALLOC;
  for (size_t a = 0; a < net->nfull; ++a) {
    rn_band_row *b = &net->band[a];
    int64_t r = net->map[a], m0 = net->map[lo[a]], p0;
    b->pos = RN_BAND_NONE;
    b->lo = (signed char)((int64_t)lo[a] - (int64_t)a);
    b->hi = (signed char)((int64_t)hi[a] - (int64_t)a);
    if (r < 0 || (lo[a] == a && hi[a] == a)) continue; /* fixed, or not in a rod */
    b->pos = RN_BAND_SEARCH;
    if (m0 < 0 || (p0 = csr_find(net, r, m0)) < 0) continue;
    int ok = p0 + (int64_t)(hi[a] - lo[a]) < net->rowptr[r + 1];
    for (size_t c = lo[a]; c <= hi[a] && ok; ++c) {
      int64_t k = (int64_t)(c - lo[a]);
      ok = net->map[c] == m0 + k && net->col[p0 + k] == m0 + k;
    }
    if (ok) b->pos = p0;
  }
  return RN_OK;
}

/* complete[a] = 0 for the full DOFs that more than one segment of the
 * Hessian assembly touches (the rod segmentation of assembly.c for the
 * Hessian: edges [j0, j0 + RN_ROD_SEGMENT), next j0 = previous end - 1; the
 * shared edge's stretching counted by the first). */
static void mark_split_rows(const rn_network *net, unsigned char *complete, int *seg_of) {
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    size_t off = r->off, n = rn_dof_rod_count(r->nv);
    for (size_t i = 0; i < n; ++i) seg_of[i] = -1;
    for (int j0 = 0, sid = 0;; ++sid) {
      int j1 = j0 + RN_ROD_SEGMENT < r->ne ? j0 + RN_ROD_SEGMENT : r->ne;
      /* stencils of the segment: stretched edges and vertices */
      for (int k = 0; k < 2; ++k) {
        int first = k == 0 ? (j0 ? j0 + 1 : j0) : j0 + 1, last = j1 - 1;
        for (int m = first; m <= last; ++m) {
          size_t s = k == 0 ? rn_dof_edge_stencil(0, m) : rn_dof_vertex_stencil(0, m);
          int len = k == 0 ? RN_EDGE_STENCIL : RN_VERTEX_STENCIL;
          if (k == 1 && m > r->nv - 2) break;
          for (size_t i = s; i < s + (size_t)len; ++i) {
            if (seg_of[i] >= 0 && seg_of[i] != sid) complete[off + i] = 0;
            seg_of[i] = sid;
          }
        }
      }
      if (j1 == r->ne) break;
      j0 = j1 - 1;
    }
  }
}

static int cmp_i64_pair(const void *a, const void *b) {
  int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
  return (x > y) - (x < y);
}

/* The rows whose rod band run is stored (assign), and the CSR ranges that
 * must be zeroed instead. */
static rn_status build_assign(rn_network *net) {
  size_t nf = net->nfull ? net->nfull : 1, nass = 0, maxlen = 1;
  unsigned char *complete = malloc(nf), *nrows = calloc(net->nred ? net->nred : 1, 1);
  int *seg_of = NULL;
  int64_t *iv = NULL;
  rn_status st = RN_ERR_ALLOC;
  for (int ir = 0; ir < net->nrods; ++ir)
    if (rn_dof_rod_count(net->rods[ir].nv) > maxlen)
      maxlen = rn_dof_rod_count(net->rods[ir].nv);
  seg_of = malloc(maxlen * sizeof(int));
  iv = malloc(2 * nf * sizeof(int64_t));
  net->hzero = malloc(2 * (nf + 1) * sizeof(int64_t));
  if (!complete || !nrows || !seg_of || !iv || !net->hzero) goto done;
  memset(complete, 1, nf);
  mark_split_rows(net, complete, seg_of);
  for (size_t a = 0; a < net->nfull; ++a) /* full rows per reduced row */
    if (net->map[a] >= 0 && nrows[net->map[a]] < 2) nrows[net->map[a]]++;
  for (size_t a = 0; a < net->nfull; ++a) {
    rn_band_row *b = &net->band[a];
    b->assign = (signed char)(b->pos >= 0 && complete[a] && nrows[net->map[a]] == 1);
    if (!b->assign) continue;
    iv[2 * nass] = b->pos;
    iv[2 * nass + 1] = b->pos + b->hi - b->lo + 1;
    nass++;
  }
  qsort(iv, nass, 2 * sizeof(int64_t), cmp_i64_pair);
  net->nhzero = 0;
  int64_t at = 0;
  for (size_t k = 0; k <= nass; ++k) {
    int64_t end = k < nass ? iv[2 * k] : (int64_t)net->nnz;
    if (end > at) {
      net->hzero[2 * net->nhzero] = at;
      net->hzero[2 * net->nhzero + 1] = end - at;
      net->nhzero++;
    }
    if (k < nass) at = iv[2 * k + 1];
  }
  st = RN_OK;
done:
  free(complete);
  free(nrows);
  free(seg_of);
  free(iv);
  return st;
}

void rn_hessian_zero(const rn_network *net, double *vals) {
  for (size_t k = 0; k < net->nhzero; ++k)
    memset(vals + net->hzero[2 * k], 0, (size_t)net->hzero[2 * k + 1] * sizeof(double));
}

void rn_hessian_pattern_free(rn_network *net) {
  free(net->rowptr);
  free(net->col);
  free(net->band);
  free(net->rod_direct);
  free(net->hzero);
  net->rowptr = NULL;
  net->col = NULL;
  net->band = NULL;
  net->rod_direct = NULL;
  net->hzero = NULL;
  net->nhzero = 0;
}

/* For each rod the longest run of edges [lo, hi) whose stencils read DOFs
 * that are free and consecutive in the reduced vector, in order (the
 * assembly evaluates them in place); none of an aliased joint end. */
static rn_status build_rod_direct(rn_network *net) {
  net->rod_direct = malloc(2 * (size_t)(net->nrods ? net->nrods : 1) * sizeof(int));
  if (!net->rod_direct) return RN_ERR_ALLOC;
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    size_t n = rn_dof_rod_count(r->nv);
    size_t best_a = 0, best_b = 0, a = 0; /* runs [a, b) of the full slice */
    for (size_t i = 0; i <= n; ++i) {
      int64_t mi = i < n ? net->map[r->off + i] : -1;
      if (i < n && net->cell && net->cell->slot[r->off + i] >= 0)
        mi = -1; /* a periodic image end: its value needs the shift (core/gather.c) */
      int joins = i > a && mi >= 0 && mi == net->map[r->off + i - 1] + 1;
      if (i == a && mi >= 0) continue; /* a run starts */
      if (joins) continue;
      if (i - a > best_b - best_a) {
        best_a = a;
        best_b = i;
      }
      a = mi >= 0 ? i : i + 1;
    }
    /* edges j with 4j >= best_a and 4j + 6 < best_b */
    int lo = (int)((best_a + 3) / 4), hi = best_b >= 3 ? (int)((best_b - 3) / 4) : 0;
    if (hi > r->ne) hi = r->ne;
    if (hi < lo) hi = lo;
    net->rod_direct[2 * ir] = lo;
    net->rod_direct[2 * ir + 1] = hi;
  }
  return RN_OK;
}

rn_status rn_build_hessian_pattern(rn_network *net) {
  size_t *lo = malloc((net->nfull ? net->nfull : 1) * sizeof(size_t));
  size_t *hi = malloc((net->nfull ? net->nfull : 1) * sizeof(size_t));
  row_lists L = {NULL, NULL, NULL, NULL};
  col_buf b = {NULL, 0, 0, 0};
  unsigned char *touch = NULL;
  contact_rows C = {NULL, NULL};
  cell_rows T = {NULL, NULL, NULL, 0, 0};
  rn_status st = RN_ERR_ALLOC;
  net->rowptr = malloc((net->nred + 1) * sizeof(int64_t));
  if (!lo || !hi || !net->rowptr || row_lists_build(net, &L)) goto done;
  stencil_ranges(net, lo, hi);
  net->bandwidth = 0;
  if (net->cell) { /* rows of the stencils at periodic images, strain rows */
    touch = calloc(net->nred ? net->nred : 1, 1);
    if (!touch) goto done;
    rn_cell_pattern_flags(net, lo, hi, touch);
    if (cell_rows_build(net, touch, &T)) goto done;
  }
  if (net->contact && contact_rows_build(net, &C)) goto done;
  if (fill_rows(net, &L, lo, hi, net->cell ? &T : NULL, &C, &b)) goto done;
  net->nnz = b.n;
  net->pattern_work = b.examined;
  { /* shrink to fit (also allocates when there are no entries) */
    int32_t *p = realloc(b.c, (b.n ? b.n : 1) * sizeof(int32_t));
    if (p) b.c = p;
  }
  net->col = b.c;
  b.c = NULL;
  st = net->col ? build_band_rows(net, lo, hi) : RN_ERR_ALLOC;
  if (st == RN_OK) st = build_rod_direct(net);
  if (st == RN_OK) st = build_assign(net);
done:
  free(T.all);
  free(T.strain);
  free(touch);
  free(C.ptr);
  free(C.col);
  free(b.c);
  free(lo);
  free(hi);
  row_lists_free(&L);
  return st;
}

rn_status rn_rebuild_hessian_pattern(rn_network *net) {
  int64_t *rowptr = net->rowptr, *hzero = net->hzero;
  int32_t *col = net->col;
  rn_band_row *band = net->band;
  int *rod_direct = net->rod_direct;
  size_t nhzero = net->nhzero, nnz = net->nnz, bandwidth = net->bandwidth;
  net->rowptr = NULL;
  net->col = NULL;
  net->band = NULL;
  net->rod_direct = NULL;
  net->hzero = NULL;
  rn_status st = rn_build_hessian_pattern(net);
  if (st) { /* back to the old one */
    rn_hessian_pattern_free(net);
    net->rowptr = rowptr;
    net->col = col;
    net->band = band;
    net->rod_direct = rod_direct;
    net->hzero = hzero;
    net->nhzero = nhzero;
    net->nnz = nnz;
    net->bandwidth = bandwidth;
    return st;
  }
  free(rowptr);
  free(col);
  free(band);
  free(rod_direct);
  free(hzero);
  return RN_OK;
}

/* Position of column c in row r, or -1. */
static int64_t csr_find(const rn_network *net, int64_t r, int64_t c) {
  int64_t lo = net->rowptr[r], hi = net->rowptr[r + 1] - 1;
  while (lo <= hi) {
    int64_t mid = lo + (hi - lo) / 2;
    if (net->col[mid] == c) return mid;
    if (net->col[mid] < c)
      lo = mid + 1;
    else
      hi = mid - 1;
  }
  return -1;
}

void rn_csr_add_block(const rn_network *net, size_t s, int n, const double *H,
                      double *vals) {
  for (int k = 0; k < n; ++k) {
    int64_t r = net->map[s + (size_t)k];
    if (r < 0) continue;
    for (int l = 0; l < n; ++l) {
      int64_t c = net->map[s + (size_t)l], pos;
      if (c < 0) continue;
      pos = csr_find(net, r, c);
      if (pos >= 0) vals[pos] += H[k * n + l];
    }
  }
}

int rn_csr_add_band(const rn_network *net, size_t s, int n, const double *band,
                    double *vals) {
  double big = 0.0; /* values above RN_HESS_BOUND or not finite */
  for (int i = 0; i < n; ++i) {
    size_t a = s + (size_t)i;
    const rn_band_row *b = &net->band[a];
    /* row[c - a] = entry (a, c) */
    const double *row = band + (size_t)i * RNK_BAND + RNK_BAND_HALF;
    if (b->pos >= 0) {
      double *v = vals + b->pos - b->lo;
      if (b->assign)
        for (int d = b->lo; d <= b->hi; ++d) {
          v[d] = row[d];
          big += fabs(row[d]) <= RN_HESS_BOUND ? 0.0 : 1.0;
        }
      else
        for (int d = b->lo; d <= b->hi; ++d) {
          v[d] += row[d];
          big += fabs(row[d]) <= RN_HESS_BOUND ? 0.0 : 1.0;
        }
    } else if (b->pos == RN_BAND_SEARCH) {
      int64_t r = net->map[a];
      for (int d = b->lo; d <= b->hi; ++d) {
        int64_t c = net->map[(size_t)((int64_t)a + d)], pos;
        if (c < 0 || row[d] == 0.0) continue;
        big += fabs(row[d]) <= RN_HESS_BOUND ? 0.0 : 1.0;
        if ((pos = csr_find(net, r, c)) >= 0) vals[pos] += row[d];
      }
    }
  }
  return big == 0.0;
}

void rn_csr_add_block_idx(const rn_network *net, const size_t *idx, int n,
                          const double *H, double *vals) {
  for (int k = 0; k < n; ++k) {
    int64_t r = net->map[idx[k]];
    if (r < 0) continue;
    for (int l = 0; l < n; ++l) {
      int64_t c = net->map[idx[l]], pos;
      if (c < 0) continue;
      pos = csr_find(net, r, c);
      if (pos >= 0) vals[pos] += H[k * n + l];
    }
  }
}

rn_status rn_network_hessian_pattern(const rn_network *net, size_t *nnz,
                                     const int64_t **rowptr, const int32_t **col) {
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, "rn_network_hessian_pattern"))) return st;
  if (!nnz || !rowptr || !col)
    return rn_fail(net->ctx, RN_ERR_ARG, "rn_network_hessian_pattern", "NULL output");
  *nnz = net->nnz;
  *rowptr = net->rowptr;
  *col = net->col;
  return RN_OK;
}

size_t rn_network_hessian_bandwidth(const rn_network *net) {
  return (net && net->finalized) ? net->bandwidth : 0;
}

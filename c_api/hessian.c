/* hessian.c - CSR pattern of the reduced Hessian (fixed at finalize) and the
 * scatter of stencil blocks into it. */
#include <stdlib.h>

#include "network_internal.h"

/* Widens [lo, hi] of every DOF of a stencil slice [s, s + n) to the slice. */
static void cover(size_t *lo, size_t *hi, size_t s, int n) {
  for (size_t a = s; a < s + (size_t)n; ++a) {
    if (s < lo[a]) lo[a] = s;
    if (s + (size_t)n - 1 > hi[a]) hi[a] = s + (size_t)n - 1;
  }
}

/* Every stencil is a contiguous slice of its rod's full vector and stencils
 * that contain a DOF overlap, so the DOFs coupled to a are the range
 * [lo(a), hi(a)]; the free ones form row map[a] (sorted, as map is
 * increasing). */
static void stencil_ranges(const rn_network *net, size_t *lo, size_t *hi) {
  for (size_t a = 0; a < net->nfull; ++a) {
    lo[a] = a;
    hi[a] = a;
  }
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    for (int j = 0; j < r->ne; ++j)
      cover(lo, hi, rn_dof_edge_stencil(r->off, j), RN_EDGE_STENCIL);
    for (int i = 1; i < r->nv - 1; ++i)
      cover(lo, hi, rn_dof_vertex_stencil(r->off, i), RN_VERTEX_STENCIL);
  }
}

static size_t fill_rows(rn_network *net, const size_t *lo, const size_t *hi, int fill) {
  size_t nnz = 0;
  for (size_t row = 0; row < net->nred; ++row) {
    size_t a = (size_t)net->red2full[row];
    if (fill) net->rowptr[row] = (int64_t)nnz;
    for (size_t b = lo[a]; b <= hi[a]; ++b) {
      if (net->map[b] < 0) continue;
      if (fill) {
        size_t d = row > (size_t)net->map[b] ? row - (size_t)net->map[b]
                                             : (size_t)net->map[b] - row;
        net->col[nnz] = (int32_t)net->map[b];
        if (d > net->bandwidth) net->bandwidth = d;
      }
      nnz++;
    }
  }
  if (fill) net->rowptr[net->nred] = (int64_t)nnz;
  return nnz;
}

rn_status rn_build_hessian_pattern(rn_network *net) {
  size_t *lo = malloc((net->nfull ? net->nfull : 1) * sizeof(size_t));
  size_t *hi = malloc((net->nfull ? net->nfull : 1) * sizeof(size_t));
  rn_status st = RN_ERR_ALLOC;
  if (!lo || !hi) goto done;
  stencil_ranges(net, lo, hi);
  net->nnz = fill_rows(net, lo, hi, 0);
  net->rowptr = malloc((net->nred + 1) * sizeof(int64_t));
  net->col = malloc((net->nnz ? net->nnz : 1) * sizeof(int32_t));
  if (!net->rowptr || !net->col) goto done;
  net->bandwidth = 0;
  fill_rows(net, lo, hi, 1);
  st = RN_OK;
done:
  free(lo);
  free(hi);
  return st;
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

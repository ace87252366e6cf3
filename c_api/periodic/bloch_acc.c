/* bloch_acc.c - the accumulator of stencil Hessian blocks onto the dense Bloch
 * matrix of a periodic cell, or onto triplets for its sparse form (homog/bloch.c;
 * docs/homogenization.md, "Stability"): each entry (k, l) of a stencil adds H_kl w(phi_l
 * - phi_k) at the Bloch DOFs of its entries, phi the phase of the entry's image record.
 */
#include <math.h>
#include <stdlib.h>

#include "periodic/periodic.h"

enum { BLOCH_MAX_STENCIL = 4 * RN_ROD_SEGMENT + 3 };

/* Phase of the own image shift of the end whose slot is joint stencil entry e
 * (its material angle belongs to the rod copy in the cell -n: phase -k . s). */
static void joint_end_phase(const rn_network *net, const rn_bloch_acc *b,
                            const rn_joint *J, int e, double *ph1, double *ph2) {
  int rigid = rn_joint_has_rotation(J), e0 = rn_joint_local_end(rigid, 0), k, m;
  double s[3] = {0.0, 0.0, 0.0};
  if (!J || !J->image || e < e0 || (e - e0) % 4 != 3) return;
  k = (e - e0) / 4;
  for (int q = 0; q < 3; ++q)
    for (m = 0; m < net->cell->dim; ++m) s[q] += J->image[3 * k + m] * net->cell->a[m][q];
  for (int q = 0; q < 3; ++q) {
    *ph1 -= b->k1[q] * s[q];
    *ph2 -= b->k2[q] * s[q];
  }
}

/* Bloch DOF and phase of stencil entry k. */
static int64_t entry(const rn_network *net, const rn_bloch_acc *b, size_t s,
                     const size_t *idx, const int32_t *img, const rn_joint *J, int k,
                     double *ph1, double *ph2) {
  const rn_cell *c = net->cell;
  size_t a = idx ? idx[k] : s + (size_t)k;
  int32_t sl = idx ? (img ? img[k] : -1) : c->slot[a];
  *ph1 = *ph2 = 0.0;
  if (J) joint_end_phase(net, b, J, k, ph1, ph2);
  if (sl < 0) return b->bidx[a];
  *ph1 = b->ph1 ? b->ph1[sl / 3] : 0.0;
  *ph2 = b->ph2 ? b->ph2[sl / 3] : 0.0;
  return b->bidx[c->img[sl / 3].base + (size_t)(sl % 3)];
}

/* Sparse mode: the triplet appended (the array doubled when full). */
static void add_triplet(rn_bloch_acc *b, int64_t r, int64_t col, double re, double im) {
  if (b->trip_failed) return;
  if (b->ntrip == b->cap_trip) {
    size_t cap = b->cap_trip ? 2 * b->cap_trip : 1024;
    rn_bloch_trip *t = realloc(b->trip, cap * sizeof *t);
    if (!t) {
      b->trip_failed = 1;
      return;
    }
    b->trip = t;
    b->cap_trip = cap;
  }
  b->trip[b->ntrip++] = (rn_bloch_trip){r, col, re, im};
}

static void add_entry(rn_bloch_acc *b, int64_t r, int64_t col, double h, double d1,
                      double d2) {
  if (!b->re) {
    if (b->raw)
      add_triplet(b, r, col, h, d1);
    else if (b->moment)
      add_triplet(b, r, col,
                  b->order == 0   ? h
                  : b->order == 1 ? h * d1
                                  : h * d1 * d2,
                  0.0);
    else
      add_triplet(b, r, col, h * cos(d1), h * sin(d1));
    return;
  }
  size_t at = (size_t)r * b->n + (size_t)col;
  if (b->im) {
    b->re[at] += h * cos(d1);
    b->im[at] += h * sin(d1);
  } else
    b->re[at] += b->order == 0 ? h : b->order == 1 ? h * d1 : h * d1 * d2;
}

void rn_bloch_add_block(const rn_network *net, rn_bloch_acc *b, size_t s,
                        const size_t *idx, const int32_t *img, int n, const double *H,
                        const rn_joint *J) {
  for (int k = 0; k < n; ++k) {
    double pk1, pk2;
    int64_t r = entry(net, b, s, idx, img, J, k, &pk1, &pk2);
    if (r < 0) continue;
    for (int l = 0; l < n; ++l) {
      double pl1, pl2;
      int64_t col = entry(net, b, s, idx, img, J, l, &pl1, &pl2);
      if (col < 0 || H[k * n + l] == 0.0) continue;
      add_entry(b, r, col, H[k * n + l], pl1 - pk1, pl2 - pk2);
    }
  }
}

void rn_bloch_add_band(const rn_network *net, rn_bloch_acc *b, size_t s, int n,
                       const double *band) {
  int64_t bi[BLOCH_MAX_STENCIL];
  double p1[BLOCH_MAX_STENCIL], p2[BLOCH_MAX_STENCIL];
  if (n > BLOCH_MAX_STENCIL) return; /* (segments are at most this long) */
  for (int k = 0; k < n; ++k)
    bi[k] = entry(net, b, s, NULL, NULL, NULL, k, &p1[k], &p2[k]);
  for (int i = 0; i < n; ++i) {
    const double *row = band + (size_t)i * RNK_BAND + RNK_BAND_HALF;
    if (bi[i] < 0) continue;
    for (int d = -RNK_BAND_HALF; d <= RNK_BAND_HALF; ++d) {
      int l = i + d;
      if (l < 0 || l >= n || bi[l] < 0 || row[d] == 0.0) continue;
      add_entry(b, bi[i], bi[l], row[d], p1[l] - p1[i], p2[l] - p2[i]);
    }
  }
}

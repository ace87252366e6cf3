/* gather.c - the gathers and scatters of the stencils: a stencil's local
 * vector from the reduced state (free entries) and net->xfull (fixed ones),
 * and back; with periodic cells, the image entries add their lattice shift
 * (docs/homogenization.md): one gather with its read rule as a parameter, one
 * scatter. */
#include <stdlib.h>

#include "core/network_internal.h"

/* ---- stencil gather / scatter --------------------------------------------- */
void rn_gather(const rn_network *net, const double *x, size_t s, int n, double *q) {
  for (int k = 0; k < n; ++k) {
    int64_t m = net->map[s + (size_t)k];
    q[k] = m >= 0 ? x[m] : net->xfull[s + (size_t)k];
  }
  if (net->cell) rn_cell_gather(net, x, s, NULL, NULL, n, q);
}

void rn_gather_dir(const rn_network *net, const double *v, size_t s, int n, double *q) {
  for (int k = 0; k < n; ++k) {
    int64_t m = net->map[s + (size_t)k];
    q[k] = m >= 0 ? v[m] : 0.0;
  }
  if (net->cell) rn_cell_gather_dir(net, v, s, NULL, NULL, n, q);
}

void rn_gather_fixed_dir(const rn_network *net, const double *vfull, size_t s, int n,
                         double *q) {
  for (int k = 0; k < n; ++k)
    q[k] = net->map[s + (size_t)k] >= 0 ? 0.0 : vfull[s + (size_t)k];
  if (net->cell) rn_cell_gather_fixed_dir(net, vfull, s, NULL, NULL, n, q);
}

void rn_scatter_add(const rn_network *net, const double *gl, size_t s, int n, double *g) {
  for (int k = 0; k < n; ++k) {
    int64_t m = net->map[s + (size_t)k];
    if (m >= 0) g[m] += gl[k];
  }
  if (net->cell) rn_cell_scatter(net, gl, s, NULL, NULL, n, g);
}

void rn_expand_state(const rn_network *net, const double *x, double *full) {
  for (size_t a = 0; a < net->nfull; ++a) {
    int64_t m = net->map[a];
    full[a] = m >= 0 ? x[m] : net->xfull[a];
  }
  if (net->cell) rn_cell_expand(net, full);
}

void rn_gather_idx(const rn_network *net, const double *x, const size_t *idx, int n,
                   double *q) {
  for (int k = 0; k < n; ++k) {
    int64_t m = net->map[idx[k]];
    q[k] = m >= 0 ? x[m] : net->xfull[idx[k]];
  }
}

void rn_gather_dir_idx(const rn_network *net, const double *v, const size_t *idx, int n,
                       double *q) {
  for (int k = 0; k < n; ++k) {
    int64_t m = net->map[idx[k]];
    q[k] = m >= 0 ? v[m] : 0.0;
  }
}

void rn_gather_fixed_dir_idx(const rn_network *net, const double *vfull,
                             const size_t *idx, int n, double *q) {
  for (int k = 0; k < n; ++k) q[k] = net->map[idx[k]] >= 0 ? 0.0 : vfull[idx[k]];
}

void rn_scatter_add_idx(const rn_network *net, const double *gl, const size_t *idx, int n,
                        double *g) {
  for (int k = 0; k < n; ++k) {
    int64_t m = net->map[idx[k]];
    if (m >= 0) g[m] += gl[k];
  }
}

/* ---- periodic cells: image entries ---------------------------------------- */
void rn_cell_shift(const rn_network *net, const rn_image *im, const double *full,
                   double out[3]) {
  const rn_cell *c = net->cell;
  for (int k = 0; k < 3; ++k) {
    out[k] = im->s[k];
    for (int v = 0; v < c->nstrain; ++v) out[k] += im->T[k][v] * full[c->off + (size_t)v];
  }
}

/* The read rule of a gather: full entry a reads free[map[a]] if it is free,
 * fixed[a] if it is fixed; a NULL side reads 0.  The state: (x, xfull); a
 * direction: (v, NULL); a direction on the fixed entries: (NULL, vfull). */
typedef struct dof_src {
  const double *free, *fixed;
} dof_src;

static inline double src_value(const rn_network *net, dof_src src, size_t a) {
  int64_t m = net->map[a];
  if (m >= 0) return src.free ? src.free[m] : 0.0;
  return src.fixed ? src.fixed[a] : 0.0;
}

/* The one gather of the image entries of a stencil (contiguous at s, or by the
 * image list img): q[k] = the unshifted entry (+ the shift at zero strain if
 * with_shift) + T eps, every value read from src. */
static inline void cell_gather(const rn_network *net, dof_src src, int with_shift,
                               size_t s, const size_t *idx, const int32_t *img, int n,
                               double *q) {
  const rn_cell *c = net->cell;
  double eps[6];
  int have = 0;
  if (!c || (idx && !img)) return;
  for (int k = 0; k < n; ++k) {
    int32_t sl = rn_cell_entry_slot(c, s, img, k);
    if (sl < 0) continue;
    const rn_image *im = &c->img[sl / 3];
    int comp = sl % 3;
    if (!have) {
      for (int w = 0; w < c->nstrain; ++w)
        eps[w] = src_value(net, src, c->off + (size_t)w);
      have = 1;
    }
    q[k] = src_value(net, src, im->base + (size_t)comp);
    if (with_shift) q[k] += im->s[comp];
    for (int w = 0; w < c->nstrain; ++w) q[k] += im->T[comp][w] * eps[w];
  }
}

/* The one scatter (the transpose): T^T gl onto the strain entries, of the
 * reduced vector g (free ones) or of the full-layout vector gfull (all). */
static inline void cell_scatter(const rn_network *net, const double *gl, size_t s,
                                const size_t *idx, const int32_t *img, int n, double *g,
                                double *gfull) {
  const rn_cell *c = net->cell;
  if (!c || (idx && !img)) return;
  for (int k = 0; k < n; ++k) {
    int32_t sl = rn_cell_entry_slot(c, s, img, k);
    if (sl < 0) continue;
    const rn_image *im = &c->img[sl / 3];
    int comp = sl % 3;
    for (int w = 0; w < c->nstrain; ++w) {
      size_t a = c->off + (size_t)w;
      if (gfull)
        gfull[a] += im->T[comp][w] * gl[k];
      else if (net->map[a] >= 0)
        g[net->map[a]] += im->T[comp][w] * gl[k];
    }
  }
}

void rn_cell_gather(const rn_network *net, const double *x, size_t s, const size_t *idx,
                    const int32_t *img, int n, double *q) {
  cell_gather(net, (dof_src){x, net->xfull}, 1, s, idx, img, n, q);
}

void rn_cell_gather_dir(const rn_network *net, const double *v, size_t s,
                        const size_t *idx, const int32_t *img, int n, double *q) {
  cell_gather(net, (dof_src){v, NULL}, 0, s, idx, img, n, q);
}

void rn_cell_gather_fixed_dir(const rn_network *net, const double *vfull, size_t s,
                              const size_t *idx, const int32_t *img, int n, double *q) {
  cell_gather(net, (dof_src){NULL, vfull}, 0, s, idx, img, n, q);
}

void rn_cell_scatter(const rn_network *net, const double *gl, size_t s, const size_t *idx,
                     const int32_t *img, int n, double *g) {
  cell_scatter(net, gl, s, idx, img, n, g, NULL);
}

void rn_cell_scatter_full(const rn_network *net, const double *gl, size_t s,
                          const size_t *idx, const int32_t *img, int n, double *gfull) {
  cell_scatter(net, gl, s, idx, img, n, NULL, gfull);
}

void rn_cell_expand(const rn_network *net, double *full) {
  const rn_cell *c = net->cell;
  if (!c || !c->slot) return;
  for (size_t a = 0; a < net->nfull; ++a) {
    int32_t sl = c->slot[a];
    double sh[3];
    if (sl < 0) continue;
    rn_cell_shift(net, &c->img[sl / 3], full, sh);
    full[a] = full[c->img[sl / 3].base + (size_t)(sl % 3)] + sh[sl % 3];
  }
}

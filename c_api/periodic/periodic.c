/* periodic.c - periodic cells (docs/homogenization.md): lattice vectors,
 * macroscopic strain DOFs, rod ends attached to periodic images of joints.
 *
 * The cell deforms with the symmetric macroscopic deformation gradient
 * F = I + sum_v eps_v B_v (Voigt components with engineering shear) applied to
 * the lattice vectors; joint and rod DOFs are positions as usual (their
 * periodic fluctuation plus the affine part).  A rod end at the image n of a
 * joint sits at x_J + F s, s = sum_m n_m a_m: an affine alias of the joint
 * position.  Only the gathers and scatters of assembly know about it
 * (core/gather.c) and the Hessian rows (this file); the kernels do not change.
 * Symmetric F removes the rigid rotations; finalize pins one joint (the
 * anchor) unless a BC already fixes a position. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "periodic/periodic.h"

void rn_cell_free(rn_cell **c) {
  if (!c || !*c) return;
  free((*c)->img);
  free((*c)->slot);
  free(*c);
  *c = NULL;
}

/* Strain basis: 2D (11, 22, 12), 3D (11, 22, 33, 23, 13, 12); shear
 * components are engineering strains, B = (e_i e_j^T + e_j e_i^T) / 2. */
static void strain_basis(rn_cell *c) {
  static const int pairs2[3][2] = {{0, 0}, {1, 1}, {0, 1}};
  static const int pairs3[6][2] = {{0, 0}, {1, 1}, {2, 2}, {1, 2}, {0, 2}, {0, 1}};
  memset(c->B, 0, sizeof(c->B));
  for (int v = 0; v < c->nstrain; ++v) {
    int i = c->dim == 2 ? pairs2[v][0] : pairs3[v][0];
    int j = c->dim == 2 ? pairs2[v][1] : pairs3[v][1];
    c->B[v][3 * i + j] += 0.5;
    c->B[v][3 * j + i] += 0.5;
  }
}

rn_status rn_network_set_periodic(rn_network *net, int dim, const double *vectors) {
  static const char *where = "rn_network_set_periodic";
  rn_status st;
  rn_cell *c;
  double n[3], scale = 0.0;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_building(net, where))) return st;
  if (net->cell)
    return rn_fail(net->ctx, RN_ERR_STATE, where, "the network is already periodic");
  if (net->njoints > 0 || net->nrods > 0)
    return rn_fail(net->ctx, RN_ERR_STATE, where,
                   "declare the periodic cell before adding rods and joints");
  if (dim != 2 && dim != 3)
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "a periodic cell has 2 or 3 lattice vectors, got %d", dim);
  if (!vectors) return rn_fail(net->ctx, RN_ERR_ARG, where, "vectors is NULL");
  if (!rn_all_finite(3 * (size_t)dim, vectors))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "a lattice vector is not finite");
  if (dim == 2 && (vectors[2] != 0.0 || vectors[5] != 0.0))
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "the lattice vectors of a 2D cell must lie in the xy plane (z = 0), "
                   "got z = %g and %g",
                   vectors[2], vectors[5]);
  c = calloc(1, sizeof(*c));
  if (!c) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  c->dim = dim;
  c->nstrain = dim == 2 ? 3 : 6;
  for (int m = 0; m < dim; ++m)
    for (int k = 0; k < 3; ++k) {
      c->a[m][k] = vectors[3 * m + k];
      scale = fmax(scale, fabs(vectors[3 * m + k]));
    }
  n[0] = c->a[0][1] * c->a[1][2] - c->a[0][2] * c->a[1][1];
  n[1] = c->a[0][2] * c->a[1][0] - c->a[0][0] * c->a[1][2];
  n[2] = c->a[0][0] * c->a[1][1] - c->a[0][1] * c->a[1][0];
  if (dim == 2)
    c->measure = fabs(n[2]);
  else
    c->measure = fabs(n[0] * c->a[2][0] + n[1] * c->a[2][1] + n[2] * c->a[2][2]);
  if (!(c->measure > 1e-12 * pow(scale, dim))) {
    free(c);
    return rn_fail(net->ctx, RN_ERR_GEOMETRY, where,
                   "the lattice vectors are degenerate (cell %s %g)",
                   dim == 2 ? "area" : "volume", dim == 2 ? fabs(n[2]) : 0.0);
  }
  strain_basis(c);
  net->cell = c;
  return RN_OK;
}

rn_status rn_cell_check(const rn_network *net, const char *where, int building) {
  rn_status st;
  if ((st =
           building ? rn_net_check_building(net, where) : rn_net_check_final(net, where)))
    return st;
  if (!net->cell)
    return rn_fail(net->ctx, RN_ERR_STATE, where,
                   "the network is not periodic (rn_network_set_periodic)");
  return RN_OK;
}

/* Contradictory control: an applied stress on a strain-controlled (prescribed)
 * component, where it would do nothing (its work is a constant).  The first such
 * component v (0-based), or -1. */
static int stress_on_fixed(int ns, const int *fixed, const double *stress) {
  for (int v = 0; v < ns; ++v)
    if (fixed[v] && stress[v] != 0.0) return v;
  return -1;
}

rn_status rn_network_set_cell_strain(rn_network *net, const int *fixed,
                                     const double *strain) {
  static const char *where = "rn_network_set_cell_strain";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_cell_check(net, where, 1))) return st;
  if (!fixed) return rn_fail(net->ctx, RN_ERR_ARG, where, "fixed is NULL");
  if (strain && !rn_all_finite((size_t)net->cell->nstrain, strain))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "strain is not finite");
  int bad = stress_on_fixed(net->cell->nstrain, fixed, net->cell->stress);
  if (bad >= 0)
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "strain component %d is prescribed but carries an applied stress %g "
                   "(contradictory control: a component is strain- or stress-controlled)",
                   bad + 1, net->cell->stress[bad]);
  for (int v = 0; v < net->cell->nstrain; ++v) {
    net->cell->fixed[v] = fixed[v] != 0;
    net->cell->strain[v] = (fixed[v] && strain) ? strain[v] : 0.0;
  }
  return RN_OK;
}

rn_status rn_network_set_cell_stress(rn_network *net, const double *stress) {
  static const char *where = "rn_network_set_cell_stress";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_cell_check(net, where, 1))) return st;
  if (!stress) return rn_fail(net->ctx, RN_ERR_ARG, where, "stress is NULL");
  if (!rn_all_finite((size_t)net->cell->nstrain, stress))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "stress is not finite");
  int bad = stress_on_fixed(net->cell->nstrain, net->cell->fixed, stress);
  if (bad >= 0)
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "stress component %d is %g but that strain component is prescribed "
                   "(contradictory control: a component is strain- or stress-controlled)",
                   bad + 1, stress[bad]);
  memcpy(net->cell->stress, stress, (size_t)net->cell->nstrain * sizeof(double));
  return RN_OK;
}

rn_status rn_network_set_cell_load(rn_network *net, const double *strain,
                                   const double *stress) {
  static const char *where = "rn_network_set_cell_load";
  if (!net) return RN_ERR_ARG;
  if (!net->cell)
    return rn_fail(net->ctx, RN_ERR_STATE, where,
                   "the network is not periodic (rn_network_set_periodic)");
  const int ns = net->cell->nstrain;
  if ((strain && !rn_all_finite((size_t)ns, strain)) ||
      (stress && !rn_all_finite((size_t)ns, stress)))
    return rn_fail(net->ctx, RN_ERR_NOT_FINITE, where, "strain or stress is not finite");
  int bad = stress ? stress_on_fixed(ns, net->cell->fixed, stress) : -1;
  if (bad >= 0)
    return rn_fail(net->ctx, RN_ERR_ARG, where,
                   "stress component %d is %g but that strain component is prescribed "
                   "(contradictory control: a component is strain- or stress-controlled)",
                   bad + 1, stress[bad]);
  for (int v = 0; v < ns; ++v)
    if (strain && net->cell->fixed[v]) net->cell->strain[v] = strain[v];
  if (stress) memcpy(net->cell->stress, stress, (size_t)ns * sizeof(double));
  if (net->finalized) rn_cell_place(net);
  return RN_OK;
}

rn_status rn_network_cell_hold_strain(rn_network *net, int hold) {
  static const char *where = "rn_network_cell_hold_strain";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_cell_check(net, where, 0))) return st;
  net->cell->held = hold != 0;
  return RN_OK;
}

/* The reduced indices of the free strain components (-1: prescribed). */
static int held_rows(const rn_network *net, int64_t *r) {
  const rn_cell *c = net->cell;
  for (int v = 0; v < c->nstrain; ++v) r[v] = net->map[c->off + (size_t)v];
  return c->nstrain;
}

void rn_cell_hold_zero(const rn_network *net, double *v) {
  int64_t r[6];
  if (!rn_cell_held(net) || !v) return;
  for (int k = 0, n = held_rows(net, r); k < n; ++k)
    if (r[k] >= 0) v[r[k]] = 0.0;
}

void rn_cell_hold_hvp(const rn_network *net, const double *v, double *Hv) {
  int64_t r[6];
  if (!rn_cell_held(net)) return;
  for (int k = 0, n = held_rows(net, r); k < n; ++k)
    if (r[k] >= 0) Hv[r[k]] = rn_cell_owned_here(net) ? v[r[k]] : 0.0;
}

void rn_cell_hold_hessian(const rn_network *net, double *vals) {
  int64_t r[6];
  if (!rn_cell_held(net) || !vals) return;
  const int n = held_rows(net, r), one = rn_cell_owned_here(net);
  for (size_t i = 0; i < net->nred; ++i) {
    int strain_row = 0;
    for (int k = 0; k < n; ++k) strain_row |= r[k] == (int64_t)i;
    for (int64_t pos = net->rowptr[i]; pos < net->rowptr[i + 1]; ++pos) {
      const int64_t c = net->col[pos];
      int strain_col = 0;
      for (int k = 0; k < n; ++k) strain_col |= r[k] == c;
      if (strain_row || strain_col) vals[pos] = (one && c == (int64_t)i) ? 1.0 : 0.0;
    }
  }
}

rn_status rn_network_cell_info(const rn_network *net, int *dim, int *nstrain,
                               double *measure, double vectors[9]) {
  if (!net) return RN_ERR_ARG;
  if (!net->cell) {
    if (dim) *dim = 0;
    if (nstrain) *nstrain = 0;
    if (measure) *measure = 0.0;
    return RN_OK;
  }
  if (dim) *dim = net->cell->dim;
  if (nstrain) *nstrain = net->cell->nstrain;
  if (measure) *measure = net->cell->measure;
  if (vectors) {
    memset(vectors, 0, 9 * sizeof(double));
    for (int m = 0; m < net->cell->dim; ++m)
      memcpy(vectors + 3 * m, net->cell->a[m], 3 * sizeof(double));
  }
  return RN_OK;
}

rn_status rn_network_cell_strain_dofs(const rn_network *net, int64_t *idx) {
  static const char *where = "rn_network_cell_strain_dofs";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_cell_check(net, where, 0))) return st;
  if (!idx) return rn_fail(net->ctx, RN_ERR_ARG, where, "idx is NULL");
  for (int v = 0; v < net->cell->nstrain; ++v)
    idx[v] = net->map[net->cell->off + (size_t)v];
  return RN_OK;
}

rn_status rn_network_cell_strain(const rn_network *net, const double *x, double *strain) {
  static const char *where = "rn_network_cell_strain";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_cell_check(net, where, 0))) return st;
  if (!strain) return rn_fail(net->ctx, RN_ERR_ARG, where, "strain is NULL");
  for (int v = 0; v < net->cell->nstrain; ++v) {
    size_t a = net->cell->off + (size_t)v;
    strain[v] = (x && net->map[a] >= 0) ? x[net->map[a]] : net->xfull[a];
  }
  return RN_OK;
}

/* ---- finalize --------------------------------------------------------------- */
/* The anchor is joint 0 of the whole network (rod 0's vertex 0 if there are no
 * joints).  A part decides from the building calls (positions_fixed counts the
 * clamps and pins of rods and joints other parts hold), pins the anchor if it
 * holds it (owned or ghost: every holder of a DOF agrees that it is fixed) and
 * records anchored on every part. */
void rn_cell_anchor(rn_network *net) {
  rn_cell *c = net->cell;
  if (!c) return;
  c->anchored = 0;
  if (net->part) {
    if (net->positions_fixed) return;
    c->anchored = 1;
    if (rn_net_num_joints_g(net) > 0) {
      if (net->njoints > 0 && net->joints[0].gid == 0) net->joints[0].pinned = RN_FIX_XYZ;
    } else if (net->nrods > 0 && net->rods[0].gid == 0)
      net->rods[0].pinned[0] = RN_FIX_XYZ;
    return;
  }
  for (int ij = 0; ij < net->njoints; ++ij)
    if (rn_joint_fixed_components(&net->joints[ij])) return;
  for (int ir = 0; ir < net->nrods; ++ir)
    for (int v = 0; v < net->rods[ir].nv; ++v)
      if (rn_rod_fixed_components(&net->rods[ir], v)) return;
  c->anchored = 1;
  if (net->njoints > 0)
    net->joints[0].pinned = RN_FIX_XYZ;
  else
    net->rods[0].pinned[0] = RN_FIX_XYZ;
}

void rn_cell_mark(rn_network *net) {
  rn_cell *c = net->cell;
  if (!c) return;
  for (int v = 0; v < c->nstrain; ++v) {
    net->map[c->off + (size_t)v] = c->fixed[v] ? -1 : 0;
    net->xfull[c->off + (size_t)v] = 0.0;
  }
}

void rn_cell_place(rn_network *net) {
  rn_cell *c = net->cell;
  if (!c) return;
  for (int v = 0; v < c->nstrain; ++v)
    if (c->fixed[v]) net->xfull[c->off + (size_t)v] = net->lambda * c->strain[v];
}

/* A new image record: lattice shift s (sign applied), base full index. */
static int add_record(rn_cell *c, size_t base, const double s[3]) {
  rn_image *im;
  if (c->nimg == c->cap_img) {
    int cap = c->cap_img ? 2 * c->cap_img : 16;
    rn_image *p = realloc(c->img, (size_t)cap * sizeof(*p));
    if (!p) return -1;
    c->img = p;
    c->cap_img = cap;
  }
  im = &c->img[c->nimg];
  im->base = base;
  memcpy(im->s, s, sizeof(im->s));
  for (int k = 0; k < 3; ++k)
    for (int v = 0; v < 6; ++v) {
      double t = 0.0;
      if (v < c->nstrain)
        for (int l = 0; l < 3; ++l) t += c->B[v][3 * k + l] * s[l];
      im->T[k][v] = t;
    }
  return c->nimg++;
}

static void lattice_shift(const rn_cell *c, const int *n, double s[3]) {
  for (int k = 0; k < 3; ++k) {
    s[k] = 0.0;
    for (int m = 0; m < c->dim; ++m) s[k] += n[m] * c->a[m][k];
  }
}

static int has_shift(const int *n) { return n[0] != 0 || n[1] != 0 || n[2] != 0; }

rn_status rn_cell_build(rn_network *net) {
  rn_cell *c = net->cell;
  if (!c) return RN_OK;
  c->nimg = 0;
  c->slot = malloc((net->nfull ? net->nfull : 1) * sizeof(int32_t));
  if (!c->slot) return RN_ERR_ALLOC;
  for (size_t a = 0; a < net->nfull; ++a) c->slot[a] = -1;
  /* rod end slots at images: x_J + F s */
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    if (!J->image) continue;
    for (int k = 0; k < J->valence; ++k) {
      const rn_rod *r = &net->rods[J->rod[k]];
      size_t v = rn_dof_vertex(r->off, rn_end_vertex(r->nv, J->end[k]));
      double s[3];
      int rec;
      if (!has_shift(J->image + 3 * k)) continue;
      lattice_shift(c, J->image + 3 * k, s);
      if ((rec = add_record(c, rn_dof_joint_position(J->off), s)) < 0)
        return RN_ERR_ALLOC;
      for (int q = 0; q < 3; ++q) c->slot[v + (size_t)q] = 3 * rec + q;
    }
  }
  /* joint stencils: the neighbour vertex of an image end seen from the joint
   * (-F s), combined with that vertex's own image (a one-edge rod) */
  for (int ij = 0; ij < net->njoints; ++ij) {
    rn_joint *J = &net->joints[ij];
    int rigid = rn_joint_has_rotation(J);
    int n = rn_joint_stencil_count(rigid, J->valence), any = 0;
    for (int k = 0; k < J->valence && !any; ++k) {
      size_t xn = J->idx[rn_joint_local_end(rigid, k)];
      any = (J->image && has_shift(J->image + 3 * k)) || c->slot[xn] >= 0;
    }
    if (!any) continue;
    J->img = malloc((size_t)n * sizeof(int32_t));
    if (!J->img) return RN_ERR_ALLOC;
    for (int i = 0; i < n; ++i) J->img[i] = -1;
    for (int k = 0; k < J->valence; ++k) {
      int e = rn_joint_local_end(rigid, k), rec;
      size_t xn = J->idx[e], base = xn;
      double s[3] = {0.0, 0.0, 0.0}, own[3] = {0.0, 0.0, 0.0};
      if (c->slot[xn] >= 0) { /* the other end of a one-edge rod, at an image */
        const rn_image *o = &c->img[c->slot[xn] / 3];
        base = o->base;
        memcpy(s, o->s, sizeof(s));
      }
      int own_shift = J->image && has_shift(J->image + 3 * k);
      if (own_shift) lattice_shift(c, J->image + 3 * k, own);
      if (base == xn && !own_shift) continue;
      for (int q = 0; q < 3; ++q) s[q] -= own[q];
      if ((rec = add_record(c, base, s)) < 0) return RN_ERR_ALLOC;
      for (int q = 0; q < 3; ++q) J->img[e + q] = 3 * rec + q;
    }
  }
  return RN_OK;
}

/* ---- evaluation ------------------------------------------------------------- */
/* Strain values of a reduced state x (fixed ones from xfull). */
static void strain_of(const rn_network *net, const double *x, double eps[6]) {
  const rn_cell *c = net->cell;
  for (int v = 0; v < 6; ++v) {
    size_t a = c->off + (size_t)v;
    eps[v] = v >= c->nstrain ? 0.0 : (net->map[a] >= 0 ? x[net->map[a]] : net->xfull[a]);
  }
}

/* Position of column col in row r of the CSR pattern, -1 if absent. */
static int64_t find(const rn_network *net, int64_t r, int64_t col) {
  int64_t lo = net->rowptr[r], hi = net->rowptr[r + 1] - 1;
  while (lo <= hi) {
    int64_t mid = lo + (hi - lo) / 2;
    if (net->col[mid] == col) return mid;
    if (net->col[mid] < col)
      lo = mid + 1;
    else
      hi = mid - 1;
  }
  return -1;
}

static void add_at(const rn_network *net, int64_t r, int64_t col, double v,
                   double *vals) {
  int64_t p;
  if (r < 0 || col < 0 || v == 0.0) return;
  if ((p = find(net, r, col)) >= 0) vals[p] += v;
}

/* The strain rows and columns from w[k * 6 + v] = (H T)_{k v} of a stencil whose
 * entry k maps to reduced row rowmap[k] (-1: fixed), T of its image entries. */
static void add_cell_terms(const rn_network *net, int n, const int64_t *rowmap,
                           const int32_t *slots, const double *w, double *vals) {
  const rn_cell *c = net->cell;
  int64_t cm[6];
  for (int v = 0; v < c->nstrain; ++v) cm[v] = net->map[c->off + (size_t)v];
  for (int k = 0; k < n; ++k)
    for (int v = 0; v < c->nstrain; ++v) {
      add_at(net, rowmap[k], cm[v], w[k * 6 + v], vals);
      add_at(net, cm[v], rowmap[k], w[k * 6 + v], vals);
    }
  for (int k = 0; k < n; ++k) {
    if (slots[k] < 0) continue;
    const rn_image *im = &c->img[slots[k] / 3];
    int comp = slots[k] % 3;
    for (int v = 0; v < c->nstrain; ++v)
      for (int u = 0; u < c->nstrain; ++u)
        add_at(net, cm[u], cm[v], im->T[comp][u] * w[k * 6 + v], vals);
  }
}

enum { MAX_CELL_STENCIL = 4 * RN_ROD_SEGMENT + 3 };

void rn_cell_hess_block(const rn_network *net, size_t s, const size_t *idx,
                        const int32_t *img, int n, const double *H, double *vals) {
  const rn_cell *c = net->cell;
  int32_t sl_buf[64], *slots = sl_buf;
  int64_t rm_buf[64], *rowmap = rm_buf;
  double w_buf[64 * 6], *w = w_buf;
  int any = 0;
  if (!c || (idx && !img)) return;
  for (int k = 0; k < n && !any; ++k) any = rn_cell_entry_slot(c, s, img, k) >= 0;
  if (!any) return;
  if (n > 64) {
    slots = malloc((size_t)n * sizeof(int32_t));
    rowmap = malloc((size_t)n * sizeof(int64_t));
    w = malloc((size_t)n * 6 * sizeof(double));
    if (!slots || !rowmap || !w) goto done; /* (tiny; never in practice) */
  }
  for (int k = 0; k < n; ++k) {
    slots[k] = rn_cell_entry_slot(c, s, img, k);
    rowmap[k] = net->map[idx ? idx[k] : s + (size_t)k];
  }
  for (int k = 0; k < n; ++k)
    for (int v = 0; v < 6; ++v) {
      double t = 0.0;
      if (v < c->nstrain)
        for (int i = 0; i < n; ++i)
          if (slots[i] >= 0) t += H[k * n + i] * c->img[slots[i] / 3].T[slots[i] % 3][v];
      w[k * 6 + v] = t;
    }
  add_cell_terms(net, n, rowmap, slots, w, vals);
done:
  if (n > 64) {
    free(slots);
    free(rowmap);
    free(w);
  }
}

void rn_cell_hess_band(const rn_network *net, size_t s, int n, const double *band,
                       double *vals) {
  const rn_cell *c = net->cell;
  int32_t slots[MAX_CELL_STENCIL];
  int64_t rowmap[MAX_CELL_STENCIL];
  double w[MAX_CELL_STENCIL * 6];
  int any = 0;
  if (!c || n > MAX_CELL_STENCIL) return;
  for (int k = 0; k < n; ++k) {
    slots[k] = c->slot[s + (size_t)k];
    rowmap[k] = net->map[s + (size_t)k];
    any |= slots[k] >= 0;
  }
  if (!any) return;
  memset(w, 0, (size_t)n * 6 * sizeof(double));
  for (int i = 0; i < n; ++i) { /* H[k][i] = H[i][k] = band row i */
    if (slots[i] < 0) continue;
    const double *T = c->img[slots[i] / 3].T[slots[i] % 3];
    const double *row = band + (size_t)i * RNK_BAND + RNK_BAND_HALF;
    for (int d = -RNK_BAND_HALF; d <= RNK_BAND_HALF; ++d) {
      int k = i + d;
      if (k < 0 || k >= n || row[d] == 0.0) continue;
      for (int v = 0; v < c->nstrain; ++v) w[k * 6 + v] += row[d] * T[v];
    }
  }
  add_cell_terms(net, n, rowmap, slots, w, vals);
}

int rn_cell_pattern_flags(const rn_network *net, const size_t *lo, const size_t *hi,
                          unsigned char *touch) {
  const rn_cell *c = net->cell;
  int any = 0;
  if (!c) return 0;
  for (size_t a = 0; a < net->nfull; ++a) {
    if (c->slot[a] < 0) continue;
    for (size_t b = lo[a]; b <= hi[a]; ++b)
      if (net->map[b] >= 0) touch[net->map[b]] = 1;
    any = 1;
  }
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    if (!J->img) continue;
    for (int k = 0; k < rn_joint_stencil_count(rn_joint_has_rotation(J), J->valence); ++k)
      if (net->map[J->idx[k]] >= 0) touch[net->map[J->idx[k]]] = 1;
    any = 1;
  }
  for (int v = 0; v < c->nstrain; ++v)
    if (net->map[c->off + (size_t)v] >= 0) touch[net->map[c->off + (size_t)v]] = 2;
  return any;
}

double rn_cell_load(const rn_network *net, const double *x, double lambda, double *g,
                    double *gfull) {
  const rn_cell *c = net->cell;
  double eps[6], E = 0.0;
  if (!c || !rn_cell_owned_here(net)) return 0.0; /* a part: the strain's owner */
  strain_of(net, x, eps);
  for (int v = 0; v < c->nstrain; ++v) {
    double f = lambda * c->measure * c->stress[v];
    int64_t m = net->map[c->off + (size_t)v];
    if (f == 0.0) continue;
    E -= f * eps[v];
    if (g && m >= 0) g[m] -= f;
    if (gfull) gfull[c->off + (size_t)v] -= f;
  }
  return E;
}

void rn_cell_image_offset(const rn_network *net, const int *n, const double *full,
                          double out[3]) {
  const rn_cell *c = net->cell;
  double s[3];
  lattice_shift(c, n, s);
  for (int k = 0; k < 3; ++k) {
    out[k] = s[k];
    for (int v = 0; full && v < c->nstrain; ++v)
      for (int l = 0; l < 3; ++l)
        out[k] += full[c->off + (size_t)v] * c->B[v][3 * k + l] * s[l];
  }
}

void rn_joint_gather_full(const rn_network *net, const rn_joint *J, const double *full,
                          double *q) {
  int n = rn_joint_stencil_count(rn_joint_has_rotation(J), J->valence);
  for (int i = 0; i < n; ++i) q[i] = full[J->idx[i]];
  if (!J->img) return;
  for (int i = 0; i < n; ++i) {
    double sh[3];
    if (J->img[i] < 0) continue;
    const rn_image *im = &net->cell->img[J->img[i] / 3];
    rn_cell_shift(net, im, full, sh);
    q[i] = full[im->base + (size_t)(J->img[i] % 3)] + sh[J->img[i] % 3];
  }
}

/* In-plane extent of edge j of rod r: the equivalent rectangle of the section
 * about the axis normal to the cell plane, t = sqrt(12 I_n / A), I_n the second
 * moment about the edge's in-plane normal direction (exact for rectangles). */
static double inplane_thickness(const rn_rod *r, int j) {
  const rn_section *s = &r->sec[j];
  double t[3], d1[3], d2[3], n[3], z[3] = {0.0, 0.0, 1.0}, nn, n1, n2, In;
  double e[3];
  for (int k = 0; k < 3; ++k) e[k] = r->x0[3 * (j + 1) + k] - r->x0[3 * j + k];
  if (rnk_material_frame(e, &r->ref_base[j], 0.0, t, d1, d2) != RNK_OK) return 0.0;
  n[0] = z[1] * t[2] - z[2] * t[1]; /* z x t: in plane, normal to the edge */
  n[1] = z[2] * t[0] - z[0] * t[2];
  n[2] = z[0] * t[1] - z[1] * t[0];
  nn = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  if (!(nn > 0.0)) return 0.0;
  n1 = (n[0] * d1[0] + n[1] * d1[1] + n[2] * d1[2]) / nn;
  n2 = (n[0] * d2[0] + n[1] * d2[1] + n[2] * d2[2]) / nn;
  In = n1 * n1 * s->I11 + 2.0 * n1 * n2 * s->I12 + n2 * n2 * s->I22;
  return sqrt(12.0 * In / s->A);
}

rn_status rn_network_cell_relative_density(const rn_network *net, double *rho) {
  static const char *where = "rn_network_cell_relative_density";
  rn_status st;
  double sum = 0.0;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_cell_check(net, where, 0))) return st;
  if (!rho) return rn_fail(net->ctx, RN_ERR_ARG, where, "rho is NULL");
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    if (!rn_rod_evaluated(r)) continue; /* a part: its owned rods */
    for (int j = 0; j < r->ne; ++j)
      sum += r->lbar[j] * (net->cell->dim == 3 ? r->sec[j].A : inplane_thickness(r, j));
  }
  *rho = sum / net->cell->measure;
  return RN_OK;
}

/* contact.c - rod-rod and rod-self contact (issue 10 section 5; docs/contact.md):
 * the settings, the contact edges and their exclusions, the broad phase (sort
 * and sweep over edge boxes inflated by the barrier's reach), the continuous
 * collision check of a trial state against the accepted one, and the pattern
 * rows the contact Hessian blocks may touch.  The per-pair math is in
 * kernels/contact.c; assembly.c sums the pairs into the energy and its
 * derivatives.  Serial only: a part of a distributed network refuses contact. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "contact/contact.h"

/* One contact edge: its rod and index, the full indices of its two end
 * vertices (p0 then p1, 3 components each), the rest arc length from the
 * rod's start to each of its ends, and its rod's contact radius. */
typedef struct rn_contact_edge {
  int rod, j;
  size_t idx[6];
  double s0, s1, r;
} rn_contact_edge;

struct rn_contact {
  rnk_contact_param p; /* radius: twice the default radius */
  double radius;       /* the default radius of a rod */
  double *rrod;        /* per-rod radius [nrad] (< 0: the default) */
  int nrad;
  int nedges;
  rn_contact_edge *e;
  double *len;   /* rest length of each rod [nrods] */
  double margin; /* of the pattern pairs beyond the barrier's reach */
  /* The pattern pairs (a ne + b, a < b, ascending): the pairs whose boxes,
   * inflated by the radius, dhat / 2 and margin / 2, overlapped at the accepted
   * state the pattern was built at. */
  uint64_t *pat;
  size_t npat;
};

rn_status rn_network_set_contact(rn_network *net, double distance, double stiffness,
                                 double radius) {
  static const char *where = "rn_network_set_contact";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_building(net, where))) return st;
  if (rn_network_is_part(net))
    return rn_fail(net->ctx, RN_ERR_STATE, where,
                   "contact is evaluated on whole networks only (serial solves); "
                   "solve a scene with contact on one rank");
  if (!(isfinite(distance) && distance > 0.0))
    return rn_fail(net->ctx, RN_ERR_ARG, where, "contact distance %g: must be > 0",
                   distance);
  if (!(isfinite(stiffness) && stiffness > 0.0))
    return rn_fail(net->ctx, RN_ERR_ARG, where, "contact stiffness %g: must be > 0",
                   stiffness);
  if (!(isfinite(radius) && radius >= 0.0))
    return rn_fail(net->ctx, RN_ERR_ARG, where, "contact radius %g: must be >= 0",
                   radius);
  if (!net->contact && !(net->contact = calloc(1, sizeof(*net->contact))))
    return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  net->contact->p.dhat = distance;
  net->contact->p.kappa = stiffness;
  net->contact->p.radius = 2.0 * radius;
  net->contact->radius = radius;
  return RN_OK;
}

int rn_network_get_contact(const rn_network *net, double *distance, double *stiffness,
                           double *radius) {
  if (!net || !net->contact) return 0;
  if (distance) *distance = net->contact->p.dhat;
  if (stiffness) *stiffness = net->contact->p.kappa;
  if (radius) *radius = net->contact->radius;
  return 1;
}

rn_status rn_network_set_rod_contact_radius(rn_network *net, int rod, double radius) {
  static const char *where = "rn_network_set_rod_contact_radius";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_building(net, where))) return st;
  if (!net->contact)
    return rn_fail(net->ctx, RN_ERR_STATE, where,
                   "contact is off (rn_network_set_contact first)");
  if (rod < 0 || rod >= net->nrods)
    return rn_fail(net->ctx, RN_ERR_ARG, where, "rod %d out of range [0, %d)", rod,
                   net->nrods);
  if (!(isfinite(radius) && radius >= 0.0))
    return rn_fail(net->ctx, RN_ERR_ARG, where, "rod %d contact radius %g: must be >= 0",
                   rod, radius);
  rn_contact *c = net->contact;
  if (rod >= c->nrad) {
    double *p = realloc(c->rrod, (size_t)net->nrods * sizeof(double));
    if (!p) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
    for (int k = c->nrad; k < net->nrods; ++k) p[k] = -1.0;
    c->rrod = p;
    c->nrad = net->nrods;
  }
  c->rrod[rod] = radius;
  return RN_OK;
}

double rn_network_rod_contact_radius(const rn_network *net, int rod) {
  if (!net || !net->contact || rod < 0 || rod >= net->nrods) return NAN;
  const rn_contact *c = net->contact;
  return rod < c->nrad && c->rrod[rod] >= 0.0 ? c->rrod[rod] : c->radius;
}

unsigned long rn_network_pattern_version(const rn_network *net) {
  return net ? net->pattern_version : 0;
}

void rn_contact_unbuild(rn_network *net) {
  if (!net->contact) return;
  free(net->contact->e);
  free(net->contact->len);
  free(net->contact->pat);
  net->contact->e = NULL;
  net->contact->len = NULL;
  net->contact->pat = NULL;
  net->contact->npat = 0;
  net->contact->nedges = 0;
}

void rn_contact_free(rn_network *net) {
  rn_contact_unbuild(net);
  if (net->contact) free(net->contact->rrod);
  free(net->contact);
  net->contact = NULL;
}

rn_status rn_contact_build(rn_network *net, const char *where) {
  rn_contact *c = net->contact;
  int ne = 0, k = 0;
  if (!c) return RN_OK;
  if (net->cell)
    return rn_fail(net->ctx, RN_ERR_STATE, where,
                   "contact is not available in periodic cells (their image edges)");
  for (int ir = 0; ir < net->nrods; ++ir) ne += net->rods[ir].ne;
  c->e = malloc((size_t)(ne > 0 ? ne : 1) * sizeof(rn_contact_edge));
  c->len = malloc((size_t)(net->nrods > 0 ? net->nrods : 1) * sizeof(double));
  if (!c->e || !c->len) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    double s = 0.0;
    for (int j = 0; j < r->ne; ++j, ++k) {
      rn_contact_edge *e = &c->e[k];
      e->rod = ir;
      e->j = j;
      for (int m = 0; m < 3; ++m) {
        e->idx[m] = rn_dof_vertex(r->off, j) + (size_t)m;
        e->idx[3 + m] = rn_dof_vertex(r->off, j + 1) + (size_t)m;
      }
      e->s0 = s;
      s += r->lbar[j];
      e->s1 = s;
      e->r = rn_network_rod_contact_radius(net, ir);
    }
    c->len[ir] = s;
  }
  c->nedges = ne;
  /* the pattern's margin: dhat plus half the mean rest edge length */
  double sum = 0.0;
  for (int ir = 0; ir < net->nrods; ++ir) sum += c->len[ir];
  c->margin = c->p.dhat + (ne > 0 ? 0.5 * sum / ne : 0.0);
  c->pat = NULL;
  c->npat = 0;
  return RN_OK;
}

/* Arc length along rod e's centre line from its end `end` to the nearer end
 * of edge e. */
static double arc_to_end(const rn_contact *c, const rn_contact_edge *e, int end) {
  return end == RN_START ? e->s0 : c->len[e->rod] - e->s1;
}

/* 1 if the pair is excluded: edges joined within the barrier's reach along
 * the rods (the rest arc length between them, along one rod or through a joint
 * both rods meet at, below the sum of the radii plus the activation
 * distance): neighbouring edges of a rod and edges meeting at a joint. */
static int excluded(const rn_network *net, const rn_contact_edge *a,
                    const rn_contact_edge *b) {
  const rn_contact *c = net->contact;
  const double reach = a->r + b->r + c->p.dhat;
  if (a->rod == b->rod) {
    if (abs(a->j - b->j) <= 1) return 1;
    const rn_contact_edge *lo = a->j < b->j ? a : b, *hi = a->j < b->j ? b : a;
    if (hi->s0 - lo->s1 < reach) return 1;
  }
  const rn_rod *ra = &net->rods[a->rod], *rb = &net->rods[b->rod];
  for (int ea = RN_START; ea <= RN_END; ++ea)
    for (int eb = RN_START; eb <= RN_END; ++eb)
      if (ra->joint[ea] >= 0 && ra->joint[ea] == rb->joint[eb] &&
          !(a->rod == b->rod && ea == eb) &&
          arc_to_end(c, a, ea) + arc_to_end(c, b, eb) < reach)
        return 1;
  return 0;
}

/* Positions of every contact edge's ends at the reduced state x (P[6 k ..]);
 * x NULL: the accepted state (xfull). */
static void edge_positions(const rn_network *net, const double *x, double *P) {
  const rn_contact *c = net->contact;
  for (int k = 0; k < c->nedges; ++k) {
    if (x)
      rn_gather_idx(net, x, c->e[k].idx, 6, P + 6 * k);
    else
      for (int m = 0; m < 6; ++m) P[6 * k + m] = net->xfull[c->e[k].idx[m]];
  }
}

typedef struct box {
  double lo[3], hi[3];
  int k;
} box;

static int cmp_box(const void *a, const void *b) {
  double x = ((const box *)a)->lo[0], y = ((const box *)b)->lo[0];
  return (x > y) - (x < y);
}

/* Growable list of pairs. */
static int push_pair(rn_contact_list *L, int a, int b) {
  if (L->n == L->cap) {
    size_t cap = L->cap ? 2 * L->cap : 64;
    int *p = realloc(L->pair, 2 * cap * sizeof(int));
    if (!p) return -1;
    L->pair = p;
    L->cap = cap;
  }
  L->pair[2 * L->n] = a;
  L->pair[2 * L->n + 1] = b;
  L->n++;
  return 0;
}

/* Broad phase: the non-excluded pairs whose boxes (of the ends in P, and in Q
 * if given: the box of the motion), inflated by their edge's radius plus pad
 * each, overlap; sort and sweep along x. */
static rn_status broad_phase(const rn_network *net, const double *P, const double *Q,
                             double pad, rn_contact_list *L) {
  const rn_contact *c = net->contact;
  box *b = malloc((size_t)(c->nedges > 0 ? c->nedges : 1) * sizeof(box));
  if (!b) return RN_ERR_ALLOC;
  for (int k = 0; k < c->nedges; ++k) {
    box *bk = &b[k];
    bk->k = k;
    for (int d = 0; d < 3; ++d) {
      double lo = fmin(P[6 * k + d], P[6 * k + 3 + d]);
      double hi = fmax(P[6 * k + d], P[6 * k + 3 + d]);
      if (Q) {
        lo = fmin(lo, fmin(Q[6 * k + d], Q[6 * k + 3 + d]));
        hi = fmax(hi, fmax(Q[6 * k + d], Q[6 * k + 3 + d]));
      }
      bk->lo[d] = lo - pad - c->e[k].r;
      bk->hi[d] = hi + pad + c->e[k].r;
    }
  }
  qsort(b, (size_t)c->nedges, sizeof(box), cmp_box);
  rn_status st = RN_OK;
  for (int i = 0; i < c->nedges && !st; ++i)
    for (int j = i + 1; j < c->nedges && b[j].lo[0] <= b[i].hi[0]; ++j) {
      if (b[j].lo[1] > b[i].hi[1] || b[i].lo[1] > b[j].hi[1] || b[j].lo[2] > b[i].hi[2] ||
          b[i].lo[2] > b[j].hi[2])
        continue;
      int ka = b[i].k < b[j].k ? b[i].k : b[j].k, kb = b[i].k < b[j].k ? b[j].k : b[i].k;
      if (excluded(net, &c->e[ka], &c->e[kb])) continue;
      if (push_pair(L, ka, kb)) st = RN_ERR_ALLOC;
    }
  free(b);
  return st;
}

static void pair_stencil(const double *P, int a, int b, double x[12]) {
  memcpy(x, P + 6 * a, 6 * sizeof(double));
  memcpy(x + 6, P + 6 * b, 6 * sizeof(double));
}

void rn_contact_pair_idx(const rn_network *net, int a, int b, size_t idx[12]) {
  memcpy(idx, net->contact->e[a].idx, 6 * sizeof(size_t));
  memcpy(idx + 6, net->contact->e[b].idx, 6 * sizeof(size_t));
}

rnk_contact_param rn_contact_pair_param(const rn_network *net, int a, int b) {
  rnk_contact_param p = net->contact->p;
  p.radius = net->contact->e[a].r + net->contact->e[b].r;
  return p;
}

rn_status rn_contact_pair_fail(const rn_network *net, rn_status st, const char *where,
                               int a, int b, const char *what) {
  const rn_contact_edge *ea = &net->contact->e[a], *eb = &net->contact->e[b];
  const rn_rod *ra = &net->rods[ea->rod], *rb = &net->rods[eb->rod];
  return rn_fail(net->ctx, st, where,
                 "contact: %s: rod %d ('%s') edge %d and rod %d ('%s') edge %d", what,
                 ra->gid, ra->name ? ra->name : "", ea->j, rb->gid,
                 rb->name ? rb->name : "", eb->j);
}

void rn_contact_list_free(rn_contact_list *L) {
  free(L->pair);
  L->pair = NULL;
  L->n = L->cap = 0;
}

/* The continuous check of the motion from the accepted state P0 to P. */
static rn_status ccd_check(const rn_network *net, const double *P0, const double *P,
                           const char *where) {
  const rn_contact *c = net->contact;
  rn_contact_list L = {NULL, 0, 0};
  rn_status st = broad_phase(net, P0, P, 0.5 * c->p.dhat, &L);
  if (st) return rn_fail(net->ctx, st, where, "out of memory");
  for (size_t i = 0; i < L.n && !st; ++i) {
    double x0[12], x1[12];
    int hit = 1, a = L.pair[2 * i], b = L.pair[2 * i + 1];
    pair_stencil(P0, a, b, x0);
    pair_stencil(P, a, b, x1);
    int rc = rnk_contact_ccd(x0, x1, c->e[a].r + c->e[b].r, c->p.dhat, &hit);
    if (rc != RNK_OK || hit)
      st = rn_contact_pair_fail(net, RN_DEGENERATE, where, a, b,
                                "the motion from the accepted state brings two edges "
                                "below 20% of their gap (or through each other)");
  }
  rn_contact_list_free(&L);
  return st;
}

rn_status rn_contact_candidates(const rn_network *net, const double *x, int ccd,
                                const char *where, rn_contact_list *L) {
  const rn_contact *c = net->contact;
  size_t np = 6 * (size_t)(c->nedges > 0 ? c->nedges : 1);
  double *P = malloc(np * sizeof(double)), *P0 = NULL;
  rn_status st = RN_OK;
  L->pair = NULL;
  L->n = L->cap = 0;
  if (!P) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  edge_positions(net, x, P);
  if (ccd) {
    if (!(P0 = malloc(np * sizeof(double)))) st = RN_ERR_ALLOC;
    if (!st) edge_positions(net, NULL, P0);
    if (!st && memcmp(P0, P, 6 * (size_t)c->nedges * sizeof(double)))
      st = ccd_check(net, P0, P, where);
    else if (st)
      st = rn_fail(net->ctx, st, where, "out of memory");
  }
  if (!st && (st = broad_phase(net, P, NULL, 0.5 * c->p.dhat, L)))
    st = rn_fail(net->ctx, st, where, "out of memory");
  free(P);
  free(P0);
  if (st) rn_contact_list_free(L);
  return st;
}

/* ---- the Hessian pattern's pairs ------------------------------------------- */

static int cmp_u64(const void *a, const void *b) {
  uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
  return (x > y) - (x < y);
}

static uint64_t pair_key(const rn_contact *c, int a, int b) {
  return (uint64_t)a * (uint64_t)c->nedges + (uint64_t)b;
}

int rn_contact_in_pattern(const rn_network *net, int a, int b) {
  const rn_contact *c = net->contact;
  const uint64_t k = pair_key(c, a, b);
  return c->npat && bsearch(&k, c->pat, c->npat, sizeof(uint64_t), cmp_u64) != NULL;
}

size_t rn_contact_pattern_count(const rn_network *net) {
  return net->contact ? net->contact->npat : 0;
}

void rn_contact_pattern_pair(const rn_network *net, size_t i, int *a, int *b) {
  const rn_contact *c = net->contact;
  const uint64_t k = c->pat[i];
  *a = (int)(k / (uint64_t)c->nedges);
  *b = (int)(k % (uint64_t)c->nedges);
}

void rn_contact_pattern_idx(const rn_network *net, size_t i, size_t idx[12]) {
  int a = 0, b = 0;
  rn_contact_pattern_pair(net, i, &a, &b);
  rn_contact_pair_idx(net, a, b, idx);
}

int rn_contact_pattern_far(const rn_network *net, size_t i) {
  int a = 0, b = 0;
  rn_contact_pattern_pair(net, i, &a, &b);
  const rn_contact_edge *ea = &net->contact->e[a], *eb = &net->contact->e[b];
  return ea->rod != eb->rod || abs(ea->j - eb->j) >= 3;
}

rn_status rn_contact_pattern_update(rn_network *net, int force, const char *where) {
  rn_contact *c = net->contact;
  rn_contact_list L = {NULL, 0, 0};
  rn_status st = RN_OK;
  if (!c || !c->nedges) return RN_OK;
  double *P = malloc(6 * (size_t)c->nedges * sizeof(double));
  if (!P) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  edge_positions(net, NULL, P);
  if (!force) { /* every pair within half the margin is in the pattern: keep it */
    if ((st = broad_phase(net, P, NULL, 0.5 * c->p.dhat + 0.25 * c->margin, &L))) {
      free(P);
      return rn_fail(net->ctx, st, where, "out of memory");
    }
    size_t i = 0;
    while (i < L.n && rn_contact_in_pattern(net, L.pair[2 * i], L.pair[2 * i + 1])) ++i;
    force = i < L.n;
    rn_contact_list_free(&L);
  }
  if (force) {
    uint64_t *keep = c->pat, *keys = NULL;
    size_t nkeep = c->npat;
    st = broad_phase(net, P, NULL, 0.5 * (c->p.dhat + c->margin), &L);
    if (!st && !(keys = malloc((L.n ? L.n : 1) * sizeof(uint64_t)))) st = RN_ERR_ALLOC;
    if (!st) {
      for (size_t i = 0; i < L.n; ++i)
        keys[i] = pair_key(c, L.pair[2 * i], L.pair[2 * i + 1]);
      qsort(keys, L.n, sizeof(uint64_t), cmp_u64);
      c->pat = keys;
      c->npat = L.n;
      st = net->rebuild_pattern ? net->rebuild_pattern(net) : RN_ERR_INTERNAL;
      if (st) { /* the old pattern stays */
        c->pat = keep;
        c->npat = nkeep;
        free(keys);
      } else {
        free(keep);
        net->pattern_version++;
      }
    }
    rn_contact_list_free(&L);
    if (st) st = rn_fail(net->ctx, st, where, "out of memory");
  }
  free(P);
  return st;
}

/* The input geometry (the rods' vertices as added, before any prescribed
 * motion) must not interpenetrate: the prescribed motions are applied by
 * the solver's load steps from there. */
rn_status rn_contact_check_initial(const rn_network *net, const char *where) {
  const rn_contact *c = net->contact;
  rn_contact_list L = {NULL, 0, 0};
  rn_status st = RN_OK;
  if (!c || !c->nedges) return RN_OK;
  double *P = malloc(6 * (size_t)c->nedges * sizeof(double));
  if (!P) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  for (int k = 0; k < c->nedges; ++k) {
    const rn_rod *r = &net->rods[c->e[k].rod];
    memcpy(P + 6 * k, r->x0 + 3 * c->e[k].j, 6 * sizeof(double));
  }
  if ((st = broad_phase(net, P, NULL, 0.5 * c->p.dhat, &L)))
    st = rn_fail(net->ctx, st, where, "out of memory");
  for (size_t i = 0; i < L.n && !st; ++i) {
    double x[12], gap = 0.0;
    int a = L.pair[2 * i], b = L.pair[2 * i + 1];
    pair_stencil(P, a, b, x);
    if (rnk_contact_gap(x, c->e[a].r + c->e[b].r, &gap) != RNK_OK || !(gap > 0.0))
      st = rn_contact_pair_fail(net, RN_ERR_GEOMETRY, where, a, b,
                                "the initial state interpenetrates (distance below "
                                "twice the contact radius)");
  }
  free(P);
  rn_contact_list_free(&L);
  return st;
}

rn_status rn_network_contact_stats(const rn_network *net, const double *x,
                                   rn_contact_stats *stats) {
  static const char *where = "rn_network_contact_stats";
  rn_contact_list L;
  rn_contact_stats out = {INFINITY, 0, 0.0, 0.0};
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!x && net->nred) return rn_fail(net->ctx, RN_ERR_ARG, where, "x is NULL");
  if (!stats) return rn_fail(net->ctx, RN_ERR_ARG, where, "stats is NULL");
  if (net->contact && net->contact->nedges) {
    if ((st = rn_contact_candidates(net, x, 0, where, &L))) return st;
    for (size_t i = 0; i < L.n && !st; ++i) {
      size_t idx[12];
      double q[12], g[12], gap = 0.0, E = 0.0, f[3];
      const rnk_contact_param pp =
          rn_contact_pair_param(net, L.pair[2 * i], L.pair[2 * i + 1]);
      rn_contact_pair_idx(net, L.pair[2 * i], L.pair[2 * i + 1], idx);
      rn_gather_idx(net, x, idx, 12, q);
      if (rnk_contact_gap(q, pp.radius, &gap) != RNK_OK ||
          rnk_contact_grad(q, &pp, &E, g) != RNK_OK) {
        st = rn_contact_pair_fail(net, RN_DEGENERATE, where, L.pair[2 * i],
                                  L.pair[2 * i + 1],
                                  "interpenetrating edges (or a zero-length edge)");
        break;
      }
      if (gap < out.min_gap) out.min_gap = gap;
      if (gap < net->contact->p.dhat) out.active++;
      out.energy += E;
      for (int k = 0; k < 3; ++k) f[k] = g[k] + g[3 + k]; /* on the first edge */
      out.force += sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    }
    rn_contact_list_free(&L);
    if (st) return st;
  }
  *stats = out;
  return RN_OK;
}

/* part.c - parts of a rod network for distributed solves (docs/parallel.md).
 *
 * A partition gives every rod to one part; a joint belongs to the part that
 * owns most of its rod ends (ties: the smallest part).  The part p of a
 * network holds
 *   - its owned rods, whole, and its owned joints: their stencils (stretch,
 *     bend-twist, forces and couples of the rods; joint stencils and joint
 *     loads) are evaluated here and nowhere else;
 *   - ghost rods: every other rod with an end at an owned joint (the joint
 *     stencil reads the vertex next to the joint, the terminal edge's angle
 *     and reference frame), and the rod of the first end of every joint held
 *     here (the joint's initial position is that end's vertex).  A ghost rod is
 *     held whole (its geometry, properties and constraints: O(its vertices)),
 *     but only the DOFs that an owned joint's stencil reads are in the part's
 *     DOF vector, and only the frames of those terminal edges are updated;
 *   - ghost joints: the joints at the ends of owned rods (their position is
 *     the rods' end vertex), and at the far end of a two-vertex ghost rod (its
 *     end vertex is then the vertex next to an owned joint).  Only their
 *     position is used; they list only the ends at rods held here.
 * The rods and joints keep their whole-network indices at the API; inside they
 * are numbered locally in increasing whole-network index.  The part's reduced
 * DOFs are its owned ones first (owned rods in order, then owned joints: each
 * rod's DOFs contiguous), then the ghost ones; each has a key, its canonical
 * index in the whole network's full DOF vector (rods concatenated in order,
 * then 6 entries per joint), and the part that owns it.
 *
 * A network in graph-only mode records the rod graph (vertices per rod, the
 * rod ends of each joint) and nothing else, so that a scene can be read once
 * cheaply, partitioned, and read again into the part. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/partition.h"
#include "joints/joints.h"
#include "parts/parts.h"

static const char *const where_part = "rn_network_set_part";

void rn_part_free(rn_part_data **pp) {
  rn_part_data *p;
  if (!pp || !*pp) return;
  p = *pp;
  free(p->rod_nv);
  free(p->jptr);
  free(p->jrods);
  free(p->jends);
  free(p->rod_endj);
  free(p->rod_ends);
  for (int j = 0; p->names && j < p->njoints; ++j) free(p->names[j]);
  free(p->names);
  free(p->points);
  free(p->rod_part);
  free(p->rod_local);
  free(p->joint_owner);
  free(p->joint_local);
  free(p->rod_key);
  free(p->entry_owned);
  free(p->keys);
  free(p->owner);
  free(p);
  *pp = NULL;
}

static rn_status check_empty(rn_network *net, const char *where) {
  rn_status st;
  if ((st = rn_net_check_building(net, where))) return st;
  if (net->part || net->nrods || net->njoints || net->nmom)
    return rn_fail(net->ctx, RN_ERR_STATE, where,
                   "the network must be empty (no rods, joints or couples yet, no "
                   "earlier part or graph mode)");
  return RN_OK;
}

/* ---- graph mode -------------------------------------------------------------- */
rn_status rn_network_set_graph_only(rn_network *net) {
  static const char *where = "rn_network_set_graph_only";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = check_empty(net, where))) return st;
  net->part = calloc(1, sizeof(*net->part));
  if (!net->part) return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  net->part->mode = MODE_GRAPH;
  net->part->nparts = 1;
  net->part->jptr = calloc(1, sizeof(int));
  if (!net->part->jptr) {
    rn_part_free(&net->part);
    return rn_fail(net->ctx, RN_ERR_ALLOC, where, "out of memory");
  }
  return RN_OK;
}

rn_status rn_network_rod_graph(const rn_network *net, int *nrods, const int **rod_nv,
                               int *njoints, const int **joint_ptr,
                               const int **joint_rods) {
  static const char *where = "rn_network_rod_graph";
  if (!net) return RN_ERR_ARG;
  if (!net->part || net->part->mode != MODE_GRAPH)
    return rn_fail(net->ctx, RN_ERR_STATE, where,
                   "the network was not built in graph-only mode");
  if (nrods) *nrods = net->part->nrods;
  if (rod_nv) *rod_nv = net->part->rod_nv;
  if (njoints) *njoints = net->part->njoints;
  if (joint_ptr) *joint_ptr = net->part->jptr;
  if (joint_rods) *joint_rods = net->part->jrods;
  return RN_OK;
}

/* ---- the partition ----------------------------------------------------------- */
/* Owner of joint j: the part holding most of its ends (ties: the smallest). */
static int joint_owner(const int *rod_part, const int *jptr, const int *jrods, int j) {
  int best = -1, best_n = 0;
  for (int a = jptr[j]; a < jptr[j + 1]; ++a) {
    int q = rod_part[jrods[a]], n = 0;
    for (int b = jptr[j]; b < jptr[j + 1]; ++b) n += rod_part[jrods[b]] == q;
    if (n > best_n || (n == best_n && q < best)) {
      best = q;
      best_n = n;
    }
  }
  return best;
}

static rn_status check_graph(rn_network *net, int nparts, int part, int nrods,
                             const int *rod_nv, const int *rod_part, int njoints,
                             const int *jptr, const int *jrods) {
  if (nparts < 1 || part < 0 || part >= nparts)
    return rn_fail(net->ctx, RN_ERR_ARG, where_part, "part %d of %d parts", part, nparts);
  if (nrods < 0 || njoints < 0 || (nrods && (!rod_nv || !rod_part)) ||
      (njoints && (!jptr || !jrods)))
    return rn_fail(net->ctx, RN_ERR_ARG, where_part, "NULL or negative graph arrays");
  for (int r = 0; r < nrods; ++r)
    if (rod_nv[r] < 2 || rod_part[r] < 0 || rod_part[r] >= nparts)
      return rn_fail(net->ctx, RN_ERR_ARG, where_part,
                     "rod %d: %d vertices, part %d (of %d)", r, rod_nv[r], rod_part[r],
                     nparts);
  if (njoints && jptr[0] != 0)
    return rn_fail(net->ctx, RN_ERR_ARG, where_part, "joint_ptr[0] must be 0");
  for (int j = 0; j < njoints; ++j) {
    if (jptr[j + 1] <= jptr[j])
      return rn_fail(net->ctx, RN_ERR_ARG, where_part, "joint %d has no ends", j);
    for (int a = jptr[j]; a < jptr[j + 1]; ++a)
      if (jrods[a] < 0 || jrods[a] >= nrods)
        return rn_fail(net->ctx, RN_ERR_ARG, where_part, "joint %d: rod %d", j, jrods[a]);
  }
  return RN_OK;
}

/* The rods and joints part p holds (see the file comment). */
static void choose_local(rn_part_data *p, const int *jptr, const int *jrods) {
  int nr = p->nrods_total, nj = p->njoints_total, me = p->part;
  for (int r = 0; r < nr; ++r) p->rod_local[r] = p->rod_part[r] == me ? 1 : 0;
  for (int j = 0; j < nj; ++j) {
    p->joint_owner[j] = joint_owner(p->rod_part, jptr, jrods, j);
    p->joint_local[j] = 0;
  }
  /* ghost rods at owned joints (2: read by an owned joint's stencil) */
  for (int j = 0; j < nj; ++j)
    if (p->joint_owner[j] == me)
      for (int a = jptr[j]; a < jptr[j + 1]; ++a)
        if (!p->rod_local[jrods[a]]) p->rod_local[jrods[a]] = 2;
  /* joints: owned, at owned rods, at the far end of two-vertex ghost rods */
  for (int j = 0; j < nj; ++j) {
    int keep = p->joint_owner[j] == me;
    for (int a = jptr[j]; a < jptr[j + 1] && !keep; ++a) {
      int r = jrods[a];
      keep = p->rod_local[r] == 1 || (p->rod_local[r] == 2 && p->rod_nv[r] == 2);
    }
    p->joint_local[j] = keep;
  }
  /* the first end's rod of every joint held here */
  for (int j = 0; j < nj; ++j)
    if (p->joint_local[j] && !p->rod_local[jrods[jptr[j]]])
      p->rod_local[jrods[jptr[j]]] = 3;
  p->nlocal_rods = 0;
  for (int r = 0; r < nr; ++r) p->rod_local[r] = p->rod_local[r] ? p->nlocal_rods++ : -1;
  for (int j = 0, n = 0; j < nj; ++j) p->joint_local[j] = p->joint_local[j] ? n++ : -1;
}

rn_status rn_network_set_part(rn_network *net, int nparts, int part, int nrods,
                              const int *rod_nv, const int *rod_part, int njoints,
                              const int *joint_ptr, const int *joint_rods) {
  rn_status st;
  rn_part_data *p;
  if (!net) return RN_ERR_ARG;
  if ((st = check_empty(net, where_part))) return st;
  if ((st = check_graph(net, nparts, part, nrods, rod_nv, rod_part, njoints, joint_ptr,
                        joint_rods)))
    return st;
  p = net->part = calloc(1, sizeof(*p));
  if (!p) return rn_fail(net->ctx, RN_ERR_ALLOC, where_part, "out of memory");
  p->mode = MODE_PART;
  p->nparts = nparts;
  p->part = part;
  p->nrods_total = nrods;
  p->njoints_total = njoints;
  p->rod_nv = malloc(((size_t)nrods + 1) * sizeof(int));
  p->rod_part = malloc(((size_t)nrods + 1) * sizeof(int));
  p->rod_local = malloc(((size_t)nrods + 1) * sizeof(int));
  p->joint_owner = malloc(((size_t)njoints + 1) * sizeof(int));
  p->joint_local = malloc(((size_t)njoints + 1) * sizeof(int));
  if (!p->rod_nv || !p->rod_part || !p->rod_local || !p->joint_owner || !p->joint_local) {
    rn_part_free(&net->part);
    return rn_fail(net->ctx, RN_ERR_ALLOC, where_part, "out of memory");
  }
  if (nrods) {
    memcpy(p->rod_nv, rod_nv, (size_t)nrods * sizeof(int));
    memcpy(p->rod_part, rod_part, (size_t)nrods * sizeof(int));
  }
  choose_local(p, joint_ptr, joint_rods);
  p->rod_key = malloc(((size_t)p->nlocal_rods + 1) * sizeof(int64_t));
  if (!p->rod_key) {
    rn_part_free(&net->part);
    return rn_fail(net->ctx, RN_ERR_ALLOC, where_part, "out of memory");
  }
  for (int r = 0; r < nrods; ++r) p->joint_key0 += (int64_t)rn_dof_rod_count(rod_nv[r]);
  return RN_OK;
}

/* ---- finalize ----------------------------------------------------------------- */
void rn_part_mark_absent(rn_network *net) {
  rn_part_data *p = net->part;
  unsigned char *pr = p->entry_owned; /* 1 present, 2 present and owned */
  memset(pr, 0, net->nfull);
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    if (!r->ghost) memset(pr + r->off, 2, rn_dof_rod_count(r->nv));
  }
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    size_t n = rn_dof_joint_count(rn_joint_has_rotation(J));
    if (J->ghost) continue;
    memset(pr + J->off, 2, n);
    for (int k = 0; k < J->valence; ++k) {
      const rn_rod *r = &net->rods[J->rod[k]];
      size_t xn = rn_dof_vertex(r->off, rn_end_neighbor(r->nv, J->end[k]));
      for (size_t c = 0; c < 3; ++c)
        if (!pr[xn + c]) pr[xn + c] = 1;
      if (!pr[rn_dof_theta(r->off, rn_end_edge(r->nv, J->end[k]))])
        pr[rn_dof_theta(r->off, rn_end_edge(r->nv, J->end[k]))] = 1;
    }
  }
  /* a joint position is present if an end vertex aliasing it is */
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    size_t xp = rn_dof_joint_position(J->off);
    for (int k = 0; k < J->valence; ++k) {
      const rn_rod *r = &net->rods[J->rod[k]];
      size_t v = rn_dof_vertex(r->off, rn_end_vertex(r->nv, J->end[k]));
      for (size_t c = 0; c < 3; ++c)
        if (pr[v + c] && !pr[xp + c]) pr[xp + c] = 1;
    }
  }
  /* periodic: the strain DOFs, owned by part 0, held by every part */
  if (net->cell)
    memset(pr + net->cell->off, rn_cell_owned_here(net) ? 2 : 1,
           (size_t)net->cell->nstrain);
  for (size_t a = 0; a < net->nfull; ++a)
    if (!pr[a]) net->map[a] = RN_DOF_ABSENT;
}

int rn_part_entry_owned(const rn_network *net, size_t a) {
  return net->part->entry_owned[a] == 2;
}

/* Canonical full index a (of a rod or joint) -> key and owner. */
static void set_key(rn_network *net, size_t a, int64_t key, int owner) {
  int64_t m = net->map[a];
  if (m < 0 || net->red2full[m] != (int64_t)a) return;
  net->part->keys[m] = key;
  net->part->owner[m] = owner;
}

rn_status rn_part_build_keys(rn_network *net) {
  rn_part_data *p = net->part;
  size_t n = net->nred + 1;
  free(p->entry_owned);
  free(p->keys);
  free(p->owner);
  p->entry_owned = NULL;
  p->keys = malloc(n * sizeof(int64_t));
  p->owner = malloc(n * sizeof(int));
  if (!p->keys || !p->owner) return RN_ERR_ALLOC;
  p->n_owned = 0;
  for (size_t m = 0; m < net->nred; ++m) p->owner[m] = -1;
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    size_t cnt = rn_dof_rod_count(r->nv);
    for (size_t c = 0; c < cnt; ++c)
      set_key(net, r->off + c, p->rod_key[ir] + (int64_t)c, r->owner);
  }
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    size_t cnt = rn_dof_joint_count(rn_joint_has_rotation(J));
    for (size_t c = 0; c < cnt; ++c)
      set_key(net, J->off + c, p->joint_key0 + 6 * (int64_t)J->gid + (int64_t)c,
              J->owner);
  }
  if (net->cell) /* after every joint's six entries */
    for (int v = 0; v < net->cell->nstrain; ++v)
      set_key(net, net->cell->off + (size_t)v,
              p->joint_key0 + 6 * (int64_t)p->njoints_total + v, 0);
  for (size_t m = 0; m < net->nred; ++m) {
    if (p->owner[m] < 0) return RN_ERR_INTERNAL;
    if (p->owner[m] == p->part) p->n_owned = m + 1;
  }
  return RN_OK;
}

rn_status rn_part_begin_numbering(rn_network *net) {
  if (!net->part) return RN_OK;
  free(net->part->entry_owned);
  net->part->entry_owned = malloc(net->nfull + 1);
  return net->part->entry_owned ? RN_OK : RN_ERR_ALLOC;
}

int rn_network_rod_owner(const rn_network *net, int rod) {
  if (!net || rod < 0 || rod >= rn_net_num_rods_g(net)) return -1;
  if (!net->part) return 0;
  return net->part->mode == MODE_PART ? net->part->rod_part[rod] : -1;
}

int rn_network_joint_owner(const rn_network *net, int joint) {
  if (!net || joint < 0 || joint >= rn_net_num_joints_g(net)) return -1;
  if (!net->part) return 0;
  return net->part->mode == MODE_PART ? net->part->joint_owner[joint] : -1;
}

rn_status rn_network_part_info(const rn_network *net, rn_part_info *info) {
  static const char *where = "rn_network_part_info";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!info) return rn_fail(net->ctx, RN_ERR_ARG, where, "info is NULL");
  memset(info, 0, sizeof(*info));
  info->nparts = net->part ? net->part->nparts : 1;
  info->part = net->part ? net->part->part : 0;
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    if (r->ghost) {
      info->ghost_rods++;
      continue;
    }
    info->owned_rods++;
    info->owned_stencils += (long)r->ne + (long)(r->nv - 2);
  }
  for (int im = 0; im < net->nmom; ++im)
    if (!net->rods[net->moments[im].rod].ghost) info->owned_stencils++;
  for (int ij = 0; ij < net->njoints; ++ij) {
    if (net->joints[ij].ghost) {
      info->ghost_joints++;
      continue;
    }
    info->owned_joints++;
    info->owned_stencils++;
  }
  info->owned_dofs =
      (net->part && net->part->mode == MODE_PART) ? net->part->n_owned : net->nred;
  info->ghost_dofs = net->nred - info->owned_dofs;
  return RN_OK;
}

rn_status rn_network_part_dofs(const rn_network *net, size_t *n_owned,
                               const int64_t **keys, const int **owners) {
  static const char *where = "rn_network_part_dofs";
  rn_status st;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!net->part || net->part->mode != MODE_PART)
    return rn_fail(net->ctx, RN_ERR_STATE, where, "the network is not a part");
  if (n_owned) *n_owned = net->part->n_owned;
  if (keys) *keys = net->part->keys;
  if (owners) *owners = net->part->owner;
  return RN_OK;
}

rn_status rn_part_graph_validate(const rn_network *net, const char *where) {
  return rn_joint_points_check(net->ctx, where, net->part->njoints, net->part->points);
}

/* ---- state of the owned rods, joints and couples, packed ------------------------ */
enum { REC_ROD = 1, REC_JOINT = 2, REC_MOMENT = 3, REC_CELL = 4, FRAME_DOUBLES = 6 };

static size_t rod_record(const rn_rod *r) {
  return 2 + rn_dof_rod_count(r->nv) + FRAME_DOUBLES * (size_t)r->ne +
         (size_t)(r->nv - 2);
}

static size_t joint_record(const rn_joint *J) {
  return 4 + rn_dof_joint_count(rn_joint_has_rotation(J)) + 19 + (size_t)J->valence;
}

static void put_frames(double *b, const rnk_frame *f, int n) {
  for (int j = 0; j < n; ++j) {
    memcpy(b + FRAME_DOUBLES * j, f[j].t, 3 * sizeof(double));
    memcpy(b + FRAME_DOUBLES * j + 3, f[j].a1, 3 * sizeof(double));
  }
}

static void get_frames(rnk_frame *f, const double *b, int n) {
  for (int j = 0; j < n; ++j) {
    memcpy(f[j].t, b + FRAME_DOUBLES * j, 3 * sizeof(double));
    memcpy(f[j].a1, b + FRAME_DOUBLES * j + 3, 3 * sizeof(double));
  }
}

static size_t pack_rod(const rn_network *net, const rn_rod *r, double *b) {
  size_t nf = rn_dof_rod_count(r->nv), o = 2;
  b[0] = REC_ROD;
  b[1] = r->gid;
  memcpy(b + o, net->xfull + r->off, nf * sizeof(double));
  o += nf;
  put_frames(b + o, r->ref, r->ne);
  o += FRAME_DOUBLES * (size_t)r->ne;
  if (r->nv > 2) memcpy(b + o, r->ref_twist, (size_t)(r->nv - 2) * sizeof(double));
  return rod_record(r);
}

static size_t pack_joint(const rn_network *net, const rn_joint *J, double *b) {
  size_t nf = rn_dof_joint_count(rn_joint_has_rotation(J)), o = 4;
  b[0] = REC_JOINT;
  b[1] = J->gid;
  b[2] = (double)nf;
  b[3] = J->valence;
  memcpy(b + o, net->xfull + J->off, nf * sizeof(double));
  o += nf;
  memcpy(b + o, J->Qhat, 9 * sizeof(double));
  memcpy(b + o + 9, J->f0, 9 * sizeof(double));
  b[o + 18] = J->angle0;
  o += 19;
  for (int k = 0; k < J->valence; ++k) b[o + (size_t)k] = J->ends[k].twist.ref_twist;
  return joint_record(J);
}

rn_status rn_network_part_state_pack(const rn_network *net, double *buf, size_t *n) {
  static const char *where = "rn_network_part_state_pack";
  rn_status st;
  size_t o = 1;
  double count = 0;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!n) return rn_fail(net->ctx, RN_ERR_ARG, where, "n is NULL");
  for (int ir = 0; ir < net->nrods; ++ir) {
    const rn_rod *r = &net->rods[ir];
    if (r->ghost) continue;
    o += buf ? pack_rod(net, r, buf + o) : rod_record(r);
    ++count;
  }
  for (int ij = 0; ij < net->njoints; ++ij) {
    const rn_joint *J = &net->joints[ij];
    if (J->ghost) continue;
    o += buf ? pack_joint(net, J, buf + o) : joint_record(J);
    ++count;
  }
  for (int im = 0; im < net->nmom; ++im) {
    const rn_moment *mo = &net->moments[im];
    if (net->rods[mo->rod].ghost) continue;
    if (buf) {
      buf[o] = REC_MOMENT;
      buf[o + 1] = mo->gid;
      memcpy(buf + o + 2, mo->f0, 9 * sizeof(double));
      buf[o + 11] = mo->angle0;
    }
    o += 12;
    ++count;
  }
  if (net->cell && rn_cell_owned_here(net)) { /* the macroscopic strain */
    const rn_cell *c = net->cell;
    if (buf) {
      buf[o] = REC_CELL;
      buf[o + 1] = c->nstrain;
      memcpy(buf + o + 2, net->xfull + c->off, (size_t)c->nstrain * sizeof(double));
    }
    o += 2 + (size_t)c->nstrain;
    ++count;
  }
  if (buf) buf[0] = count;
  *n = o;
  return RN_OK;
}

/* Local index of the moment with whole-network number gid, -1 if none. */
static int find_moment(const rn_network *net, int gid) {
  for (int im = 0; im < net->nmom; ++im)
    if (net->moments[im].gid == gid) return im;
  return -1;
}

static rn_status unpack_rod(rn_network *net, const double *b, size_t left, size_t *used) {
  int lr = (int)b[1];
  rn_rod *r;
  size_t o = 2, nf;
  if (rn_net_rod(net, "rn_network_part_state_unpack", &lr) != RN_OK) return RN_ERR_ARG;
  r = &net->rods[lr];
  if (left < rod_record(r)) return RN_ERR_ARG;
  nf = rn_dof_rod_count(r->nv);
  memcpy(net->xfull + r->off, b + o, nf * sizeof(double));
  o += nf;
  get_frames(r->ref, b + o, r->ne);
  o += FRAME_DOUBLES * (size_t)r->ne;
  if (r->nv > 2) memcpy(r->ref_twist, b + o, (size_t)(r->nv - 2) * sizeof(double));
  *used = rod_record(r);
  return RN_OK;
}

static rn_status unpack_joint(rn_network *net, const double *b, size_t left,
                              size_t *used) {
  int lj = (int)b[1];
  rn_joint *J;
  size_t o = 4, nf;
  if (left < 4 || rn_net_joint(net, "rn_network_part_state_unpack", &lj) != RN_OK)
    return RN_ERR_ARG;
  J = &net->joints[lj];
  nf = rn_dof_joint_count(rn_joint_has_rotation(J));
  if ((size_t)b[2] != nf || (int)b[3] != J->valence || left < joint_record(J))
    return RN_ERR_ARG;
  memcpy(net->xfull + J->off, b + o, nf * sizeof(double));
  o += nf;
  memcpy(J->Qhat, b + o, 9 * sizeof(double));
  memcpy(J->f0, b + o + 9, 9 * sizeof(double));
  J->angle0 = b[o + 18];
  o += 19;
  for (int k = 0; k < J->valence; ++k) J->ends[k].twist.ref_twist = b[o + (size_t)k];
  *used = joint_record(J);
  return RN_OK;
}

rn_status rn_network_part_state_unpack(rn_network *net, const double *buf, size_t n) {
  static const char *where = "rn_network_part_state_unpack";
  rn_status st;
  size_t o = 1, count;
  if (!net) return RN_ERR_ARG;
  if ((st = rn_net_check_final(net, where))) return st;
  if (!buf || n < 1 || !(buf[0] >= 0))
    return rn_fail(net->ctx, RN_ERR_ARG, where, "no state");
  count = (size_t)buf[0];
  for (size_t c = 0; c < count; ++c) {
    size_t used = 0;
    int type = o + 2 <= n ? (int)buf[o] : 0;
    st = RN_ERR_ARG;
    if (type == REC_ROD) st = unpack_rod(net, buf + o, n - o, &used);
    if (type == REC_JOINT) st = unpack_joint(net, buf + o, n - o, &used);
    if (type == REC_MOMENT && o + 12 <= n) {
      int im = find_moment(net, (int)buf[o + 1]);
      if (im >= 0) {
        memcpy(net->moments[im].f0, buf + o + 2, 9 * sizeof(double));
        net->moments[im].angle0 = buf[o + 11];
        used = 12;
        st = RN_OK;
      }
    }
    if (type == REC_CELL && net->cell && (int)buf[o + 1] == net->cell->nstrain &&
        o + 2 + (size_t)net->cell->nstrain <= n) {
      used = 2 + (size_t)net->cell->nstrain;
      memcpy(net->xfull + net->cell->off, buf + o + 2, (used - 2) * sizeof(double));
      st = RN_OK;
    }
    if (st)
      return rn_fail(net->ctx, RN_ERR_ARG, where,
                     "record %zu does not match this network (another scene?)", c);
    o += used;
  }
  rn_joints_sync(net);
  return RN_OK;
}

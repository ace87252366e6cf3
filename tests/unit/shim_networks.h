/* shim_networks.h - small rod networks with joints built through rodnet.h for
 * the solver (shim) tests: portal frames and a square grid with both joint
 * models, loaded so that the joints turn by finite angles. */
#ifndef RN_SHIM_NETWORKS_H
#define RN_SHIM_NETWORKS_H

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "rodnet_solve.h"
#include "testutil.h"

/* Material of the networks: E = 1e7, nu = 0.3; circle r = 0.01 (E I = 0.0785). */
static inline void shimnet_props(rn_material *m, rn_section *s) {
  CHECK_STATUS(rn_material_from_E_nu(1e7, 0.3, 0.0, m), RN_OK);
  CHECK_STATUS(rn_section_circle(0.01, s), RN_OK);
}

/* Straight rod from a to b with ne edges, d1 given; returns its index. */
static inline int shimnet_line(rn_network *net, const char *name, const double a[3],
                               const double b[3], int ne, const double d1[3]) {
  rn_material m;
  rn_section s;
  int rod = -1;
  double *x = malloc(sizeof(double) * 3 * (size_t)(ne + 1));
  shimnet_props(&m, &s);
  for (int i = 0; i <= ne; ++i)
    for (int k = 0; k < 3; ++k) x[3 * i + k] = a[k] + (b[k] - a[k]) * i / ne;
  CHECK_STATUS(rn_network_add_rod(net, name, ne + 1, x, d1, &rod), RN_OK);
  free(x);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
  return rod;
}

/* Portal frame in the xz plane: columns of height 1 at x = 0 and x = 1, beam on
 * top, ne edges per rod, corner joints A (x = 0) and B of the given models.
 * Column 0 is clamped at its base (rod clamp); column 1 stands on a clamped
 * valence-1 joint C whose rotation is prescribed (0.05 rad about y, scaled by
 * the load factor).  Loads: lateral force P on A, a downward force P on the
 * beam's middle vertex, a couple 0.02 about y on B and a couple 0.01 about x
 * on the beam's vertex next to A.  Not finalized when finalize = 0. */
static inline rn_network *shimnet_portal(rn_context *ctx, int model_a, int model_b,
                                         int ne, double P, int finalize) {
  rn_network *net = NULL;
  const double d1[3] = {0, 1, 0};
  const double a0[3] = {0, 0, 0}, a1[3] = {0, 0, 1}, b0[3] = {1, 0, 0}, b1[3] = {1, 0, 1};
  const double f[3] = {P, 0, 0}, fb[3] = {0, 0, -P}, mb[3] = {0, 0.02, 0},
               mr[3] = {0.01, 0, 0}, rot[3] = {0, 0.05, 0};
  int c0, c1, bm, ja, jb, jc;
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  c0 = shimnet_line(net, "col0", a0, a1, ne, d1);
  c1 = shimnet_line(net, "col1", b0, b1, ne, d1);
  bm = shimnet_line(net, "beam", a1, b1, 2 * ne, d1);
  {
    int ra[2] = {c0, bm}, ea[2] = {RN_END, RN_START};
    int rb[2] = {c1, bm}, eb[2] = {RN_END, RN_END};
    int rc[1] = {c1}, ec[1] = {RN_START};
    CHECK_STATUS(rn_network_add_joint(net, "A", (rn_joint_model)model_a, 2, ra, ea, &ja),
                 RN_OK);
    CHECK_STATUS(rn_network_add_joint(net, "B", (rn_joint_model)model_b, 2, rb, eb, &jb),
                 RN_OK);
    CHECK_STATUS(rn_network_add_joint(net, "C", RN_JOINT_RIGID, 1, rc, ec, &jc), RN_OK);
  }
  CHECK_STATUS(rn_network_clamp(net, c0, RN_START), RN_OK);
  CHECK_STATUS(rn_network_clamp_joint(net, jc), RN_OK);
  CHECK_STATUS(rn_network_displace_joint(net, jc, NULL, rot), RN_OK);
  CHECK_STATUS(rn_network_add_joint_force(net, ja, f), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, bm, ne, fb), RN_OK);
  CHECK_STATUS(rn_network_add_joint_moment(net, jb, mb), RN_OK);
  CHECK_STATUS(rn_network_add_moment(net, bm, 1, mr), RN_OK);
  if (finalize) CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

/* Square grid of 3 x 3 cells of size 1 in the xy plane (4 x 4 joints, 24 rods of
 * ne edges, d1 = +z), joint models in a checkerboard (rigid where i + j is even).
 * The four corner joints are clamped; the four interior joints carry an
 * out-of-plane force P, the joint (1, 0) an in-plane force P along x and the
 * joint (2, 1) a couple 0.02 about y. */
static inline rn_network *shimnet_grid(rn_context *ctx, int ne, double P) {
  enum { N = 4 };
  rn_network *net = NULL;
  int rods[N * N][4], ends[N * N][4], cnt[N * N], jid[N * N];
  const double d1[3] = {0, 0, 1};
  char name[32];
  memset(cnt, 0, sizeof cnt);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i) {
      const double p[3] = {i, j, 0};
      const int u = j * N + i;
      if (i + 1 < N) {
        const double q[3] = {i + 1, j, 0};
        const int w = u + 1;
        int r;
        snprintf(name, sizeof name, "x%d_%d", i, j);
        r = shimnet_line(net, name, p, q, ne, d1);
        rods[u][cnt[u]] = r, ends[u][cnt[u]++] = RN_START;
        rods[w][cnt[w]] = r, ends[w][cnt[w]++] = RN_END;
      }
      if (j + 1 < N) {
        const double q[3] = {i, j + 1, 0};
        const int w = u + N;
        int r;
        snprintf(name, sizeof name, "y%d_%d", i, j);
        r = shimnet_line(net, name, p, q, ne, d1);
        rods[u][cnt[u]] = r, ends[u][cnt[u]++] = RN_START;
        rods[w][cnt[w]] = r, ends[w][cnt[w]++] = RN_END;
      }
    }
  for (int j = 0; j < N; ++j)
    for (int i = 0; i < N; ++i) {
      const int u = j * N + i;
      const rn_joint_model model = (i + j) % 2 == 0 ? RN_JOINT_RIGID : RN_JOINT_ELASTIC;
      snprintf(name, sizeof name, "j%d_%d", i, j);
      CHECK_STATUS(
          rn_network_add_joint(net, name, model, cnt[u], rods[u], ends[u], &jid[u]),
          RN_OK);
    }
  {
    const double fz[3] = {0, 0, P}, fx[3] = {P, 0, 0}, m[3] = {0, 0.02, 0};
    const int corners[4] = {0, N - 1, N * (N - 1), N * N - 1};
    for (int c = 0; c < 4; ++c)
      CHECK_STATUS(rn_network_clamp_joint(net, jid[corners[c]]), RN_OK);
    for (int j = 1; j < N - 1; ++j)
      for (int i = 1; i < N - 1; ++i)
        CHECK_STATUS(rn_network_add_joint_force(net, jid[j * N + i], fz), RN_OK);
    CHECK_STATUS(rn_network_add_joint_force(net, jid[1], fx), RN_OK);
    CHECK_STATUS(rn_network_add_joint_moment(net, jid[N + 2], m), RN_OK);
  }
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

/* Reduced indices of the rotation DOFs of the free rigid joints: joint DOFs follow
 * all rods in the reduced vector (position unless pinned or clamped, then the
 * rotation of a rigid joint unless clamped).  Fills idx (3 per such joint) and
 * returns their count. */
static inline int shimnet_rigid_rotation_dofs(const rn_network *net, const int *pinned,
                                              const int *clamped, size_t *idx) {
  const int nj = rn_network_num_joints(net);
  size_t tail = 0, at;
  int count = 0;
  for (int j = 0; j < nj; ++j) {
    tail += (pinned[j] || clamped[j]) ? 0 : 3;
    tail += (rn_network_joint_model(net, j) == RN_JOINT_RIGID && !clamped[j]) ? 3 : 0;
  }
  at = rn_network_num_dofs(net) - tail;
  for (int j = 0; j < nj; ++j) {
    at += (pinned[j] || clamped[j]) ? 0 : 3;
    if (rn_network_joint_model(net, j) == RN_JOINT_RIGID && !clamped[j]) {
      for (int c = 0; c < 3; ++c) idx[count++] = at++;
    }
  }
  return count;
}

/* Physical state of a network: every rod's vertices and d1 directors, every
 * joint's position and rotation, concatenated into v (allocated; *n entries). */
static inline double *shimnet_physical_state(const rn_network *net, size_t *n) {
  size_t len = 0, at = 0;
  const int nr = rn_network_num_rods(net), nj = rn_network_num_joints(net);
  double *v;
  for (int r = 0; r < nr; ++r) {
    const int nv = rn_network_rod_num_vertices(net, r);
    len += 3 * (size_t)nv + 3 * (size_t)(nv - 1);
  }
  len += 12 * (size_t)nj;
  v = calloc(len, sizeof(double));
  for (int r = 0; r < nr; ++r) {
    const int nv = rn_network_rod_num_vertices(net, r);
    CHECK_STATUS(rn_network_rod_vertices(net, r, v + at), RN_OK);
    at += 3 * (size_t)nv;
    CHECK_STATUS(rn_network_rod_frames(net, r, v + at, NULL), RN_OK);
    at += 3 * (size_t)(nv - 1);
  }
  for (int j = 0; j < nj; ++j) {
    CHECK_STATUS(rn_network_joint_position(net, j, v + at), RN_OK);
    CHECK_STATUS(rn_network_joint_rotation(net, j, v + at + 3), RN_OK);
    at += 12;
  }
  *n = len;
  return v;
}

#endif

/* api_part.c - parts of a network (rn_network_set_part) in one process: for
 * several networks (a single rod; independent rods; a grid with rigid joints;
 * a frame with elastic joints, a clamped joint turned and a pinned joint moved;
 * a lattice of one-edge rods with both joint models and component pins;
 * periodic cells: a 2D square supercell with mixed strain / stress control and
 * the anchor, a 2D cell of one-edge rods, a 3D cubic cell under stress pinned on
 * a rod's vertex) and
 * partitions into K = 1 .. 5 parts (more parts than rods included), built
 * through the same calls with whole-network indices:
 *   - the one-part partition numbers the DOFs exactly as the whole network and
 *     evaluates bit-identically;
 *   - the parts' owned DOFs and stencils add up to the whole network's; every
 *     DOF has one owner and the keys of the parts name whole-network DOFs;
 *   - at perturbed states the parts' energies add up to the whole energy, and
 *     their gradients, Hessian-vector products and CSR Hessians, summed by
 *     global DOF, to the whole network's (to round-off);
 *   - after reference updates of every part at the same accepted state (ghost
 *     values equal to the owners' values) the sums still agree, and the
 *     updated owned values equal the whole network's;
 *   - graph-only mode records the graph; a mismatching graph is rejected. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "testutil.h"

typedef void (*builder)(rn_network *net);

static void props(rn_network *net, int rod, double rho) {
  rn_material m;
  rn_section s;
  CHECK_STATUS(rn_material_from_E_nu(1e7, 0.3, rho, &m), RN_OK);
  CHECK_STATUS(rn_section_ellipse(0.012, 0.008, &s), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
}

/* Straight rod a -> b with ne edges (slightly bowed by bow along +z). */
static int line(rn_network *net, const double a[3], const double b[3], int ne,
                double bow) {
  double *x = malloc(sizeof(double) * 3 * (size_t)(ne + 1));
  int rod = -1;
  for (int i = 0; i <= ne; ++i) {
    double t = (double)i / ne;
    for (int k = 0; k < 3; ++k) x[3 * i + k] = a[k] + (b[k] - a[k]) * t;
    x[3 * i + 2] += bow * t * (1.0 - t);
  }
  CHECK_STATUS(rn_network_add_rod(net, NULL, ne + 1, x, NULL, &rod), RN_OK);
  free(x);
  props(net, rod, 800.0);
  return rod;
}

static void build_single_rod(rn_network *net) {
  const double a[3] = {0, 0, 0}, b[3] = {1, 0.2, 0}, f[3] = {0, 0.3, -0.5},
               m[3] = {0.01, 0.02, 0}, w[3] = {0, 0, -0.2}, g[3] = {0, 0, -9.81};
  int r = line(net, a, b, 11, 0.05);
  CHECK_STATUS(rn_network_clamp(net, r, RN_START), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, r, -1, f), RN_OK);
  CHECK_STATUS(rn_network_add_moment(net, r, 5, m), RN_OK);
  CHECK_STATUS(rn_network_add_line_load(net, r, w), RN_OK);
  CHECK_STATUS(rn_network_add_gravity(net, g), RN_OK);
}

static void build_independent(rn_network *net) {
  for (int i = 0; i < 3; ++i) {
    const double a[3] = {0, i, 0}, b[3] = {1, i, 0.1 * i}, f[3] = {0.1, 0, -0.2 * i},
                 d[3] = {0.01 * i, 0, 0}, m[3] = {0, 0, 0.01};
    int r = line(net, a, b, 5 + i, 0.02);
    CHECK_STATUS(rn_network_clamp(net, r, RN_START), RN_OK);
    CHECK_STATUS(rn_network_displace_end(net, r, RN_START, d, NULL), RN_OK);
    CHECK_STATUS(rn_network_add_force(net, r, -1, f), RN_OK);
    CHECK_STATUS(rn_network_add_moment(net, r, -1, m), RN_OK);
  }
}

/* n x n cells of a square grid, rods of ne edges, joints of the model given
 * (-1: checkerboard); corner joints pinned, a force, couples. */
static void grid(rn_network *net, int n, int ne, int model) {
  int nj = (n + 1) * (n + 1), *hor = malloc(sizeof(int) * (size_t)(n * (n + 1)));
  int *ver = malloc(sizeof(int) * (size_t)(n * (n + 1)));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i < n; ++i) {
      const double a[3] = {i, j, 0}, b[3] = {i + 1, j, 0};
      hor[j * n + i] = line(net, a, b, ne, 0.03 * ((i + j) % 2 ? 1 : -1));
    }
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j < n; ++j) {
      const double a[3] = {i, j, 0}, b[3] = {i, j + 1, 0};
      ver[i * n + j] = line(net, a, b, ne, 0.0);
    }
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      int rods[4], ends[4], v = 0, jt;
      int mdl = model >= 0 ? model : ((i + j) % 2 ? RN_JOINT_ELASTIC : RN_JOINT_RIGID);
      if (i > 0) rods[v] = hor[j * n + i - 1], ends[v++] = RN_END;
      if (i < n) rods[v] = hor[j * n + i], ends[v++] = RN_START;
      if (j > 0) rods[v] = ver[i * n + j - 1], ends[v++] = RN_END;
      if (j < n) rods[v] = ver[i * n + j], ends[v++] = RN_START;
      CHECK_STATUS(
          rn_network_add_joint(net, NULL, (rn_joint_model)mdl, v, rods, ends, &jt),
          RN_OK);
      CHECK(jt == j * (n + 1) + i);
    }
  {
    const double f[3] = {0.02, 0.01, 0.3}, m[3] = {0.001, -0.002, 0.003},
                 d[3] = {0, 0, 0.01};
    CHECK_STATUS(rn_network_pin_joint(net, 0), RN_OK);
    CHECK_STATUS(rn_network_pin_joint(net, n), RN_OK);
    CHECK_STATUS(rn_network_pin_joint_components(net, nj - 1, RN_FIX_Z), RN_OK);
    CHECK_STATUS(rn_network_displace_joint(net, nj - 1, d, NULL), RN_OK);
    CHECK_STATUS(rn_network_pin_joint_components(net, nj - n - 1, RN_FIX_X | RN_FIX_Z),
                 RN_OK);
    CHECK_STATUS(rn_network_add_joint_force(net, nj / 2, f), RN_OK);
    CHECK_STATUS(rn_network_add_joint_moment(net, n + 2, m), RN_OK);
    CHECK_STATUS(rn_network_add_moment(net, hor[1], 1, m), RN_OK);
  }
  free(hor);
  free(ver);
}

static void build_rigid_grid(rn_network *net) { grid(net, 3, 3, RN_JOINT_RIGID); }
static void build_mixed_grid(rn_network *net) { grid(net, 3, 1, -1); }

/* A frame with elastic joints: two columns and a beam, a valence-3 joint, a
 * clamped joint with prescribed rotation, a pinned joint moved, a free end. */
static void build_elastic_frame(rn_network *net) {
  const double p0[3] = {0, 0, 0}, p1[3] = {0, 0, 1}, p2[3] = {1, 0, 1}, p3[3] = {1, 0, 0},
               p4[3] = {1.5, 0.3, 1.4};
  const double rot[3] = {0, 0.05, 0.02}, d[3] = {0.01, 0, 0}, f[3] = {0.1, 0.05, -0.2},
               m[3] = {0, 0.01, 0};
  int c0 = line(net, p0, p1, 4, 0.02), bm = line(net, p1, p2, 6, 0.05);
  int c1 = line(net, p3, p2, 4, -0.02), br = line(net, p2, p4, 3, 0.0);
  int ja, jb, jc, jd;
  int ra[2] = {c0, bm}, ea[2] = {RN_END, RN_START};
  int rb[3] = {bm, c1, br}, eb[3] = {RN_END, RN_END, RN_START};
  int rc[1] = {c1}, ec[1] = {RN_START};
  int rd[1] = {c0}, ed[1] = {RN_START};
  CHECK_STATUS(rn_network_add_joint(net, "A", RN_JOINT_ELASTIC, 2, ra, ea, &ja), RN_OK);
  CHECK_STATUS(rn_network_add_joint(net, "B", RN_JOINT_ELASTIC, 3, rb, eb, &jb), RN_OK);
  CHECK_STATUS(rn_network_add_joint(net, "C", RN_JOINT_ELASTIC, 1, rc, ec, &jc), RN_OK);
  CHECK_STATUS(rn_network_add_joint(net, "D", RN_JOINT_RIGID, 1, rd, ed, &jd), RN_OK);
  CHECK_STATUS(rn_network_clamp_joint(net, jc), RN_OK);
  CHECK_STATUS(rn_network_displace_joint(net, jc, NULL, rot), RN_OK);
  CHECK_STATUS(rn_network_pin_joint(net, jd), RN_OK);
  CHECK_STATUS(rn_network_displace_joint(net, jd, d, NULL), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, br, -1, f), RN_OK);
  CHECK_STATUS(rn_network_add_joint_moment(net, jb, m), RN_OK);
  CHECK_STATUS(rn_network_add_joint_force(net, ja, f), RN_OK);
  CHECK_STATUS(rn_network_fix_theta(net, br, -1), RN_OK);
}

typedef struct whole_ref {
  rn_network *net;
  size_t n;
  const int64_t *keys; /* of its one-part twin */
} whole_ref;

/* Index of key in the whole network's reduced vector (keys of the one-part
 * twin are increasing). */
static long key_index(const whole_ref *w, int64_t key) {
  long lo = 0, hi = (long)w->n - 1;
  while (lo <= hi) {
    long mid = (lo + hi) / 2;
    if (w->keys[mid] == key) return mid;
    if (w->keys[mid] < key)
      lo = mid + 1;
    else
      hi = mid - 1;
  }
  return -1;
}

static rn_network *build(rn_context *ctx, builder b, int nparts, int part, const int *rp,
                         const int *gnv, int nr, int nj, const int *jp, const int *jr) {
  rn_network *net = NULL;
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  if (rp)
    CHECK_STATUS(rn_network_set_part(net, nparts, part, nr, gnv, rp, nj, jp, jr), RN_OK);
  b(net);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

static double rel_err(size_t n, const double *a, const double *b) {
  double d = 0.0, s = 0.0;
  for (size_t i = 0; i < n; ++i) {
    d = fmax(d, fabs(a[i] - b[i]));
    s = fmax(s, fabs(b[i]));
  }
  return s > 0.0 ? d / s : d;
}

/* Parts' evaluations at the whole state xw (direction v) summed by global DOF
 * against the whole network's; H_w dense [n n]. */
static void compare_sums(const whole_ref *w, rn_network **parts, int K, const double *xw,
                         const double *v, const char *label) {
  size_t n = w->n;
  double Ew = 0.0, Es = 0.0, *gw = calloc(n + 1, sizeof(double));
  double *gs = calloc(n + 1, sizeof(double)), *hw = calloc(n + 1, sizeof(double));
  double *hs = calloc(n + 1, sizeof(double)), *Hd = calloc(n * n + 1, sizeof(double));
  double *Hs = calloc(n * n + 1, sizeof(double));
  size_t nnz;
  const int64_t *rp;
  const int32_t *col;
  CHECK_STATUS(rn_network_gradient(w->net, xw, &Ew, gw), RN_OK);
  CHECK_STATUS(rn_network_hvp(w->net, xw, v, hw), RN_OK);
  CHECK_STATUS(rn_network_hessian_pattern(w->net, &nnz, &rp, &col), RN_OK);
  {
    double *vals = malloc((nnz + 1) * sizeof(double));
    CHECK_STATUS(rn_network_hessian_values(w->net, xw, vals), RN_OK);
    for (size_t i = 0; i < n; ++i)
      for (int64_t k = rp[i]; k < rp[i + 1]; ++k) Hd[i * n + (size_t)col[k]] = vals[k];
    free(vals);
  }
  for (int p = 0; p < K; ++p) {
    size_t m = rn_network_num_dofs(parts[p]), pn;
    const int64_t *keys;
    const int *own;
    double E = 0.0, *x = malloc((m + 1) * sizeof(double)),
           *vl = malloc((m + 1) * sizeof(double));
    double *g = malloc((m + 1) * sizeof(double)), *h = malloc((m + 1) * sizeof(double));
    long *gi = malloc((m + 1) * sizeof(long));
    CHECK_STATUS(rn_network_part_dofs(parts[p], &pn, &keys, &own), RN_OK);
    for (size_t i = 0; i < m; ++i) {
      gi[i] = key_index(w, keys[i]);
      CHECK(gi[i] >= 0);
      if (gi[i] < 0) gi[i] = 0;
      x[i] = xw[gi[i]];
      vl[i] = v[gi[i]];
    }
    CHECK_STATUS(rn_network_gradient(parts[p], x, &E, g), RN_OK);
    CHECK_STATUS(rn_network_hvp(parts[p], x, vl, h), RN_OK);
    Es += E;
    for (size_t i = 0; i < m; ++i) {
      gs[gi[i]] += g[i];
      hs[gi[i]] += h[i];
    }
    CHECK_STATUS(rn_network_hessian_pattern(parts[p], &nnz, &rp, &col), RN_OK);
    {
      double *vals = malloc((nnz + 1) * sizeof(double));
      CHECK_STATUS(rn_network_hessian_values(parts[p], x, vals), RN_OK);
      for (size_t i = 0; i < m; ++i)
        for (int64_t k = rp[i]; k < rp[i + 1]; ++k)
          Hs[(size_t)gi[i] * n + (size_t)gi[col[k]]] += vals[k];
      free(vals);
    }
    free(x);
    free(vl);
    free(g);
    free(h);
    free(gi);
  }
  {
    double eg = rel_err(n, gs, gw), eh = rel_err(n, hs, hw), eH = rel_err(n * n, Hs, Hd);
    if (!(fabs(Es - Ew) <= 1e-12 * fabs(Ew) && eg <= 1e-12 && eh <= 1e-12 && eH <= 1e-12))
      printf("%s: K = %d: energy %.17g vs %.17g, gradient %.3g, HVP %.3g, Hessian %.3g\n",
             label, K, Es, Ew, eg, eh, eH);
    CHECK_REL(Es, Ew, 1e-12);
    CHECK(eg <= 1e-12);
    CHECK(eh <= 1e-12);
    CHECK(eH <= 1e-12);
  }
  free(gw);
  free(gs);
  free(hw);
  free(hs);
  free(Hd);
  free(Hs);
}

/* Accept x (whole-network vector) on every part (their vectors gathered from
 * x before anything changes) and on the whole network: the parts' updated
 * owned values equal the whole network's (rigid rotations reset by their
 * joint's owner). */
static void accept_all(whole_ref *w, rn_network **parts, int K, double *x) {
  double *xp[5];
  for (int p = 0; p < K; ++p) {
    size_t m = rn_network_num_dofs(parts[p]);
    const int64_t *keys;
    xp[p] = malloc((m + 1) * sizeof(double));
    CHECK_STATUS(rn_network_part_dofs(parts[p], NULL, &keys, NULL), RN_OK);
    for (size_t i = 0; i < m; ++i) {
      long gi = key_index(w, keys[i]);
      xp[p][i] = x[gi < 0 ? 0 : gi];
    }
  }
  CHECK_STATUS(rn_network_update_reference(w->net, x), RN_OK);
  for (int p = 0; p < K; ++p) {
    size_t pn;
    const int64_t *keys;
    CHECK_STATUS(rn_network_update_reference(parts[p], xp[p]), RN_OK);
    CHECK_STATUS(rn_network_part_dofs(parts[p], &pn, &keys, NULL), RN_OK);
    for (size_t i = 0; i < pn; ++i) CHECK(xp[p][i] == x[key_index(w, keys[i])]);
    free(xp[p]);
  }
}

static void perturb(size_t n, const double *x0, double *x, double amp, uint64_t *seed) {
  for (size_t i = 0; i < n; ++i) x[i] = x0[i] + amp * rn_test_rand(seed);
}

/* Partition choices: blocks, round robin, scattered; nparts may exceed rods. */
static void choose_parts(int kind, int nrods, int K, int *rp) {
  for (int r = 0; r < nrods; ++r) {
    if (kind == 0)
      rp[r] = (int)((long)r * K / nrods);
    else if (kind == 1)
      rp[r] = r % K;
    else
      rp[r] = (int)(((unsigned)r * 2654435761u) >> 7) % K;
  }
}

static void check_network(rn_context *ctx, builder b, const char *label) {
  rn_network *g = NULL, *whole, *one;
  int nr, nj;
  const int *gnv, *jp, *jr;
  whole_ref w;
  size_t n;
  CHECK_STATUS(rn_network_create(ctx, &g), RN_OK);
  CHECK_STATUS(rn_network_set_graph_only(g), RN_OK);
  b(g);
  CHECK_STATUS(rn_network_finalize(g), RN_OK);
  CHECK_STATUS(rn_network_rod_graph(g, &nr, &gnv, &nj, &jp, &jr), RN_OK);
  CHECK(rn_network_num_dofs(g) == 0);
  whole = build(ctx, b, 1, 0, NULL, NULL, 0, 0, NULL, NULL);
  CHECK(rn_network_num_rods(whole) == nr);
  CHECK(rn_network_num_joints(whole) == nj);
  n = rn_network_num_dofs(whole);
  {
    int *rp = calloc((size_t)nr + 1, sizeof(int));
    size_t pn;
    const int *own;
    one = build(ctx, b, 1, 0, rp, gnv, nr, nj, jp, jr);
    free(rp);
    CHECK(rn_network_num_dofs(one) == n);
    CHECK_STATUS(rn_network_part_dofs(one, &pn, &w.keys, &own), RN_OK);
    CHECK(pn == n);
    for (size_t i = 1; i < n; ++i) CHECK(w.keys[i] > w.keys[i - 1]);
  }
  w.net = whole;
  w.n = n;
  {
    uint64_t seed = 7;
    double *x0 = malloc((n + 1) * sizeof(double)), *x = malloc((n + 1) * sizeof(double));
    double *v = malloc((n + 1) * sizeof(double)), E1, E2, *g1 = malloc((n + 1) * 8);
    double *g2 = malloc((n + 1) * 8);
    CHECK_STATUS(rn_network_get_dofs(whole, x0), RN_OK);
    perturb(n, x0, x, 1e-3, &seed);
    CHECK_STATUS(rn_network_gradient(whole, x, &E1, g1), RN_OK);
    CHECK_STATUS(rn_network_gradient(one, x, &E2, g2), RN_OK);
    CHECK(E1 == E2);
    CHECK(memcmp(g1, g2, n * sizeof(double)) == 0);
    free(g1);
    free(g2);
    for (int K = 2; K <= 5; ++K)
      for (int kind = 0; kind < 3; ++kind) {
        rn_network *parts[5];
        rn_part_info tot, info;
        int *rp = malloc(sizeof(int) * ((size_t)nr + 1));
        size_t owned = 0;
        long stencils = 0;
        choose_parts(kind, nr, K, rp);
        for (int p = 0; p < K; ++p) {
          parts[p] = build(ctx, b, K, p, rp, gnv, nr, nj, jp, jr);
          CHECK_STATUS(rn_network_part_info(parts[p], &info), RN_OK);
          CHECK(info.nparts == K && info.part == p);
          owned += info.owned_dofs;
          stencils += info.owned_stencils;
        }
        CHECK_STATUS(rn_network_part_info(whole, &tot), RN_OK);
        CHECK(owned == tot.owned_dofs);
        CHECK(stencils == tot.owned_stencils);
        /* the start, perturbed states, then after two reference updates */
        CHECK_STATUS(rn_network_get_dofs(whole, x0), RN_OK);
        perturb(n, x0, v, 1.0, &seed);
        compare_sums(&w, parts, K, x0, v, label);
        for (int step = 0; step < 3; ++step) {
          perturb(n, x0, x, 2e-3, &seed);
          compare_sums(&w, parts, K, x, v, label);
          if (step < 2) accept_all(&w, parts, K, x);
        }
        for (int p = 0; p < K; ++p) rn_network_destroy(&parts[p]);
        free(rp);
        /* the next partition starts from the initial state again */
        rn_network_destroy(&whole);
        whole = build(ctx, b, 1, 0, NULL, NULL, 0, 0, NULL, NULL);
        w.net = whole;
      }
    free(x0);
    free(x);
    free(v);
  }
  rn_network_destroy(&one);
  rn_network_destroy(&whole);
  rn_network_destroy(&g);
}

/* A periodic n x n supercell of the unit square lattice (2D cell, lattice
 * vectors n e1, n e2): joint (i, j) joins the rods starting there with the rods
 * ending there, those across the cell's edges at the images (1, 0) and (0, 1).
 * Mixed control: E11 prescribed, an applied stress on E22, E12 free; no support
 * (the anchor: joint 0).  model -1: joints alternate elastic and rigid. */
static void square_cell(rn_network *net, int n, int ne, int model) {
  const double vec[6] = {n, 0, 0, 0, n, 0};
  const int fixed[3] = {1, 0, 0};
  const double strain[3] = {2e-3, 0, 0}, stress[3] = {0, -40.0, 0};
  int *hor = malloc(sizeof(int) * (size_t)(n * n)),
      *ver = malloc(sizeof(int) * (size_t)(n * n));
  CHECK_STATUS(rn_network_set_periodic(net, 2, vec), RN_OK);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double a[3] = {i, j, 0}, b[3] = {i + 1, j, 0}, c[3] = {i, j + 1, 0};
      hor[j * n + i] = line(net, a, b, ne, ne > 1 ? 0.03 * ((i + j) % 2 ? 1 : -1) : 0.0);
      ver[j * n + i] = line(net, a, c, ne, ne > 1 ? 0.02 : 0.0);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      int rods[4], ends[4], img[12] = {0}, jt;
      int mdl = model >= 0 ? model : ((i + j) % 2 ? RN_JOINT_ELASTIC : RN_JOINT_RIGID);
      int il = (i + n - 1) % n, jl = (j + n - 1) % n;
      rods[0] = hor[j * n + i], ends[0] = RN_START;
      rods[1] = ver[j * n + i], ends[1] = RN_START;
      rods[2] = hor[j * n + il], ends[2] = RN_END;
      rods[3] = ver[jl * n + i], ends[3] = RN_END;
      img[6] = i == 0;
      img[10] = j == 0;
      CHECK_STATUS(rn_network_add_joint_images(net, NULL, (rn_joint_model)mdl, 4, rods,
                                               ends, img, &jt),
                   RN_OK);
      CHECK(jt == j * n + i);
    }
  CHECK_STATUS(rn_network_set_cell_strain(net, fixed, strain), RN_OK);
  CHECK_STATUS(rn_network_set_cell_stress(net, stress), RN_OK);
  free(hor);
  free(ver);
}

static void build_square_supercell(rn_network *net) { square_cell(net, 3, 3, -1); }
static void build_square_one_edge(rn_network *net) { square_cell(net, 2, 1, -1); }

/* A 3D periodic 2 x 1 x 1 supercell of the simple cubic lattice with rigid
 * joints, stress control on every component (E33 compressed, a shear), and a pin
 * of a rod's vertex instead of the anchor (the part holding that rod is not the
 * one holding joint 0). */
static void build_cubic_cell(rn_network *net) {
  const double vec[9] = {2, 0, 0, 0, 1, 0, 0, 0, 1};
  const int fixed[6] = {0};
  const double stress[6] = {0, 0, -30.0, 0, 8.0, 0};
  int r[2][3];
  CHECK_STATUS(rn_network_set_periodic(net, 3, vec), RN_OK);
  for (int i = 0; i < 2; ++i)
    for (int d = 0; d < 3; ++d) {
      double a[3] = {i, 0, 0}, b[3] = {i, 0, 0};
      b[d] += 1.0;
      r[i][d] = line(net, a, b, 3, d == 2 ? 0.0 : 0.02);
    }
  for (int i = 0; i < 2; ++i) {
    int rods[6], ends[6], img[18] = {0};
    for (int d = 0; d < 3; ++d) {
      rods[2 * d] = r[i][d], ends[2 * d] = RN_START;
      rods[2 * d + 1] = d == 0 ? r[1 - i][0] : r[i][d], ends[2 * d + 1] = RN_END;
      img[3 * (2 * d + 1) + d] = d == 0 ? (i == 0) : 1;
    }
    CHECK_STATUS(
        rn_network_add_joint_images(net, NULL, RN_JOINT_RIGID, 6, rods, ends, img, NULL),
        RN_OK);
  }
  CHECK_STATUS(rn_network_set_cell_strain(net, fixed, NULL), RN_OK);
  CHECK_STATUS(rn_network_set_cell_stress(net, stress), RN_OK);
  CHECK_STATUS(rn_network_pin(net, r[1][2], 1), RN_OK);
}

/* Two pairs of rods whose joints coincide: graph-only mode finds it (no part holds
 * both joints of a two-part partition); a part built from another graph fails. */
static void build_cross(rn_network *net) {
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {2, 0, 0}, d[3] = {1, -1, 0},
               e[3] = {1, 1, 0};
  int r[4], j, ra[2], ea[2] = {RN_END, RN_START};
  r[0] = line(net, a, b, 3, 0.0);
  r[1] = line(net, b, c, 3, 0.0);
  r[2] = line(net, d, b, 3, 0.0);
  r[3] = line(net, b, e, 3, 0.0);
  ra[0] = r[0], ra[1] = r[1];
  CHECK_STATUS(rn_network_add_joint(net, "J1", RN_JOINT_ELASTIC, 2, ra, ea, &j), RN_OK);
  ra[0] = r[2], ra[1] = r[3];
  CHECK_STATUS(rn_network_add_joint(net, "J2", RN_JOINT_ELASTIC, 2, ra, ea, &j), RN_OK);
}

static void check_graph_errors(rn_context *ctx) {
  rn_network *g = NULL, *p = NULL;
  const int nv[4] = {4, 4, 4, 5}, rp[4] = {0, 0, 1, 1}, jp[3] = {0, 2, 4},
            jr[4] = {0, 1, 2, 3};
  CHECK_STATUS(rn_network_create(ctx, &g), RN_OK);
  CHECK_STATUS(rn_network_set_graph_only(g), RN_OK);
  build_cross(g);
  CHECK_STATUS(rn_network_finalize(g), RN_ERR_GEOMETRY);
  CHECK(
      strstr(rn_context_last_error(ctx), "joints 0 ('J1') and 1 ('J2') are coincident"));
  rn_network_destroy(&g);
  /* a graph whose rod 3 has 5 vertices does not describe this network */
  CHECK_STATUS(rn_network_create(ctx, &p), RN_OK);
  CHECK_STATUS(rn_network_set_part(p, 2, 0, 4, nv, rp, 2, jp, jr), RN_OK);
  {
    const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0};
    int r = -1;
    double x[12];
    for (int i = 0; i < 4; ++i)
      for (int k = 0; k < 3; ++k) x[3 * i + k] = a[k] + (b[k] - a[k]) * i / 3.0;
    for (int i = 0; i < 3; ++i)
      CHECK_STATUS(rn_network_add_rod(p, NULL, 4, x, NULL, &r), RN_OK);
    CHECK_STATUS(rn_network_add_rod(p, NULL, 4, x, NULL, &r), RN_ERR_ARG);
    CHECK(strstr(rn_context_last_error(ctx), "is not rod 3 of the partition's graph"));
  }
  CHECK_STATUS(rn_network_set_graph_only(p), RN_ERR_STATE);
  rn_network_destroy(&p);
}

int main(void) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  check_graph_errors(ctx);
  check_network(ctx, build_single_rod, "single rod");
  check_network(ctx, build_independent, "independent rods");
  check_network(ctx, build_rigid_grid, "rigid grid");
  check_network(ctx, build_mixed_grid, "one-edge rods, mixed joints");
  check_network(ctx, build_elastic_frame, "elastic frame");
  check_network(ctx, build_square_supercell, "periodic 3 x 3 square supercell");
  check_network(ctx, build_square_one_edge, "periodic 2 x 2 cell of one-edge rods");
  check_network(ctx, build_cubic_cell, "periodic 3D cubic 2 x 1 x 1 cell");
  rn_context_destroy(&ctx);
  return rn_test_finish("api_part");
}

/* api_joints.c - joints in the C API, both models (elastic, rigid):
 *  - FD checks over an h-sweep (fitted order ~2) of gradient and HVP, Hessian
 *    symmetry and CSR == HVP on random deformed star networks of valence 1..8
 *    and 12 (anisotropic sections with I12 != 0, rest curvature and twist;
 *    other rod ends free, or clamped/pinned with joint force and couple),
 *    every DOF perturbed including rotation DOFs; the FD table is printed;
 *  - zero energy and gradient at rest, identity rotation at rest;
 *  - the energy unchanged by rn_network_update_reference (rigid rotation DOFs
 *    reset to 0, joint rotation and couple angle continued);
 *  - invariance of the energy under rigid motions;
 *  - several rods between the same two joints, rods of a single edge between
 *    joints, clamped joints with prescribed motion, joint loads;
 *  - every error path of the joint API. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "testutil.h"

enum { MAXN = 600, N_H = 7, N_FIT = 5, MAXV = 12, TABLE_V = 8, MAXNV = 5 };

static uint64_t rng = 20240607;

static double urand(void) { return rn_test_rand(&rng); }

static double dot(size_t n, const double *a, const double *b) {
  double s = 0.0;
  for (size_t i = 0; i < n; ++i) s += a[i] * b[i];
  return s;
}

static double norm(size_t n, const double *a) { return sqrt(dot(n, a, a)); }

static int contains(const char *s, const char *sub) { return strstr(s, sub) != NULL; }

/* Rotation matrix of the rotation vector w (Rodrigues), row-major. */
static void rotmat(const double w[3], double R[9]) {
  double th = norm(3, w), k[3] = {0, 0, 0}, c = cos(th), s = sin(th);
  if (th > 0.0)
    for (int i = 0; i < 3; ++i) k[i] = w[i] / th;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[3 * i + j] = (i == j ? c : 0.0) + (1 - c) * k[i] * k[j];
  R[1] -= s * k[2];
  R[2] += s * k[1];
  R[3] += s * k[2];
  R[5] -= s * k[0];
  R[6] -= s * k[1];
  R[7] += s * k[0];
}

static void matvec(const double R[9], const double v[3], double out[3]) {
  double t[3];
  for (int i = 0; i < 3; ++i)
    t[i] = R[3 * i] * v[0] + R[3 * i + 1] * v[1] + R[3 * i + 2] * v[2];
  memcpy(out, t, sizeof(t));
}

/* Anisotropic section with I12 != 0, varying with j. */
static rn_section aniso(int j) {
  rn_section s;
  s.A = 1e-2 * (1.0 + 0.1 * j);
  s.I11 = 3e-4 * (1.0 + 0.05 * j);
  s.I22 = 1e-4;
  s.I12 = 5e-5;
  s.J = 2e-4;
  return s;
}

/* ---- star networks: v rods meeting at one joint ---------------------------- */
typedef struct star_spec {
  int v;
  int nv[MAXV], end[MAXV]; /* end of rod k at the joint */
  double xyz[MAXV][3 * MAXNV];
  double d1[MAXV][3];
  int has_d1[MAXV];
  double kap[MAXV][2 * MAXNV], tau[MAXV][MAXNV];
  int bcs;  /* 1: far ends clamped (nv >= 3) or pinned, loads on the joint */
  int rest; /* 1: rest curvature and twist overridden (not at rest) */
} star_spec;

/* Rod k leaves the joint at c along a random direction, turning by up to
 * ~30 degrees per vertex; edges 0.08 .. 0.12.  Odd rods end at the joint
 * (vertex order reversed). */
static void star_make(star_spec *s, int v, int bcs) {
  double c[3] = {0.3 + 0.1 * urand(), -0.2 + 0.1 * urand(), 0.1 + 0.1 * urand()};
  memset(s, 0, sizeof(*s));
  s->v = v;
  s->bcs = bcs;
  s->rest = 1;
  for (int k = 0; k < v; ++k) {
    double dir[3] = {urand(), urand(), urand()}, pts[3 * MAXNV];
    int nv = 2 + (k + v) % 4;
    double n0 = norm(3, dir);
    for (int i = 0; i < 3; ++i) dir[i] /= n0;
    s->nv[k] = nv;
    s->end[k] = k % 2 ? RN_END : RN_START;
    memcpy(pts, c, sizeof(c));
    for (int i = 1; i < nv; ++i) {
      double w[3] = {0.3 * urand(), 0.3 * urand(), 0.3 * urand()}, R[9];
      double len = 0.1 + 0.02 * urand();
      rotmat(w, R);
      matvec(R, dir, dir);
      for (int q = 0; q < 3; ++q) pts[3 * i + q] = pts[3 * (i - 1) + q] + len * dir[q];
    }
    for (int i = 0; i < nv; ++i) /* reversed for rods that end at the joint */
      memcpy(s->xyz[k] + 3 * i, pts + 3 * (s->end[k] == RN_END ? nv - 1 - i : i),
             3 * sizeof(double));
    s->has_d1[k] = k % 3 != 2;
    for (int q = 0; q < 3; ++q) s->d1[k][q] = urand();
    for (int i = 0; i < nv - 2; ++i) {
      s->kap[k][2 * i] = 0.3 * urand();
      s->kap[k][2 * i + 1] = 0.3 * urand();
      s->tau[k][i] = 0.2 * urand();
    }
  }
}

/* Builds the star with its geometry rotated by W (NULL: as is). */
static rn_network *star_build(rn_context *ctx, const star_spec *s, rn_joint_model model,
                              const double *W) {
  rn_network *net = NULL;
  rn_material m = {1.0, 0.4, 0.5};
  int rods[MAXV], J;
  double R[9], f[3] = {0.02, -0.01, 0.015}, M[3] = {0.004, -0.006, 0.003};
  double g[3] = {0.0, 0.0, -0.5}, rf[3] = {-0.01, 0.02, 0.0};
  rotmat(W ? W : (const double[3]){0, 0, 0}, R);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  for (int k = 0; k < s->v; ++k) {
    double x[3 * MAXNV], d1[3];
    for (int i = 0; i < s->nv[k]; ++i) matvec(R, s->xyz[k] + 3 * i, x + 3 * i);
    matvec(R, s->d1[k], d1);
    CHECK_STATUS(
        rn_network_add_rod(net, NULL, s->nv[k], x, s->has_d1[k] ? d1 : NULL, &rods[k]),
        RN_OK);
    CHECK_STATUS(rn_network_set_material(net, k, -1, &m), RN_OK);
    for (int j = 0; j < s->nv[k] - 1; ++j) {
      rn_section sec = aniso(j + k);
      CHECK_STATUS(rn_network_set_section(net, k, j, &sec), RN_OK);
    }
    if (s->rest) {
      CHECK_STATUS(rn_network_set_rest_curvature(net, k, s->kap[k]), RN_OK);
      CHECK_STATUS(rn_network_set_rest_twist(net, k, s->tau[k]), RN_OK);
    }
    if (!s->bcs) continue;
    if (s->nv[k] >= 3)
      CHECK_STATUS(rn_network_clamp(net, k, 1 - s->end[k]), RN_OK);
    else
      CHECK_STATUS(rn_network_pin(net, k, s->end[k] == RN_START ? -1 : 0), RN_OK);
    CHECK_STATUS(rn_network_add_force(net, k, s->end[k] == RN_START ? 1 : -2, rf), RN_OK);
  }
  CHECK_STATUS(rn_network_add_joint(net, "hub", model, s->v, rods, s->end, &J), RN_OK);
  if (s->bcs) {
    CHECK_STATUS(rn_network_add_joint_force(net, J, f), RN_OK);
    CHECK_STATUS(rn_network_add_joint_moment(net, J, M), RN_OK);
    CHECK_STATUS(rn_network_add_gravity(net, g), RN_OK);
    CHECK_STATUS(rn_network_set_load_factor(net, 0.8), RN_OK);
  }
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

/* Perturbs every DOF: positions (nonzero at the input state) by pos, angles
 * and rotation vectors (zero there) by ang. */
static void deform(const rn_network *net, double *x, double pos, double ang) {
  size_t n = rn_network_num_dofs(net);
  for (size_t i = 0; i < n; ++i) x[i] += (x[i] == 0.0 ? ang : pos) * urand();
}

/* ---- FD checks ------------------------------------------------------------- */
typedef struct fd_stats {
  double eg, eh; /* worst over cases of the best relative error over h */
  double sg, sh; /* smallest fitted order over cases */
} fd_stats;

static void fd_init(fd_stats *st) {
  st->eg = st->eh = 0.0;
  st->sg = st->sh = INFINITY;
}

/* Gradient and HVP against central differences, h = 1e-2 .. 1e-5 (half
 * decades) along a random direction with entries 0.1 r (positions and
 * angles alike): second order (slope fitted over h = 1e-2 .. 1e-4, where
 * truncation dominates) and small error at the best h. */
static void fd_sweep(const rn_network *net, const double *x, const char *label,
                     fd_stats *st) {
  size_t n = rn_network_num_dofs(net);
  static double d[MAXN], g[MAXN], hv[MAXN], xp[MAXN], xm[MAXN], gp[MAXN], gm[MAXN];
  double h[N_H], eg[N_H], eh[N_H], gd, hvn, den, sg, sh, bg = INFINITY, bh = INFINITY;
  CHECK(n <= MAXN);
  for (size_t i = 0; i < n; ++i) d[i] = 0.1 * urand();
  CHECK_STATUS(rn_network_gradient(net, x, NULL, g), RN_OK);
  CHECK_STATUS(rn_network_hvp(net, x, d, hv), RN_OK);
  gd = dot(n, g, d);
  hvn = norm(n, hv);
  den = fmax(fabs(gd), norm(n, g) * norm(n, d) / sqrt((double)n));
  for (int k = 0; k < N_H; ++k) {
    double Ep, Em, r2 = 0.0;
    h[k] = pow(10.0, -2.0 - 0.5 * k);
    for (size_t i = 0; i < n; ++i) {
      xp[i] = x[i] + h[k] * d[i];
      xm[i] = x[i] - h[k] * d[i];
    }
    CHECK_STATUS(rn_network_gradient(net, xp, &Ep, gp), RN_OK);
    CHECK_STATUS(rn_network_gradient(net, xm, &Em, gm), RN_OK);
    eg[k] = fabs((Ep - Em) / (2.0 * h[k]) - gd) / den;
    for (size_t i = 0; i < n; ++i) {
      double r = (gp[i] - gm[i]) / (2.0 * h[k]) - hv[i];
      r2 += r * r;
    }
    eh[k] = sqrt(r2) / hvn;
    bg = fmin(bg, eg[k]);
    bh = fmin(bh, eh[k]);
  }
  sg = rn_test_loglog_slope(N_FIT, h, eg);
  sh = rn_test_loglog_slope(N_FIT, h, eh);
  if (!(sg > 1.8 && sg < 2.2) || !(sh > 1.8 && sh < 2.2) || getenv("RN_VERBOSE"))
    for (int k = 0; k < N_H; ++k)
      fprintf(stderr, "%s: h %.1e grad %.3e hvp %.3e (orders %.2f %.2f)\n", label, h[k],
              eg[k], eh[k], sg, sh);
  CHECK(sg > 1.8 && sg < 2.2);
  CHECK(sh > 1.8 && sh < 2.2);
  CHECK(bg < 1e-8);
  CHECK(bh < 1e-8);
  st->eg = fmax(st->eg, bg);
  st->eh = fmax(st->eh, bh);
  st->sg = fmin(st->sg, sg);
  st->sh = fmin(st->sh, sh);
}

/* CSR values: symmetric and equal to the HVP for random vectors. */
static void csr_checks(const rn_network *net, const double *x) {
  size_t n = rn_network_num_dofs(net), nnz;
  const int64_t *rp;
  const int32_t *cl;
  static double v[MAXN], hv[MAXN];
  double *vals, asym = 0.0, amax = 0.0;
  size_t bw = 0;
  CHECK_STATUS(rn_network_hessian_pattern(net, &nnz, &rp, &cl), RN_OK);
  vals = malloc(nnz * sizeof(double));
  CHECK_STATUS(rn_network_hessian_values(net, x, vals), RN_OK);
  for (size_t r = 0; r < n; ++r)
    for (int64_t p = rp[r]; p < rp[r + 1]; ++p) {
      int64_t q = rp[cl[p]];
      if (p > rp[r]) CHECK(cl[p] > cl[p - 1]); /* sorted, unique */
      {
        size_t d = (size_t)cl[p] > r ? (size_t)cl[p] - r : r - (size_t)cl[p];
        if (d > bw) bw = d;
      }
      while (q < rp[cl[p] + 1] && (size_t)cl[q] != r) q++;
      CHECK(q < rp[cl[p] + 1]);
      if (q < rp[cl[p] + 1]) asym = fmax(asym, fabs(vals[p] - vals[q]));
      amax = fmax(amax, fabs(vals[p]));
    }
  CHECK(asym <= 1e-13 * amax);
  CHECK(rp[n] == (int64_t)nnz);
  CHECK(bw == rn_network_hessian_bandwidth(net));
  for (int trial = 0; trial < 3; ++trial) {
    double diff = 0.0;
    for (size_t i = 0; i < n; ++i) v[i] = urand();
    CHECK_STATUS(rn_network_hvp(net, x, v, hv), RN_OK);
    for (size_t r = 0; r < n; ++r) {
      double y = 0.0;
      for (int64_t p = rp[r]; p < rp[r + 1]; ++p) y += vals[p] * v[cl[p]];
      diff += (y - hv[r]) * (y - hv[r]);
    }
    CHECK(sqrt(diff) <= 1e-13 * norm(n, hv));
  }
  free(vals);
}

/* FD table over both models and valence 1..8, both BC variants. */
static void test_fd_stars(rn_context *ctx) {
  static const char *names[2] = {"elastic", "rigid"};
  fd_stats tab[2][MAXV + 1];
  for (int model = 0; model < 2; ++model)
    for (int v = 1; v <= MAXV; v += v < TABLE_V ? 1 : MAXV - TABLE_V) {
      fd_init(&tab[model][v]);
      for (int bcs = 0; bcs < 2; ++bcs) {
        star_spec s;
        rn_network *net;
        double x[MAXN];
        char label[64];
        star_make(&s, v, bcs);
        net = star_build(ctx, &s, (rn_joint_model)model, NULL);
        snprintf(label, sizeof(label), "%s valence %d %s", names[model], v,
                 bcs ? "clamped" : "free");
        CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
        deform(net, x, 0.015, 0.3);
        fd_sweep(net, x, label, &tab[model][v]);
        fd_sweep(net, x, label, &tab[model][v]);
        csr_checks(net, x);
        rn_network_destroy(&net);
      }
    }
  printf("FD error table (best relative error over h = 1e-2 .. 1e-5, worst of 4 cases;\n"
         "order fitted over h = 1e-2 .. 1e-4, smallest of 4 cases)\n");
  printf("%-8s %3s %12s %12s %10s %10s\n", "model", "v", "grad err", "HVP err",
         "grad order", "HVP order");
  for (int model = 0; model < 2; ++model)
    for (int v = 1; v <= MAXV; v += v < TABLE_V ? 1 : MAXV - TABLE_V)
      printf("%-8s %3d %12.2e %12.2e %10.2f %10.2f\n", names[model], v, tab[model][v].eg,
             tab[model][v].eh, tab[model][v].sg, tab[model][v].sh);
}

/* The built-in self-test covers joint DOFs (rotation DOFs perturbed in
 * radians). */
static void test_self_check(rn_context *ctx) {
  for (int model = 0; model < 2; ++model) {
    star_spec s;
    rn_network *net;
    rn_check_report rep;
    double x[MAXN];
    star_make(&s, 5, 1);
    net = star_build(ctx, &s, (rn_joint_model)model, NULL);
    CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
    deform(net, x, 0.01, 0.3);
    CHECK_STATUS(rn_network_check_derivatives(net, x, 2, 0.05, 11, &rep), RN_OK);
    if (getenv("RN_VERBOSE"))
      fprintf(stderr,
              "self-check %d: grad %.2e (%.2f) hvp %.2e (%.2f) sym %.2e csr %.2e\n",
              model, rep.grad_rel_err, rep.grad_order, rep.hvp_rel_err, rep.hvp_order,
              rep.hess_sym_err, rep.hess_hvp_err);
    CHECK(rep.n_points == 3);
    CHECK(rep.grad_rel_err < 1e-7 && rep.hvp_rel_err < 1e-7);
    CHECK(rep.hess_sym_err < 1e-13 && rep.hess_hvp_err < 1e-13);
    CHECK(rep.grad_order > 1.8 && rep.grad_order < 2.2);
    CHECK(rep.hvp_order > 1.8 && rep.hvp_order < 2.2);
    rn_network_destroy(&net);
  }
}

/* ---- rest state, rotations ------------------------------------------------- */
static void check_identity(const rn_network *net, int joint, double tol) {
  double R[9];
  CHECK_STATUS(rn_network_joint_rotation(net, joint, R), RN_OK);
  for (int i = 0; i < 9; ++i) CHECK_NEAR(R[i], i % 4 == 0 ? 1.0 : 0.0, tol);
}

/* No loads, no motion: E = 0 and g = 0 for both models at every valence;
 * rotation identity, position the input one; the Hessian is positive
 * semidefinite along random directions. */
static void test_rest(rn_context *ctx) {
  for (int model = 0; model < 2; ++model)
    for (int v = 1; v <= MAXV; v += 3) { /* 1, 4, 7, 10 */
      star_spec s;
      rn_network *net;
      double x[MAXN], g[MAXN], d[MAXN], hv[MAXN], E, terms[RN_TERM_COUNT], xj[3];
      size_t n;
      star_make(&s, v, 0);
      s.rest = 0;
      net = star_build(ctx, &s, (rn_joint_model)model, NULL);
      n = rn_network_num_dofs(net);
      CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
      CHECK_STATUS(rn_network_gradient(net, x, &E, g), RN_OK);
      CHECK_STATUS(rn_network_energy_terms(net, x, terms), RN_OK);
      CHECK(fabs(E) < 1e-28);
      for (int t = 0; t < RN_TERM_COUNT; ++t) CHECK(fabs(terms[t]) < 1e-28);
      CHECK(norm(n, g) < 1e-14);
      check_identity(net, 0, 1e-15);
      CHECK_STATUS(rn_network_joint_position(net, 0, xj), RN_OK);
      for (int k = 0; k < 3; ++k) CHECK(xj[k] == s.xyz[0][k]); /* rod 0 starts there */
      for (int trial = 0; trial < 3; ++trial) {
        for (size_t i = 0; i < n; ++i) d[i] = urand();
        CHECK_STATUS(rn_network_hvp(net, x, d, hv), RN_OK);
        CHECK(dot(n, d, hv) > 0.0);
      }
      rn_network_destroy(&net);
    }
}

/* ---- reference update ------------------------------------------------------ */
/* Energy, energy terms and joint rotation are unchanged by the update; the
 * rotation DOFs of a rigid joint become 0 (everything else in x stays);
 * derivatives remain exact after it. */
static void test_update_reference(rn_context *ctx) {
  for (int model = 0; model < 2; ++model) {
    star_spec s;
    rn_network *net;
    double x[MAXN], x0[MAXN], t1[RN_TERM_COUNT], t2[RN_TERM_COUNT], E1, E2, R1[9], R2[9];
    size_t n, nw = 0;
    fd_stats st;
    star_make(&s, 4, 1);
    net = star_build(ctx, &s, (rn_joint_model)model, NULL);
    n = rn_network_num_dofs(net);
    CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
    for (int step = 0; step < 3; ++step) {
      deform(net, x, 0.02, 0.4);
      memcpy(x0, x, n * sizeof(double));
      CHECK_STATUS(rn_network_energy(net, x, &E1), RN_OK);
      CHECK_STATUS(rn_network_energy_terms(net, x, t1), RN_OK);
      CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK);
      CHECK_STATUS(rn_network_joint_rotation(net, 0, R1), RN_OK);
      CHECK_STATUS(rn_network_update_reference(net, x), RN_OK);
      CHECK_STATUS(rn_network_energy(net, x, &E2), RN_OK);
      CHECK_STATUS(rn_network_energy_terms(net, x, t2), RN_OK);
      CHECK_REL(E2, E1, 1e-12);
      for (int t = 0; t < RN_TERM_COUNT; ++t) CHECK_NEAR(t2[t], t1[t], 1e-12 * fabs(E1));
      CHECK(t1[RN_TERM_LOAD] != 0.0); /* the couple and forces did work */
      CHECK_STATUS(rn_network_joint_rotation(net, 0, R2), RN_OK);
      for (int i = 0; i < 9; ++i) CHECK_NEAR(R2[i], R1[i], 1e-14);
      /* rigid: the joint's 3 rotation DOFs (last in x) are reset */
      nw = 0;
      for (size_t i = 0; i < n; ++i)
        if (x[i] != x0[i]) {
          nw++;
          CHECK(model == RN_JOINT_RIGID && i >= n - 3 && x[i] == 0.0);
        }
      if (model == RN_JOINT_RIGID) CHECK(nw == 3);
      {
        double y[MAXN];
        CHECK_STATUS(rn_network_get_dofs(net, y), RN_OK);
        CHECK(memcmp(x, y, n * sizeof(double)) == 0);
      }
    }
    fd_init(&st);
    deform(net, x, 0.01, 0.2);
    fd_sweep(net, x, "after update_reference", &st);
    csr_checks(net, x);
    rn_network_destroy(&net);
  }
}

/* ---- rigid motions ---------------------------------------------------------- */
/* DOF kinds of a star without BCs, from the layout of rodnet.h: each rod's
 * full DOFs minus its vertex at the joint, then the joint position and (rigid)
 * rotation.  kind: 'x' first coordinate of a position, 'a' angle, 'w' first
 * rotation-vector entry, '.' the other coordinates. */
static size_t star_kinds(const star_spec *s, int rigid, char *kind) {
  size_t n = 0;
  for (int k = 0; k < s->v; ++k) {
    int jv = s->end[k] == RN_START ? 0 : s->nv[k] - 1;
    for (int i = 0; i < s->nv[k]; ++i) {
      if (i != jv) {
        kind[n++] = 'x';
        kind[n++] = '.';
        kind[n++] = '.';
      }
      if (i < s->nv[k] - 1) kind[n++] = 'a';
    }
  }
  kind[n++] = 'x';
  kind[n++] = '.';
  kind[n++] = '.';
  if (rigid) {
    kind[n++] = 'w';
    kind[n++] = '.';
    kind[n++] = '.';
  }
  return n;
}

/* A translated state has the same energy; a rotated copy of the network
 * (input geometry and d1 rotated) in the rotated state (positions and
 * rotation vectors rotated, angles kept) has the same energy. */
static void test_rigid_motion(rn_context *ctx) {
  double W[3] = {0.8, -0.5, 1.2}, c[3] = {1.5, -2.0, 0.7}, R[9];
  rotmat(W, R);
  for (int model = 0; model < 2; ++model)
    for (int v = 1; v <= MAXV; v += 2) {
      star_spec s;
      rn_network *net, *rnet;
      double x[MAXN], y[MAXN], E, Ey;
      char kind[MAXN];
      size_t n;
      star_make(&s, v, 0);
      for (int k = 0; k < v; ++k) s.has_d1[k] = 1; /* derived axes are not equivariant */
      net = star_build(ctx, &s, (rn_joint_model)model, NULL);
      rnet = star_build(ctx, &s, (rn_joint_model)model, W);
      n = rn_network_num_dofs(net);
      CHECK(star_kinds(&s, model == RN_JOINT_RIGID, kind) == n);
      CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
      deform(net, x, 0.02, 0.4);
      CHECK_STATUS(rn_network_energy(net, x, &E), RN_OK);
      CHECK(E > 0.0);
      memcpy(y, x, n * sizeof(double));
      for (size_t i = 0; i < n; ++i)
        if (kind[i] == 'x')
          for (int k = 0; k < 3; ++k) y[i + (size_t)k] += c[k];
      CHECK_STATUS(rn_network_energy(net, y, &Ey), RN_OK);
      CHECK_REL(Ey, E, 1e-11);
      memcpy(y, x, n * sizeof(double));
      for (size_t i = 0; i < n; ++i)
        if (kind[i] == 'x' || kind[i] == 'w') matvec(R, x + i, y + i);
      CHECK_STATUS(rn_network_energy(rnet, y, &Ey), RN_OK);
      CHECK_REL(Ey, E, 1e-11);
      rn_network_destroy(&net);
      rn_network_destroy(&rnet);
    }
}

/* ---- two joints ---------------------------------------------------------------- */
/* Joints A at a and B at b joined by four rods (two curved ones of 4 and 5
 * vertices and two single edges, one each way: A's stencil then holds B's
 * position twice), plus a single-edge rod from B to a third joint C (valence
 * 1) and a free rod from A.  A is clamped with a prescribed
 * motion, or pinned; B carries a force and a couple. */
static rn_network *build_pair(rn_context *ctx, rn_joint_model model, int clamp_a,
                              double lambda) {
  rn_network *net = NULL;
  double a[3] = {0.1, 0.2, -0.1}, b[3] = {0.4, 0.25, 0.0}, cpt[3] = {0.45, 0.5, 0.1};
  double r0[12], r1[15], r2[6], r3[6], r4[9], r5[6];
  double up[3] = {0.0, 0.0, 0.08}, side[3] = {0.0, -0.07, 0.03};
  double disp[3] = {0.01, -0.02, 0.005}, rot[3] = {0.1, 0.2, -0.15};
  double f[3] = {0.0, 0.01, -0.02}, M[3] = {0.003, 0.001, -0.002};
  rn_material m = {1.0, 0.4, 0.0};
  int ra[5] = {0, 1, 2, 4, 5}, ea[5] = {RN_START, RN_END, RN_START, RN_END, RN_END};
  int rb[5] = {0, 1, 2, 3, 5}, eb[5] = {RN_END, RN_START, RN_END, RN_START, RN_START};
  int rc[1] = {3}, ec[1] = {RN_END}, J;
  for (int k = 0; k < 3; ++k) {
    r0[k] = a[k];
    r0[3 + k] = a[k] + (b[k] - a[k]) / 3 + up[k];
    r0[6 + k] = a[k] + 2 * (b[k] - a[k]) / 3 + up[k];
    r0[9 + k] = b[k];
    for (int i = 0; i < 5; ++i) /* from b to a, bulging sideways */
      r1[3 * i + k] = b[k] + (a[k] - b[k]) * i / 4.0 + (i % 4 ? side[k] : 0.0);
    r2[k] = r5[3 + k] = a[k];
    r2[3 + k] = r5[k] = b[k];
    r3[k] = b[k];
    r3[3 + k] = cpt[k];
    r4[k] = a[k] - 0.2;
    r4[3 + k] = a[k] - 0.1 + 0.02 * k;
    r4[6 + k] = a[k];
  }
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "r0", 4, r0, NULL, NULL), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "r1", 5, r1, NULL, NULL), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "r2", 2, r2, NULL, NULL), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "r3", 2, r3, up, NULL), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "r4", 3, r4, NULL, NULL), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "r5", 2, r5, side, NULL), RN_OK);
  for (int r = 0; r < 6; ++r) {
    rn_section s = aniso(r);
    CHECK_STATUS(rn_network_set_material(net, r, -1, &m), RN_OK);
    CHECK_STATUS(rn_network_set_section(net, r, -1, &s), RN_OK);
  }
  CHECK_STATUS(rn_network_add_joint(net, "A", model, 5, ra, ea, &J), RN_OK);
  CHECK(J == 0);
  CHECK_STATUS(rn_network_add_joint(net, "B", model, 5, rb, eb, &J), RN_OK);
  CHECK_STATUS(rn_network_add_joint(net, NULL, RN_JOINT_RIGID, 1, rc, ec, &J), RN_OK);
  CHECK(J == 2);
  if (clamp_a) {
    CHECK_STATUS(rn_network_clamp_joint(net, 0), RN_OK);
    CHECK_STATUS(rn_network_displace_joint(net, 0, disp, rot), RN_OK);
  } else {
    CHECK_STATUS(rn_network_pin_joint(net, 0), RN_OK);
    CHECK_STATUS(rn_network_displace_joint(net, 0, disp, NULL), RN_OK);
    CHECK_STATUS(rn_network_pin(net, 4, 0), RN_OK); /* no free rigid motion */
  }
  CHECK_STATUS(rn_network_add_joint_force(net, 1, f), RN_OK);
  CHECK_STATUS(rn_network_add_joint_moment(net, 1, M), RN_OK);
  CHECK_STATUS(rn_network_add_joint_moment(net, 2, M), RN_OK);
  CHECK_STATUS(rn_network_set_load_factor(net, lambda), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

static void test_pair(rn_context *ctx) {
  double disp[3] = {0.01, -0.02, 0.005}, rot[3] = {0.1, 0.2, -0.15};
  for (int model = 0; model < 2; ++model)
    for (int clamp_a = 0; clamp_a < 2; ++clamp_a) {
      rn_network *net = build_pair(ctx, (rn_joint_model)model, clamp_a, 0.6);
      double x[MAXN], xa[3], xb[3], v0[12], v1[15], R[9], Rl[9], wl[3];
      size_t n = rn_network_num_dofs(net);
      int rigid = model == RN_JOINT_RIGID;
      fd_stats st;
      /* full: rods 15 + 19 + 7 + 7 + 11 + 7 = 66, joints 3 or 6 each (C
       * rigid); reduced: minus 11 aliased end vertices (33 entries), minus A's
       * 6 fixed DOFs, or A's position and the pinned vertex of r4 */
      CHECK(rn_network_num_joints(net) == 3);
      CHECK(rn_network_num_full_dofs(net) ==
            (size_t)(66 + (rigid || clamp_a ? 6 : 3) + (rigid ? 6 : 3) + 6));
      CHECK(n == rn_network_num_full_dofs(net) - 33 - 6);
      CHECK(rn_network_joint_valence(net, 1) == 5 &&
            rn_network_joint_valence(net, 2) == 1);
      CHECK(rn_network_joint_model(net, 2) == RN_JOINT_RIGID);
      CHECK(strcmp(rn_network_joint_name(net, 1), "B") == 0);
      CHECK(strcmp(rn_network_joint_name(net, 2), "") == 0);
      /* A moved by lambda disp; its rod end vertices follow */
      CHECK_STATUS(rn_network_joint_position(net, 0, xa), RN_OK);
      CHECK_STATUS(rn_network_rod_vertices(net, 0, v0), RN_OK);
      CHECK_STATUS(rn_network_rod_vertices(net, 1, v1), RN_OK);
      CHECK_STATUS(rn_network_joint_position(net, 1, xb), RN_OK);
      for (int k = 0; k < 3; ++k) {
        CHECK_NEAR(xa[k], (k == 0 ? 0.1 : k == 1 ? 0.2 : -0.1) + 0.6 * disp[k], 1e-16);
        CHECK(v0[k] == xa[k] && v1[12 + k] == xa[k] && v0[9 + k] == xb[k] &&
              v1[k] == xb[k]);
        wl[k] = 0.6 * rot[k];
      }
      /* a clamped joint turns with R(lambda rotvec), whatever its model */
      if (clamp_a) {
        CHECK_STATUS(rn_network_joint_rotation(net, 0, R), RN_OK);
        rotmat(wl, Rl);
        for (int i = 0; i < 9; ++i) CHECK_NEAR(R[i], Rl[i], 1e-15);
      } else if (rigid) { /* an elastic A turns with its displaced rods */
        check_identity(net, 0, 1e-15);
      }
      CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
      deform(net, x, 0.01, 0.3);
      fd_init(&st);
      fd_sweep(net, x, "two joints", &st);
      fd_sweep(net, x, "two joints", &st);
      csr_checks(net, x);
      /* the joint positions and angles move with set_dofs; aliases follow */
      CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK);
      CHECK_STATUS(rn_network_joint_position(net, 1, xb), RN_OK);
      CHECK_STATUS(rn_network_rod_vertices(net, 2, v0), RN_OK);
      for (int k = 0; k < 3; ++k) CHECK(v0[3 + k] == xb[k]);
      /* the load factor moves A again (and its aliases) */
      CHECK_STATUS(rn_network_set_load_factor(net, 1.0), RN_OK);
      CHECK_STATUS(rn_network_joint_position(net, 0, xa), RN_OK);
      CHECK_STATUS(rn_network_rod_vertices(net, 2, v0), RN_OK);
      for (int k = 0; k < 3; ++k) CHECK(v0[k] == xa[k]);
      CHECK_NEAR(xa[1], 0.2 + disp[1], 1e-16);
      fd_sweep(net, x, "two joints, lambda 1", &st);
      rn_network_destroy(&net);
    }
}

/* Dead force and couple on joints: at rest the gradient is -lambda f on the
 * joint position and -lambda M on a rigid joint's rotation vector; the
 * couple's work goes to RN_TERM_LOAD. */
static void test_joint_loads(rn_context *ctx) {
  double xyz[9] = {0, 0, 0, 0.1, 0, 0, 0.2, 0.01, 0}, f[3] = {0.1, -0.2, 0.3},
         M[3] = {0.02, 0.01, -0.03};
  rn_material m = {1.0, 0.4, 0.0};
  rn_section s = aniso(0);
  for (int model = 0; model < 2; ++model) {
    rn_network *net = NULL;
    int rod = 0, end = RN_START;
    double x[16], g[16], E, terms[RN_TERM_COUNT], w = 0.2, Mn = norm(3, M);
    CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
    CHECK_STATUS(rn_network_add_rod(net, "a", 3, xyz, NULL, NULL), RN_OK);
    CHECK_STATUS(rn_network_set_material(net, 0, -1, &m), RN_OK);
    CHECK_STATUS(rn_network_set_section(net, 0, -1, &s), RN_OK);
    CHECK_STATUS(
        rn_network_add_joint(net, "j", (rn_joint_model)model, 1, &rod, &end, NULL),
        RN_OK);
    CHECK_STATUS(rn_network_add_joint_force(net, 0, f), RN_OK);
    CHECK_STATUS(rn_network_add_joint_moment(net, 0, M), RN_OK);
    CHECK_STATUS(rn_network_set_load_factor(net, 0.5), RN_OK);
    CHECK_STATUS(rn_network_finalize(net), RN_OK);
    /* reduced: theta0, x1, theta1, x2 (8), then x_J and (rigid) w */
    CHECK(rn_network_num_dofs(net) == (size_t)(model ? 14 : 11));
    CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
    CHECK_STATUS(rn_network_gradient(net, x, &E, g), RN_OK);
    /* positions x1, x2, x_J: the couple's part of the gradient sums to 0 */
    for (int k = 0; k < 3; ++k)
      CHECK_NEAR(g[1 + k] + g[5 + k] + g[8 + k], -0.5 * f[k], 1e-15);
    if (model == RN_JOINT_RIGID) {
      for (int k = 0; k < 3; ++k) CHECK_NEAR(g[8 + k], -0.5 * f[k], 1e-15);
      for (int k = 0; k < 3; ++k) CHECK_NEAR(g[11 + k], -0.5 * M[k], 1e-15);
      /* turn the joint by w about M's axis: couple work 0.5 |M| w */
      for (int k = 0; k < 3; ++k) x[11 + k] = w * M[k] / Mn;
      CHECK_STATUS(rn_network_energy_terms(net, x, terms), RN_OK);
      CHECK_NEAR(terms[RN_TERM_LOAD], -0.5 * Mn * w - 0.5 * dot(3, f, x + 8), 1e-15);
      CHECK(terms[RN_TERM_BEND] > 0.0);
    } else {
      /* elastic: the couple acts through the fitted rotation of the joint,
       * i.e. on the rod's terminal edge (its angle theta0 turns it about t) */
      double t[3] = {1, 0, 0};
      CHECK_NEAR(g[0], -0.5 * dot(3, M, t), 1e-15);
    }
    rn_network_destroy(&net);
  }
}

/* ---- errors ------------------------------------------------------------------ */
static rn_network *two_rods(rn_context *ctx, int nv) {
  rn_network *net = NULL;
  double a[15], b[15];
  rn_material m = {1.0, 0.4, 0.0};
  rn_section s = aniso(0);
  for (int i = 0; i < nv; ++i) {
    a[3 * i] = 0.1 * i;
    a[3 * i + 1] = a[3 * i + 2] = 0.0;
    b[3 * i] = 0.0;
    b[3 * i + 1] = 0.1 * i;
    b[3 * i + 2] = 0.0;
  }
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "a", nv, a, NULL, NULL), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "b", nv, b, NULL, NULL), RN_OK);
  for (int r = 0; r < 2; ++r) {
    CHECK_STATUS(rn_network_set_material(net, r, -1, &m), RN_OK);
    CHECK_STATUS(rn_network_set_section(net, r, -1, &s), RN_OK);
  }
  return net;
}

static const int RODS01[2] = {0, 1}, STARTS[2] = {RN_START, RN_START};

static void test_add_errors(rn_context *ctx) {
  rn_network *net = two_rods(ctx, 3);
  int rods[2] = {0, 1}, ends[2] = {RN_START, RN_START}, J = -7;
  double v[3] = {0, 0, 0}, Rm[9];
  /* NULL network */
  CHECK_STATUS(rn_network_add_joint(NULL, "j", RN_JOINT_RIGID, 2, rods, ends, &J),
               RN_ERR_ARG);
  CHECK_STATUS(rn_network_clamp_joint(NULL, 0), RN_ERR_ARG);
  CHECK_STATUS(rn_network_pin_joint(NULL, 0), RN_ERR_ARG);
  CHECK_STATUS(rn_network_displace_joint(NULL, 0, v, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_add_joint_force(NULL, 0, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_add_joint_moment(NULL, 0, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_joint_position(NULL, 0, v), RN_ERR_ARG);
  CHECK_STATUS(rn_network_joint_rotation(NULL, 0, Rm), RN_ERR_ARG);
  CHECK(rn_network_num_joints(NULL) == 0);
  CHECK(rn_network_joint_model(NULL, 0) == -1 && rn_network_joint_valence(NULL, 0) == -1);
  CHECK(strcmp(rn_network_joint_name(NULL, 0), "") == 0);
  /* bad arguments */
  CHECK_STATUS(rn_network_add_joint(net, "j", RN_JOINT_RIGID, 0, rods, ends, &J),
               RN_ERR_ARG);
  CHECK(contains(rn_context_last_error(ctx), "at least one rod end"));
  CHECK_STATUS(rn_network_add_joint(net, "j", RN_JOINT_RIGID, 2, NULL, ends, &J),
               RN_ERR_ARG);
  CHECK_STATUS(rn_network_add_joint(net, "j", (rn_joint_model)7, 2, rods, ends, &J),
               RN_ERR_ARG);
  rods[1] = 2;
  CHECK_STATUS(rn_network_add_joint(net, "j", RN_JOINT_RIGID, 2, rods, ends, &J),
               RN_ERR_RANGE);
  rods[1] = 1;
  ends[1] = 5;
  CHECK_STATUS(rn_network_add_joint(net, "j", RN_JOINT_RIGID, 2, rods, ends, &J),
               RN_ERR_ARG);
  ends[1] = RN_START;
  /* the same end twice */
  rods[1] = 0;
  CHECK_STATUS(rn_network_add_joint(net, "j", RN_JOINT_RIGID, 2, rods, ends, &J),
               RN_ERR_ARG);
  CHECK(contains(rn_context_last_error(ctx), "listed twice"));
  rods[1] = 1;
  /* ends that do not coincide: rod a's end (0.2, 0, 0) and rod b's start */
  ends[0] = RN_END;
  CHECK_STATUS(rn_network_add_joint(net, "far", RN_JOINT_ELASTIC, 2, rods, ends, &J),
               RN_ERR_GEOMETRY);
  CHECK(contains(rn_context_last_error(ctx), "joint 0 ('far')"));
  CHECK(contains(rn_context_last_error(ctx), "rod 1 ('b')"));
  CHECK(contains(rn_context_last_error(ctx), "coincide"));
  CHECK(J == -7 && rn_network_num_joints(net) == 0);
  /* a near miss within the tolerance is accepted: move nothing, test the
   * good case, then a rod end in two joints */
  ends[0] = RN_START;
  CHECK_STATUS(rn_network_add_joint(net, "j0", RN_JOINT_ELASTIC, 2, rods, ends, &J),
               RN_OK);
  CHECK(J == 0 && rn_network_num_joints(net) == 1);
  CHECK_STATUS(rn_network_add_joint(net, "j1", RN_JOINT_RIGID, 1, rods + 1, ends + 1, &J),
               RN_ERR_ARG);
  CHECK(contains(rn_context_last_error(ctx), "already belongs to joint 0 ('j0')"));
  CHECK(contains(rn_context_last_error(ctx), "rod 1 ('b')"));
  /* joint BC/load argument errors */
  CHECK_STATUS(rn_network_clamp_joint(net, 1), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_pin_joint(net, -1), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_displace_joint(net, 3, v, NULL), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_add_joint_force(net, 0, NULL), RN_ERR_ARG);
  v[1] = NAN;
  CHECK_STATUS(rn_network_add_joint_moment(net, 0, v), RN_ERR_NOT_FINITE);
  CHECK_STATUS(rn_network_displace_joint(net, 0, NULL, v), RN_ERR_NOT_FINITE);
  v[1] = 0.0;
  /* results before finalize */
  CHECK_STATUS(rn_network_joint_position(net, 0, v), RN_ERR_STATE);
  CHECK_STATUS(rn_network_joint_rotation(net, 0, Rm), RN_ERR_STATE);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  /* modifications after finalize */
  ends[0] = ends[1] = RN_END;
  CHECK_STATUS(rn_network_add_joint(net, "late", RN_JOINT_RIGID, 1, rods, ends, &J),
               RN_ERR_STATE);
  CHECK_STATUS(rn_network_clamp_joint(net, 0), RN_ERR_STATE);
  CHECK_STATUS(rn_network_pin_joint(net, 0), RN_ERR_STATE);
  CHECK_STATUS(rn_network_displace_joint(net, 0, v, v), RN_ERR_STATE);
  CHECK_STATUS(rn_network_add_joint_force(net, 0, v), RN_ERR_STATE);
  CHECK_STATUS(rn_network_add_joint_moment(net, 0, v), RN_ERR_STATE);
  /* results: range and NULL */
  CHECK_STATUS(rn_network_joint_position(net, 1, v), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_joint_rotation(net, -1, Rm), RN_ERR_RANGE);
  CHECK_STATUS(rn_network_joint_position(net, 0, NULL), RN_ERR_ARG);
  CHECK(rn_network_joint_model(net, 1) == -1 && rn_network_joint_valence(net, 5) == -1);
  CHECK(rn_network_joint_model(net, 0) == RN_JOINT_ELASTIC);
  rn_network_destroy(&net);
}

/* Finalize errors: BCs on rod vertices of a joint, motion of an unconstrained
 * joint, coincident joints, a degenerate fit at the initial state. */
typedef enum { BC_CLAMP, BC_CLAMP_OTHER, BC_PIN, BC_DISPLACE } rod_bc;

static void expect_finalize(rn_network *net, rn_status st, const char *msg) {
  rn_context *ctx = rn_network_context(net);
  CHECK_STATUS(rn_network_finalize(net), st);
  if (!contains(rn_context_last_error(ctx), msg))
    fprintf(stderr, "message '%s' lacks '%s'\n", rn_context_last_error(ctx), msg);
  CHECK(contains(rn_context_last_error(ctx), msg));
  CHECK(rn_network_num_dofs(net) == 0); /* still building */
  rn_network_destroy(&net);
}

static void test_finalize_errors(rn_context *ctx) {
  double d[3] = {0.01, 0, 0};
  for (int bc = BC_CLAMP; bc <= BC_DISPLACE; ++bc) {
    rn_network *net = two_rods(ctx, bc == BC_CLAMP_OTHER ? 2 : 3);
    CHECK_STATUS(rn_network_add_joint(net, "j", RN_JOINT_RIGID, 2, RODS01, STARTS, NULL),
                 RN_OK);
    if (bc == BC_CLAMP) CHECK_STATUS(rn_network_clamp(net, 1, RN_START), RN_OK);
    if (bc == BC_CLAMP_OTHER) CHECK_STATUS(rn_network_clamp(net, 1, RN_END), RN_OK);
    if (bc == BC_PIN) CHECK_STATUS(rn_network_pin(net, 0, 0), RN_OK);
    if (bc == BC_DISPLACE) CHECK_STATUS(rn_network_displace_vertex(net, 0, 0, d), RN_OK);
    expect_finalize(net, RN_ERR_BC, "belongs to joint 0 ('j')");
  }
  { /* motion of a free joint; rotation of a pinned one */
    rn_network *net = two_rods(ctx, 3);
    CHECK_STATUS(rn_network_add_joint(net, "j", RN_JOINT_RIGID, 2, RODS01, STARTS, NULL),
                 RN_OK);
    CHECK_STATUS(rn_network_displace_joint(net, 0, d, NULL), RN_OK);
    expect_finalize(net, RN_ERR_BC, "neither pinned nor clamped");
    net = two_rods(ctx, 3);
    CHECK_STATUS(
        rn_network_add_joint(net, "j", RN_JOINT_ELASTIC, 2, RODS01, STARTS, NULL), RN_OK);
    CHECK_STATUS(rn_network_pin_joint(net, 0), RN_OK);
    CHECK_STATUS(rn_network_displace_joint(net, 0, NULL, d), RN_OK);
    expect_finalize(net, RN_ERR_BC, "not clamped");
  }
  { /* coincident joints: the ends of a and b at the origin, two joints */
    rn_network *net = two_rods(ctx, 3);
    CHECK_STATUS(rn_network_add_joint(net, "p", RN_JOINT_RIGID, 1, RODS01, STARTS, NULL),
                 RN_OK);
    CHECK_STATUS(
        rn_network_add_joint(net, "q", RN_JOINT_ELASTIC, 1, RODS01 + 1, STARTS, NULL),
        RN_OK);
    expect_finalize(net, RN_ERR_GEOMETRY, "joints 0 ('p') and 1 ('q') are coincident");
  }
  { /* zero-length rod */
    rn_network *net = NULL;
    double z[6] = {1, 2, 3, 1, 2, 3};
    CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
    CHECK_STATUS(rn_network_add_rod(net, "z", 2, z, NULL, NULL), RN_ERR_GEOMETRY);
    CHECK(contains(rn_context_last_error(ctx), "zero-length"));
    rn_network_destroy(&net);
  }
  { /* singular fit at the prescribed state: rods a (along x) and b (along y)
     * start at an elastic joint; their second vertices are pinned and moved
     * so that the terminal frames turn by +100 and -80 degrees about z:
     * M = Rz(100) + Rz(-80) has a zero xy block.  The initial geometry (load
     * factor 0, where finalize checks the joints) is regular; the state at load
     * factor 1 is a degenerate trial point (which rn_solve ramps through). */
    rn_network *net = two_rods(ctx, 3);
    double deg = acos(-1.0) / 180.0;
    double c1 = cos(100 * deg), s1 = sin(100 * deg), c2 = cos(-80 * deg),
           s2 = sin(-80 * deg);
    /* vertex 1 of a to 0.1 Rz(100) (1, 0, 0), of b to 0.1 Rz(-80) (0, 1, 0) */
    double da[3] = {0.1 * (c1 - 1.0), 0.1 * s1, 0.0};
    double db[3] = {-0.1 * s2, 0.1 * (c2 - 1.0), 0.0};
    CHECK_STATUS(
        rn_network_add_joint(net, "fit", RN_JOINT_ELASTIC, 2, RODS01, STARTS, NULL),
        RN_OK);
    CHECK_STATUS(rn_network_pin(net, 0, 1), RN_OK);
    CHECK_STATUS(rn_network_pin(net, 1, 1), RN_OK);
    CHECK_STATUS(rn_network_displace_vertex(net, 0, 1, da), RN_OK);
    CHECK_STATUS(rn_network_displace_vertex(net, 1, 1, db), RN_OK);
    CHECK_STATUS(rn_network_finalize(net), RN_OK);
    {
      size_t nd = rn_network_num_dofs(net);
      double *x = malloc((nd + 1) * sizeof(double)), E = 0.0;
      CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
      CHECK_STATUS(rn_network_energy(net, x, &E), RN_DEGENERATE);
      CHECK_STATUS(rn_network_set_load_factor(net, 0.0), RN_OK);
      CHECK_STATUS(rn_network_energy(net, x, &E), RN_OK);
      free(x);
    }
    rn_network_destroy(&net);
  }
}

int main(void) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  test_add_errors(ctx);
  test_finalize_errors(ctx);
  test_rest(ctx);
  test_joint_loads(ctx);
  test_rigid_motion(ctx);
  test_update_reference(ctx);
  test_pair(ctx);
  test_self_check(ctx);
  test_fd_stars(ctx);
  if (rn_test_failures) fprintf(stderr, "last error: %s\n", rn_context_last_error(ctx));
  rn_context_destroy(&ctx);
  return rn_test_finish("api_joints");
}

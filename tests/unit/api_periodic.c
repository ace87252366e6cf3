/* api_periodic.c - periodic cells (c_api/periodic/periodic.c): rod ends at periodic
 * images of joints and the macroscopic strain DOFs.
 *
 * - energy, gradient, HVP and CSR Hessian with respect to the fluctuation and
 *   strain DOFs against central differences (h-sweep, second order), on 2D and
 *   3D cells with skew lattice vectors, curved rods, anisotropic sections, both
 *   joint models, one-edge rods with images on both ends;
 * - zero energy and gradient at rest; image end positions x_J + F s after
 *   set_dofs and reference updates; energy unchanged by a reference update;
 * - a prescribed uniform strain on a square cell of bars: energy EA/2 (e a)^2 / a;
 * - the load-step predictor (rn_network_load_increment) with a prescribed strain
 *   against the load-factor derivative of the gradient (h-sweep, second order);
 * - errors: degenerate cell, 2D cell out of plane, image without a cell, image
 *   component beyond the cell's dimension, an end off its image. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "testutil.h"

enum { MAXJ = 4, MAXB = 8, NV = 5, MAXN = 4096 };

typedef struct bar {
  int a, b;     /* joints */
  int img[3];   /* image of b's end */
  int nv;       /* vertices */
  double bulge; /* transverse bulge of the rest shape (fraction of length) */
} bar;

typedef struct cell_spec {
  int dim;
  double vec[9];
  int nj;
  double p[MAXJ][3];
  int nb;
  bar bars[MAXB];
} cell_spec;

static void add_bars(rn_network *net, const cell_spec *c, int model, int aniso) {
  rn_material mat;
  rn_section sec;
  int rods[2 * MAXB], ends[2 * MAXB], imgs[6 * MAXB];
  CHECK_STATUS(rn_material_from_E_nu(1e3, 0.3, 0.0, &mat), RN_OK);
  if (aniso)
    CHECK_STATUS(rn_section_ellipse(0.03, 0.018, &sec), RN_OK);
  else
    CHECK_STATUS(rn_section_circle(0.025, &sec), RN_OK);
  for (int ib = 0; ib < c->nb; ++ib) {
    const bar *b = &c->bars[ib];
    double xyz[3 * 16], q[3], d[3], n[3] = {0.0, 0.0, 1.0}, len;
    int rod;
    for (int k = 0; k < 3; ++k) {
      q[k] = c->p[b->b][k];
      for (int m = 0; m < c->dim; ++m) q[k] += b->img[m] * c->vec[3 * m + k];
      d[k] = q[k] - c->p[b->a][k];
    }
    len = sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    if (fabs(d[2]) > 0.5 * len) n[0] = 1.0, n[2] = 0.0;
    for (int v = 0; v < b->nv; ++v) {
      double t = (double)v / (b->nv - 1),
             bump = b->bulge * len * sin(3.14159265358979 * t);
      for (int k = 0; k < 3; ++k)
        xyz[3 * v + k] = c->p[b->a][k] + t * d[k] + bump * (k == 2 ? 0.3 : 1.0) * n[k];
    }
    CHECK_STATUS(rn_network_add_rod(net, NULL, b->nv, xyz, NULL, &rod), RN_OK);
    CHECK_STATUS(rn_network_set_material(net, rod, -1, &mat), RN_OK);
    CHECK_STATUS(rn_network_set_section(net, rod, -1, &sec), RN_OK);
  }
  for (int j = 0; j < c->nj; ++j) {
    int n = 0, joint;
    for (int ib = 0; ib < c->nb; ++ib) {
      const bar *b = &c->bars[ib];
      if (b->a == j) {
        rods[n] = ib;
        ends[n] = RN_START;
        imgs[3 * n] = imgs[3 * n + 1] = imgs[3 * n + 2] = 0;
        n++;
      }
      if (b->b == j) {
        rods[n] = ib;
        ends[n] = RN_END;
        memcpy(imgs + 3 * n, b->img, 3 * sizeof(int));
        n++;
      }
    }
    CHECK_STATUS(rn_network_add_joint_images(net, NULL, (rn_joint_model)model, n, rods,
                                             ends, imgs, &joint),
                 RN_OK);
  }
}

/* Skew 2D cell with two joints (a honeycomb-like graph with a one-edge rod). */
static void cell2d(cell_spec *c) {
  memset(c, 0, sizeof(*c));
  c->dim = 2;
  double v[9] = {1.0, 0.05, 0.0, 0.45, 0.9, 0.0, 0, 0, 0};
  memcpy(c->vec, v, sizeof(v));
  c->nj = 2;
  double p0[3] = {0.0, 0.0, 0.0}, p1[3] = {0.5, 0.32, 0.02};
  memcpy(c->p[0], p0, sizeof(p0));
  memcpy(c->p[1], p1, sizeof(p1));
  c->nb = 3;
  c->bars[0] = (bar){0, 1, {0, 0, 0}, NV, 0.05};
  c->bars[1] = (bar){0, 1, {-1, 0, 0}, NV, -0.03};
  c->bars[2] = (bar){1, 0, {0, 1, 0}, 2, 0.0}; /* one edge, image on one end */
}

/* Honeycomb cell with elastic-joint ordering traps: the last rod ends at the
 * image of joint 1, whose position DOFs directly follow that rod's DOFs when
 * joint 0 is the pinned anchor (the in-place rod evaluation must stop before
 * an image end). */
static void cellhc(cell_spec *c) {
  memset(c, 0, sizeof(*c));
  c->dim = 2;
  double v[9] = {1.7320508075688772, 0, 0, 0.8660254037844386, 1.5, 0, 0, 0, 0};
  memcpy(c->vec, v, sizeof(v));
  c->nj = 2;
  c->p[1][1] = 1.0;
  c->nb = 3;
  c->bars[0] = (bar){0, 1, {0, 0, 0}, NV, 0.02};
  c->bars[1] = (bar){0, 1, {0, -1, 0}, NV, -0.02};
  c->bars[2] = (bar){0, 1, {1, -1, 0}, NV, 0.03};
}

/* Skew 3D cell: one joint with three bars to its images and a diagonal. */
static void cell3d(cell_spec *c) {
  memset(c, 0, sizeof(*c));
  c->dim = 3;
  double v[9] = {1.0, 0.1, 0.0, 0.05, 0.95, 0.1, 0.1, -0.05, 1.05};
  memcpy(c->vec, v, sizeof(v));
  c->nj = 1;
  c->nb = 4;
  c->bars[0] = (bar){0, 0, {1, 0, 0}, NV, 0.04};
  c->bars[1] = (bar){0, 0, {0, 1, 0}, NV, -0.02};
  c->bars[2] = (bar){0, 0, {0, 0, 1}, NV, 0.03};
  c->bars[3] = (bar){0, 0, {1, 1, 1}, 2, 0.0}; /* one edge, both ends images */
}

static rn_network *build(rn_context *ctx, const cell_spec *c, int model, int aniso) {
  rn_network *net;
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_set_periodic(net, c->dim, c->vec), RN_OK);
  add_bars(net, c, model, aniso);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  if (rn_network_num_dofs(net) == 0) fprintf(stderr, "%s\n", rn_context_last_error(ctx));
  return net;
}

static void deform(const rn_network *net, double *x, double amp, uint64_t seed) {
  int64_t idx[6];
  int nstrain;
  size_t n = rn_network_num_dofs(net);
  for (size_t i = 0; i < n; ++i) x[i] += 0.1 * amp * rn_test_rand(&seed);
  CHECK_STATUS(rn_network_cell_info(net, NULL, &nstrain, NULL, NULL), RN_OK);
  CHECK_STATUS(rn_network_cell_strain_dofs(net, idx), RN_OK);
  for (int v = 0; v < nstrain; ++v)
    if (idx[v] >= 0) x[idx[v]] += amp * rn_test_rand(&seed);
}

/* FD of energy -> gradient and gradient -> HVP along random directions
 * (including the strain DOFs), h-sweep, by the library's self-check. */
static void test_derivatives(rn_context *ctx) {
  for (int d = 2; d <= 4; ++d) /* 4: the honeycomb cell */
    for (int model = 0; model < 2; ++model)
      for (int aniso = 0; aniso < 2; ++aniso) {
        cell_spec c;
        rn_check_report rep;
        double x[MAXN];
        if (d == 2)
          cell2d(&c);
        else if (d == 3)
          cell3d(&c);
        else
          cellhc(&c);
        rn_network *net = build(ctx, &c, model, aniso);
        CHECK(rn_network_num_dofs(net) < MAXN);
        CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
        deform(net, x, 0.05, 3 + (uint64_t)model);
        CHECK_STATUS(rn_network_check_derivatives(net, x, 2, 0.05, 11, &rep), RN_OK);
        if (getenv("RN_VERBOSE"))
          fprintf(stderr,
                  "%dD model %d aniso %d: grad %.2e (%.2f) hvp %.2e (%.2f) sym %.2e csr "
                  "%.2e\n",
                  d, model, aniso, rep.grad_rel_err, rep.grad_order, rep.hvp_rel_err,
                  rep.hvp_order, rep.hess_sym_err, rep.hess_hvp_err);
        CHECK(rep.n_points == 3);
        CHECK(rep.grad_rel_err < 1e-7 && rep.hvp_rel_err < 1e-7);
        CHECK(rep.hess_sym_err < 1e-12 && rep.hess_hvp_err < 1e-12);
        CHECK(rep.grad_order > 1.8 && rep.grad_order < 2.2);
        CHECK(rep.hvp_order > 1.8 && rep.hvp_order < 2.2);
        rn_network_destroy(&net);
      }
}

/* Second derivatives with respect to the strain alone: d2E/de_u de_v by central
 * differences of the gradient's strain entries, against the CSR Hessian. */
static void test_strain_block(rn_context *ctx) {
  cell_spec c;
  cell3d(&c);
  rn_network *net = build(ctx, &c, 1, 1);
  size_t n = rn_network_num_dofs(net), nnz;
  const int64_t *rp;
  const int32_t *col;
  double x[MAXN], xp[MAXN], gp[MAXN], gm[MAXN], *vals;
  int64_t idx[6];
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  deform(net, x, 0.05, 5);
  CHECK_STATUS(rn_network_cell_strain_dofs(net, idx), RN_OK);
  CHECK_STATUS(rn_network_hessian_pattern(net, &nnz, &rp, &col), RN_OK);
  vals = malloc(nnz * sizeof(double));
  CHECK_STATUS(rn_network_hessian_values(net, x, vals), RN_OK);
  for (int u = 0; u < 6; ++u) {
    double err[3], hs[3] = {1e-3, 5e-4, 2.5e-4};
    for (int ih = 0; ih < 3; ++ih) {
      double h = hs[ih], worst = 0.0;
      memcpy(xp, x, n * sizeof(double));
      xp[idx[u]] += h;
      CHECK_STATUS(rn_network_gradient(net, xp, NULL, gp), RN_OK);
      xp[idx[u]] -= 2 * h;
      CHECK_STATUS(rn_network_gradient(net, xp, NULL, gm), RN_OK);
      for (int v = 0; v < 6; ++v) {
        int64_t r = idx[v];
        double hv = 0.0, fd = (gp[r] - gm[r]) / (2 * h);
        for (int64_t p = rp[r]; p < rp[r + 1]; ++p)
          if (col[p] == idx[u]) hv = vals[p];
        worst = fmax(worst, fabs(hv - fd) / fmax(fabs(hv), 1.0));
      }
      err[ih] = worst;
    }
    double slope = rn_test_loglog_slope(3, hs, err);
    if (getenv("RN_VERBOSE"))
      fprintf(stderr, "strain %d: FD errors %.2e %.2e %.2e order %.2f\n", u, err[0],
              err[1], err[2], slope);
    CHECK(err[2] < 1e-5);
    CHECK(slope > 1.8 && slope < 2.2);
  }
  free(vals);
  rn_network_destroy(&net);
}

/* Zero energy and gradient at rest; image ends at x_J + F s. */
static void test_rest_and_images(rn_context *ctx) {
  cell_spec c;
  cell2d(&c);
  rn_network *net = build(ctx, &c, 0, 0);
  size_t n = rn_network_num_dofs(net);
  double x[MAXN], g[MAXN], E, xyz[3 * 16], xj[3], eps[3];
  int64_t idx[3];
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_gradient(net, x, &E, g), RN_OK);
  CHECK_NEAR(E, 0.0, 1e-13);
  for (size_t i = 0; i < n; ++i) CHECK_NEAR(g[i], 0.0, 1e-9);
  CHECK_STATUS(rn_network_cell_strain_dofs(net, idx), RN_OK);
  x[idx[0]] = 0.01;
  x[idx[1]] = -0.02;
  x[idx[2]] = 0.03;
  CHECK_STATUS(rn_network_set_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_cell_strain(net, NULL, eps), RN_OK);
  CHECK_NEAR(eps[2], 0.03, 0.0);
  /* bar 1 ends at joint 1's image (-1, 0): x_1 - F a_1 */
  CHECK_STATUS(rn_network_rod_vertices(net, 1, xyz), RN_OK);
  CHECK_STATUS(rn_network_joint_position(net, 1, xj), RN_OK);
  {
    double F[9] = {1 + eps[0], eps[2] / 2, 0, eps[2] / 2, 1 + eps[1], 0, 0, 0, 1};
    for (int k = 0; k < 3; ++k) {
      double Fa = 0.0;
      for (int l = 0; l < 3; ++l) Fa += F[3 * k + l] * c.vec[l];
      CHECK_NEAR(xyz[3 * (NV - 1) + k], xj[k] - Fa, 1e-14);
    }
  }
  { /* a reference update keeps the energy and the images */
    double E0, E1;
    deform(net, x, 0.02, 9);
    CHECK_STATUS(rn_network_energy(net, x, &E0), RN_OK);
    CHECK_STATUS(rn_network_update_reference(net, x), RN_OK);
    CHECK_STATUS(rn_network_energy(net, x, &E1), RN_OK);
    CHECK_REL(E1, E0, 1e-12);
  }
  rn_network_destroy(&net);
}

/* Square cell of straight bars (a = 1) under a prescribed uniform strain e11:
 * each horizontal bar stretches by e a: E = EA/2 (e a)^2 / a, the vertical one
 * not at all (no Poisson coupling in a square lattice). */
static void test_uniform_strain(rn_context *ctx) {
  cell_spec c;
  rn_network *net;
  int fixed[3] = {1, 1, 1};
  double strain[3] = {1e-3, 0.0, 0.0}, x[MAXN], E, sig[3];
  rn_section sec;
  memset(&c, 0, sizeof(c));
  c.dim = 2;
  c.vec[0] = 1.0;
  c.vec[4] = 1.0;
  c.nj = 1;
  c.nb = 2;
  c.bars[0] = (bar){0, 0, {1, 0, 0}, 9, 0.0};
  c.bars[1] = (bar){0, 0, {0, 1, 0}, 9, 0.0};
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_set_periodic(net, 2, c.vec), RN_OK);
  add_bars(net, &c, 1, 0);
  CHECK_STATUS(rn_network_set_cell_strain(net, fixed, strain), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  { /* the affine state x = F X (the joint at the origin is the anchor) */
    size_t n = rn_network_num_dofs(net);
    rn_dof_info info[MAXN];
    CHECK_STATUS(rn_network_dof_info(net, info), RN_OK);
    for (size_t i = 0; i < n; ++i)
      if (info[i].kind == RN_DOF_POSITION && info[i].component == 0)
        x[i] *= 1.0 + strain[0];
  }
  CHECK_STATUS(rn_network_energy(net, x, &E), RN_OK);
  CHECK_STATUS(rn_section_circle(0.025, &sec), RN_OK);
  /* the affine state is the equilibrium here: straight bars, uniform stretch */
  CHECK_REL(E, 0.5 * 1e3 * sec.A * 1e-6, 1e-10);
  CHECK_STATUS(rn_network_cell_stress(net, x, sig), RN_OK);
  CHECK_REL(sig[0], 1e3 * sec.A * 1e-3, 1e-9); /* EA e / a per unit length */
  CHECK_NEAR(sig[1], 0.0, 1e-12);
  { /* rn_network_set_cell_load after finalize: the prescribed strain moves (scaled
     * by the load factor), the applied stress enters the gradient of free ones */
    double s2[3] = {2e-3, -1e-3, 0.0}, st2[3] = {0.5, 0.25, 0.0}, e[3];
    CHECK_STATUS(rn_network_set_load_factor(net, 0.5), RN_OK);
    /* issue 22 item 4: a stress on a prescribed (strain-controlled) component is
     * contradictory control, refused (it did nothing) */
    CHECK_STATUS(rn_network_set_cell_load(net, s2, st2), RN_ERR_ARG);
    CHECK_STATUS(rn_network_set_cell_stress(net, st2), RN_ERR_STATE); /* finalized */
    st2[0] = st2[1] = 0.0;
    CHECK_STATUS(rn_network_set_cell_load(net, s2, st2), RN_OK);
    CHECK_STATUS(rn_network_cell_strain(net, NULL, e), RN_OK);
    CHECK_NEAR(e[0], 1e-3, 1e-15);
    CHECK_NEAR(e[1], -5e-4, 1e-15);
    CHECK_NEAR(e[2], 0.0, 1e-15);
    CHECK_STATUS(rn_network_cell_stress(net, x, sig), RN_OK); /* elastic part only */
    CHECK_STATUS(rn_network_set_cell_load(net, NULL, NULL), RN_OK);
    s2[0] = NAN;
    CHECK_STATUS(rn_network_set_cell_load(net, s2, NULL), RN_ERR_NOT_FINITE);
  }
  rn_network_destroy(&net);
}

/* The load-step predictor with a prescribed strain: rn_network_load_increment
 * (t_prev -> t) over (t - t_prev) equals the load-factor derivative of the
 * gradient at fixed free DOFs (central differences, h-sweep, second order). */
static void test_load_increment(rn_context *ctx) {
  for (int model = 0; model < 2; ++model) {
    cell_spec c;
    rn_network *net;
    int fixed[3] = {1, 0, 1};
    double strain[3] = {0.02, 0.0, -0.03}, x[MAXN], dg[MAXN], gp[MAXN], gm[MAXN];
    double hs[3] = {1e-2, 5e-3, 2.5e-3}, err[3];
    const double t0 = 0.5;
    cell2d(&c);
    CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
    CHECK_STATUS(rn_network_set_periodic(net, 2, c.vec), RN_OK);
    add_bars(net, &c, model, 1);
    CHECK_STATUS(rn_network_set_cell_strain(net, fixed, strain), RN_OK);
    CHECK_STATUS(rn_network_finalize(net), RN_OK);
    CHECK_STATUS(rn_network_set_load_factor(net, t0), RN_OK);
    size_t n = rn_network_num_dofs(net);
    CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
    deform(net, x, 0.03, 17);
    CHECK_STATUS(rn_network_load_increment(net, x, t0, t0 + 0.1, dg), RN_OK);
    double scale = 0.0;
    for (size_t i = 0; i < n; ++i) scale = fmax(scale, fabs(dg[i]) / 0.1);
    for (int k = 0; k < 3; ++k) {
      double worst = 0.0;
      CHECK_STATUS(rn_network_set_load_factor(net, t0 + hs[k]), RN_OK);
      CHECK_STATUS(rn_network_gradient(net, x, NULL, gp), RN_OK);
      CHECK_STATUS(rn_network_set_load_factor(net, t0 - hs[k]), RN_OK);
      CHECK_STATUS(rn_network_gradient(net, x, NULL, gm), RN_OK);
      for (size_t i = 0; i < n; ++i)
        worst = fmax(worst, fabs((gp[i] - gm[i]) / (2 * hs[k]) - dg[i] / 0.1));
      err[k] = worst / scale;
    }
    CHECK_STATUS(rn_network_set_load_factor(net, t0), RN_OK);
    double slope = rn_test_loglog_slope(3, hs, err);
    if (getenv("RN_VERBOSE"))
      fprintf(stderr, "load increment model %d: FD errors %.2e %.2e %.2e order %.2f\n",
              model, err[0], err[1], err[2], slope);
    CHECK(scale > 0.0);
    CHECK(err[2] < 1e-5);
    CHECK(slope > 1.8 && slope < 2.2);
    rn_network_destroy(&net);
  }
}

static void test_errors(rn_context *ctx) {
  rn_network *net;
  double flat[6] = {1, 0, 0, 2, 0, 0}, tilted[6] = {1, 0, 0, 0, 1, 0.1};
  double good[6] = {1, 0, 0, 0, 1, 0}, xyz[6] = {0, 0, 0, 1, 0, 0};
  int rod, joint, rods[2] = {0, 0}, ends[2] = {RN_START, RN_END};
  int img_bad[6] = {0, 0, 0, 0, 0, 1}, img_ok[6] = {0, 0, 0, 1, 0, 0};
  int img_off[6] = {0, 0, 0, 0, 1, 0};
  rn_material mat;
  rn_section sec;
  CHECK_STATUS(rn_material_from_E_nu(1.0, 0.3, 0.0, &mat), RN_OK);
  CHECK_STATUS(rn_section_circle(0.01, &sec), RN_OK);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_set_periodic(net, 2, flat), RN_ERR_GEOMETRY);
  CHECK_STATUS(rn_network_set_periodic(net, 2, tilted), RN_ERR_ARG);
  CHECK_STATUS(rn_network_set_periodic(net, 4, good), RN_ERR_ARG);
  CHECK_STATUS(rn_network_add_rod(net, NULL, 2, xyz, NULL, &rod), RN_OK);
  CHECK_STATUS(rn_network_add_joint_images(net, NULL, RN_JOINT_RIGID, 2, rods, ends,
                                           img_ok, &joint),
               RN_ERR_STATE);                                        /* not periodic */
  CHECK_STATUS(rn_network_set_periodic(net, 2, good), RN_ERR_STATE); /* rods exist */
  rn_network_destroy(&net);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_set_periodic(net, 2, good), RN_OK);
  CHECK_STATUS(rn_network_set_periodic(net, 2, good), RN_ERR_STATE);
  CHECK_STATUS(rn_network_add_rod(net, NULL, 2, xyz, NULL, &rod), RN_OK);
  CHECK_STATUS(rn_network_add_joint_images(net, NULL, RN_JOINT_RIGID, 2, rods, ends,
                                           img_bad, &joint),
               RN_ERR_ARG); /* a 2D cell has no third image component */
  CHECK_STATUS(rn_network_add_joint_images(net, NULL, RN_JOINT_RIGID, 2, rods, ends,
                                           img_off, &joint),
               RN_ERR_GEOMETRY); /* the end is not at that image */
  CHECK(strstr(rn_context_last_error(ctx), "coincide") != NULL);
  CHECK_STATUS(rn_network_add_joint_images(net, NULL, RN_JOINT_RIGID, 2, rods, ends,
                                           img_ok, &joint),
               RN_OK);
  { /* issue 22 item 4: a non-zero stress on a prescribed strain component is
     * contradictory control, refused in either order; zero there is fine */
    int fix1[3] = {1, 0, 0}, none[3] = {0, 0, 0};
    double e1[3] = {1e-3, 0.0, 0.0}, s1[3] = {1.0, 0.0, 0.0}, s0[3] = {0.0, 2.0, 0.0};
    CHECK_STATUS(rn_network_set_cell_strain(net, fix1, e1), RN_OK);
    CHECK_STATUS(rn_network_set_cell_stress(net, s1), RN_ERR_ARG);
    CHECK(strstr(rn_context_last_error(ctx), "contradictory") != NULL);
    CHECK_STATUS(rn_network_set_cell_stress(net, s0), RN_OK);
    CHECK_STATUS(rn_network_set_cell_strain(net, none, NULL), RN_OK);
    CHECK_STATUS(rn_network_set_cell_stress(net, s1), RN_OK);
    CHECK_STATUS(rn_network_set_cell_strain(net, fix1, e1), RN_ERR_ARG);
    CHECK_STATUS(rn_network_set_cell_load(net, NULL, s1), RN_OK); /* nothing fixed */
  }
  rn_network_destroy(&net);
}

int main(void) {
  rn_context *ctx;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  test_derivatives(ctx);
  test_strain_block(ctx);
  test_rest_and_images(ctx);
  test_uniform_strain(ctx);
  test_load_increment(ctx);
  test_errors(ctx);
  rn_context_destroy(&ctx);
  return rn_test_finish("api_periodic");
}

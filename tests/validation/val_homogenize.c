/* val_homogenize.c - linear effective elasticity of periodic rod lattices
 * (rn_homogenize) against closed forms (VALIDATION.md section 6; docs/homogenization.md).
 *
 * Rigid joints, straight members of N DER edges between joints (member length l).
 *  - square lattice (cell l x l), along the axes: E1 = E2 = EA/l, nu12 = 0 to
 *    round-off (affine stretching is exact in DER); G12 = 6 EI/l^3 N^2/(N^2+2)
 *    to 1e-9 (discrete-exact guided members), i.e. second order in 1/N;
 *  - regular hexagonal honeycomb: E = 16 sqrt(3) (EI/l^3)/(1+36s),
 *    nu = (1-12s)/(1+36s), s = EI/(EA l^2) (frame theory with axial stretching,
 *    Gibson-Ashby's (t/l)^3 law in the limit); at t/l = 0.05 (rectangle t x b),
 *    N = 16: within 1 %, second order in 1/N, and the (t/l)^3 scaling of E;
 *  - triangular lattice: isotropic, E -> 2 EA/(sqrt(3) l), nu -> 1/3 (the
 *    stretch-dominated pin-jointed limit) as the slenderness r/l -> 0: within
 *    1e-3 at r/l = 0.005;
 *  - octet truss (FCC primitive cell, 6 members per joint): C11 = 2 sqrt(2) EA/a^2,
 *    C12 = C44 = C11/2, E = rho E_s / 9 (Deshpande, Fleck & Ashby 2001) as
 *    r/l -> 0: within 1e-3 at r/l = 0.005;
 *  - the tensor is symmetric, positive definite, and agrees with finite
 *    differences of the relaxed energy density (micro problems solved at small
 *    prescribed strains) to 1e-4 relative, on the honeycomb and on a skew 3D cell. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "rodnet_solve.h"
#include "testutil.h"
#include "valutil.h"

enum { MAXJ = 4, MAXB = 8 };

typedef struct bar {
  int a, b, img[3];
} bar;

typedef struct cell_spec {
  int dim;
  double vec[9];
  int nj;
  double p[MAXJ][3];
  int nb;
  bar bars[MAXB];
} cell_spec;

/* The cell with nedges straight edges per member, rigid joints, section s,
 * E = 1 (nu = 0.3); strain components with fixed[v] prescribed (NULL: free). */
static rn_network *build_stressed(rn_context *ctx, const cell_spec *c, int nedges,
                                  const rn_section *s, const int *fixed,
                                  const double *strain, const double *stress) {
  rn_network *net;
  rn_material mat;
  int rods[2 * MAXB], ends[2 * MAXB], imgs[6 * MAXB];
  CHECK_STATUS(rn_material_from_E_nu(1.0, 0.3, 0.0, &mat), RN_OK);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_set_periodic(net, c->dim, c->vec), RN_OK);
  for (int ib = 0; ib < c->nb; ++ib) {
    const bar *b = &c->bars[ib];
    double *xyz = malloc(3 * (size_t)(nedges + 1) * sizeof(double)), q[3], d1[3];
    int rod;
    for (int k = 0; k < 3; ++k) {
      q[k] = c->p[b->b][k];
      for (int m = 0; m < c->dim; ++m) q[k] += b->img[m] * c->vec[3 * m + k];
    }
    for (int v = 0; v <= nedges; ++v)
      for (int k = 0; k < 3; ++k)
        xyz[3 * v + k] = c->p[b->a][k] + (q[k] - c->p[b->a][k]) * v / nedges;
    d1[0] = d1[1] = 0.0; /* planar cells: d1 = +z (width out of plane) */
    d1[2] = 1.0;
    CHECK_STATUS(
        rn_network_add_rod(net, NULL, nedges + 1, xyz, c->dim == 2 ? d1 : NULL, &rod),
        RN_OK);
    CHECK_STATUS(rn_network_set_material(net, rod, -1, &mat), RN_OK);
    CHECK_STATUS(rn_network_set_section(net, rod, -1, s), RN_OK);
    free(xyz);
  }
  for (int j = 0; j < c->nj; ++j) {
    int n = 0, joint;
    for (int ib = 0; ib < c->nb; ++ib) {
      if (c->bars[ib].a == j) {
        rods[n] = ib;
        ends[n] = RN_START;
        imgs[3 * n] = imgs[3 * n + 1] = imgs[3 * n + 2] = 0;
        n++;
      }
      if (c->bars[ib].b == j) {
        rods[n] = ib;
        ends[n] = RN_END;
        memcpy(imgs + 3 * n, c->bars[ib].img, sizeof(c->bars[ib].img));
        n++;
      }
    }
    CHECK_STATUS(rn_network_add_joint_images(net, NULL, RN_JOINT_RIGID, n, rods, ends,
                                             imgs, &joint),
                 RN_OK);
  }
  if (fixed) CHECK_STATUS(rn_network_set_cell_strain(net, fixed, strain), RN_OK);
  if (stress) CHECK_STATUS(rn_network_set_cell_stress(net, stress), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

static rn_network *build(rn_context *ctx, const cell_spec *c, int nedges,
                         const rn_section *s, const int *fixed, const double *strain) {
  return build_stressed(ctx, c, nedges, s, fixed, strain, NULL);
}

static rn_homogenization homogenize(rn_context *ctx, const cell_spec *c, int nedges,
                                    const rn_section *s) {
  rn_homogenization h;
  rn_network *net = build(ctx, c, nedges, s, NULL, NULL);
  CHECK_STATUS(rn_homogenize(net, &h), RN_OK);
  rn_network_destroy(&net);
  return h;
}

/* 2D constants from C (3 x 3): E1, E2, nu12, G12. */
static void constants2d(const double *C, double *E1, double *E2, double *nu12,
                        double *G12) {
  double det = C[0] * C[4] - C[1] * C[3];
  /* in-plane compliance (no coupling of shear for the lattices here) */
  *E1 = det / C[4];
  *E2 = det / C[0];
  *nu12 = C[1] / C[4];
  *G12 = C[8];
}

static void square(cell_spec *c, double l) {
  memset(c, 0, sizeof(*c));
  c->dim = 2;
  c->vec[0] = l;
  c->vec[4] = l;
  c->nj = 1;
  c->nb = 2;
  c->bars[0] = (bar){0, 0, {1, 0, 0}};
  c->bars[1] = (bar){0, 0, {0, 1, 0}};
}

static void honeycomb(cell_spec *c, double l) {
  memset(c, 0, sizeof(*c));
  c->dim = 2;
  c->vec[0] = sqrt(3.0) * l;
  c->vec[3] = 0.5 * sqrt(3.0) * l;
  c->vec[4] = 1.5 * l;
  c->nj = 2;
  c->p[1][1] = l;
  c->nb = 3;
  c->bars[0] = (bar){0, 1, {0, 0, 0}};
  c->bars[1] = (bar){0, 1, {0, -1, 0}};
  c->bars[2] = (bar){0, 1, {1, -1, 0}};
}

static void triangular(cell_spec *c, double l) {
  memset(c, 0, sizeof(*c));
  c->dim = 2;
  c->vec[0] = l;
  c->vec[3] = 0.5 * l;
  c->vec[4] = 0.5 * sqrt(3.0) * l;
  c->nj = 1;
  c->nb = 3;
  c->bars[0] = (bar){0, 0, {1, 0, 0}};
  c->bars[1] = (bar){0, 0, {0, 1, 0}};
  c->bars[2] = (bar){0, 0, {-1, 1, 0}};
}

static void octet(cell_spec *c, double a) {
  static const int img[6][3] = {{1, 0, 0},  {0, 1, 0},  {0, 0, 1},
                                {1, -1, 0}, {0, 1, -1}, {-1, 0, 1}};
  double v[9] = {0, 0.5 * a, 0.5 * a, 0.5 * a, 0, 0.5 * a, 0.5 * a, 0.5 * a, 0};
  memset(c, 0, sizeof(*c));
  c->dim = 3;
  memcpy(c->vec, v, sizeof(v));
  c->nj = 1;
  c->nb = 6;
  for (int b = 0; b < 6; ++b) c->bars[b] = (bar){0, 0, {img[b][0], img[b][1], img[b][2]}};
}

static void check_spd(const rn_homogenization *h) {
  int n = h->nstrain;
  double L[36];
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) CHECK(h->C[i * n + j] == h->C[j * n + i]);
  memcpy(L, h->C, sizeof(L)); /* Cholesky: positive definite */
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < j; ++k) L[j * n + j] -= L[j * n + k] * L[j * n + k];
    CHECK(L[j * n + j] > 0.0);
    L[j * n + j] = sqrt(fabs(L[j * n + j]));
    for (int i = j + 1; i < n; ++i) {
      for (int k = 0; k < j; ++k) L[i * n + j] -= L[i * n + k] * L[j * n + k];
      L[i * n + j] /= L[j * n + j];
    }
  }
}

static void test_square(rn_context *ctx) {
  const double l = 1.0, t = 0.02;
  rn_section s;
  double err[3], hN[3];
  const int Ns[3] = {8, 16, 32};
  CHECK_STATUS(rn_section_rectangle(1.0, t, &s), RN_OK);
  const double EA = s.A, EI = s.I22;
  for (int i = 0; i < 3; ++i) {
    cell_spec c;
    double E1, E2, nu, G;
    square(&c, l);
    rn_homogenization h = homogenize(ctx, &c, Ns[i], &s);
    check_spd(&h);
    constants2d(h.C, &E1, &E2, &nu, &G);
    CHECK_REL(E1, EA / l, 1e-10);
    CHECK_REL(E2, EA / l, 1e-10);
    CHECK_NEAR(nu, 0.0, 1e-10);
    err[i] = fabs(G / (6.0 * EI / (l * l * l)) - 1.0);
    /* discrete-exact: members of N edges between rigid joints (connection
     * edges of half Voronoi length) are guided beams of stiffness
     * 12 EI/l^3 N^2/(N^2 + 2) */
    CHECK_REL(G, 6.0 * EI / (l * l * l) * Ns[i] * Ns[i] / (Ns[i] * Ns[i] + 2.0), 1e-9);
    hN[i] = 1.0 / Ns[i];
    printf(
        "square t/l = %.2f N = %2d: E1 l/EA = %.12f nu12 = %.1e G12 l^3/(6EI) = %.8f\n",
        t, Ns[i], E1 * l / EA, nu, G * l * l * l / (6 * EI));
    CHECK_REL(h.relative_density, 2.0 * t / l, 1e-12);
  }
  double slope = rn_test_loglog_slope(3, hN, err);
  printf("square: G12 error order in 1/N = %.2f\n", slope);
  CHECK(err[2] < 2e-3);
  CHECK(slope > 1.8 && slope < 2.2);
}

static void test_honeycomb(rn_context *ctx) {
  const double l = 1.0;
  const int Ns[3] = {8, 16, 32};
  const double tl[2] = {0.05, 0.025};
  double E05 = 0.0, E025 = 0.0;
  for (int it = 0; it < 2; ++it) {
    double eE[3], enu[3], hN[3];
    rn_section sec;
    CHECK_STATUS(rn_section_rectangle(1.0, tl[it] * l, &sec), RN_OK);
    const double EA = sec.A, EI = sec.I22, sl = EI / (EA * l * l);
    const double Eref = 16.0 * sqrt(3.0) * EI / (l * l * l) / (1.0 + 36.0 * sl);
    const double nuref = (1.0 - 12.0 * sl) / (1.0 + 36.0 * sl);
    for (int i = 0; i < 3; ++i) {
      cell_spec c;
      double E1, E2, nu, G;
      honeycomb(&c, l);
      rn_homogenization h = homogenize(ctx, &c, Ns[i], &sec);
      check_spd(&h);
      constants2d(h.C, &E1, &E2, &nu, &G);
      CHECK_REL(E2, E1, 1e-8);                     /* isotropic */
      CHECK_REL(G, E1 / (2.0 * (1.0 + nu)), 1e-8); /* isotropic */
      CHECK_REL(h.relative_density, 2.0 / sqrt(3.0) * tl[it], 1e-12);
      eE[i] = fabs(E1 / Eref - 1.0);
      enu[i] = fabs(nu / nuref - 1.0);
      hN[i] = 1.0 / Ns[i];
      printf("honeycomb t/l = %.3f N = %2d: E/Eref = %.6f nu = %.6f (ref %.6f) E/E_s = "
             "%.6e\n",
             tl[it], Ns[i], E1 / Eref, nu, nuref, E1 / EA * tl[it] * l);
      if (Ns[i] == 16) {
        CHECK(eE[i] < 0.01);
        CHECK(enu[i] < 0.01);
        if (it == 0) E05 = E1 / EA;
        if (it == 1) E025 = E1 / EA;
      }
    }
    double sE = rn_test_loglog_slope(3, hN, eE);
    printf("honeycomb t/l = %.3f: E error order in 1/N = %.2f\n", tl[it], sE);
    CHECK(sE > 1.8 && sE < 2.2);
  }
  /* (t/l)^3 scaling of E (per unit depth, E/E_s = E2D/(E_s b)): E2D/EA ~ (t/l)^2 */
  double expo = log(E05 / E025) / log(2.0) + 1.0;
  printf("honeycomb: E/E_s ~ (t/l)^%.3f between t/l = 0.025 and 0.05\n", expo);
  CHECK(fabs(expo - 3.0) < 0.05);
}

static void test_triangular(rn_context *ctx) {
  const double l = 1.0, r = 0.005 * l;
  rn_section s;
  cell_spec c;
  double E1, E2, nu, G;
  CHECK_STATUS(rn_section_circle(r, &s), RN_OK);
  triangular(&c, l);
  rn_homogenization h = homogenize(ctx, &c, 8, &s);
  check_spd(&h);
  constants2d(h.C, &E1, &E2, &nu, &G);
  printf("triangular r/l = %.3f: E l/EA = %.8f (ref %.8f) nu = %.8f G/(E/(2(1+nu))) = "
         "%.8f\n",
         r / l, E1 * l / s.A, 2.0 / sqrt(3.0), nu, G * 2.0 * (1.0 + nu) / E1);
  CHECK_REL(E1, 2.0 / sqrt(3.0) * s.A / l, 1e-3);
  CHECK_REL(E2, E1, 1e-8);
  CHECK_NEAR(nu, 1.0 / 3.0, 1e-3);
  CHECK_REL(G, E1 / (2.0 * (1.0 + nu)), 1e-8);
}

static void test_octet(rn_context *ctx) {
  const double a = 1.0, l = a / sqrt(2.0), r = 0.005 * l;
  rn_section s;
  cell_spec c;
  CHECK_STATUS(rn_section_circle(r, &s), RN_OK);
  octet(&c, a);
  rn_homogenization h = homogenize(ctx, &c, 8, &s);
  check_spd(&h);
  const double C11 = 2.0 * sqrt(2.0) * s.A / (a * a);
  const double rho = 12.0 * sqrt(2.0) * s.A / (a * a);
  /* E1 from the compliance of the cubic block */
  const double c11 = h.C[0], c12 = h.C[1], c44 = h.C[21];
  const double E1 = c11 - 2.0 * c12 * c12 / (c11 + c12);
  printf("octet r/l = %.3f: C11/ref = %.8f C12/C11 = %.8f C44/C11 = %.8f E/(rho E_s/9) = "
         "%.8f rho = %.6e (ref %.6e)\n",
         r / l, c11 / C11, c12 / c11, c44 / c11, E1 / (rho / 9.0), h.relative_density,
         rho);
  CHECK_REL(h.relative_density, rho, 1e-12);
  CHECK_REL(c11, C11, 1e-3);
  CHECK_REL(c12, 0.5 * C11, 1e-3);
  CHECK_REL(c44, 0.5 * C11, 1e-3);
  CHECK_REL(E1, rho / 9.0, 1e-3);
  CHECK_REL(h.C[7], c11, 1e-8); /* cubic symmetry: C22 = C33 = C11 */
  CHECK_REL(h.C[14], c11, 1e-8);
  check_spd(&h);
}

/* C against finite differences of the relaxed energy density W(eps) / measure:
 * micro problems at prescribed strains +-h e_u +-h e_v, solved by rn_solve. */
static double relaxed_energy(rn_context *ctx, const cell_spec *c, int nedges,
                             const rn_section *s, const double *eps) {
  int fixed[6] = {1, 1, 1, 1, 1, 1};
  double E, x[20000];
  rn_network *net = build(ctx, c, nedges, s, fixed, eps);
  rn_solve_options opt;
  rn_solve_report rep;
  rn_solve_options_default(&opt);
  opt.gtol_rel = 1e-12;
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  CHECK(rn_network_num_dofs(net) <= 20000);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_energy(net, x, &E), RN_OK);
  rn_network_destroy(&net);
  return E;
}

static void fd_check(rn_context *ctx, const cell_spec *c, const rn_section *s,
                     const char *name) {
  const int nedges = 6;
  rn_homogenization h = homogenize(ctx, c, nedges, s);
  const int n = h.nstrain;
  const double step = 1e-4;
  double worst = 0.0, cmax = 0.0;
  for (int i = 0; i < n * n; ++i) cmax = fmax(cmax, fabs(h.C[i]));
  for (int u = 0; u < n; ++u)
    for (int v = u; v < n; ++v) {
      double e[6] = {0}, W[4];
      const int su[4] = {1, 1, -1, -1}, sv[4] = {1, -1, 1, -1};
      for (int k = 0; k < 4; ++k) {
        memset(e, 0, sizeof(e));
        e[u] += su[k] * step;
        e[v] += sv[k] * step;
        W[k] = relaxed_energy(ctx, c, nedges, s, e);
      }
      double fd = (W[0] - W[1] - W[2] + W[3]) / (4.0 * step * step) / h.measure;
      worst = fmax(worst, fabs(fd - h.C[u * n + v]) / cmax);
    }
  printf("%s: C against FD of the relaxed energy: worst |diff| / max|C| = %.2e\n", name,
         worst);
  CHECK(worst < 1e-4);
}

/* Mixed control: uniaxial macroscopic stress on the honeycomb (every strain
 * component a DOF, stress (s, 0, 0)) solved by rn_solve: e11 = s / E1 and
 * e22 = -nu12 e11 of the homogenised tensor (to 1e-3: the nonlinearity at
 * strain 1e-5), no shear; the stress read back equals the applied one. */
static void test_stress_control(rn_context *ctx) {
  cell_spec c;
  rn_section s;
  double E1, E2, nu, G, eps[3], sig[3], x[4096];
  honeycomb(&c, 1.0);
  CHECK_STATUS(rn_section_rectangle(1.0, 0.05, &s), RN_OK);
  rn_homogenization h = homogenize(ctx, &c, 8, &s);
  constants2d(h.C, &E1, &E2, &nu, &G);
  const double stress[3] = {1e-5 * E1, 0.0, 0.0};
  rn_network *net = build_stressed(ctx, &c, 8, &s, NULL, NULL, stress);
  rn_solve_options opt;
  rn_solve_report rep;
  rn_solve_options_default(&opt);
  opt.gtol_rel = 1e-12;
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  CHECK_STATUS(rn_network_cell_strain(net, NULL, eps), RN_OK);
  CHECK(rn_network_num_dofs(net) <= 4096);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_cell_stress(net, x, sig), RN_OK);
  printf(
      "uniaxial stress on the honeycomb: e11 E1/s = %.6f, -e22/e11 = %.6f (nu12 %.6f), "
      "g12 = %.1e, stress read back %.6f of applied\n",
      eps[0] * E1 / stress[0], -eps[1] / eps[0], nu, eps[2], sig[0] / stress[0]);
  CHECK_REL(eps[0], stress[0] / E1, 1e-3);
  CHECK_REL(-eps[1] / eps[0], nu, 1e-3);
  CHECK(fabs(eps[2]) < 1e-8 * fabs(eps[0]));
  CHECK_REL(sig[0], stress[0], 1e-6);
  CHECK(fabs(sig[1]) < 1e-6 * stress[0] && fabs(sig[2]) < 1e-6 * stress[0]);
  rn_network_destroy(&net);
}

int main(void) {
  rn_context *ctx;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  test_square(ctx);
  test_honeycomb(ctx);
  test_triangular(ctx);
  test_octet(ctx);
  test_stress_control(ctx);
  {
    cell_spec c;
    rn_section s;
    honeycomb(&c, 1.0);
    CHECK_STATUS(rn_section_rectangle(1.0, 0.1, &s), RN_OK);
    fd_check(ctx, &c, &s, "honeycomb t/l = 0.1");
    octet(&c, 1.0);
    c.vec[0] = 0.05; /* skew it: no symmetry left */
    c.vec[5] = 0.55;
    CHECK_STATUS(rn_section_ellipse(0.04, 0.025, &s), RN_OK);
    fd_check(ctx, &c, &s, "skew octet, elliptic section");
  }
  rn_context_destroy(&ctx);
  return rn_test_finish("val_homogenize");
}

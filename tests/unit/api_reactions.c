/* api_reactions.c - DOF kinds, the full-layout gradient and the reactions of
 * every support (rn_network_reactions):
 *  - the reactions are the derivative of the energy with respect to the
 *    prescribed motions: with the free DOFs held, dE/dlambda = sum over supports
 *    of F . d + M . r (d, r the prescribed translation and rotation rates),
 *    checked against central differences in the load factor with an h-sweep
 *    (second order), on a portal frame with a clamped rod end moved and turned,
 *    a clamped joint moved and turned, a pinned joint moved, a component pin
 *    moved and a fixed material angle;
 *  - at equilibrium (rn_solve) they balance the applied loads: the cantilever's
 *    clamp carries -P and the moment -(x_tip - p) x P; the reactions of the
 *    moved portal frame (no loads) sum to zero, forces and moments;
 *  - rn_network_gradient_full agrees with rn_network_gradient on free DOFs of a
 *    single rod, rn_network_gradient_magnitude bounds |g| (and is much larger
 *    where stencil forces cancel), and rn_network_dof_kinds counts positions,
 *    angles, rotations. */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "shim_networks.h"
#include "shim_rods.h"

static double norm3(const double v[3]) {
  return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

static void cross_add(const double a[3], const double b[3], double out[3]) {
  out[0] += a[1] * b[2] - a[2] * b[1];
  out[1] += a[2] * b[0] - a[0] * b[2];
  out[2] += a[0] * b[1] - a[1] * b[0];
}

/* Portal frame (shimnet_line rods of ne edges, joints A, B rigid/elastic, C a
 * clamped valence-1 joint under column 1) without loads, every support moved:
 * the column-0 clamp by disp0 and rot0, joint C by dispc and rotc, joint A pinned
 * in x and moved by ax, the beam's middle vertex pinned in z and moved by bz;
 * column 0's middle edge has a fixed angle. */
static const double disp0[3] = {0.01, 0.0, 0.02}, rot0[3] = {0.0, 0.03, 0.01};
static const double dispc[3] = {-0.02, 0.01, 0.0}, rotc[3] = {0.02, -0.04, 0.0};
static const double ax = 0.015, bz = -0.01;

static rn_network *moved_portal(rn_context *ctx, int ne) {
  rn_network *net = NULL;
  const double d1[3] = {0, 1, 0};
  const double a0[3] = {0, 0, 0}, a1[3] = {0, 0, 1}, b0[3] = {1, 0, 0}, b1[3] = {1, 0, 1};
  const double da[3] = {ax, 0, 0}, db[3] = {0, 0, bz};
  int ra[2], ea[2] = {RN_END, RN_START}, rb[2], eb[2] = {RN_END, RN_END}, rc[1],
             ec[1] = {RN_START}, ja, jb, jc;
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  const int c0 = shimnet_line(net, "col0", a0, a1, ne, d1);
  const int c1 = shimnet_line(net, "col1", b0, b1, ne, d1);
  const int bm = shimnet_line(net, "beam", a1, b1, 2 * ne, d1);
  ra[0] = c0, ra[1] = bm, rb[0] = c1, rb[1] = bm, rc[0] = c1;
  CHECK_STATUS(rn_network_add_joint(net, "A", RN_JOINT_RIGID, 2, ra, ea, &ja), RN_OK);
  CHECK_STATUS(rn_network_add_joint(net, "B", RN_JOINT_ELASTIC, 2, rb, eb, &jb), RN_OK);
  CHECK_STATUS(rn_network_add_joint(net, "C", RN_JOINT_RIGID, 1, rc, ec, &jc), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, c0, RN_START), RN_OK);
  CHECK_STATUS(rn_network_displace_end(net, c0, RN_START, disp0, rot0), RN_OK);
  CHECK_STATUS(rn_network_clamp_joint(net, jc), RN_OK);
  CHECK_STATUS(rn_network_displace_joint(net, jc, dispc, rotc), RN_OK);
  CHECK_STATUS(rn_network_pin_joint_components(net, ja, RN_FIX_X), RN_OK);
  CHECK_STATUS(rn_network_displace_joint(net, ja, da, NULL), RN_OK);
  CHECK_STATUS(rn_network_pin_components(net, bm, ne, RN_FIX_Z), RN_OK);
  CHECK_STATUS(rn_network_displace_vertex(net, bm, ne, db), RN_OK);
  CHECK_STATUS(rn_network_fix_theta(net, c0, ne / 2), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

/* Work rate of the reactions on the prescribed motions (the load-factor
 * derivative of every prescribed DOF), in the order of rn_network_reactions. */
static double reaction_power(const rn_reaction *r, int n) {
  double P = 0.0;
  for (int i = 0; i < n; ++i) {
    const rn_reaction *R = &r[i];
    const double *d = NULL, *w = NULL;
    if (R->kind == RN_SUPPORT_CLAMP) d = disp0, w = rot0;
    if (R->kind == RN_SUPPORT_JOINT && R->fixed_rotation) d = dispc, w = rotc;
    if (R->kind == RN_SUPPORT_JOINT && !R->fixed_rotation) P += R->force[0] * ax;
    if (R->kind == RN_SUPPORT_VERTEX) P += R->force[2] * bz;
    for (int k = 0; d && k < 3; ++k) P += R->force[k] * d[k] + R->moment[k] * w[k];
  }
  return P;
}

static double energy_at(rn_network *net, const double *x, double lambda) {
  double E = 0.0;
  CHECK_STATUS(rn_network_set_load_factor(net, lambda), RN_OK);
  CHECK_STATUS(rn_network_energy(net, x, &E), RN_OK);
  return E;
}

static void check_power(rn_context *ctx) {
  rn_network *net = moved_portal(ctx, 6);
  const size_t n = rn_network_num_dofs(net);
  const int ns = rn_network_num_supports(net);
  double *x = malloc(n * sizeof *x);
  rn_reaction r[8];
  CHECK(ns == 5);
  CHECK_STATUS(rn_network_reactions(net, NULL, r, ns + 1), RN_ERR_ARG);
  /* a state away from equilibrium: the start plus a smooth perturbation */
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  for (size_t i = 0; i < n; ++i) x[i] += 2e-3 * sin(0.37 * (double)i + 0.1);
  const double t0 = 0.5;
  CHECK_STATUS(rn_network_set_load_factor(net, t0), RN_OK);
  CHECK_STATUS(rn_network_reactions(net, x, r, ns), RN_OK);
  CHECK(r[0].kind == RN_SUPPORT_CLAMP && r[1].kind == RN_SUPPORT_THETA &&
        r[2].kind == RN_SUPPORT_VERTEX && r[3].kind == RN_SUPPORT_JOINT &&
        r[4].kind == RN_SUPPORT_JOINT && r[4].fixed_rotation == 1);
  CHECK(r[2].force[0] == 0.0 && r[2].force[1] == 0.0 && r[3].force[1] == 0.0);
  const double P = reaction_power(r, ns);
  double err_prev = 0.0, order = 0.0;
  printf("dE/dlambda = %.12e from the reactions\n", P);
  for (int k = 0; k < 4; ++k) {
    const double h = 1e-2 / pow(2.0, k);
    const double fd = (energy_at(net, x, t0 + h) - energy_at(net, x, t0 - h)) / (2.0 * h);
    const double err = fabs(fd - P) / fabs(P);
    if (k > 0) order = log(err_prev / err) / log(2.0);
    printf("  h = %.3e: central difference %.12e, rel. error %.3e, order %.3f\n", h, fd,
           err, order);
    if (k == 3) CHECK(err < 1e-6);
    err_prev = err;
  }
  CHECK(order > 1.9 && order < 2.1);
  free(x);
  rn_network_destroy(&net);
}

/* Sum of reaction forces plus applied forces, and of moments about the origin. */
static void check_balance(rn_network *net, const double *fext, const double *xext,
                          int next, const double *mext, double rel_tol,
                          const char *what) {
  const size_t n = rn_network_num_dofs(net);
  const int ns = rn_network_num_supports(net);
  double *x = malloc(n * sizeof *x), F[3] = {0, 0, 0}, M[3] = {0, 0, 0}, fbig = 0.0,
         mbig = 0.0;
  rn_reaction *r = malloc((size_t)ns * sizeof *r);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_reactions(net, x, r, ns), RN_OK);
  for (int i = 0; i < ns; ++i) {
    for (int k = 0; k < 3; ++k) F[k] += r[i].force[k], M[k] += r[i].moment[k];
    cross_add(r[i].point, r[i].force, M);
    fbig = fmax(fbig, norm3(r[i].force));
    mbig = fmax(mbig, norm3(r[i].moment));
  }
  for (int i = 0; i < next; ++i) {
    for (int k = 0; k < 3; ++k) F[k] += fext[3 * i + k], M[k] += mext[3 * i + k];
    cross_add(&xext[3 * i], &fext[3 * i], M);
    fbig = fmax(fbig, norm3(&fext[3 * i]));
  }
  printf("%s: |sum F| = %.3e (largest %.3e), |sum M| = %.3e (largest %.3e)\n", what,
         norm3(F), fbig, norm3(M), mbig);
  CHECK(norm3(F) <= rel_tol * fbig);
  CHECK(norm3(M) <= rel_tol * fmax(mbig, fbig));
  free(r);
  free(x);
}

static void check_equilibrium(rn_context *ctx) {
  rn_solve_options opt;
  rn_solve_report rep;
  rn_solve_options_default(&opt);
  /* cantilever: tip force P, the clamp at the midpoint of the first edge */
  const double P = 2.0 * shim_cantilever_EI();
  rn_network *net = shim_cantilever(ctx, P);
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  CHECK(rep.converged == 1);
  double xyz[3 * 21], fext[3] = {0, 0, -P}, zero[3] = {0, 0, 0};
  rn_reaction r[1];
  CHECK(rn_network_num_supports(net) == 1);
  {
    double *x = malloc(rn_network_num_dofs(net) * sizeof *x);
    CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
    CHECK_STATUS(rn_network_reactions(net, x, r, 1), RN_OK);
    free(x);
  }
  CHECK_STATUS(rn_network_rod_vertices(net, 0, xyz), RN_OK);
  double mexp[3] = {0, 0, 0}, d[3];
  for (int k = 0; k < 3; ++k) d[k] = xyz[60 + k] - r[0].point[k];
  cross_add(d, fext, mexp);
  printf("cantilever clamp: force (%.9f %.9f %.9f), moment y %.9f (expected %.9f) at x = "
         "%.4f\n",
         r[0].force[0], r[0].force[1], r[0].force[2], r[0].moment[1], -mexp[1],
         r[0].point[0]);
  CHECK(fabs(r[0].point[0] - 0.025) < 1e-12 && r[0].kind == RN_SUPPORT_CLAMP);
  CHECK(fabs(r[0].force[2] - P) <= 1e-8 * P && fabs(r[0].force[0]) <= 1e-8 * P);
  CHECK(fabs(r[0].moment[1] + mexp[1]) <= 1e-8 * fabs(mexp[1]));
  check_balance(net, fext, &xyz[60], 1, zero, 1e-8, "cantilever");
  rn_network_destroy(&net);

  /* the moved portal frame: no loads, the reactions balance each other */
  net = moved_portal(ctx, 6);
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  CHECK(rep.converged == 1);
  check_balance(net, NULL, NULL, 0, NULL, 1e-8, "moved portal frame");
  rn_network_destroy(&net);
}

static void check_full_and_kinds(rn_context *ctx) {
  rn_network *net = shimnet_portal(ctx, RN_JOINT_RIGID, RN_JOINT_ELASTIC, 4, 0.3, 1);
  const size_t n = rn_network_num_dofs(net);
  int *kind = malloc(n * sizeof *kind), cnt[3] = {0, 0, 0};
  CHECK_STATUS(rn_network_dof_kinds(net, kind), RN_OK);
  for (size_t i = 0; i < n; ++i) cnt[kind[i]]++;
  /* 3 rods of 4, 4, 8 edges: 16 angles, none fixed but column 0's first; joints A
   * (rigid, free: 3 rotations), B (elastic), C (clamped) */
  printf("kinds: %d positions, %d angles, %d rotations\n", cnt[0], cnt[1], cnt[2]);
  CHECK(cnt[1] == 15 && cnt[2] == 3 && (size_t)(cnt[0] + cnt[1] + cnt[2]) == n);
  free(kind);
  rn_network_destroy(&net);

  /* one rod: the full gradient's free entries are the reduced gradient */
  const double f[3] = {0.1, 0.0, -0.2};
  rn_section s;
  CHECK_STATUS(rn_section_circle(0.01, &s), RN_OK);
  net = shim_clamped_rod(ctx, 11, 1.0, 0, &s, 1e7, f);
  const size_t nr = rn_network_num_dofs(net);
  const size_t nfr = rn_network_num_full_dofs(net);
  double *x = malloc(nr * sizeof *x), *g = malloc(nr * sizeof *g),
         *gf = malloc(nfr * sizeof *gf);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  for (size_t i = 0; i < nr; ++i) x[i] += 1e-3 * cos(0.5 * (double)i);
  CHECK_STATUS(rn_network_gradient(net, x, NULL, g), RN_OK);
  CHECK_STATUS(rn_network_gradient_full(net, x, gf), RN_OK);
  /* the clamp fixes x_0, theta^0, x_1: the first 7 full DOFs */
  /* the magnitude of the stencil forces bounds the gradient, and exceeds it where
   * forces cancel; it also bounds the rounding error of the sums */
  double *ga = malloc(nr * sizeof *ga), excess = 0.0;
  int below = 0;
  CHECK_STATUS(rn_network_gradient_magnitude(net, x, ga), RN_OK);
  /* the full-layout gradient sums each stencil's contribution separately (the
   * stencil kernels), the reduced one runs the whole-rod kernels: the same sums
   * up to their rounding, at most a few units of eps times the stencil forces */
  double d = 0.0, gn = 0.0, dr = 0.0;
  CHECK(nfr == nr + 7);
  for (size_t i = 0; i < nr; ++i) {
    d = fmax(d, fabs(gf[i + 7] - g[i])), gn = fmax(gn, fabs(g[i]));
    dr = fmax(dr, fabs(gf[i + 7] - g[i]) / (DBL_EPSILON * ga[i]));
  }
  printf("one rod: max |g_full - g| on free DOFs %.3e (max |g| %.3e), %.2f eps of the "
         "stencil forces\n",
         d, gn, dr);
  CHECK(dr <= 8.0);
  CHECK_STATUS(rn_network_gradient_full(net, NULL, gf), RN_ERR_ARG);
  for (size_t i = 0; i < nr; ++i) {
    below += ga[i] < fabs(g[i]) * (1.0 - 1e-14);
    excess = fmax(excess, ga[i] - fabs(g[i]));
  }
  printf("gradient magnitude: %d entries below |g|, largest excess %.3e\n", below,
         excess);
  CHECK(below == 0 && excess > 0.1 * gn);
  free(ga);
  free(x), free(g), free(gf);
  rn_network_destroy(&net);
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_runtime_initialize(&argc, &argv), RN_OK);
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  check_full_and_kinds(ctx);
  check_power(ctx);
  check_equilibrium(ctx);
  rn_context_destroy(&ctx);
  rn_runtime_finalize();
  return rn_test_finish("api_reactions");
}

/* api_rings.c - closed rods and smooth joints (issue 10 section 4):
 *  - derivatives of a non-planar twisted closed rod with an anisotropic section
 *    (rn_network_check_derivatives: h-sweep order 2, CSR Hessian = HVP);
 *  - a free ring whose input is an ellipse and whose rest curvature is that of
 *    the regular polygon: the polygon has zero energy and zero gradient;
 *  - the same ring as two rods joined end to start by two smooth joints: the
 *    same energy and gradient as the closed rod to round-off;
 *  - link conservation: a ring with link 2 keeps its total twist 4 pi over
 *    reference updates with large rigid rotations (2.5 rad per step), closed
 *    rod and loop through a smooth joint;
 *  - the anisotropic ribbon ring of VALIDATION.md 7.4 (flat and conical rings:
 *    psi*, energies, equilibrium), discrete-exact;
 *  - Michell's instability of a twisted ring: the lowest eigenvalue of the
 *    Hessian without its rigid modes crosses zero at C/B = sqrt(3)/n (link n),
 *    the critical C/B converging to it at order 2 in the number of edges (32,
 *    64, 128 edges; a naturally straight rod, r / R = 0.002). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "testutil.h"

void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda,
            double *w, double *work, const int *lwork, int *info, size_t, size_t);

static const double PI = 3.14159265358979323846;

/* Regular N-gon of radius R in the xy plane (ellipse factor ex on x), with a
 * small out-of-plane wave of amplitude wz. */
static double *polygon(int N, double R, double ex, double wz) {
  double *x = malloc(3 * (size_t)N * sizeof(double));
  for (int i = 0; i < N; ++i) {
    double a = 2.0 * PI * i / N;
    x[3 * i] = ex * R * cos(a);
    x[3 * i + 1] = R * sin(a);
    x[3 * i + 2] = wz * sin(3.0 * a);
  }
  return x;
}

static void props(rn_network *net, int rod, double nu, int aniso, double r) {
  rn_material m;
  rn_section s;
  CHECK_STATUS(rn_material_from_E_nu(1e6, nu, 0.0, &m), RN_OK);
  if (aniso)
    CHECK_STATUS(rn_section_rectangle(2.0 * r, r, &s), RN_OK);
  else
    CHECK_STATUS(rn_section_circle(r, &s), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
}

/* A closed rod through xyz[3N]; joint receives its closing joint. */
static rn_network *ring(rn_context *ctx, int N, const double *xyz, double nu, int aniso,
                        double r, int link, int *joint) {
  rn_network *net = NULL;
  const double d1[3] = {0, 0, 1};
  int rod = -1;
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_closed_rod(net, "ring", N, xyz, d1, &rod, joint), RN_OK);
  CHECK(rn_network_rod_is_closed(net, rod) == 1);
  CHECK(rn_network_rod_num_vertices(net, rod) == N + 1);
  props(net, rod, nu, aniso, r);
  CHECK_STATUS(rn_network_set_joint_link(net, *joint, link), RN_OK);
  return net;
}

/* Total twist of every rod plus every smooth joint at the current state. */
static double total_twist(const rn_network *net) {
  double tw = 0.0;
  for (int r = 0; r < rn_network_num_rods(net); ++r) {
    int nv = rn_network_rod_num_vertices(net, r);
    double *tau = calloc((size_t)nv, sizeof(double));
    CHECK_STATUS(rn_network_rod_strains(net, r, NULL, NULL, tau), RN_OK);
    for (int i = 0; i < nv - 2; ++i) tw += tau[i];
    free(tau);
  }
  for (int j = 0; j < rn_network_num_joints(net); ++j) {
    double t = 0.0;
    if (rn_network_joint_model(net, j) != RN_JOINT_SMOOTH) continue;
    CHECK_STATUS(rn_network_joint_twist(net, j, &t), RN_OK);
    tw += t;
  }
  return tw;
}

/* Reduced layout of a free closed rod of N vertices (no BCs): theta_j at 4 j,
 * vertex i (1 .. N-1) at 4 i - 3, vertex 0 (the joint) at 4 N - 3. */
static int vdof(int N, int i) { return i == 0 ? 4 * N - 3 : 4 * i - 3; }
static int tdof(int j) { return 4 * j; }

static void rotate(int N, double *x, const double axis[3], double ang) {
  double c = cos(ang), s = sin(ang), *v;
  for (int i = 0; i < N; ++i) {
    double p[3], kxp[3], kp;
    v = x + vdof(N, i);
    memcpy(p, v, sizeof(p));
    rn_test_cross3(axis, p, kxp);
    kp = axis[0] * p[0] + axis[1] * p[1] + axis[2] * p[2];
    for (int k = 0; k < 3; ++k) v[k] = p[k] * c + kxp[k] * s + axis[k] * kp * (1.0 - c);
  }
}

static void test_derivatives(rn_context *ctx) {
  int joint = -1;
  double *xyz = polygon(10, 1.0, 1.3, 0.2);
  rn_network *net = ring(ctx, 10, xyz, 0.3, 1, 0.05, 1, &joint);
  rn_check_report rep;
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK(rn_network_num_dofs(net) == 40);
  CHECK_STATUS(rn_network_check_derivatives(net, NULL, 3, 0.05, 7, &rep), RN_OK);
  printf("closed rod derivatives: grad %.2e (order %.2f) hvp %.2e (order %.2f) sym %.2e "
         "csr %.2e\n",
         rep.grad_rel_err, rep.grad_order, rep.hvp_rel_err, rep.hvp_order,
         rep.hess_sym_err, rep.hess_hvp_err);
  CHECK(rep.grad_rel_err < 1e-6 && rep.hvp_rel_err < 1e-6);
  CHECK(rep.grad_order > 1.8 && rep.grad_order < 2.2);
  CHECK(rep.hvp_order > 1.8 && rep.hvp_order < 2.2);
  CHECK(rep.hess_sym_err < 1e-13 && rep.hess_hvp_err < 1e-12);
  rn_network_destroy(&net);
  free(xyz);
}

/* Regular-polygon state of a ring network built from an ellipse: x at the
 * polygon, thetas 0. */
static void polygon_state(const rn_network *net, int N, double *x) {
  double *p = polygon(N, 1.0, 1.0, 0.0);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  for (int i = 0; i < N; ++i) memcpy(x + vdof(N, i), p + 3 * i, 3 * sizeof(double));
  for (int j = 0; j < N; ++j) x[tdof(j)] = 0.0;
  free(p);
}

static void test_rest_circle(rn_context *ctx) {
  enum { N = 24 };
  int joint = -1;
  double *xyz = polygon(N, 1.0, 1.4, 0.0), kap[2 * N], tau[N], len[N], E, E0;
  double x[4 * N], g[4 * N], gmax = 0.0;
  rn_network *net = ring(ctx, N, xyz, 0.3, 1, 0.02, 0, &joint);
  for (int i = 0; i < N; ++i) { /* the polygon's curvature: about d2 = t x z */
    kap[2 * i] = 0.0;
    kap[2 * i + 1] = -2.0 * tan(PI / N);
    tau[i] = 0.0;
    len[i] = 2.0 * sin(PI / N);
  }
  CHECK_STATUS(rn_network_set_rest_curvature(net, 0, kap + 2), RN_OK);
  CHECK_STATUS(rn_network_set_rest_twist(net, 0, tau + 1), RN_OK);
  CHECK_STATUS(rn_network_set_joint_rest_strains(net, joint, kap, tau[0]), RN_OK);
  CHECK_STATUS(rn_network_set_rest_lengths(net, 0, len), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_energy(net, x, &E0), RN_OK);
  polygon_state(net, N, x);
  CHECK_STATUS(rn_network_gradient(net, x, &E, g), RN_OK);
  for (int k = 0; k < 4 * N; ++k) gmax = fmax(gmax, fabs(g[k]));
  printf("rest circle: energy at the ellipse %.6e, at the polygon %.3e, |g| %.3e\n", E0,
         E, gmax);
  CHECK(E0 > 1e-3);
  CHECK(fabs(E) <= 1e-14 * E0);
  CHECK(gmax <= 1e-10);
  rn_network_destroy(&net);
  free(xyz);
}

/* The ring as two rods joined by two smooth joints: same energy and gradient. */
static void test_two_rods(rn_context *ctx) {
  enum { N = 12, H = 6 };
  int joint = -1, ra = -1, rb = -1, j1 = -1, j2 = -1;
  double *xyz = polygon(N, 1.0, 1.2, 0.15), a[3 * (H + 1)], b[3 * (H + 1)];
  const double d1[3] = {0, 0, 1};
  double xc[4 * N], xl[4 * N], gc[4 * N], gl[4 * N], Ec, El, gd = 0.0, gn = 0.0;
  double fr[3 * N];
  rn_network *closed = ring(ctx, N, xyz, 0.3, 1, 0.05, 1, &joint), *loop = NULL;
  CHECK_STATUS(rn_network_finalize(closed), RN_OK);
  /* rod b starts with the ring's material axis at edge H (the same frames): at
   * theta = 0 (the ring's initial angles spread its stored turn) the material
   * frames are the reference frames */
  CHECK_STATUS(rn_network_get_dofs(closed, xc), RN_OK);
  for (int j = 0; j < N; ++j) xc[tdof(j)] = 0.0;
  CHECK_STATUS(rn_network_set_dofs(closed, xc), RN_OK);
  CHECK_STATUS(rn_network_rod_frames(closed, 0, fr, NULL), RN_OK);
  memcpy(a, xyz, 3 * (H + 1) * sizeof(double));
  memcpy(b, xyz + 3 * H, 3 * H * sizeof(double));
  memcpy(b + 3 * H, xyz, 3 * sizeof(double));
  CHECK_STATUS(rn_network_create(ctx, &loop), RN_OK);
  CHECK_STATUS(rn_network_add_rod(loop, "a", H + 1, a, d1, &ra), RN_OK);
  CHECK_STATUS(rn_network_add_rod(loop, "b", H + 1, b, fr + 3 * H, &rb), RN_OK);
  props(loop, ra, 0.3, 1, 0.05);
  props(loop, rb, 0.3, 1, 0.05);
  {
    int r1[2] = {ra, rb}, e1[2] = {RN_END, RN_START};
    int r2[2] = {ra, rb}, e2[2] = {RN_START, RN_END}; /* swapped into end, start */
    CHECK_STATUS(rn_network_add_joint(loop, "j1", RN_JOINT_SMOOTH, 2, r1, e1, &j1),
                 RN_OK);
    CHECK_STATUS(rn_network_add_joint(loop, "j2", RN_JOINT_SMOOTH, 2, r2, e2, &j2),
                 RN_OK);
  }
  CHECK_STATUS(rn_network_set_joint_link(loop, j2, 1), RN_OK);
  CHECK_STATUS(rn_network_finalize(loop), RN_OK);
  CHECK(rn_network_num_dofs(loop) == 4 * N);
  CHECK_STATUS(rn_network_get_dofs(closed, xc), RN_OK);
  for (int k = 0; k < 4 * N; ++k) xc[k] += 0.02 * sin(1.7 * k);
  /* the same state in the loop's layout: rod a (theta_0, x_1, .., theta_5), rod b
   * (theta_6, x_7, .., theta_11), j1 (vertex 6), j2 (vertex 0) */
  for (int j = 0; j < N; ++j) xl[j < H ? 4 * j : 4 * j - 3] = xc[tdof(j)];
  for (int i = 1; i < N; ++i)
    if (i != H)
      memcpy(xl + (i < H ? 4 * i - 3 : 4 * i - 6), xc + vdof(N, i), 3 * sizeof(double));
  memcpy(xl + 4 * N - 6, xc + vdof(N, H), 3 * sizeof(double));
  memcpy(xl + 4 * N - 3, xc + vdof(N, 0), 3 * sizeof(double));
  CHECK_STATUS(rn_network_gradient(closed, xc, &Ec, gc), RN_OK);
  CHECK_STATUS(rn_network_gradient(loop, xl, &El, gl), RN_OK);
  for (int j = 0; j < N; ++j)
    gd = fmax(gd, fabs(gl[j < H ? 4 * j : 4 * j - 3] - gc[tdof(j)]));
  for (int k = 0; k < 4 * N; ++k) gn = fmax(gn, fabs(gc[k]));
  printf("closed rod vs two rods + smooth joints: E %.15e vs %.15e, theta gradient "
         "diff %.2e of %.2e\n",
         Ec, El, gd, gn);
  CHECK(fabs(Ec - El) <= 1e-12 * fabs(Ec));
  CHECK(gd <= 1e-10 * gn);
  rn_network_destroy(&closed);
  rn_network_destroy(&loop);
  free(xyz);
}

static void test_link(rn_context *ctx) {
  enum { N = 20 };
  int joint = -1;
  double *xyz = polygon(N, 1.0, 1.0, 0.0), x[4 * N], tw0, tw;
  const double axes[3][3] = {{1, 0, 0}, {0, 0.6, 0.8}, {0.48, 0.6, -0.64}};
  rn_network *net = ring(ctx, N, xyz, 0.3, 0, 0.05, 2, &joint);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  for (int j = 0; j < N; ++j) x[tdof(j)] = 4.0 * PI * j / N; /* uniform twist */
  CHECK_STATUS(rn_network_update_reference(net, x), RN_OK);
  tw0 = total_twist(net);
  CHECK_NEAR(tw0, 4.0 * PI, 1e-12);
  for (int step = 0; step < 9; ++step) {
    rotate(N, x, axes[step % 3], 2.5);
    CHECK_STATUS(rn_network_update_reference(net, x), RN_OK);
    tw = total_twist(net);
    CHECK_NEAR(tw, 4.0 * PI, 1e-9);
  }
  printf("link 2 ring: total twist %.15f after 9 rotations of 2.5 rad (4 pi = %.15f)\n",
         tw, 4.0 * PI);
  rn_network_destroy(&net);
  free(xyz);
}

/* Lowest eigenvalue of H with its 7 zero modes (3 translations, 3 rotations,
 * the uniform spin of the material angles) shifted away, at the twisted ring. */
static double michell_lowest(rn_context *ctx, int N, double nu, int link, double *gmax) {
  int joint = -1, n = 4 * N, nnz_ok;
  double *xyz = polygon(N, 1.0, 1.0, 0.0), *x = calloc((size_t)n, sizeof(double));
  double *g = calloc((size_t)n, sizeof(double)),
         *H = calloc((size_t)n * n, sizeof(double));
  double *V = calloc(7 * (size_t)n, sizeof(double)), hmax = 0.0, E;
  rn_network *net = ring(ctx, N, xyz, nu, 0, 0.002, link, &joint);
  size_t nnz = 0;
  const int64_t *rowptr;
  const int32_t *col;
  { /* a naturally straight rod closed into a ring */
    double *zero = calloc(2 * (size_t)N, sizeof(double));
    CHECK_STATUS(rn_network_set_rest_curvature(net, 0, zero), RN_OK);
    CHECK_STATUS(rn_network_set_joint_rest_straight(net, joint), RN_OK);
    free(zero);
  }
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  for (int j = 0; j < N; ++j) x[tdof(j)] = 2.0 * PI * link * j / N;
  CHECK_STATUS(rn_network_gradient(net, x, &E, g), RN_OK);
  *gmax = 0.0;
  for (int k = 0; k < n; ++k) *gmax = fmax(*gmax, fabs(g[k]));
  CHECK_STATUS(rn_network_hessian_pattern(net, &nnz, &rowptr, &col), RN_OK);
  {
    double *vals = calloc(nnz, sizeof(double));
    CHECK_STATUS(rn_network_hessian_values(net, x, vals), RN_OK);
    for (int i = 0; i < n; ++i)
      for (int64_t k = rowptr[i]; k < rowptr[i + 1]; ++k) {
        H[i + (size_t)n * (size_t)col[k]] = vals[k];
        hmax = fmax(hmax, fabs(vals[k]));
      }
    free(vals);
  }
  for (int m = 0; m < 7; ++m) { /* the zero modes */
    double *v = V + (size_t)m * n;
    for (int i = 0; i < N; ++i) {
      const double *p = x + vdof(N, i);
      if (m < 3) v[vdof(N, i) + m] = 1.0;
      if (m >= 3 && m < 6) {
        double w[3] = {0, 0, 0}, wxp[3];
        w[m - 3] = 1.0;
        rn_test_cross3(w, p, wxp);
        memcpy(v + vdof(N, i), wxp, sizeof(wxp));
      }
    }
    for (int j = 0; j < N; ++j) {
      const double *p0 = x + vdof(N, j), *p1 = x + vdof(N, (j + 1) % N);
      double t[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
      rn_test_normalize3(t);
      if (m >= 3 && m < 6) v[tdof(j)] = t[m - 3];
      if (m == 6) v[tdof(j)] = 1.0;
    }
    { /* H v = 0 (the mode is exact) */
      double hv = 0.0;
      for (int a = 0; a < n; ++a) {
        double s = 0.0;
        for (int b = 0; b < n; ++b) s += H[a + (size_t)n * b] * v[b];
        hv = fmax(hv, fabs(s));
      }
      nnz_ok = hv <= 1e-9 * hmax;
      CHECK(nnz_ok);
    }
    for (int l = 0; l < m; ++l) { /* Gram-Schmidt */
      double d = 0.0, *u = V + (size_t)l * n;
      for (int k = 0; k < n; ++k) d += u[k] * v[k];
      for (int k = 0; k < n; ++k) v[k] -= d * u[k];
    }
    {
      double nv = 0.0;
      for (int k = 0; k < n; ++k) nv += v[k] * v[k];
      nv = sqrt(nv);
      for (int k = 0; k < n; ++k) v[k] /= nv;
    }
  }
  for (int m = 0; m < 7; ++m) /* H + s V V^T: the zero modes move to s */
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        H[a + (size_t)n * b] += hmax * V[(size_t)m * n + a] * V[(size_t)m * n + b];
  {
    int info = 0, lwork = 8 * n;
    double *w = calloc((size_t)n, sizeof(double)),
           *work = calloc((size_t)lwork, sizeof(double));
    dsyev_("N", "L", &n, H, &n, w, work, &lwork, &info, 1, 1);
    CHECK(info == 0);
    E = w[0];
    free(w);
    free(work);
  }
  rn_network_destroy(&net);
  free(xyz);
  free(x);
  free(g);
  free(H);
  free(V);
  return E;
}

static void test_michell(rn_context *ctx) {
  const int link = 2, Ns[3] = {32, 64, 128};
  const double exact = sqrt(3.0) / link; /* critical C/B = 1/(1+nu) for a circle */
  double err[3], h[3];
  for (int t = 0; t < 3; ++t) {
    double lo = 0.0, hi = 0.4, gmax = 0.0, l_lo, l_hi;
    l_lo = michell_lowest(ctx, Ns[t], lo, link, &gmax); /* C/B = 1: unstable */
    CHECK(gmax <= 1e-9);
    l_hi = michell_lowest(ctx, Ns[t], hi, link, &gmax); /* C/B = 0.714: stable */
    CHECK(l_lo < 0.0 && l_hi > 0.0);
    for (int it = 0; it < 40; ++it) {
      double mid = 0.5 * (lo + hi);
      if (michell_lowest(ctx, Ns[t], mid, link, &gmax) < 0.0)
        lo = mid;
      else
        hi = mid;
    }
    err[t] = fabs(1.0 / (1.0 + 0.5 * (lo + hi)) - exact) / exact;
    h[t] = 1.0 / Ns[t];
    printf(
        "Michell ring, link %d, %d edges: critical C/B %.10f (exact sqrt(3)/%d = %.10f), "
        "rel. error %.3e\n",
        link, Ns[t], 1.0 / (1.0 + 0.5 * (lo + hi)), link, exact, err[t]);
  }
  { /* pre-asymptotic at 32 edges (orders 1.40, then 1.88 measured) */
    double order = log(err[1] / err[2]) / log(h[1] / h[2]);
    printf("Michell: order %.2f between %d and %d edges\n", order, Ns[1], Ns[2]);
    CHECK(err[0] > err[1] && err[1] > err[2]);
    CHECK(err[2] < 3e-4);
    CHECK(order > 1.7 && order < 2.3);
  }
}

/* VALIDATION.md 7.4: an anisotropic ribbon (B11 = B22 / 100, soft d1) with rest
 * curvature about its stiff axis closed into a planar ring tilted uniformly by
 * psi (theta = psi on every edge):
 * E(psi) = N / (2 vlen) [B11 k^2 sin^2 psi + B22 (k cos psi - kbar)^2] with the
 * integrated k = 2 tan(pi / N), discrete-exact; flat (psi = 0) and conical
 * (cos psi* = B22 kbar / ((B22 - B11) k)) rings are equilibria. */
static void test_ribbon(rn_context *ctx) {
  enum { N = 48 };
  const double ratio[3] = {1.02, 1.5, 2.0}, psi_ref[3] = {7.9889, 47.6699, 59.6653};
  const double e_ref[3] = {0.015149 / 0.020000, 0.61995 / 12.5, 1.49495 / 50.0};
  for (int t = 0; t < 3; ++t) {
    int joint = -1, rod = -1;
    double *xyz = polygon(N, 1.0, 1.0, 0.0), kap[2 * N], x[4 * N], g[4 * N];
    const double d1[3] = {0, 0, 1}, k = 2.0 * tan(PI / N), kbar = k / ratio[t];
    const double vlen = 2.0 * sin(PI / N), B22 = 1.0, B11 = 0.01;
    double psi = acos(B22 * kbar / ((B22 - B11) * k)), E0, Ep, gmax = 0.0, gs = 0.0;
    rn_network *net = NULL;
    rn_material m;
    rn_section sec = {1e-2, B11, B22, 0.0, 1.0};
    CHECK_STATUS(rn_material_from_E_nu(1.0, 0.3, 0.0, &m), RN_OK);
    CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
    CHECK_STATUS(rn_network_add_closed_rod(net, "ribbon", N, xyz, d1, &rod, &joint),
                 RN_OK);
    CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
    CHECK_STATUS(rn_network_set_section(net, rod, -1, &sec), RN_OK);
    for (int i = 0; i < N; ++i) { /* kappa2 = -kb . d1: the ring's is -k */
      kap[2 * i] = 0.0;
      kap[2 * i + 1] = -kbar;
    }
    CHECK_STATUS(rn_network_set_rest_curvature(net, rod, kap + 2), RN_OK);
    CHECK_STATUS(rn_network_set_joint_rest_strains(net, joint, kap, 0.0), RN_OK);
    CHECK_STATUS(rn_network_finalize(net), RN_OK);
    CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
    CHECK_STATUS(rn_network_energy(net, x, &E0), RN_OK);
    for (int j = 0; j < N; ++j) x[tdof(j)] = psi;
    CHECK_STATUS(rn_network_gradient(net, x, &Ep, g), RN_OK);
    for (int q = 0; q < 4 * N; ++q) gmax = fmax(gmax, fabs(g[q]));
    for (int j = 0; j < N; ++j) gs += g[tdof(j)];
    printf("ribbon ring k/kbar %.2f: psi* %.4f deg (VALIDATION %.4f), E(0) %.10e (closed "
           "form %.10e), E(psi*) %.10e (%.10e), |g| %.2e\n",
           ratio[t], psi * 180.0 / PI, psi_ref[t], E0,
           0.5 * N / vlen * B22 * (k - kbar) * (k - kbar), Ep,
           0.5 * N / vlen *
               (B11 * k * k * sin(psi) * sin(psi) +
                B22 * (k * cos(psi) - kbar) * (k * cos(psi) - kbar)),
           gmax);
    CHECK_NEAR(psi * 180.0 / PI, psi_ref[t], 1e-4);
    CHECK_REL(E0, 0.5 * N / vlen * B22 * (k - kbar) * (k - kbar), 1e-12);
    CHECK_REL(Ep,
              0.5 * N / vlen *
                  (B11 * k * k * sin(psi) * sin(psi) +
                   B22 * (k * cos(psi) - kbar) * (k * cos(psi) - kbar)),
              1e-12);
    CHECK(Ep < E0);
    /* the conical ring is an equilibrium (forces of order B22 k / vlen = 1) */
    CHECK(gmax <= 1e-11 * B22 * k / vlen);
    CHECK_REL(Ep / E0, e_ref[t], 2e-4); /* VALIDATION.md's energies, 5 digits */
    CHECK(fabs(gs) <= 1e-12 * E0);
    rn_network_destroy(&net);
    free(xyz);
  }
}

int main(void) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  test_derivatives(ctx);
  test_rest_circle(ctx);
  test_two_rods(ctx);
  test_link(ctx);
  test_michell(ctx);
  test_ribbon(ctx);
  rn_context_destroy(&ctx);
  return rn_test_finish("api_rings");
}

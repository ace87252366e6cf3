/* hard_cases.c - the hard-case suite of issue 10 section 6 (ctest label `hard`,
 * docs/hard-cases.md).  `hard_cases CASE` runs one case; every solve must end
 * converged at a verified local minimum (rn_solve_report.stability) with finite
 * DOFs, and its result is checked against a closed form or an accurately
 * integrated elastica:
 *  folded     a clamped rod with a straight rest shape started as a Z with turning
 *             angles of 170, 179 and 179.9 degrees unfolds to the straight line;
 *  ratio      cantilevers with E A L^2 / (E I) = 1e2 ... 1e8 under the tip load
 *             P = E I / L^2: the tip deflection against the elastica;
 *  saddle     a perfectly straight clamped-free column at 1.3 x its Euler load:
 *             tr-minres and tr-krylov leave the saddle, and the buckled energy
 *             converges to the elastica's at second order in the edge length;
 *  scale      the cantilever at lengths 1e-6 and 1e6 (tiny and huge edges) gives
 *             the same shape; a graded rod with one edge 1e-6 of the others too;
 *  rest       straight rods with rest curvatures of arcs of 270 and 342 degrees
 *             relax to their rest polygons (zero energy). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "rodnet_solve.h"
#include "testutil.h"

#define PI 3.14159265358979323846

/* ---- building rods ------------------------------------------------------- */

typedef struct rod_spec {
  int nv;
  const double *xyz;   /* initial vertices */
  double E;            /* Young's modulus (nu = 0.3) */
  rn_section section;  /* section of every edge */
  double d1[3];        /* material axis of the first edge */
  double tip_force[3]; /* force on the last vertex */
  const double *kappa; /* rest curvature (2 (nv - 2)) or NULL: initial shape */
  const double *len;   /* rest lengths (nv - 1) or NULL: initial shape */
} rod_spec;

/* A rod clamped at its start. */
static rn_network *make_rod(rn_context *ctx, const rod_spec *r) {
  rn_network *net = NULL;
  rn_material m;
  int rod = -1;
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_material_from_E_nu(r->E, 0.3, 0.0, &m), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "rod", r->nv, r->xyz, r->d1, &rod), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &r->section), RN_OK);
  if (r->kappa) CHECK_STATUS(rn_network_set_rest_curvature(net, rod, r->kappa), RN_OK);
  if (r->len) CHECK_STATUS(rn_network_set_rest_lengths(net, rod, r->len), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, rod, RN_START), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, rod, -1, r->tip_force), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  return net;
}

/* Solve with the solver kind; assert a converged, verified local minimum with
 * finite DOFs; the last vertex in tip[3]. */
static rn_solve_report solve_verified(rn_network *net, rn_solver_kind kind,
                                      const char *label, double tip[3]) {
  rn_solve_options opt;
  rn_solve_report rep;
  rn_solve_options_default(&opt);
  opt.solver = kind;
  const rn_status st = rn_solve(net, &opt, &rep);
  if (st != RN_OK)
    printf("  %s: %s: %s\n", label, rn_status_name(st),
           rn_context_last_error(rn_network_context(net)));
  CHECK_STATUS(st, RN_OK);
  const size_t n = rn_network_num_dofs(net);
  double *x = calloc(n, sizeof(double));
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  int finite = 1;
  for (size_t i = 0; i < n; ++i) finite = finite && isfinite(x[i]);
  const int nv = rn_network_rod_num_vertices(net, 0);
  double *v = calloc((size_t)(3 * nv), sizeof(double));
  CHECK_STATUS(rn_network_rod_vertices(net, 0, v), RN_OK);
  memcpy(tip, v + 3 * (nv - 1), 3 * sizeof(double));
  printf("  %-28s %-9s stop %-8s its %4d, E %+.10e, lowest eigenvalue %+.3e (scale "
         "%.2e, %.1e relative), zero modes %d, verified %d\n",
         label, rn_solver_name(kind), rn_solve_stop_name(rep.stop), rep.iterations,
         rep.energy, rep.stability.lowest_eigenvalue, rep.stability.scale,
         rep.stability.lowest_eigenvalue / rep.stability.scale, rep.stability.zero_modes,
         rep.stability.verified_minimum);
  CHECK(finite);
  CHECK(isfinite(rep.energy));
  CHECK(rep.converged == 1);
  CHECK(rep.stability.checked == 1);
  CHECK(rep.stability.verified_minimum == 1);
  free(x);
  free(v);
  return rep;
}

/* Solve; either a converged, verified local minimum (returns 1) or a clear stop
 * (returns 0): an error status with a message (only if allow_error), or a reported
 * non-converged stop, with finite DOFs either way. */
static int solve_or_clear_stop(rn_network *net, rn_solver_kind kind, const char *label,
                               int allow_error) {
  rn_solve_options opt;
  rn_solve_report rep;
  rn_solve_options_default(&opt);
  opt.solver = kind;
  const rn_status st = rn_solve(net, &opt, &rep);
  const size_t n = rn_network_num_dofs(net);
  double *x = calloc(n, sizeof(double));
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  int finite = 1;
  for (size_t i = 0; i < n; ++i) finite = finite && isfinite(x[i]);
  free(x);
  CHECK(finite);
  if (st != RN_OK) {
    const char *msg = rn_context_last_error(rn_network_context(net));
    printf("  %-28s %-9s stopped: %s: %s\n", label, rn_solver_name(kind),
           rn_status_name(st), msg);
    CHECK(msg && strlen(msg) > 10);
    CHECK(rep.converged == 0 && rep.stop == RN_STOP_FAILED);
    CHECK(allow_error);
    return 0;
  }
  printf("  %-28s %-9s stop %-8s its %4d, converged %d, verified %d\n", label,
         rn_solver_name(kind), rn_solve_stop_name(rep.stop), rep.iterations,
         rep.converged, rep.stability.verified_minimum);
  if (!rep.converged) {
    CHECK(rep.stop == RN_STOP_MAX_ITER || rep.stop == RN_STOP_RADIUS);
    CHECK(rep.stability.verified_minimum == 0);
    return 0;
  }
  CHECK(rep.stability.verified_minimum == 1);
  return 1;
}

/* ---- elastica references (RK4, 20000 steps: error far below the tests') ---- */

/* y = (phi, phi', int phi'^2 / 2, int cos phi, int sin phi) over s in [0, L], with
 * phi'' = -a cos(phi) (cantilever, phi below the horizontal, tip force) or
 * phi'' = -a sin(phi) (column, phi from the vertical, dead axial load). */
static void elastica_rhs(int column, double a, const double *y, double *dy) {
  dy[0] = y[1];
  dy[1] = column ? -a * sin(y[0]) : -a * cos(y[0]);
  dy[2] = 0.5 * y[1] * y[1];
  dy[3] = cos(y[0]);
  dy[4] = sin(y[0]);
}

static void elastica_shoot(int column, double a, double L, double m, double *y) {
  enum { STEPS = 20000 };
  const double h = L / STEPS;
  double k1[5], k2[5], k3[5], k4[5], t[5];
  y[0] = 0.0;
  y[1] = m;
  y[2] = y[3] = y[4] = 0.0;
  for (int s = 0; s < STEPS; ++s) {
    elastica_rhs(column, a, y, k1);
    for (int i = 0; i < 5; ++i) t[i] = y[i] + 0.5 * h * k1[i];
    elastica_rhs(column, a, t, k2);
    for (int i = 0; i < 5; ++i) t[i] = y[i] + 0.5 * h * k2[i];
    elastica_rhs(column, a, t, k3);
    for (int i = 0; i < 5; ++i) t[i] = y[i] + h * k3[i];
    elastica_rhs(column, a, t, k4);
    for (int i = 0; i < 5; ++i)
      y[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
  }
}

/* The clamped-free elastica with phi'(L) = 0: bisection on phi'(0) in [lo, hi]
 * (phi'(L) changes sign there); y as elastica_shoot at the root. */
static void elastica_solve(int column, double a, double L, double lo, double hi,
                           double *y) {
  double ylo[5];
  elastica_shoot(column, a, L, lo, ylo);
  const double flo = ylo[1];
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    elastica_shoot(column, a, L, mid, y);
    if ((y[1] < 0.0) == (flo < 0.0))
      lo = mid;
    else
      hi = mid;
  }
  elastica_shoot(column, a, L, 0.5 * (lo + hi), y);
}

/* ---- cases --------------------------------------------------------------- */

/* Straight rod along x (nv vertices, length L) for a cantilever. */
static double *line_x(int nv, double L) {
  double *xyz = calloc((size_t)(3 * nv), sizeof(double));
  for (int i = 0; i < nv; ++i) xyz[3 * i] = L * i / (nv - 1);
  return xyz;
}

/* Rest lengths and zero rest curvature: a straight rest shape of edge h. */
static void straight_rest(int nv, double h, double *len, double *kappa) {
  for (int e = 0; e < nv - 1; ++e) len[e] = h;
  for (int k = 0; k < 2 * (nv - 2); ++k) kappa[k] = 0.0;
}

static void case_folded(rn_context *ctx) {
  enum { NV = 13 };
  const double angles[3] = {170.0, 179.0, 179.9};
  const double h = 0.1;
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 2; ++k) {
      const rn_solver_kind kind = k ? RN_SOLVER_TR_KRYLOV : RN_SOLVER_TR_MINRES;
      /* a Z: 4 edges along x, 4 back at the turning angle, 4 forward again */
      double xyz[3 * NV], len[NV - 1], kappa[2 * (NV - 2)], dir = 0.0;
      const double turn = angles[c] * PI / 180.0;
      xyz[0] = xyz[1] = xyz[2] = 0.0;
      for (int e = 0; e < NV - 1; ++e) {
        if (e == 4) dir += turn;
        if (e == 8) dir -= turn;
        xyz[3 * (e + 1)] = xyz[3 * e] + h * cos(dir);
        xyz[3 * (e + 1) + 1] = xyz[3 * e + 1] + h * sin(dir);
        xyz[3 * (e + 1) + 2] = 0.0;
      }
      straight_rest(NV, h, len, kappa);
      rod_spec r = {.nv = NV,
                    .xyz = xyz,
                    .E = 1e7,
                    .d1 = {0.0, 0.0, 1.0},
                    .tip_force = {0.0, 0.0, 0.0},
                    .kappa = kappa,
                    .len = len};
      CHECK_STATUS(rn_section_circle(0.01, &r.section), RN_OK);
      rn_network *net = make_rod(ctx, &r);
      char label[64];
      double tip[3];
      snprintf(label, sizeof label, "folded %.1f deg", angles[c]);
      /* tr-minres at 179 degrees and beyond: no error (its shift search once gave
       * up at 10^10 with RN_ERR_LAPACK where H had outgrown the metric, a shift
       * of ~10^12 being needed: shim_shift_search), but the iteration limit: its
       * iterates slide into a fold whose turning angle tends to 180 degrees at
       * finite energy (the curvature from the averaged material frames is 0/0
       * there) and never reach the straight rod; asserted as a clear stop, a known
       * limitation (docs/hard-cases.md) */
      if (kind == RN_SOLVER_TR_MINRES && angles[c] >= 179.0) {
        if (!solve_or_clear_stop(net, kind, label, 0)) {
          /* the largest turning angle has grown past the start's: into the fold */
          double fold = 0.0;
          CHECK_STATUS(rn_network_rod_vertices(net, 0, xyz), RN_OK);
          for (int i = 1; i < NV - 1; ++i) {
            double a[3], b[3];
            for (int k3 = 0; k3 < 3; ++k3) {
              a[k3] = xyz[3 * i + k3] - xyz[3 * i - 3 + k3];
              b[k3] = xyz[3 * i + 3 + k3] - xyz[3 * i + k3];
            }
            const double cs = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) /
                              sqrt((a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) *
                                   (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]));
            fold = fmax(fold, acos(fmax(-1.0, fmin(1.0, cs))) * 180.0 / PI);
          }
          /* there the curvature has vanished and the twist is pi (a twisted fold) */
          double kap[2 * (NV - 2)], tau[NV - 2], tw = 0.0, kf = 0.0;
          CHECK_STATUS(rn_network_rod_strains(net, 0, NULL, kap, tau), RN_OK);
          for (int i = 0; i < NV - 2; ++i)
            if (fabs(tau[i]) > fabs(tw)) {
              tw = tau[i];
              kf = hypot(kap[2 * i], kap[2 * i + 1]);
            }
          printf("  %-28s %-9s at the stop: largest turning angle %.4f deg, twist %.4f "
                 "and curvature %.3f there\n",
                 label, rn_solver_name(kind), fold, tw, kf);
          CHECK(fold > angles[c] && fold < 180.0);
          CHECK(fabs(fabs(tw) - PI) < 0.01 && kf < 0.1);
          rn_network_destroy(&net);
          continue;
        }
        CHECK_STATUS(rn_network_rod_vertices(net, 0, xyz), RN_OK);
        memcpy(tip, xyz + 3 * (NV - 1), sizeof tip);
      } else {
        solve_verified(net, kind, label, tip);
      }
      /* the straight rod of length (NV - 1) h along x, unstressed */
      CHECK_NEAR(tip[0], (NV - 1) * h, 1e-9);
      CHECK_NEAR(tip[1], 0.0, 1e-9);
      CHECK_NEAR(tip[2], 0.0, 1e-9);
      rn_network_destroy(&net);
    }
}

/* Cantilever along x, nv vertices from 0 to L: with its first edge clamped, the
 * continuum clamp sits at the edge's midpoint (VALIDATION.md), so its length is
 * Le = L - h / 2.  Square section of side b with E A Le^2 / (E I) = 12 Le^2 / b^2 =
 * ratio, tip load P = alpha E I / Le^2 along -z; returns the tip deflection / Le. */
static double cantilever_deflection(rn_context *ctx, int nv, double L, double ratio,
                                    double alpha, rn_solver_kind kind,
                                    const char *label) {
  const double Le = L * (1.0 - 0.5 / (nv - 1)), b = Le * sqrt(12.0 / ratio), E = 1e7;
  double *xyz = line_x(nv, L), tip[3];
  rod_spec r = {.nv = nv,
                .xyz = xyz,
                .E = E,
                .d1 = {0.0, 1.0, 0.0},
                .tip_force = {0.0, 0.0, 0.0},
                .kappa = NULL,
                .len = NULL};
  CHECK_STATUS(rn_section_rectangle(b, b, &r.section), RN_OK);
  r.tip_force[2] = -alpha * E * r.section.I11 / (Le * Le);
  rn_network *net = make_rod(ctx, &r);
  solve_verified(net, kind, label, tip);
  rn_network_destroy(&net);
  free(xyz);
  return -tip[2] / Le;
}

static void case_ratio(rn_context *ctx) {
  double y[5];
  elastica_solve(0, 1.0, 1.0, 0.0, 1.0, y); /* alpha = P L^2 / E I = 1 */
  const double ref = y[4];
  printf("  elastica (P L^2 / E I = 1): tip deflection / L = %.10f\n", ref);
  const double ratios[4] = {1e2, 1e4, 1e6, 1e8};
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 2; ++k) {
      const rn_solver_kind kind = k ? RN_SOLVER_TR_KRYLOV : RN_SOLVER_TR_MINRES;
      char label[64];
      snprintf(label, sizeof label, "E A L^2 / E I = %.0e", ratios[c]);
      const double d = cantilever_deflection(ctx, 41, 1.0, ratios[c], 1.0, kind, label);
      printf("    tip deflection / L = %.10f, relative to the elastica %+.3e\n", d,
             d / ref - 1.0);
      /* discretisation (40 edges, O(h^2)): 1e-3; stretching adds about
       * P / (E A) = 1 / ratio */
      CHECK(fabs(d / ref - 1.0) <= 1e-3 + 2.0 / ratios[c]);
    }
}

/* Clamped-free column along z, nv vertices from 0 to 1 (continuum length Le = 1 -
 * h / 2 from the mid-edge clamp), rectangle 0.02 x 0.01, E = 1e7, dead load 1.3 x
 * the Euler load pi^2 E I / (4 Le^2) on its tip; the buckled energy minus the
 * straight unloaded one. */
static double column_energy(rn_context *ctx, int nv, rn_solver_kind kind, double *P) {
  const double Le = 1.0 - 0.5 / (nv - 1);
  double *xyz = calloc((size_t)(3 * nv), sizeof(double)), tip[3];
  for (int i = 0; i < nv; ++i) xyz[3 * i + 2] = (double)i / (nv - 1);
  rod_spec r = {.nv = nv,
                .xyz = xyz,
                .E = 1e7,
                .d1 = {0.0, 1.0, 0.0},
                .tip_force = {0.0, 0.0, 0.0},
                .kappa = NULL,
                .len = NULL};
  CHECK_STATUS(rn_section_rectangle(0.02, 0.01, &r.section), RN_OK);
  const double EI = 1e7 * fmin(r.section.I11, r.section.I22);
  *P = 1.3 * PI * PI * EI / (4.0 * Le * Le);
  r.tip_force[2] = -*P;
  rn_network *net = make_rod(ctx, &r);
  const size_t n = rn_network_num_dofs(net);
  double *x0 = calloc(n, sizeof(double)), E0 = 0.0;
  CHECK_STATUS(rn_network_get_dofs(net, x0), RN_OK);
  CHECK_STATUS(rn_network_energy(net, x0, &E0), RN_OK);
  char label[64];
  snprintf(label, sizeof label, "column, %d edges", nv - 1);
  const rn_solve_report rep = solve_verified(net, kind, label, tip);
  CHECK(fabs(tip[0]) + fabs(tip[1]) > 0.1); /* left the straight branch */
  rn_network_destroy(&net);
  free(x0);
  free(xyz);
  return rep.energy - E0;
}

static void case_saddle(rn_context *ctx) {
  for (int k = 0; k < 2; ++k) {
    const rn_solver_kind kind = k ? RN_SOLVER_TR_KRYLOV : RN_SOLVER_TR_MINRES;
    double P = 0.0, err[2];
    for (int c = 0; c < 2; ++c) {
      const int nv = c ? 41 : 21;
      const double dE = column_energy(ctx, nv, kind, &P), Le = 1.0 - 0.5 / (nv - 1);
      rn_section s;
      CHECK_STATUS(rn_section_rectangle(0.02, 0.01, &s), RN_OK);
      const double EI = 1e7 * fmin(s.I11, s.I22), lambda2 = P / EI;
      double y[5];
      elastica_solve(1, lambda2, Le, 1e-6, 2.0 * sqrt(lambda2) * (1.0 - 1e-12), y);
      const double U = EI * y[2] - P * (Le - y[3]);
      err[c] = dE / U - 1.0;
      printf("    energy %.10e, elastica %.10e (tip angle %.4f rad), relative error "
             "%+.3e\n",
             dE, U, y[0], err[c]);
    }
    const double order = log(fabs(err[0] / err[1])) / log(2.0);
    printf("    observed order %.3f\n", order);
    CHECK(fabs(err[1]) <= 5e-3);
    CHECK(order > 1.7 && order < 2.3);
  }
}

static void case_scale(rn_context *ctx) {
  const double ref = cantilever_deflection(ctx, 21, 1.0, 1e4, 1.0, RN_SOLVER_TR_MINRES,
                                           "cantilever L = 1");
  const double scales[2] = {1e-6, 1e6};
  for (int c = 0; c < 2; ++c) {
    char label[64];
    snprintf(label, sizeof label, "cantilever L = %.0e", scales[c]);
    const double d =
        cantilever_deflection(ctx, 21, scales[c], 1e4, 1.0, RN_SOLVER_TR_MINRES, label);
    printf("    tip deflection / L = %.12f (L = 1: %.12f)\n", d, ref);
    CHECK_NEAR(d, ref, 1e-8);
  }
  /* a graded rod: 20 edges of 0.05 and one of 5e-8 inserted after the tenth */
  enum { NV = 22 };
  double xyz[3 * NV], tip[3], y[5];
  for (int i = 0; i < NV; ++i) {
    xyz[3 * i] = i <= 10 ? 0.05 * i : 0.05 * (i - 1) + 5e-8;
    xyz[3 * i + 1] = xyz[3 * i + 2] = 0.0;
  }
  const double b = sqrt(12.0 / 1e4);
  rod_spec r = {.nv = NV,
                .xyz = xyz,
                .E = 1e7,
                .d1 = {0.0, 1.0, 0.0},
                .tip_force = {0.0, 0.0, 0.0},
                .kappa = NULL,
                .len = NULL};
  CHECK_STATUS(rn_section_rectangle(b, b, &r.section), RN_OK);
  const double L = xyz[3 * (NV - 1)] - 0.025; /* from the mid-edge clamp */
  r.tip_force[2] = -1e7 * r.section.I11 / (L * L);
  rn_network *net = make_rod(ctx, &r);
  solve_verified(net, RN_SOLVER_TR_MINRES, "graded, one edge 1e-6 h", tip);
  elastica_solve(0, 1.0, 1.0, 0.0, 1.0, y);
  printf("    tip deflection / L = %.10f, elastica %.10f\n", -tip[2] / L, y[4]);
  /* 20 regular edges: the discretisation error of the uniform rod (2e-3) */
  CHECK(fabs(-tip[2] / L / y[4] - 1.0) <= 3e-3);
  rn_network_destroy(&net);
}

static void case_rest(rn_context *ctx) {
  enum { NV = 41 };
  const double arcs[2] = {270.0, 342.0};
  for (int c = 0; c < 2; ++c)
    for (int k = 0; k < 2; ++k) {
      const rn_solver_kind kind = k ? RN_SOLVER_TR_KRYLOV : RN_SOLVER_TR_MINRES;
      const double h = 1.0 / (NV - 1), phi = arcs[c] * PI / 180.0 / (NV - 2);
      double *xyz = line_x(NV, 1.0), kappa[2 * (NV - 2)], tip[3], ex = 0.0, ey = 0.0;
      for (int v = 0; v < NV - 2; ++v) {
        kappa[2 * v] = 2.0 * tan(0.5 * phi);
        kappa[2 * v + 1] = 0.0;
      }
      rod_spec r = {.nv = NV,
                    .xyz = xyz,
                    .E = 1e7,
                    .d1 = {0.0, 1.0, 0.0},
                    .tip_force = {0.0, 0.0, 0.0},
                    .kappa = kappa,
                    .len = NULL};
      CHECK_STATUS(rn_section_circle(0.01, &r.section), RN_OK);
      rn_network *net = make_rod(ctx, &r);
      char label[64];
      snprintf(label, sizeof label, "rest arc %.0f deg", arcs[c]);
      const rn_solve_report rep = solve_verified(net, kind, label, tip);
      /* the rest polygon: edge e along the angle e phi */
      for (int e = 0; e < NV - 1; ++e) {
        ex += h * cos(e * phi);
        ey += h * sin(e * phi);
      }
      printf("    tip (%.10f, %.10f, %.1e), rest polygon (%.10f, %.10f)\n", tip[0],
             tip[1], tip[2], ex, ey);
      CHECK_NEAR(tip[0], ex, 1e-8);
      CHECK_NEAR(fabs(tip[1]), ey, 1e-8);
      CHECK_NEAR(tip[2], 0.0, 1e-8);
      CHECK(fabs(rep.energy) <= 1e-12);
      rn_network_destroy(&net);
      free(xyz);
    }
}

int main(int argc, char **argv) {
  static const struct {
    const char *name;
    void (*run)(rn_context *);
  } cases[] = {{"folded", case_folded},
               {"ratio", case_ratio},
               {"saddle", case_saddle},
               {"scale", case_scale},
               {"rest", case_rest}};
  if (argc != 2) {
    fprintf(stderr, "usage: hard_cases folded|ratio|saddle|scale|rest\n");
    return 2;
  }
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_runtime_initialize(NULL, NULL), RN_OK);
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  int found = 0;
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i)
    if (strcmp(argv[1], cases[i].name) == 0) {
      printf("hard case %s:\n", cases[i].name);
      cases[i].run(ctx);
      found = 1;
    }
  CHECK(found);
  rn_context_destroy(&ctx);
  rn_runtime_finalize();
  return rn_test_finish(argv[1]);
}

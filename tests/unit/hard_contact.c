/* hard_contact.c - contact hard cases (issue 10 sections 5 and 6, docs/contact.md),
 * one ctest per case:
 *   crossed     two crossed rods pressed together: a rigid rod a (every vertex
 *               pinned) under a rod b loaded by F across the crossing; at the
 *               solution the barrier force equals F and the gap solves
 *               -b'(g) = F (one active pair), no interpenetration, a verified
 *               minimum;
 *   plectoneme  a clamped-clamped rod (L = 100, B = 1.345, C = 0.789, radius
 *               0.35, 100 edges: the Gazzola / PyElastica set-up of VALIDATION.md
 *               5.2) with slack D = 3, twisted by 40 turns (past the 27 of the
 *               localised helix) in 100 load steps (0.4 turn each), until it
 *               winds onto itself (first contact near 23 turns): every step
 *               converges, no accepted state interpenetrates (min gap > 0), the
 *               final state is in self contact and a verified minimum;
 *   lattice     a 2 x 2 honeycomb (tests/data/contact/honeycomb_dense.json, the
 *               path given as argv[2]) compressed by 70 % between gripped faces
 *               until its cell walls touch, one rn_solve (automatic load
 *               steps): converged, no accepted iterate on the way
 *               interpenetrates (min gap > 0 at every Newton iteration), pairs in
 *               contact at the end, a verified minimum;
 *   knot        a tight trefoil: a naturally straight closed rod (length 10,
 *               150 vertices) tied in a trefoil and let go, bending pulling it
 *               tight against its own contact (contact radius 1/6 and 1/8,
 *               rope length over diameter 30 and 40): converged, no accepted
 *               iterate interpenetrates, still knotted (total turning angle
 *               above 4 pi, Fary-Milnor), bending energy above the bound
 *               B (sum of turning angles)^2 / (2 L) >= 8 pi^2 B / L of
 *               Fary-Milnor and Cauchy-Schwarz and falling towards it as the
 *               rod gets thinner (the elastic trefoil tends to the doubly
 *               covered circle, Gerlach, Reiter and von der Mosel 2017), a
 *               verified minimum. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet.h"
#include "rodnet_contact.h"
#include "rodnet_scene.h"
#include "rodnet_solve.h"
#include "testutil.h"

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* -b'(g) of the barrier -k (g - h)^2 log(g / h): the repulsive force. */
static double barrier_force(double g, double h, double k) {
  return k * (2.0 * (g - h) * log(g / h) + (g - h) * (g - h) / g);
}

static void crossed(rn_context *ctx) {
  enum { NV = 9 };
  const double r = 0.02, dhat = 0.05, kappa = 5.0, F = 0.4;
  double xa[3 * NV], xb[3 * NV], f[3] = {0.0, 0.0, -0.5 * F};
  rn_material m = {1.0e6, 4.0e5, 0.0};
  rn_section s;
  rn_network *net = NULL;
  int rod;
  for (int i = 0; i < NV; ++i) {
    xa[3 * i] = -1.0 + 0.25 * i;
    xa[3 * i + 1] = xa[3 * i + 2] = 0.0;
    xb[3 * i] = 0.125;                 /* over the middle of a's edge 4 */
    xb[3 * i + 1] = -0.875 + 0.25 * i; /* b's edge 3 over the crossing */
    xb[3 * i + 2] = 2 * r + 0.9 * dhat;
  }
  CHECK_STATUS(rn_section_circle(r, &s), RN_OK);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "a", NV, xa, NULL, &rod), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "b", NV, xb, NULL, &rod), RN_OK);
  for (int k = 0; k < 2; ++k) {
    CHECK_STATUS(rn_network_set_material(net, k, -1, &m), RN_OK);
    CHECK_STATUS(rn_network_set_section(net, k, -1, &s), RN_OK);
  }
  CHECK_STATUS(rn_network_clamp(net, 0, RN_START), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, 0, RN_END), RN_OK);
  for (int i = 0; i < NV; ++i) CHECK_STATUS(rn_network_pin(net, 0, i), RN_OK);
  CHECK_STATUS(rn_network_pin_components(net, 1, 0, RN_FIX_X | RN_FIX_Y), RN_OK);
  CHECK_STATUS(rn_network_pin_components(net, 1, NV - 1, RN_FIX_X | RN_FIX_Y), RN_OK);
  CHECK_STATUS(rn_network_fix_theta(net, 1, 0), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, 1, 3, f), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, 1, 4, f), RN_OK);
  CHECK_STATUS(rn_network_set_contact(net, dhat, kappa, r), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);

  rn_solve_options opt;
  rn_solve_report rep;
  rn_solve_options_default(&opt);
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  size_t n = rn_network_num_dofs(net);
  double *x = malloc(n * sizeof(double));
  rn_contact_stats cs;
  CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
  CHECK_STATUS(rn_network_contact_stats(net, x, &cs), RN_OK);
  /* the closed form: the gap where the barrier force is F (bisection) */
  double lo = 1e-12, hi = dhat;
  for (int it = 0; it < 200; ++it) {
    double mid = 0.5 * (lo + hi);
    if (barrier_force(mid, dhat, kappa) > F)
      lo = mid;
    else
      hi = mid;
  }
  printf("  crossed: stop %s, %d its, verified %d, gap %.12g (closed form %.12g), "
         "contact force %.12g (load %.3g), active pairs %zu\n",
         rn_solve_stop_name(rep.stop), rep.iterations, rep.stability.verified_minimum,
         cs.min_gap, 0.5 * (lo + hi), cs.force, F, cs.active);
  CHECK(rep.converged == 1);
  CHECK(rep.stability.checked == 1 && rep.stability.verified_minimum == 1);
  CHECK(cs.active == 1);
  CHECK(cs.min_gap > 0.0);
  CHECK_REL(cs.min_gap, 0.5 * (lo + hi), 1e-6);
  CHECK_REL(cs.force, F, 1e-6);
  free(x);
  rn_network_destroy(&net);
}

/* The plectoneme: turns full turns of the end clamp with slack D, in nsteps
 * load steps (the load factor raised by 1 / nsteps, rn_solve from the last
 * state: a rotation below pi per step); a transverse force of 1e-4 T at the
 * middle breaks the symmetry of the straight rod. */
static void plectoneme(rn_context *ctx, int dd) {
  enum { NV = 101 };
  const double L = 100.0, B = 1.345, C = 0.789, D = 3.0, r = 0.35, turns = 40.0;
  const int nsteps = 100;
  const double I = M_PI * r * r * r * r / 4.0;
  double xyz[3 * NV], disp[3] = {-D, 0.0, 0.0}, rot[3] = {2.0 * M_PI * turns, 0.0, 0.0};
  double f[3] = {0.0, 4e-5, 0.0};
  rn_material m = {B / I, C / (2.0 * I), 0.0};
  rn_section s;
  rn_network *net = NULL;
  int rod;
  for (int i = 0; i < NV; ++i) {
    xyz[3 * i] = L * i / (NV - 1);
    xyz[3 * i + 1] = xyz[3 * i + 2] = 0.0;
  }
  CHECK_STATUS(rn_section_circle(r, &s), RN_OK);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "rod", NV, xyz, NULL, &rod), RN_OK);
  CHECK_STATUS(rn_network_set_material(net, 0, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, 0, -1, &s), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, 0, RN_START), RN_OK);
  CHECK_STATUS(rn_network_clamp(net, 0, RN_END), RN_OK);
  CHECK_STATUS(rn_network_displace_end(net, 0, RN_END, disp, rot), RN_OK);
  CHECK_STATUS(rn_network_add_force(net, 0, NV / 2, f), RN_OK);
  CHECK_STATUS(rn_network_set_contact(net, 0.1, 1.0, r), RN_OK);
  CHECK_STATUS(rn_network_set_load_factor(net, 0.0), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  size_t n = rn_network_num_dofs(net);
  double *x = malloc(n * sizeof(double)), min_gap = INFINITY;
  rn_contact_stats cs = {INFINITY, 0, 0.0, 0.0};
  rn_solve_report rep;
  int k = 1, first_contact = 0;
  for (; k <= nsteps; ++k) {
    rn_solve_options opt;
    rn_solve_options_default(&opt);
    if (dd) opt.solver = RN_SOLVER_TR_KRYLOV, opt.preconditioner = RN_PRECOND_DD;
    opt.stability = k == nsteps;
    CHECK_STATUS(rn_network_set_load_factor(net, (double)k / nsteps), RN_OK);
    rn_status st = rn_solve(net, &opt, &rep);
    CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
    CHECK_STATUS(rn_network_contact_stats(net, x, &cs), RN_OK);
    if (cs.min_gap < min_gap) min_gap = cs.min_gap;
    if (cs.active && !first_contact) first_contact = k;
    if (getenv("RN_VERBOSE") || k == nsteps || st || !rep.converged)
      printf("  plectoneme step %3d (%.2f turns): %s %s, %d its, energy %.9g, min gap "
             "%.4g, active pairs %zu, contact force %.4g\n",
             k, turns * k / nsteps, st ? "error" : rn_solve_stop_name(rep.stop),
             rep.converged ? "converged" : "NOT converged", rep.iterations, rep.energy,
             cs.min_gap, cs.active, cs.force);
    CHECK(st == RN_OK && isfinite(rep.energy));
    if (st || !rep.converged) break;
  }
  printf("  plectoneme: first contact at step %d; smallest gap over the path %.4g; "
         "final: verified %d, lowest eigenvalue %.3g (scale %.3g)\n",
         first_contact, min_gap, rep.stability.verified_minimum,
         rep.stability.lowest_eigenvalue, rep.stability.scale);
  CHECK(min_gap > 0.0);     /* no accepted state interpenetrates */
  CHECK(first_contact > 0); /* it winds onto itself */
  CHECK(k > nsteps);        /* every step converged */
  CHECK(cs.active > 0);
  CHECK(rep.stability.checked == 1 && rep.stability.verified_minimum == 1);
  free(x);
  rn_network_destroy(&net);
}

/* The contact state at every Newton iteration of a solve (its accepted state). */
typedef struct path_watch {
  rn_network *net;
  double *x;
  double min_gap;
  long iterations, in_contact; /* iterations seen, those with active pairs */
  double first_contact;        /* load factor of the first contact (-1: none) */
  int failed;
} path_watch;

static void watch_iteration(void *user, const rn_iteration_info *info) {
  path_watch *w = user;
  rn_contact_stats cs;
  if (rn_network_get_dofs(w->net, w->x) || rn_network_contact_stats(w->net, w->x, &cs)) {
    w->failed = 1;
    return;
  }
  w->iterations++;
  if (cs.min_gap < w->min_gap) w->min_gap = cs.min_gap;
  if (cs.active) {
    w->in_contact++;
    if (w->first_contact < 0.0) w->first_contact = info->load_factor;
  }
}

/* The compressed honeycomb: one rn_solve to the full compression (its
 * automatic load steps), the contact state of every accepted iterate on the
 * way (progress callback). */
static void lattice(rn_context *ctx, const char *path, int dd) {
  rn_scene *scene = NULL;
  CHECK_STATUS(rn_scene_load(ctx, path, &scene), RN_OK);
  if (!scene) return;
  rn_network *net = rn_scene_network(scene);
  size_t n = rn_network_num_dofs(net);
  path_watch w = {net, malloc(n * sizeof(double)), INFINITY, 0, 0, -1.0, 0};
  rn_contact_stats cs = {INFINITY, 0, 0.0, 0.0};
  rn_solve_options opt;
  rn_solve_report rep;
  const unsigned long v0 = rn_network_pattern_version(net);
  CHECK(rn_network_get_contact(net, NULL, NULL, NULL) == 1);
  CHECK(rn_network_load_factor(net) == 1.0);
  rn_solve_options_default(&opt);
  rn_scene_apply_solver(scene, &opt);
  if (dd) opt.solver = RN_SOLVER_TR_KRYLOV, opt.preconditioner = RN_PRECOND_DD;
  opt.progress = watch_iteration;
  opt.progress_user = &w;
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  CHECK_STATUS(rn_network_get_dofs(net, w.x), RN_OK);
  CHECK_STATUS(rn_network_contact_stats(net, w.x, &cs), RN_OK);
  printf("  lattice: %s %s, %d its, %d load steps, energy %.9g; final min gap %.4g, "
         "active pairs %zu, contact force %.4g; on the path: %ld iterates, %ld in "
         "contact (first at load factor %.3f), smallest gap %.4g, pattern rebuilds "
         "%lu; stability: verified %d, lowest eigenvalue %.3g (scale %.3g)\n",
         rn_solve_stop_name(rep.stop), rep.converged ? "converged" : "NOT converged",
         rep.iterations, rep.load_steps, rep.energy, cs.min_gap, cs.active, cs.force,
         w.iterations, w.in_contact, w.first_contact, w.min_gap,
         rn_network_pattern_version(net) - v0, rep.stability.verified_minimum,
         rep.stability.lowest_eigenvalue, rep.stability.scale);
  CHECK(!w.failed); /* (a return to a watchdog anchor is not reported again) */
  CHECK(w.iterations > rep.iterations / 2);
  CHECK(w.min_gap > 0.0); /* no accepted state interpenetrates */
  CHECK(w.in_contact > 0 && w.first_contact > 0.0); /* the cell walls touch */
  CHECK(rep.converged == 1);
  CHECK(cs.active > 0 && cs.min_gap > 0.0 && cs.min_gap < 0.01);
  CHECK(rep.stability.checked == 1 && rep.stability.verified_minimum == 1);
  free(w.x);
  rn_scene_destroy(&scene);
}

/* The tight trefoil: a closed rod of length L through nv vertices on the
 * trefoil (sin t + 2 sin 2t, cos t - 2 cos 2t, -sin 3t), naturally straight
 * and untwisted (rest curvature and twist 0, also at the closing joint), section
 * radius 1/24 (E = 1e6, G = 4e5), contact radius rc, activation distance rc / 2,
 * stiffness 1; rigid motions held by the closing joint (pinned), vertex 50 (x,
 * y) and vertex 100 (z).  One rn_solve from the loose knot; the contact state of
 * every accepted iterate (progress callback).  Returns the bending energy (NAN
 * on failure) and its lower bound B (sum of turning angles)^2 / (2 L). */
static double trefoil(rn_context *ctx, double rc, double *bound) {
  enum { NV = 150 };
  const double L = 10.0, a = 1.0 / 24.0;
  double xyz[3 * NV], len = 0.0, kappa[2 * (NV - 1)] = {0}, tau[NV - 1] = {0};
  rn_material m = {1.0e6, 4.0e5, 0.0};
  rn_section s;
  rn_network *net = NULL;
  int rod = -1, joint = -1;
  for (int i = 0; i < NV; ++i) {
    const double t = 2.0 * M_PI * i / NV;
    xyz[3 * i] = sin(t) + 2.0 * sin(2.0 * t);
    xyz[3 * i + 1] = cos(t) - 2.0 * cos(2.0 * t);
    xyz[3 * i + 2] = -sin(3.0 * t);
  }
  for (int i = 0; i < NV; ++i) {
    const double *p = &xyz[3 * i], *q = &xyz[3 * ((i + 1) % NV)];
    len += sqrt((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) +
                (q[2] - p[2]) * (q[2] - p[2]));
  }
  for (int i = 0; i < 3 * NV; ++i) xyz[i] *= L / len;
  CHECK_STATUS(rn_section_circle(a, &s), RN_OK);
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_closed_rod(net, "knot", NV, xyz, NULL, &rod, &joint),
               RN_OK);
  CHECK_STATUS(rn_network_set_material(net, rod, -1, &m), RN_OK);
  CHECK_STATUS(rn_network_set_section(net, rod, -1, &s), RN_OK);
  CHECK_STATUS(rn_network_set_rest_curvature(net, rod, kappa), RN_OK);
  CHECK_STATUS(rn_network_set_rest_twist(net, rod, tau), RN_OK);
  CHECK_STATUS(rn_network_set_joint_rest_straight(net, joint), RN_OK);
  CHECK_STATUS(rn_network_pin_joint(net, joint), RN_OK);
  CHECK_STATUS(rn_network_pin_components(net, rod, 50, RN_FIX_X | RN_FIX_Y), RN_OK);
  CHECK_STATUS(rn_network_pin_components(net, rod, 100, RN_FIX_Z), RN_OK);
  CHECK_STATUS(rn_network_set_contact(net, 0.5 * rc, 1.0, rc), RN_OK);
  CHECK_STATUS(rn_network_finalize(net), RN_OK);
  if (rn_test_failures) {
    rn_network_destroy(&net);
    return NAN;
  }
  const size_t n = rn_network_num_dofs(net);
  path_watch w = {net, malloc(n * sizeof(double)), INFINITY, 0, 0, -1.0, 0};
  double *x0 = malloc(n * sizeof(double));
  rn_contact_stats cs = {INFINITY, 0, 0.0, 0.0};
  rn_solve_options opt;
  rn_solve_report rep;
  double E[RN_TERM_COUNT] = {0}, v[3 * (NV + 1)], turning = 0.0;
  CHECK_STATUS(rn_network_get_dofs(net, x0), RN_OK);
  rn_solve_options_default(&opt);
  opt.progress = watch_iteration;
  opt.progress_user = &w;
  CHECK_STATUS(rn_solve(net, &opt, &rep), RN_OK);
  CHECK_STATUS(rn_network_get_dofs(net, w.x), RN_OK);
  CHECK_STATUS(rn_network_contact_stats(net, w.x, &cs), RN_OK);
  CHECK_STATUS(rn_network_energy_terms(net, w.x, E), RN_OK);
  CHECK_STATUS(rn_network_rod_vertices(net, rod, v), RN_OK);
  for (int i = 0; i < NV; ++i) { /* turning angle at vertex i (periodic) */
    const double *p = &v[3 * ((i + NV - 1) % NV)], *q = &v[3 * i], *r = &v[3 * (i + 1)];
    double e[3], f[3], c[3];
    for (int k = 0; k < 3; ++k) e[k] = q[k] - p[k], f[k] = r[k] - q[k];
    c[0] = e[1] * f[2] - e[2] * f[1];
    c[1] = e[2] * f[0] - e[0] * f[2];
    c[2] = e[0] * f[1] - e[1] * f[0];
    turning += atan2(sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]),
                     e[0] * f[0] + e[1] * f[1] + e[2] * f[2]);
  }
  const double B = m.E * M_PI * a * a * a * a / 4.0;
  *bound = B * turning * turning / (2.0 * L);
  printf("  knot (contact radius %.4g, L/D %.0f): %s %s, %d its, energy %.9g (bend "
         "%.9g, twist %.3g, stretch %.3g, contact %.3g); total turning %.6f pi, bend "
         "bound %.9g (8 pi^2 B / L = %.9g); final min gap %.4g, active pairs %zu; on the "
         "path: %ld iterates, smallest gap %.4g; stability: verified %d, lowest "
         "eigenvalue %.3g (scale %.3g, %d zero modes)\n",
         rc, L / (2.0 * rc), rn_solve_stop_name(rep.stop),
         rep.converged ? "converged" : "NOT converged", rep.iterations, rep.energy,
         E[RN_TERM_BEND], E[RN_TERM_TWIST], E[RN_TERM_STRETCH], E[RN_TERM_LOAD],
         turning / M_PI, *bound, 8.0 * M_PI * M_PI * B / L, cs.min_gap, cs.active,
         w.iterations, w.min_gap, rep.stability.verified_minimum,
         rep.stability.lowest_eigenvalue, rep.stability.scale, rep.stability.zero_modes);
  /* The monitor reports every iteration but a return to a watchdog anchor (an
   * iterate reported already). */
  CHECK(!w.failed);
  CHECK(w.iterations > rep.iterations / 2);
  CHECK(w.min_gap > 0.0); /* no accepted state interpenetrates */
  CHECK(rep.converged == 1 && rep.stop == RN_STOP_GRADIENT);
  CHECK(cs.active > 0 && cs.min_gap > 0.0 && cs.min_gap < 0.5 * rc); /* pulled tight */
  CHECK(turning > 4.0 * M_PI);      /* still knotted (Fary-Milnor) */
  CHECK(E[RN_TERM_BEND] >= *bound); /* the discrete energy's Cauchy-Schwarz bound */
  CHECK(rep.stability.checked == 1 && rep.stability.verified_minimum == 1);
  CHECK(rep.load_steps == 1);
  /* tr-krylov from the loose knot again: converged or a clear stop (docs/contact.md:
   * it stalls on the knot's soft mode), in one load step (nothing depends on the load
   * factor: no cuts), never NaN */
  if (rc > 0.15) {
    rn_solve_report rk;
    CHECK_STATUS(rn_network_set_dofs(net, x0), RN_OK);
    opt.progress = NULL;
    opt.solver = RN_SOLVER_TR_KRYLOV;
    opt.preconditioner = RN_PRECOND_FACTOR;
    opt.stability = 0;
    CHECK_STATUS(rn_solve(net, &opt, &rk), RN_OK);
    printf("  knot, tr-krylov + factor: %s, %d its, %d load steps, |g| %.3g\n",
           rn_solve_stop_name(rk.stop), rk.iterations, rk.load_steps, rk.gradient_norm);
    CHECK(rk.converged == 1 || rk.stop == RN_STOP_RADIUS);
    CHECK(rk.load_steps == 1 && isfinite(rk.energy) && isfinite(rk.gradient_norm));
  }
  free(w.x);
  free(x0);
  rn_network_destroy(&net);
  return E[RN_TERM_BEND];
}

static void knot(rn_context *ctx) {
  double bound6 = 0.0, bound8 = 0.0;
  const double e6 = trefoil(ctx, 1.0 / 6.0, &bound6),
               e8 = trefoil(ctx, 1.0 / 8.0, &bound8);
  /* A thinner rod ties a tighter knot with less bending, nearer the bound. */
  CHECK(e8 < e6);
  CHECK(e8 / bound8 < e6 / bound6);
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  const char *which = argc > 1 ? argv[1] : "crossed";
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  if (!strcmp(which, "crossed"))
    crossed(ctx);
  else if (!strcmp(which, "plectoneme") || !strcmp(which, "plectoneme_dd"))
    plectoneme(ctx, !strcmp(which, "plectoneme_dd"));
  else if (!strcmp(which, "knot"))
    knot(ctx);
  else if ((!strcmp(which, "lattice") || !strcmp(which, "lattice_dd")) && argc > 2)
    lattice(ctx, argv[2], !strcmp(which, "lattice_dd"));
  else
    rn_test_fail(__FILE__, __LINE__, "unknown case %s", which);
  rn_context_destroy(&ctx);
  return rn_test_finish("hard_contact");
}

/* val_path.c - path following (rn_path_follow, docs/path-following.md) against
 * closed forms, on the scenes of problems/scenes/path/ (argv[1]: that folder;
 * argv[2]: "validation", "hard" or "arch", which cases to run):
 *  (1) von Mises truss, load control: the limit point is located where the
 *      closed form puts it.  The rod's two edges stretch (E A / L0) and its apex
 *      bends by a linear spring in the apex height h (the turning angle's
 *      integrated curvature 2 tan(phi/2) = 2 h / a exactly), so
 *      P(h) = 2 EA h (1/L - 1/L0) + 4 B (h0 - h) / (L0 a^2) is the exact
 *      discrete path and its maximum, at L^3 = a^2 L0 / (1 + 2 B / (EA a^2)), the
 *      limit load.  Tolerance 1e-8 relative: the limit is found by a secant
 *      search on the lowest eigenvalue to 1e-12 of its scale, and the load is
 *      stationary there (error quadratic in the location error).  The path then
 *      runs down the unstable branch (negative eigenvalue) until the load factor
 *      leaves [0, 1].
 *  (2) the same truss under displacement control of the apex (load factor 0)
 *      from h0 through the flat state to -h0: the conjugate force is -P(h) and
 *      the energy EA/L0 (L - L0)^2 + 2 B (h - h0)^2 / (L0 a^2) at every point, to
 *      1e-9 of their largest values (Newton converged to 1e-9 of the force
 *      scale); the snap-through that load control jumps is continuous here.
 *  (3) Euler column, load control: the bifurcation of the straight state is
 *      located at the discrete buckling load P (1 - P/EA) = (4 B / h^2)
 *      sin^2(pi / 2n) (VALIDATION.md 3.1-3.2; exact for the discrete rod, the
 *      factor 1 - P/EA the compression of the edges) to 1e-8 relative; branch
 *      switching leaves it onto the buckled branch, which is stable and whose
 *      load rises; at the scene's load (P / P_E = 2.026) the end shortening
 *      matches the inextensible elastica Delta/L = 2 (1 - E(k)/K(k)),
 *      P / P_E = (2 K(k) / pi)^2 (VALIDATION.md 3.3): at 16, 32 and 64 edges
 *      the shortening converges at order 2 (asserted within [1.7, 2.3]) and its
 *      Richardson extrapolation matches the elastica to 1e-3 relative (the
 *      rest of the O(h^2) series).
 *  (4) hard: the buckled clamped-clamped strip pushed sideways at its midpoint
 *      (displacement control) through to the mirrored shape: the symmetric
 *      path bifurcates (the largest force: the limit point of a force-
 *      controlled push), branch switching follows the stable asymmetric
 *      branch, no point after it is unstable, the path ends at the mirror
 *      image of the start (force 0 to 1e-6 of the largest force, energy equal
 *      to 1e-8), and the energy is continuous: sum over the steps of
 *      |dE - (F1 + F0)/2 du| (trapezoidal work of the conjugate force) is
 *      below 2 % of the energy's range.  Then back from the mirror image (the
 *      end state asserted; its continuity measured only, see strip()).
 *  (5) arch: snap-through of a pinned shallow circular arch under a central
 *      load (load control, steps of at most 0.01): stable up to the upper limit
 *      point, unstable down to the lower one, stable on the inverted arch (2
 *      limit points, no bifurcation: the rise parameter h/r = 3 makes the snap
 *      symmetric); both limit loads within 3e-3 of the extensible elastica
 *      (tests/validation/arch_elastica.py) at 32 edges; the upper limit load at
 *      16, 32, 64 edges converges at order 2 (asserted in [1.8, 2.2]) and its
 *      Richardson extrapolation matches the elastica to 1e-6 relative. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet_solve.h"
#include "scene/scene.h"
#include "testutil.h"
#include "valutil.h"

typedef struct points {
  rn_path_point p[4096];
  int n;
} points;

static int collect(void *user, const rn_path_point *pt) {
  points *ps = user;
  if (ps->n < 4096) ps->p[ps->n++] = *pt;
  return 0;
}

static rn_scene *load(rn_context *ctx, const char *dir, const char *name) {
  char path[4096];
  snprintf(path, sizeof path, "%s/%s", dir, name);
  rn_scene *s = NULL;
  CHECK_STATUS(rn_scene_load(ctx, path, &s), RN_OK);
  return s;
}

/* Reduced DOF of coordinate comp of vertex v of rod 0. */
static long vertex_dof(rn_network *net, int v, int comp) {
  size_t n = rn_network_num_dofs(net);
  rn_dof_info *info = malloc(n * sizeof *info);
  CHECK_STATUS(rn_network_dof_info(net, info), RN_OK);
  long found = -1;
  for (size_t i = 0; i < n; i++)
    if (info[i].kind == RN_DOF_POSITION && info[i].rod == 0 && info[i].index == v &&
        info[i].component == comp)
      found = (long)i;
  free(info);
  CHECK(found >= 0);
  return found;
}

/* Solves the start at load factor lf (< 0: the scene's), empties ps and returns
 * the default options that collect the points into ps. */
static rn_path_options start(rn_network *net, double lf, points *ps) {
  if (lf >= 0) CHECK_STATUS(rn_network_set_load_factor(net, lf), RN_OK);
  rn_solve_report rep;
  CHECK_STATUS(rn_solve(net, NULL, &rep), RN_OK);
  CHECK(rep.converged);
  ps->n = 0;
  rn_path_options o;
  rn_path_options_default(&o);
  o.callback = collect;
  o.user = ps;
  return o;
}

/* ---- (1), (2) von Mises truss -------------------------------------------- */
static const double ta = 1.0, th0 = 0.2;
static double tEA(void) { return 1e6 * M_PI * 1e-4; }
static double tB(void) { return 1e6 * M_PI * 1e-8 / 4; }
static double tL0(void) { return hypot(ta, th0); }
static double truss_P(double h) {
  double L = hypot(ta, h);
  return 2 * tEA() * h * (1 / L - 1 / tL0()) + 4 * tB() * (th0 - h) / (tL0() * ta * ta);
}
static double truss_E(double h) {
  double L = hypot(ta, h);
  return tEA() / tL0() * (L - tL0()) * (L - tL0()) +
         2 * tB() * (h - th0) * (h - th0) / (tL0() * ta * ta);
}

static void truss_load(rn_context *ctx, const char *dir) {
  rn_scene *s = load(ctx, dir, "von_mises_truss.json");
  rn_network *net = rn_scene_network(s);
  static points ps;
  rn_path_options o = start(net, 0.0, &ps);
  rn_path_report rep;
  CHECK_STATUS(rn_path_follow(net, &o, &rep), RN_OK);
  double Ls = cbrt(ta * ta * tL0() / (1 + 2 * tB() / (tEA() * ta * ta)));
  double hs = sqrt(Ls * Ls - ta * ta), lam = truss_P(hs) / 2.0;
  printf("truss, load control: %d steps, stop %s, limit at load factor %.12f (closed "
         "form %.12f), apex %.10f (%.10f)\n",
         rep.steps, rn_path_stop_name(rep.stop), rep.limit_load_factor, lam,
         rep.limit_control, hs);
  CHECK(rep.limit_points == 1);
  CHECK(rep.bifurcations == 0);
  CHECK_REL(rep.limit_load_factor, lam, 1e-8);
  CHECK_NEAR(rep.limit_control, hs, 1e-5);
  CHECK(rep.stop == RN_PATH_STOP_RANGE);
  int after = 0;
  for (int i = 0; i < ps.n; i++) {
    const rn_path_point *p = &ps.p[i];
    if (p->event == RN_PATH_LIMIT) {
      after = 1;
      continue;
    }
    CHECK(p->stability == (after ? -1 : 1));
    /* the load control path is the closed form too, to the corrector's
     * tolerance: residual 1e-9 of the largest stencil force (the bars' axial
     * forces, up to 2.5 P here) */
    CHECK_NEAR(2.0 * p->load_factor, truss_P(p->control), 2e-8);
  }
  rn_scene_destroy(&s);
}

static void truss_dof(rn_context *ctx, const char *dir) {
  rn_scene *s = load(ctx, dir, "von_mises_truss.json");
  rn_network *net = rn_scene_network(s);
  static points ps;
  rn_path_options o = start(net, 0.0, &ps);
  o.control = RN_PATH_DOF;
  o.dof = (size_t)vertex_dof(net, 1, 2);
  o.direction = -1;
  o.target = -th0;
  rn_path_report rep;
  CHECK_STATUS(rn_path_follow(net, &o, &rep), RN_OK);
  CHECK(rep.stop == RN_PATH_STOP_TARGET);
  double Pmax = 0.9327, Emax = truss_E(0.0), ferr = 0, eerr = 0;
  for (int i = 0; i < ps.n; i++) {
    const rn_path_point *p = &ps.p[i];
    ferr = fmax(ferr, fabs(p->force + truss_P(p->control)) / Pmax);
    eerr = fmax(eerr, fabs(p->energy - truss_E(p->control)) / Emax);
    CHECK(p->stability == 1);
  }
  printf("truss, displacement control: %d points from %.3f to %.10f, force error %.2e "
         "of P_max, energy error %.2e of E(0)\n",
         ps.n, ps.p[0].control, ps.p[ps.n - 1].control, ferr, eerr);
  CHECK_NEAR(ps.p[ps.n - 1].control, -th0, 1e-14);
  CHECK(ferr < 1e-9);
  CHECK(eerr < 1e-9);
  rn_scene_destroy(&s);
}

/* ---- (3) Euler column ------------------------------------------------------ */
/* The column scene with nv vertices (the file's 17 replaced). */
static rn_scene *column_scene(rn_context *ctx, const char *dir, int nv) {
  char path[4096], *text = malloc(1 << 16), *out = malloc(1 << 16);
  snprintf(path, sizeof path, "%s/euler_column.json", dir);
  FILE *f = fopen(path, "rb");
  CHECK(f != NULL);
  size_t len = f ? fread(text, 1, (1 << 16) - 1, f) : 0;
  if (f) fclose(f);
  text[len] = '\0';
  char *at = strstr(text, "\"vertices\": 17");
  CHECK(at != NULL);
  snprintf(out, 1 << 16, "%.*s\"vertices\": %d%s", (int)(at - text), text, nv,
           at + strlen("\"vertices\": 17"));
  rn_scene *s = NULL;
  CHECK_STATUS(rn_scene_parse(ctx, path, out, strlen(out), &s), RN_OK);
  free(text);
  free(out);
  return s;
}

/* Follows the column with n edges; returns the end shortening at the scene's load. */
static double column(rn_context *ctx, const char *dir, int n) {
  rn_scene *s = column_scene(ctx, dir, n + 1);
  rn_network *net = rn_scene_network(s);
  static points ps;
  rn_path_options o = start(net, 0.0, &ps);
  o.branch_switch = 1;
  rn_path_report rep;
  CHECK_STATUS(rn_path_follow(net, &o, &rep), RN_OK);
  const double h = 1.0 / n, B = 1.0, EA = 1e6, P = 20.0;
  double Pn = 4 * B / (h * h) * pow(sin(M_PI / (2 * n)), 2);
  double Pcr = (1 - sqrt(1 - 4 * Pn / EA)) / (2 / EA); /* P (1 - P/EA) = Pn */
  printf("column, %d edges: %d steps, stop %s, bifurcation at load factor %.12f "
         "(discrete %.12f)\n",
         n, rep.steps, rn_path_stop_name(rep.stop), rep.bifurcation_load_factor, Pcr / P);
  CHECK(rep.bifurcations == 1);
  CHECK(rep.limit_points == 0);
  CHECK_REL(rep.bifurcation_load_factor, Pcr / P, 1e-8);
  CHECK(rep.stop == RN_PATH_STOP_TARGET);
  int sw = -1;
  for (int i = 0; i < ps.n; i++)
    if (ps.p[i].event == RN_PATH_BRANCH_SWITCH) sw = i;
  CHECK(sw > 0);
  /* the buckled branch: never unstable (its lowest eigenvalue grows from 0 with
   * the amplitude: critical next to the bifurcation), stable at the end, and the
   * load rises (a supercritical pitchfork) */
  for (int i = sw + 1; i < ps.n; i++) {
    CHECK(ps.p[i].stability >= 0);
    CHECK(ps.p[i].load_factor > ps.p[i - 1].load_factor);
  }
  const rn_path_point *last = &ps.p[ps.n - 1];
  CHECK(last->stability == 1);
  CHECK_NEAR(last->load_factor, 1.0, 1e-14);
  rn_scene_destroy(&s);
  return -last->displacement;
}

/* The shortening at 16, 32 and 64 edges converges at second order to the
 * elastica's: the Richardson extrapolation of the last two to 1e-3. */
static void column_convergence(rn_context *ctx, const char *dir) {
  double r = 20.0 / (M_PI * M_PI), lo = 0.0, hi = 0.999999;
  for (int it = 0; it < 200; it++) {
    double k = 0.5 * (lo + hi), K = val_ellK(k);
    if (pow(2 * K / M_PI, 2) < r)
      lo = k;
    else
      hi = k;
  }
  double k = 0.5 * (lo + hi), delta = 2 * (1 - val_ellE(k) / val_ellK(k));
  double d[3];
  for (int i = 0; i < 3; i++) d[i] = column(ctx, dir, 16 << i);
  double order = log((d[1] - d[0]) / (d[2] - d[1])) / log(2.0);
  double extrap = d[2] + (d[2] - d[1]) / 3.0;
  printf("  end shortening at P/P_E = %.4f: %.6f %.6f %.6f (16, 32, 64 edges), order "
         "%.3f, extrapolated %.6f, elastica %.6f (k = %.6f)\n",
         r, d[0], d[1], d[2], order, extrap, delta, k);
  CHECK(order > 1.7 && order < 2.3);
  CHECK_REL(extrap, delta, 1e-3);
}

/* ---- (4) strip pushed sideways (hard) ---------------------------------------- */
/* Pushes the midpoint from the buckled state the network is in to its mirror. */
static void strip_push(rn_network *net, const char *label) {
  static points ps;
  rn_path_options o = start(net, -1.0, &ps);
  double x[3];
  val_vertex(net, 20, x);
  CHECK(fabs(x[2]) > 0.02); /* buckled (either way) */
  /* the push from +z is asserted in full, the one from -z (the other sign of
   * every branch) only at its end: see strip() */
  const int continuity = x[2] > 0;
  o.control = RN_PATH_DOF;
  o.dof = (size_t)vertex_dof(net, 20, 2);
  o.direction = x[2] > 0 ? -1 : 1;
  o.target = -x[2];
  o.max_steps = 1000;
  o.ds = 0.005;
  o.ds_max = 0.005;
  o.branch_switch = 1;
  rn_path_report rep;
  rn_status st = rn_path_follow(net, &o, &rep);
  if (st != RN_OK) printf("%s\n", rn_context_last_error(rn_network_context(net)));
  CHECK_STATUS(st, RN_OK);
  CHECK(rep.stop == RN_PATH_STOP_TARGET);
  CHECK(rep.bifurcations >= 1);
  double fbig = 0, emin = 1e300, emax = -1e300, work_err = 0;
  int sw = -1;
  const rn_path_point *prev = NULL;
  for (int i = 0; i < ps.n; i++) {
    const rn_path_point *p = &ps.p[i];
    fbig = fmax(fbig, fabs(p->force));
    emin = fmin(emin, p->energy);
    emax = fmax(emax, p->energy);
    if (p->event == RN_PATH_BRANCH_SWITCH && sw < 0) sw = i;
    if (sw >= 0 && i > sw) CHECK(p->stability >= 0); /* never unstable */
    /* located events lie on the path between the points around them */
    if (prev)
      work_err += fabs(p->energy - prev->energy -
                       0.5 * (p->force + prev->force) * (p->control - prev->control));
    prev = p;
  }
  const rn_path_point *last = &ps.p[ps.n - 1];
  printf(
      "strip (%s): %d steps, %d points, stop %s, %d bifurcation(s), first at %.6f with "
      "force %.6f (largest |force| %.6f); end at %.6f: force %.3e, energy %.10f "
      "(start %.10f); trapezoid work error %.3e of the energy range %.3e\n",
      label, rep.steps, ps.n, rn_path_stop_name(rep.stop), rep.bifurcations,
      rep.bifurcation_control, rep.bifurcation_force, fbig, last->control, last->force,
      last->energy, ps.p[0].energy, work_err, emax - emin);
  CHECK(sw > 0);
  CHECK(last->stability == 1);
  CHECK(fabs(last->force) < 1e-6 * fbig);
  CHECK_REL(last->energy, ps.p[0].energy, 1e-8);
  if (continuity) {
    /* the largest force is at a bifurcation (located to ~1e-5 of the force) */
    CHECK_NEAR(fabs(rep.bifurcation_force), fbig, 1e-4 * fbig);
    CHECK(work_err < 2e-2 * (emax - emin));
  }
}

static void strip(rn_context *ctx, const char *dir) {
  rn_scene *s = load(ctx, dir, "strip_snap.json");
  rn_network *net = rn_scene_network(s);
  /* from the twin the start solve finds to its mirror image, and back: the
   * push from -z (the other sign of every branch) goes round the asymmetric loop
   * more often, and where a step crosses a junction of branches the force jumps
   * (docs/path-following.md, Limits: 2.6 % trapezoid error, a point 3e-4 above
   * the bifurcation force): its end state is asserted, its continuity measured */
  strip_push(net, "there");
  strip_push(net, "back");
  rn_scene_destroy(&s);
}

/* ---- (5) shallow arch snap-through (hard) ------------------------------------ */
/* The pinned circular arch of problems/scenes/path/shallow_arch.json: span
 * arch_L, rise arch_h, EI = 1, EA = 1e4 (rise parameter h / r = 3, r the radius
 * of gyration), n edges (n even: a vertex at the crown), in the x-z plane (every
 * vertex held in y), a load arch_P down on the crown.  Reference limit loads:
 * the extensible elastica with the arch's rest curvature, shot on the half arch
 * by tests/validation/arch_elastica.py (RK4 at 200, 400, 800 steps: the digits
 * below are stable to 1e-12). */
static const double arch_L = 1.0, arch_h = 0.03, arch_P = 3.0;
static const double arch_upper = 2.0725733696, arch_lower = 0.9102677165;
/* Steps of at most 0.01: with the default largest step (0.05) the corrector
 * next to the upper limit point lands on the inverted branch and the path runs
 * on without an event (docs/path-following.md, Limits). */
static const double arch_ds = 0.01;

/* The arch scene with n edges, as JSON text (malloc'ed). */
static char *arch_json(int n) {
  size_t cap = 4096 + (size_t)n * 160;
  char *t = malloc(cap);
  size_t k = 0;
  const double R = (arch_h * arch_h + 0.25 * arch_L * arch_L) / (2 * arch_h);
  const double alpha = asin(0.5 * arch_L / R);
  k += (size_t)snprintf(
      t + k, cap - k,
      "{\"materials\": {\"m\": {\"E\": 1.0, \"nu\": 0.3}},\n"
      " \"sections\": {\"s\": {\"shape\": \"explicit\", \"A\": 1.0e4, "
      "\"I11\": 1.0, \"I22\": 1.0, \"J\": 1.0}},\n"
      " \"rods\": [{\"name\": \"arch\", \"material\": \"m\", \"section\": "
      "\"s\", \"d1\": [0, 1, 0], \"vertices\": [");
  for (int i = 0; i <= n; i++) {
    double phi = alpha * (2.0 * i / n - 1.0);
    /* the crown exactly at x = 0 */
    double x = i == n / 2 ? 0.0 : R * sin(phi), z = R * cos(phi) - (R - arch_h);
    k += (size_t)snprintf(t + k, cap - k, "%s[%.17g, 0, %.17g]", i ? ", " : "", x, z);
  }
  k += (size_t)snprintf(
      t + k, cap - k,
      "]}],\n \"constraints\": [{\"type\": \"pin\", \"rod\": \"arch\", "
      "\"vertex\": 0}, {\"type\": \"pin\", \"rod\": \"arch\", \"vertex\": "
      "-1}, {\"type\": \"fix_theta\", \"rod\": \"arch\", \"edge\": 0}");
  for (int i = 1; i < n; i++)
    k += (size_t)snprintf(t + k, cap - k,
                          ",\n  {\"type\": \"pin\", \"rod\": \"arch\", \"vertex\": %d, "
                          "\"components\": [\"y\"]}",
                          i);
  k += (size_t)snprintf(t + k, cap - k,
                        "],\n \"loads\": [{\"type\": \"force\", \"rod\": \"arch\", "
                        "\"vertex\": %d, \"value\": [0, 0, %.17g]}]}\n",
                        n / 2, -arch_P);
  CHECK(k < cap);
  return t;
}

static rn_scene *arch_scene(rn_context *ctx, int n) {
  char *text = arch_json(n);
  rn_scene *s = NULL;
  CHECK_STATUS(rn_scene_parse(ctx, "arch.json", text, strlen(text), &s), RN_OK);
  free(text);
  return s;
}

static int stop_at_limit(void *user, const rn_path_point *pt) {
  collect(user, pt);
  return pt->event == RN_PATH_LIMIT;
}

/* Load control from the unloaded arch to its first limit point (n edges):
 * returns the limit load. */
static double arch_limit(rn_context *ctx, int n) {
  rn_scene *s = arch_scene(ctx, n);
  rn_network *net = rn_scene_network(s);
  static points ps;
  rn_path_options o = start(net, 0.0, &ps);
  o.ds = o.ds_max = arch_ds;
  o.callback = stop_at_limit;
  rn_path_report rep;
  CHECK_STATUS(rn_path_follow(net, &o, &rep), RN_OK);
  CHECK(rep.stop == RN_PATH_STOP_CALLBACK);
  CHECK(rep.limit_points == 1);
  CHECK(rep.bifurcations == 0); /* a symmetric limit point, no bifurcation first */
  for (int i = 0; i + 1 < ps.n; i++) CHECK(ps.p[i].stability == 1);
  printf("arch, %d edges: first limit point at load %.10f (%d steps)\n", n,
         rep.limit_load_factor * arch_P, rep.steps);
  rn_scene_destroy(&s);
  return rep.limit_load_factor * arch_P;
}

/* The whole snap-through on the shipped scene (32 edges), then the limit load's
 * convergence in the number of edges. */
static void arch(rn_context *ctx, const char *dir) {
  rn_scene *s = load(ctx, dir, "shallow_arch.json");
  rn_network *net = rn_scene_network(s);
  static points ps;
  rn_path_options o = start(net, 0.0, &ps);
  o.ds = o.ds_max = arch_ds;
  o.max_steps = 1000;
  rn_path_report rep;
  CHECK_STATUS(rn_path_follow(net, &o, &rep), RN_OK);
  /* stable up to the upper limit point, unstable down to the lower one, stable
   * on the inverted arch up to the scene's load */
  CHECK(rep.stop == RN_PATH_STOP_TARGET);
  CHECK(rep.limit_points == 2);
  CHECK(rep.bifurcations == 0);
  int phase = 0, nlim = 0;
  double lim[2] = {NAN, NAN};
  for (int i = 0; i < ps.n; i++) {
    const rn_path_point *p = &ps.p[i];
    if (p->event == RN_PATH_LIMIT) {
      if (nlim < 2) lim[nlim] = p->load_factor * arch_P;
      nlim++;
      phase++;
      continue;
    }
    CHECK(p->event == RN_PATH_POINT);
    CHECK(p->stability == (phase == 1 ? -1 : 1));
  }
  const rn_path_point *last = &ps.p[ps.n - 1];
  CHECK(nlim == 2);
  CHECK_NEAR(last->load_factor, 1.0, 1e-14);
  /* snapped: the crown below the supports (inverted) */
  CHECK(last->control < -0.5 * arch_h);
  printf("arch (shallow_arch.json, 32 edges): %d steps, %d points, %ld corrector "
         "iterations, %.3f s; limit points at load %.10f (crown %.8f) and %.10f; "
         "end: crown %.6f at load %.3f\n",
         rep.steps, ps.n, rep.corrector_iterations, rep.time_s, lim[0], rep.limit_control,
         lim[1], last->control, last->load_factor * arch_P);
  CHECK_REL(rep.limit_load_factor * arch_P, lim[0], 1e-15);
  /* 32 edges: within 3e-3 of the elastica (the O(1/n^2) error is -1.8e-3) */
  CHECK_REL(lim[0], arch_upper, 3e-3);
  CHECK_REL(lim[1], arch_lower, 3e-3);
  rn_scene_destroy(&s);
  /* The default step sizes: the steps next to the upper limit point are halved,
   * and a corrector that converges far from its predictor (on the inverted branch)
   * is refused, so the path still goes round both limit points (without that check
   * it jumped onto the inverted arch with no event; docs/path-following.md). */
  {
    rn_scene *s2 = load(ctx, dir, "shallow_arch.json");
    static points ps2;
    rn_path_options o2 = start(rn_scene_network(s2), 0.0, &ps2);
    o2.max_steps = 1000;
    rn_path_report rep2;
    CHECK_STATUS(rn_path_follow(rn_scene_network(s2), &o2, &rep2), RN_OK);
    CHECK(rep2.stop == RN_PATH_STOP_TARGET);
    CHECK(rep2.limit_points == 2);
    CHECK(rep2.bifurcations == 0);
    double lim2[2] = {NAN, NAN};
    int n2 = 0;
    for (int i = 0; i < ps2.n; i++)
      if (ps2.p[i].event == RN_PATH_LIMIT && n2 < 2)
        lim2[n2++] = ps2.p[i].load_factor * arch_P;
    printf("arch, default steps (ds %g, at most %g): %d steps, limit loads %.10f and "
           "%.10f\n",
           o2.ds, o2.ds_max, rep2.steps, lim2[0], lim2[1]);
    /* both located by the secant search on the eigenvalue from other steps: the
     * same limit loads to 1e-7 (observed 2.5e-9 and 2.7e-8) */
    CHECK_REL(lim2[0], lim[0], 1e-7);
    CHECK_REL(lim2[1], lim[1], 1e-7);
    CHECK(ps2.p[ps2.n - 1].control < -0.5 * arch_h);
    rn_scene_destroy(&s2);
  }
  /* the same load from the arch generated here (the scene file's geometry) */
  double p[3];
  for (int i = 0; i < 3; i++) p[i] = arch_limit(ctx, 16 << i);
  CHECK_REL(p[1], lim[0], 1e-8);
  double order = log((p[1] - p[0]) / (p[2] - p[1])) / log(2.0);
  double extrap = p[2] + (p[2] - p[1]) / 3.0;
  printf("  upper limit load at 16, 32, 64 edges: %.10f %.10f %.10f, order %.3f, "
         "extrapolated %.10f, elastica %.10f (relative %.2e)\n",
         p[0], p[1], p[2], order, extrap, arch_upper, extrap / arch_upper - 1);
  CHECK(order > 1.8 && order < 2.2);
  /* observed 1.5e-7: the rest of the O(1/n^2) series and the event's location */
  CHECK_REL(extrap, arch_upper, 1e-6);
}

int main(int argc, char **argv) {
  if (argc < 3) {
    fprintf(stderr, "usage: val_path SCENE_DIR validation|hard|arch\n");
    return 2;
  }
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  if (strcmp(argv[2], "hard") == 0) {
    strip(ctx, argv[1]);
  } else if (strcmp(argv[2], "arch") == 0) {
    arch(ctx, argv[1]);
  } else {
    truss_load(ctx, argv[1]);
    truss_dof(ctx, argv[1]);
    column_convergence(ctx, argv[1]);
  }
  rn_context_destroy(&ctx);
  return rn_test_finish("val_path");
}

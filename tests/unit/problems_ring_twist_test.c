/* problems_ring_twist_test.c - a closed rod's twist given as a total twist
 * ("twist": {"total": T} in the scene, rn_network_set_ring_total_twist;
 * issue 10 section 4):
 *  - a planar ring with total 2 pi n is the ring with link n: the same energy
 *    and gradient at the input state and at a perturbed one (to round-off);
 *  - a naturally straight planar isotropic ring (rest curvature and twist 0)
 *    with a total twist T that is not a multiple of 2 pi (1.3 and 2 pi + 1.3)
 *    stores it: its geometric total twist at the input is the whole turns (0,
 *    2 pi), and with those spread evenly (the stored twist T / N per vertex) the gradient
 *    vanishes, the twisting energy is the closed form GJ T^2 / (2 L) and the
 *    bending energy the polygon's N B (2 tan(pi/N))^2 / (2 l) (L = N l),
 *    times cos^2(pi k / N) for k whole turns: the material curvature takes the
 *    mean of the two edges' material frames, which differ by the geometric twist
 *    2 pi k / N (a naturally curved ring would also bend as its frame turns);
 *  - a ring's whole turns start evenly spread over its vertices (link n: the
 *    evenly twisted polygon at the input state, issue 22 section 4);
 *  - errors: both keys, a non-finite or non-numeric total, an open rod (scene
 *    and C API), a NaN total (C API). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet_ring.h"
#include "scene/scene.h"
#include "testutil.h"

static const double PI = 3.14159265358979323846;
enum { N = 24 };
static const double E = 1e6, NU = 0.3, RAD = 0.05;

/* A ring of N vertices of radius 1 in the xy plane with the given "twist"
 * object ("" for none); ' stands for ". */
static char *ring_json(const char *twist, int straight) {
  size_t cap = 8192;
  char *t = malloc(cap);
  size_t k =
      (size_t)snprintf(t, cap,
                       "{'materials': {'m': {'E': %g, 'nu': %g}}, 'sections': "
                       "{'s': {'shape': 'circle', 'radius': %g}}, 'rods': [{'name': "
                       "'ring', 'material': 'm', 'section': 's', 'closed': true, "
                       "'d1': [0, 0, 1], 'vertices': [",
                       E, NU, RAD);
  for (int i = 0; i < N; ++i)
    k += (size_t)snprintf(t + k, cap - k, "%s[%.17g, %.17g, 0]", i ? ", " : "",
                          cos(2 * PI * i / N), sin(2 * PI * i / N));
  k += (size_t)snprintf(t + k, cap - k, "]");
  if (straight) { /* naturally straight and untwisted: rest arrays of zeros */
    k += (size_t)snprintf(t + k, cap - k, ", 'rest': {'curvature': [");
    for (int i = 0; i < N; ++i)
      k += (size_t)snprintf(t + k, cap - k, "%s[0, 0]", i ? ", " : "");
    k += (size_t)snprintf(t + k, cap - k, "], 'twist': [");
    for (int i = 0; i < N; ++i)
      k += (size_t)snprintf(t + k, cap - k, "%s0", i ? ", " : "");
    k += (size_t)snprintf(t + k, cap - k, "]}");
  }
  k += (size_t)snprintf(t + k, cap - k, "%s%s}]}", *twist ? ", 'twist': " : "", twist);
  CHECK(k < cap);
  for (char *c = t; *c; ++c)
    if (*c == '\'') *c = '"';
  return t;
}

static rn_status parse(rn_context *ctx, const char *text, rn_scene **s) {
  return rn_scene_parse(ctx, "ring.json", text, strlen(text), s);
}

static rn_scene *ring(rn_context *ctx, const char *twist, int straight) {
  char *text = ring_json(twist, straight);
  rn_scene *s = NULL;
  CHECK_STATUS(parse(ctx, text, &s), RN_OK);
  free(text);
  return s;
}

/* Total twist: the rod's interior vertices plus its closing joint. */
static double total_twist(const rn_network *net) {
  int nv = rn_network_rod_num_vertices(net, 0);
  double *tau = calloc((size_t)nv, sizeof(double)), tw = 0.0, tj = 0.0;
  CHECK_STATUS(rn_network_rod_strains(net, 0, NULL, NULL, tau), RN_OK);
  for (int i = 0; i < nv - 2; ++i) tw += tau[i];
  free(tau);
  CHECK_STATUS(rn_network_joint_twist(net, 0, &tj), RN_OK);
  return tw + tj;
}

/* Sets every material angle of edge j to f(j) = a j / N (b: a perturbation). */
static void set_angles(const rn_network *net, double *x, double a, double b) {
  size_t n = rn_network_num_dofs(net);
  rn_dof_info *info = malloc(n * sizeof *info);
  CHECK_STATUS(rn_network_dof_info(net, info), RN_OK);
  for (size_t i = 0; i < n; ++i) {
    if (info[i].kind == RN_DOF_THETA)
      x[i] = a * info[i].index / N + b * sin(3.0 * info[i].index);
    else
      x[i] += b * cos(1.7 * (double)i);
  }
  free(info);
}

static void link_equals_total(rn_context *ctx) {
  for (int n = -2; n <= 2; ++n) {
    char total[64], link[64];
    snprintf(total, sizeof total, "{'total': %.17g}", 2 * PI * n);
    snprintf(link, sizeof link, "{'link': %d}", n);
    rn_scene *a = ring(ctx, link, 0), *b = ring(ctx, total, 0);
    rn_network *na = rn_scene_network(a), *nb = rn_scene_network(b);
    size_t nd = rn_network_num_dofs(na);
    CHECK(nd == rn_network_num_dofs(nb));
    double *x = malloc(nd * sizeof(double)), *ga = malloc(nd * sizeof(double)),
           *gb = malloc(nd * sizeof(double));
    double dmax = 0.0, gmax = 0.0, ea = 0, eb = 0;
    for (int pert = 0; pert < 2; ++pert) {
      CHECK_STATUS(rn_network_get_dofs(na, x), RN_OK);
      if (pert) set_angles(na, x, 0.0, 1e-3);
      CHECK_STATUS(rn_network_gradient(na, x, &ea, ga), RN_OK);
      CHECK_STATUS(rn_network_gradient(nb, x, &eb, gb), RN_OK);
      CHECK_REL(eb, ea, 1e-13);
      for (size_t i = 0; i < nd; ++i) {
        dmax = fmax(dmax, fabs(ga[i] - gb[i]));
        gmax = fmax(gmax, fabs(ga[i]));
      }
    }
    CHECK_NEAR(total_twist(nb), 2 * PI * n, 1e-12);
    CHECK(dmax <= 1e-12 * gmax);
    printf("total %+.6f = link %+d: energies %.15e %.15e, gradient difference %.1e of "
           "%.1e\n",
           2 * PI * n, n, ea, eb, dmax, gmax);
    free(x);
    free(ga);
    free(gb);
    rn_scene_destroy(&a);
    rn_scene_destroy(&b);
  }
}

/* T = 1.3 and 2 pi + 1.3: the whole turns (0, 1) are the geometric total twist
 * at the input, the remainder a rest-twist offset; the ring stores T. */
static void fractional_total(rn_context *ctx) {
  const double Ts[2] = {1.3, 2 * PI + 1.3};
  for (int c = 0; c < 2; ++c) {
    const double T = Ts[c];
    char twist[64];
    snprintf(twist, sizeof twist, "{'total': %.17g}", T);
    rn_scene *s = ring(ctx, twist, 1);
    rn_network *net = rn_scene_network(s);
    CHECK_NEAR(total_twist(net), 2 * PI * c, 1e-14);
    size_t nd = rn_network_num_dofs(net);
    double *x = malloc(nd * sizeof(double)), *g = malloc(nd * sizeof(double)), En = 0;
    CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
    /* the whole turns spread evenly (2 pi c / N per vertex), with the rest twist
     * offset -r / N: T / N stored per vertex */
    set_angles(net, x, 2 * PI * c, 0.0);
    CHECK_STATUS(rn_network_gradient(net, x, &En, g), RN_OK);
    double Et[RN_TERM_COUNT];
    CHECK_STATUS(rn_network_energy_terms(net, x, Et), RN_OK);
    const double G = E / (2 * (1 + NU)), J = PI * pow(RAD, 4) / 2,
                 B = E * PI * pow(RAD, 4) / 4;
    const double l = 2 * sin(PI / N), L = N * l, kb = 2 * tan(PI / N);
    const double etw = G * J * T * T / (2 * L),
                 bend = N * B * kb * kb / (2 * l) * pow(cos(PI * c / N), 2);
    double gmax = 0.0;
    for (size_t i = 0; i < nd; ++i) gmax = fmax(gmax, fabs(g[i]));
    printf(
        "total twist %.4f rad on a naturally straight planar ring of %d edges: twisting "
        "energy %.15e, GJ T^2/(2L) %.15e (relative %.1e); bending %.15e (polygon %.15e); "
        "largest gradient %.1e of the bending force %.1e\n",
        T, N, Et[RN_TERM_TWIST], etw, Et[RN_TERM_TWIST] / etw - 1, Et[RN_TERM_BEND], bend,
        gmax, B * kb / (l * l));
    CHECK_REL(Et[RN_TERM_TWIST], etw, 1e-12);
    CHECK_REL(Et[RN_TERM_BEND], bend, 1e-12);
    CHECK_REL(En, etw + bend, 1e-12);
    CHECK(gmax <= 1e-12 * B * kb / (l * l));
    free(x);
    free(g);
    rn_scene_destroy(&s);
  }
}

/* A ring's whole turns start evenly spread (issue 22 section 4): at the input
 * state of a naturally straight planar isotropic ring with link n the twisting
 * energy is GJ (2 pi n)^2 / (2 L), not the N times larger energy of the whole
 * turns at the closing vertex, and the state is the evenly twisted polygon
 * (bending N B (2 tan(pi/N))^2 / (2 l) cos^2(pi n / N), gradient zero). */
static void link_starts_spread(rn_context *ctx) {
  for (int n = -2; n <= 2; ++n) {
    char twist[64];
    snprintf(twist, sizeof twist, "{'link': %d}", n);
    rn_scene *s = ring(ctx, twist, 1);
    rn_network *net = rn_scene_network(s);
    size_t nd = rn_network_num_dofs(net);
    double *x = malloc(nd * sizeof(double)), *g = malloc(nd * sizeof(double)), En = 0;
    double Et[RN_TERM_COUNT], gmax = 0.0;
    CHECK_STATUS(rn_network_get_dofs(net, x), RN_OK);
    CHECK_STATUS(rn_network_gradient(net, x, &En, g), RN_OK);
    CHECK_STATUS(rn_network_energy_terms(net, x, Et), RN_OK);
    const double G = E / (2 * (1 + NU)), J = PI * pow(RAD, 4) / 2,
                 B = E * PI * pow(RAD, 4) / 4;
    const double l = 2 * sin(PI / N), L = N * l, kb = 2 * tan(PI / N);
    const double etw = G * J * pow(2 * PI * n, 2) / (2 * L),
                 bend = N * B * kb * kb / (2 * l) * pow(cos(PI * n / N), 2);
    for (size_t i = 0; i < nd; ++i) gmax = fmax(gmax, fabs(g[i]));
    printf("link %+d at the input state: twisting energy %.15e, GJ (2 pi n)^2/(2L) "
           "%.15e; bending %.15e (polygon %.15e); largest gradient %.1e\n",
           n, Et[RN_TERM_TWIST], etw, Et[RN_TERM_BEND], bend, gmax);
    CHECK_NEAR(Et[RN_TERM_TWIST], etw, 1e-12 * (etw + bend));
    CHECK_REL(Et[RN_TERM_BEND], bend, 1e-12);
    CHECK(gmax <= 1e-12 * B * kb / (l * l));
    CHECK_NEAR(total_twist(net), 2 * PI * n, 1e-12);
    free(x);
    free(g);
    rn_scene_destroy(&s);
  }
}

static void expect_error(rn_context *ctx, const char *twist, int closed,
                         const char *where, const char *reason) {
  char *text = ring_json(twist, 0);
  if (!closed) { /* the same rod, open */
    char *c = strstr(text, "\"closed\": true, ");
    CHECK(c != NULL);
    if (c) memmove(c, c + strlen("\"closed\": true, "), strlen(c + 16) + 1);
  }
  rn_scene *s = NULL;
  rn_status st = parse(ctx, text, &s);
  const char *msg = rn_context_last_error(ctx);
  printf("%s -> %s\n", twist, msg);
  CHECK(st < 0);
  CHECK(s == NULL);
  CHECK(strstr(msg, where) != NULL);
  CHECK(strstr(msg, reason) != NULL);
  free(text);
}

static void errors(rn_context *ctx) {
  expect_error(ctx, "{'link': 1, 'total': 6.283185307179586}", 1,
               "ring.json: $.rods[0].twist: ", "either \"link\" or \"total\", not both");
  expect_error(ctx, "{'total': 1e999}", 1,
               "$.rods[0].twist.total: ", "expected a finite number");
  expect_error(ctx, "{'total': 'pi'}", 1,
               "$.rods[0].twist.total: ", "expected a finite number");
  expect_error(ctx, "{}", 1, "$.rods[0].twist: ", "expected \"link\"");
  expect_error(ctx, "{'total': 1.0}", 0,
               "$.rods[0].twist: ", "applies to closed rods only");
  /* the C API: NaN, and a smooth joint that does not close a ring */
  rn_network *net = NULL;
  const double xyz[12] = {1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0}, d1[3] = {0, 0, 1};
  const double a[9] = {0, 0, 0, 1, 0, 0, 2, 0, 0}, b[9] = {2, 0, 0, 3, 0, 0, 4, 0.5, 0};
  int rod = -1, joint = -1, ra = -1, rb = -1, j2 = -1;
  CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
  CHECK_STATUS(rn_network_add_closed_rod(net, "ring", 4, xyz, d1, &rod, &joint), RN_OK);
  CHECK_STATUS(rn_network_set_ring_total_twist(net, joint, NAN), RN_ERR_NOT_FINITE);
  CHECK(rn_network_set_ring_total_twist(net, joint + 7, 1.0) < 0);
  CHECK_STATUS(rn_network_add_rod(net, "a", 3, a, d1, &ra), RN_OK);
  CHECK_STATUS(rn_network_add_rod(net, "b", 3, b, d1, &rb), RN_OK);
  const int rods[2] = {ra, rb}, ends[2] = {RN_END, RN_START};
  CHECK_STATUS(rn_network_add_joint(net, "j", RN_JOINT_SMOOTH, 2, rods, ends, &j2),
               RN_OK);
  CHECK_STATUS(rn_network_set_ring_total_twist(net, j2, 1.0), RN_ERR_ARG);
  printf("C API, open rods: %s\n", rn_context_last_error(ctx));
  CHECK(strstr(rn_context_last_error(ctx), "does not close a ring") != NULL);
  CHECK_STATUS(rn_network_set_ring_total_twist(net, joint, 1.0), RN_OK);
  rn_network_destroy(&net);
}

int main(void) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  link_equals_total(ctx);
  link_starts_spread(ctx);
  fractional_total(ctx);
  errors(ctx);
  rn_context_destroy(&ctx);
  return rn_test_finish("problems_ring_twist");
}

/* problems_joint_rest_test.c - joint rest frames in the scene ("rest":
 * {"frames": [...]} on a rigid or elastic joint; issue 10 section 4):
 *  - the scene gives the network that rn_network_set_joint_rest_frames gives
 *    (an L of two rods, rigid and elastic joints, frames not those of the
 *    input): the same energy and gradient at the input and at a perturbed
 *    state, to round-off;
 *  - a loop: a naturally straight rod bent into a circle whose ends meet at a
 *    rigid or elastic joint, with rest frames that continue the rod straight
 *    through the joint (both ends' frames the input frame of the arriving
 *    edge), is the loop with "rest": "straight" (no spurious rest kink
 *    stored); for the elastic joint a common rotation of both frames changes
 *    nothing (its rotation is their fit); with the default (the input's kink)
 *    the joint stores the kink instead: a different energy;
 *  - errors: wrong count of frames, of rows, non-orthonormal or left-handed
 *    frames (named by their place), frames on a smooth joint, both forms. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/scene.h"
#include "testutil.h"

static const double PI = 3.14159265358979323846;

static char *swap_quotes(char *t) {
  for (char *c = t; *c; ++c)
    if (*c == '\'') *c = '"';
  return t;
}

#define MS                                       \
  "{'materials': {'m': {'E': 1e7, 'nu': 0.3}}, " \
  "'sections': {'s': {'shape': 'circle', 'radius': 0.01}}, "

/* Two rods meeting at (1, 0, 0): a along x, b up and out of the plane. */
static const double LA[9] = {0, 0, 0, 0.5, 0, 0, 1, 0, 0};
static const double LB[9] = {1, 0, 0, 1, 0.5, 0.1, 1, 1, 0.25};

static char *l_json(const char *model, const char *rest) {
  char *t = malloc(4096);
  snprintf(t, 4096,
           MS
           "'rods': [{'name': 'a', 'material': 'm', 'section': 's', 'd1': [0, 0, 1], "
           "'vertices': [[0, 0, 0], [0.5, 0, 0], [1, 0, 0]]}, {'name': 'b', 'material': "
           "'m', 'section': 's', 'd1': [0, 0, 1], 'vertices': [[1, 0, 0], [1, 0.5, 0.1], "
           "[1, 1, 0.25]]}], 'joints': [{'name': 'j', 'model': '%s', 'ends': [{'rod': "
           "'a', 'end': 'end'}, {'rod': 'b', 'end': 'start'}]%s%s}], 'constraints': "
           "[{'type': 'clamp', 'rod': 'a', 'end': 'start'}]}",
           model, *rest ? ", 'rest': " : "", rest);
  return swap_quotes(t);
}

static rn_status parse(rn_context *ctx, const char *text, rn_scene **s) {
  return rn_scene_parse(ctx, "joint.json", text, strlen(text), s);
}

/* Rotation about the unit axis u by angle a, row-major. */
static void rotation(const double u[3], double a, double R[9]) {
  double c = cos(a), s = sin(a);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[3 * i + j] = (1 - c) * u[i] * u[j] + (i == j ? c : 0.0);
  R[1] -= s * u[2];
  R[2] += s * u[1];
  R[3] += s * u[2];
  R[5] -= s * u[0];
  R[6] -= s * u[1];
  R[7] += s * u[0];
}

static void frame_json(const double F[9], char *out, size_t cap) {
  snprintf(out, cap,
           "[[%.17g, %.17g, %.17g], [%.17g, %.17g, %.17g], [%.17g, %.17g, %.17g]]", F[0],
           F[1], F[2], F[3], F[4], F[5], F[6], F[7], F[8]);
}

/* Largest difference of energy and gradient between two networks with the same
 * DOFs at their input state and at a perturbed one, relative to the largest. */
static double compare(const rn_network *a, const rn_network *b, double *ea_out,
                      double *eb_out) {
  size_t n = rn_network_num_dofs(a);
  CHECK(n == rn_network_num_dofs(b));
  double *x = malloc(n * sizeof(double)), *ga = malloc(n * sizeof(double)),
         *gb = malloc(n * sizeof(double));
  double dmax = 0.0, big = 0.0, ea = 0.0, eb = 0.0;
  for (int pert = 0; pert < 2; ++pert) {
    CHECK_STATUS(rn_network_get_dofs(a, x), RN_OK);
    for (size_t i = 0; pert && i < n; ++i) x[i] += 1e-2 * sin(1.3 * (double)i + 0.4);
    CHECK_STATUS(rn_network_gradient(a, x, &ea, ga), RN_OK);
    CHECK_STATUS(rn_network_gradient(b, x, &eb, gb), RN_OK);
    dmax = fmax(dmax, fabs(ea - eb));
    big = fmax(big, fabs(ea));
    for (size_t i = 0; i < n; ++i) {
      dmax = fmax(dmax, fabs(ga[i] - gb[i]));
      big = fmax(big, fabs(ga[i]));
    }
  }
  if (ea_out) *ea_out = ea;
  if (eb_out) *eb_out = eb;
  free(x);
  free(ga);
  free(gb);
  return dmax / big;
}

static void scene_equals_api(rn_context *ctx) {
  const double u[3] = {0.48, 0.6, 0.64}, v[3] = {0, 0.6, 0.8};
  double F[18];
  char f0[256], f1[256], rest[600];
  rotation(u, 0.7, F);
  rotation(v, -1.1, F + 9);
  frame_json(F, f0, sizeof f0);
  frame_json(F + 9, f1, sizeof f1);
  snprintf(rest, sizeof rest, "{'frames': [%s, %s]}", f0, f1);
  const char *models[2] = {"rigid", "elastic"};
  const rn_joint_model kinds[2] = {RN_JOINT_RIGID, RN_JOINT_ELASTIC};
  for (int m = 0; m < 2; ++m) {
    char *text = l_json(models[m], rest);
    rn_scene *s = NULL;
    CHECK_STATUS(parse(ctx, text, &s), RN_OK);
    free(text);
    /* the same network through the C API */
    rn_network *net = NULL;
    rn_material mat;
    rn_section sec;
    const double d1[3] = {0, 0, 1};
    int ra = -1, rb = -1, j = -1;
    CHECK_STATUS(rn_material_from_E_nu(1e7, 0.3, 0.0, &mat), RN_OK);
    CHECK_STATUS(rn_section_circle(0.01, &sec), RN_OK);
    CHECK_STATUS(rn_network_create(ctx, &net), RN_OK);
    CHECK_STATUS(rn_network_add_rod(net, "a", 3, LA, d1, &ra), RN_OK);
    CHECK_STATUS(rn_network_add_rod(net, "b", 3, LB, d1, &rb), RN_OK);
    for (int r = 0; r < 2; ++r) {
      CHECK_STATUS(rn_network_set_material(net, r, -1, &mat), RN_OK);
      CHECK_STATUS(rn_network_set_section(net, r, -1, &sec), RN_OK);
    }
    const int rods[2] = {ra, rb}, ends[2] = {RN_END, RN_START};
    CHECK_STATUS(rn_network_add_joint(net, "j", kinds[m], 2, rods, ends, &j), RN_OK);
    CHECK_STATUS(rn_network_set_joint_rest_frames(net, j, F), RN_OK);
    CHECK_STATUS(rn_network_clamp(net, ra, RN_START), RN_OK);
    CHECK_STATUS(rn_network_finalize(net), RN_OK);
    double ea = 0, eb = 0, d = compare(rn_scene_network(s), net, &ea, &eb);
    printf("%s joint, scene rest frames vs C API: energies %.15e %.15e, largest "
           "difference %.1e (relative)\n",
           models[m], ea, eb, d);
    CHECK(d <= 1e-14);
    CHECK(ea > 0.0); /* the frames are not the input's: the joint is stressed */
    rn_network_destroy(&net);
    rn_scene_destroy(&s);
  }
}

/* A straight-rest rod of n edges bent into a circle, its ends at a joint of
 * the given model, with the given joint "rest" ("" for none). */
enum { NLOOP = 24 };
static rn_scene *loop(rn_context *ctx, const char *model, const char *rest) {
  size_t cap = 16384, k = 0;
  char *t = malloc(cap);
  k += (size_t)snprintf(t + k, cap - k,
                        MS "'rods': [{'name': 'a', 'material': 'm', 'section': 's', "
                           "'d1': [0, 0, 1], 'vertices': [");
  for (int i = 0; i <= NLOOP; ++i) {
    double a = 2 * PI * (i % NLOOP) / NLOOP;
    k += (size_t)snprintf(t + k, cap - k, "%s[%.17g, %.17g, 0]", i ? ", " : "", cos(a),
                          sin(a));
  }
  k += (size_t)snprintf(t + k, cap - k, "], 'rest': {'curvature': [");
  for (int i = 0; i < NLOOP - 1; ++i)
    k += (size_t)snprintf(t + k, cap - k, "%s[0, 0]", i ? ", " : "");
  k += (size_t)snprintf(t + k, cap - k, "], 'twist': [");
  for (int i = 0; i < NLOOP - 1; ++i)
    k += (size_t)snprintf(t + k, cap - k, "%s0", i ? ", " : "");
  k += (size_t)snprintf(t + k, cap - k,
                        "]}}], 'joints': [{'name': 'j', 'model': '%s', 'ends': [{'rod': "
                        "'a', 'end': 'end'}, {'rod': 'a', 'end': 'start'}]%s%s}]}",
                        model, *rest ? ", 'rest': " : "", rest);
  CHECK(k < cap);
  rn_scene *s = NULL;
  swap_quotes(t);
  rn_status st = parse(ctx, t, &s);
  if (st) printf("%s\n", rn_context_last_error(ctx));
  CHECK_STATUS(st, RN_OK);
  free(t);
  return s;
}

/* The loop with both ends' rest frames equal to F (rows): "{'frames': [F, F]}". */
static rn_scene *loop_frames(rn_context *ctx, const char *model, const double F[9]) {
  char f[256], rest[600];
  frame_json(F, f, sizeof f);
  snprintf(rest, sizeof rest, "{'frames': [%s, %s]}", f, f);
  return loop(ctx, model, rest);
}

static void loop_no_kink(rn_context *ctx) {
  /* the input frame of the rod's last edge, which ends at the joint (1, 0, 0):
   * t along it, d1 = z (the given d1, parallel transported in the plane) */
  double a = 2 * PI * (NLOOP - 1) / NLOOP, t[3] = {1 - cos(a), -sin(a), 0};
  double tn = hypot(t[0], t[1]), F[9], Q[9], QF[9];
  t[0] /= tn;
  t[1] /= tn;
  const double F0[9] = {t[0], t[1], 0, 0, 0, 1, t[1], -t[0], 0}; /* d2 = t x d1 */
  memcpy(F, F0, sizeof F);
  const double u[3] = {0.0, 0.8, 0.6};
  rotation(u, 2.0, Q);
  for (int r = 0; r < 3; ++r) /* every row turned by Q */
    for (int c = 0; c < 3; ++c)
      QF[3 * r + c] =
          Q[3 * c] * F[3 * r] + Q[3 * c + 1] * F[3 * r + 1] + Q[3 * c + 2] * F[3 * r + 2];
  const char *models[2] = {"rigid", "elastic"};
  for (int m = 0; m < 2; ++m) {
    rn_scene *straight = loop(ctx, models[m], "'straight'");
    rn_scene *input = loop(ctx, models[m], "");
    rn_scene *frames = loop_frames(ctx, models[m], F);
    double e_s = 0, e_f = 0, e_i = 0;
    double d1 = compare(rn_scene_network(straight), rn_scene_network(frames), &e_s, &e_f);
    compare(rn_scene_network(straight), rn_scene_network(input), NULL, &e_i);
    printf("loop through a %s joint: rest frames [F, F] vs \"straight\" %.1e (relative); "
           "energies %.10e (straight), %.10e (frames), %.10e (input kink)\n",
           models[m], d1, e_s, e_f, e_i);
    CHECK(d1 <= 1e-13);
    CHECK(fabs(e_i - e_s) > 1e-3 * e_s); /* the input rest stores the kink */
    if (m == 1) {
      /* elastic: the joint's rotation is the fit of the rest frames, so a common
       * rotation of both frames is absorbed exactly */
      rn_scene *turned = loop_frames(ctx, models[m], QF);
      double d2 =
          compare(rn_scene_network(straight), rn_scene_network(turned), NULL, NULL);
      printf("  both frames turned by 2 rad: %.1e (relative)\n", d2);
      CHECK(d2 <= 1e-12);
      rn_scene_destroy(&turned);
    }
    rn_scene_destroy(&straight);
    rn_scene_destroy(&input);
    rn_scene_destroy(&frames);
  }
}

static void expect_error(rn_context *ctx, const char *model, const char *rest,
                         const char *where, const char *reason) {
  char r[1024];
  snprintf(r, sizeof r, "%s", rest);
  char *text = l_json(model, swap_quotes(r));
  rn_scene *s = NULL;
  rn_status st = parse(ctx, text, &s);
  const char *msg = rn_context_last_error(ctx);
  printf("%s -> %s\n", rest, msg);
  CHECK(st < 0);
  CHECK(s == NULL);
  CHECK(strstr(msg, where) != NULL);
  CHECK(strstr(msg, reason) != NULL);
  free(text);
}

#define ID "[[1, 0, 0], [0, 1, 0], [0, 0, 1]]"
static void errors(rn_context *ctx) {
  expect_error(ctx, "rigid", "{'frames': [" ID "]}",
               "joint.json: $.joints[0].rest.frames: ", "expected 2 frames (one per end");
  expect_error(ctx, "elastic", "{'frames': [" ID ", " ID ", " ID "]}",
               "$.joints[0].rest.frames: ", "got 3");
  expect_error(ctx, "rigid", "{'frames': [" ID ", [[1, 0, 0], [0, 1, 0]]]}",
               "$.joints[0].rest.frames[1]: ", "expected 3 rows [t, d1, d2], got 2");
  expect_error(ctx, "rigid", "{'frames': [" ID ", [[1, 0, 0], [0, 1, 0], [0, 0]]]}",
               "$.joints[0].rest.frames[1][2]: ", "expected an array of 3 numbers");
  expect_error(ctx, "rigid",
               "{'frames': [[[1, 0, 0], [0, 1.001, 0], [0, 0, 1]], " ID "]}",
               "$.joints[0].rest.frames[0]: ", "not orthonormal and right-handed");
  expect_error(ctx, "elastic", "{'frames': [" ID ", [[1, 0, 0], [0, 1, 0], [0, 0, -1]]]}",
               "$.joints[0].rest.frames[1]: ", "not orthonormal and right-handed");
  expect_error(ctx, "smooth", "{'frames': [" ID ", " ID "]}",
               "$.joints[0].rest: ", "does not apply to a smooth joint");
  expect_error(ctx, "rigid", "{'frames': [" ID ", " ID "], 'twist': 0}",
               "$.joints[0].rest: ", "not both");
  expect_error(ctx, "rigid", "'bent'", "$.joints[0].rest: ", "{\"frames\"}");
}

int main(void) {
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  scene_equals_api(ctx);
  loop_no_kink(ctx);
  errors(ctx);
  rn_context_destroy(&ctx);
  return rn_test_finish("problems_joint_rest");
}

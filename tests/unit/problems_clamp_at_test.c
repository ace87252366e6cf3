/* problems_clamp_at_test.c - the clamp convention of a scene ("at" of a clamp,
 * docs/scene-format.md): with "at": "midpoint" a rod given by "line" is laid out
 * so that the clamped edge's midpoint is the line's end point (edge h = L /
 * (n - 1.5), the rod starts h/2 before "from"); "vertex" and no "at" give the
 * usual layout bit for bit; both ends at midpoints; errors for a bad value, for
 * a rod given by "vertices" and for too few vertices. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "scene/scene.h"
#include "testutil.h"

static rn_scene *parse(rn_context *ctx, const char *text) {
  rn_scene *s = NULL;
  rn_status st = rn_scene_parse(ctx, "clamp_at.json", text, strlen(text), &s);
  if (st) printf("  error: %s\n", rn_context_last_error(ctx));
  return s;
}

/* A straight rod from (0,0,0) to (2,0,0), nv vertices, clamps as given. */
static void scene_text(char *buf, size_t size, int nv, const char *clamps) {
  snprintf(buf, size,
           "{\"materials\": {\"m\": {\"E\": 1e7, \"nu\": 0.5}},"
           " \"sections\": {\"s\": {\"shape\": \"circle\", \"radius\": 0.01}},"
           " \"rods\": [{\"name\": \"b\", \"material\": \"m\", \"section\": \"s\","
           " \"line\": {\"from\": [0, 0, 0], \"to\": [2, 0, 0], \"vertices\": %d}}],"
           " \"constraints\": [%s]}",
           nv, clamps);
}

static void vertices(rn_scene *s, double *x) {
  rn_network_rod_vertices(rn_scene_network(s), 0, x);
}

static void expect_error(rn_context *ctx, const char *text, const char *what) {
  rn_scene *s = NULL;
  rn_status st = rn_scene_parse(ctx, "clamp_at.json", text, strlen(text), &s);
  CHECK(st != RN_OK && s == NULL);
  CHECK(strstr(rn_context_last_error(ctx), what) != NULL);
  printf("  expected error: %s\n", rn_context_last_error(ctx));
}

int main(void) {
  rn_context *ctx = NULL;
  char text[2048];
  double x[3 * 11], y[3 * 11];
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);

  /* midpoint at the start: h = 2 / 9.5, vertex i at (i - 1/2) h, the last at 2 */
  scene_text(text, sizeof text, 11,
             "{\"type\": \"clamp\", \"rod\": \"b\", \"end\": \"start\", \"at\": "
             "\"midpoint\"}");
  rn_scene *s = parse(ctx, text);
  CHECK(s != NULL);
  if (s) {
    vertices(s, x);
    const double h = 2.0 / 9.5;
    for (int i = 0; i < 11; i++) CHECK_NEAR(x[3 * i], (i - 0.5) * h, 1e-15);
    CHECK(x[30] == 2.0);
    CHECK_NEAR(0.5 * (x[0] + x[3]), 0.0, 1e-15); /* the clamped edge's midpoint */
    rn_scene_destroy(&s);
  }
  /* "vertex" and no "at": the usual layout, bit for bit */
  scene_text(text, sizeof text, 11,
             "{\"type\": \"clamp\", \"rod\": \"b\", \"end\": \"start\", \"at\": "
             "\"vertex\"}");
  s = parse(ctx, text);
  CHECK(s != NULL);
  if (s) vertices(s, x);
  rn_scene_destroy(&s);
  scene_text(text, sizeof text, 11,
             "{\"type\": \"clamp\", \"rod\": \"b\", \"end\": \"start\"}");
  s = parse(ctx, text);
  CHECK(s != NULL);
  if (s) vertices(s, y);
  rn_scene_destroy(&s);
  CHECK(memcmp(x, y, sizeof x) == 0);
  CHECK(x[0] == 0.0 && x[30] == 2.0 && x[3] == 0.2);
  /* both ends at midpoints: h = 2 / 9, symmetric about x = 1 */
  scene_text(text, sizeof text, 11,
             "{\"type\": \"clamp\", \"rod\": \"b\", \"end\": \"start\", \"at\": "
             "\"midpoint\"}, {\"type\": \"clamp\", \"rod\": \"b\", \"end\": \"end\", "
             "\"at\": \"midpoint\"}");
  s = parse(ctx, text);
  CHECK(s != NULL);
  if (s) {
    vertices(s, x);
    for (int i = 0; i < 11; i++) CHECK_NEAR(x[3 * i], (i - 0.5) * 2.0 / 9.0, 1e-15);
    CHECK_NEAR(0.5 * (x[27] + x[30]), 2.0, 1e-15);
    rn_scene_destroy(&s);
  }
  /* errors */
  scene_text(text, sizeof text, 11,
             "{\"type\": \"clamp\", \"rod\": \"b\", \"end\": \"start\", \"at\": "
             "\"middle\"}");
  expect_error(ctx, text, "$.constraints[0].at: expected \"midpoint\" or \"vertex\"");
  scene_text(text, sizeof text, 2,
             "{\"type\": \"clamp\", \"rod\": \"b\", \"end\": \"start\", \"at\": "
             "\"midpoint\"}, {\"type\": \"clamp\", \"rod\": \"b\", \"end\": \"end\", "
             "\"at\": \"midpoint\"}");
  expect_error(ctx, text, "at both ends needs at least 3 vertices");
  expect_error(ctx,
               "{\"materials\": {\"m\": {\"E\": 1e7, \"nu\": 0.5}},"
               " \"sections\": {\"s\": {\"shape\": \"circle\", \"radius\": 0.01}},"
               " \"rods\": [{\"name\": \"b\", \"material\": \"m\", \"section\": \"s\","
               " \"vertices\": [[0, 0, 0], [1, 0, 0], [2, 0, 0]]}],"
               " \"constraints\": [{\"type\": \"clamp\", \"rod\": \"b\", \"end\": "
               "\"start\", \"at\": \"midpoint\"}]}",
               "lays out a rod given by \"line\"");
  rn_context_destroy(&ctx);
  return rn_test_finish("problems_clamp_at");
}

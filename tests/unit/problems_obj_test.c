/* problems_obj_test.c - the OBJ line-graph reader (problems/scene/obj.h): a valid
 * file with every accepted feature reads to the right graph, and every class
 * of bad input gets a non-zero status and ONE line "g.obj:LINE: reason"
 * (or "g.obj: reason" for a file-level problem).
 * argv[1]: a folder with the seed files (tests/data/obj). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/obj.h"
#include "testutil.h"

/* Comments, ignored records, CRLF, forward and negative (relative) indices,
 * "i/t" and "i//n" index forms, a polyline, blank lines. */
static const char good[] = "# a small graph\r\n"
                           "mtllib x.mtl\n"
                           "o graph\n"
                           "g group\n"
                           "s off\n"
                           "v 0 0 0      # 1\n"
                           "v 1 0 0\r\n"
                           "vn 0 0 1\n"
                           "vt 0.5 0.5\n"
                           "usemtl m\n"
                           "\n"
                           "v 1 1 0\n"
                           "l 1 2 -1\n" /* polyline 1-2, 2-3 */
                           "l 3/1 4//2\n"
                           "v\t0   1 0\n" /* 4, after its use */
                           "l -4 -1\n"    /* 1-4 */
                           "v 5 5 5\n";   /* unused */

static void check_good(rn_context *ctx) {
  rn_obj_graph *g = NULL;
  CHECK_STATUS(rn_obj_graph_parse(ctx, "g.obj", good, strlen(good), &g), RN_OK);
  if (!g) {
    fprintf(stderr, "%s\n", rn_context_last_error(ctx));
    return;
  }
  CHECK(rn_obj_graph_num_vertices(g) == 5);
  CHECK(rn_obj_graph_num_segments(g) == 4);
  static const int want[4][2] = {{0, 1}, {1, 2}, {2, 3}, {0, 3}};
  static const int lines[4] = {13, 13, 14, 16};
  for (int s = 0; s < 4; s++) {
    int e[2] = {-1, -1};
    CHECK_STATUS(rn_obj_graph_segment(g, s, e), RN_OK);
    CHECK(e[0] == want[s][0] && e[1] == want[s][1]);
    CHECK(rn_obj_graph_segment_line(g, s) == lines[s]);
  }
  static const int valence[5] = {2, 2, 2, 2, 0};
  for (int v = 0; v < 5; v++) CHECK(rn_obj_graph_valence(g, v) == valence[v]);
  double x[3];
  CHECK_STATUS(rn_obj_graph_vertex(g, 3, x), RN_OK);
  CHECK(x[0] == 0 && x[1] == 1 && x[2] == 0);
  CHECK(rn_obj_graph_vertex_line(g, 3) == 15);
  CHECK_STATUS(rn_obj_graph_vertex(g, 5, x), RN_ERR_RANGE);
  CHECK_STATUS(rn_obj_graph_segment(g, -1, (int[2]){0, 0}), RN_ERR_RANGE);
  CHECK(rn_obj_graph_valence(g, 7) == -1);
  rn_obj_graph_destroy(&g);
  CHECK(g == NULL);
  rn_obj_graph_destroy(&g);
  rn_obj_graph_destroy(NULL);
}

typedef struct bad_case {
  const char *what, *text;
  const char *where;  /* expected text after "g.obj" */
  const char *reason; /* expected substring */
} bad_case;

#define TRI "v 0 0 0\nv 1 0 0\nv 0 1 0\n"

static const bad_case cases[] = {
    {"bad number", "v 0 0 0\nv 1 x 0\n", ":2: ", "coordinate y: bad number 'x'"},
    {"number with junk", "v 0 0 0\nv 1 0 2z\n", ":2: ", "coordinate z: bad number '2z'"},
    {"NaN", "v nan 0 0\n", ":1: ", "coordinate x: 'nan' is not a finite number"},
    {"infinity", "v 0 inf 0\n", ":1: ", "coordinate y: 'inf' is not a finite number"},
    {"overflow", "v 0 0 1e999\n", ":1: ", "coordinate z: '1e999' is not a finite number"},
    {"two coordinates", "v 1 2\n", ":1: ", "needs 3 coordinates (x y z), got 2"},
    {"four coordinates", "v 1 2 3 1\n", ":1: ", "exactly 3 coordinates"},
    {"index out of range", TRI "l 1 4\n",
     ":4: ", "vertex index 4 is out of range (the file defines 3 vertices)"},
    {"index zero", TRI "l 0 1\n", ":4: ", "vertex index 0 is invalid"},
    {"relative index out of range", TRI "l 1 -4\n", ":4: ",
     "relative vertex index -4 is out of range (3 vertices defined before this line)"},
    {"index not a number", TRI "l 1 b\n", ":4: ", "bad vertex index 'b'"},
    {"fractional index", TRI "l 1 2.5\n", ":4: ", "bad vertex index '2.5'"},
    {"huge index", TRI "l 1 99999999999999999999\n", ":4: ", "bad vertex index"},
    {"one index", TRI "l 2\n", ":4: ", "needs at least 2 vertex indices, got 1"},
    {"segment to itself", TRI "l 1 2\nl 3 3\n",
     ":5: ", "segment from vertex 3 to itself"},
    {"relative self loop", TRI "l 3 -1\n", ":4: ", "segment from vertex 3 to itself"},
    {"duplicate segment", TRI "l 1 2\nl 2 3\nl 2 1\n",
     ":6: ", "segment 2-1 is given twice (first on line 4)"},
    {"duplicate in a polyline", TRI "l 1 2 3 1 2\n", ":4: ", "is given twice"},
    {"zero length", "v 0 0 0\nv 1 0 0\nv 1 0 0\nl 1 2\nl 2 3\n",
     ":5: ", "segment 2-3 has zero length"},
    {"coincident vertices", "v 0 0 0\nv 1 0 0\nv 1 0 0\nv 2 0 0\nl 1 2\nl 3 4\n",
     ":3: ", "vertex 3 is at the same position as vertex 2 (line 2)"},
    {"overflowing length", "v -1e308 0 0\nv 1e308 0 0\nl 1 2\n", ":3: ", "too long"},
    {"faces", TRI "f 1 2 3\n", ":4: ", "faces (f records) are not supported"},
    {"unknown record", TRI "curv 0 1 1 2\n", ":4: ", "unknown record 'curv'"},
    {"no segments", TRI, ": ", "no line segments"},
    {"empty file", "", ": ", "no line segments"},
    {"only comments", "# nothing\n\n", ": ", "no line segments"},
};

static void check_case(rn_context *ctx, const bad_case *c) {
  rn_obj_graph *g = (rn_obj_graph *)1;
  rn_status st = rn_obj_graph_parse(ctx, "g.obj", c->text, strlen(c->text), &g);
  const char *msg = rn_context_last_error(ctx);
  char expect[64];
  snprintf(expect, sizeof expect, "g.obj%s", c->where);
  int ok = st == RN_ERR_PARSE && g == NULL && strncmp(msg, expect, strlen(expect)) == 0 &&
           strstr(msg, c->reason) != NULL && strchr(msg, '\n') == NULL;
  CHECK(ok);
  if (!ok) fprintf(stderr, "case '%s': status %d, message: %s\n", c->what, (int)st, msg);
  rn_obj_graph_destroy(&g);
}

/* A NUL byte, a text without a final newline, and the file loader. */
static void check_special(rn_context *ctx, const char *dir) {
  const char nul[] = "v 0 0 0\nv 1\0 0 0\nl 1 2\n";
  rn_obj_graph *g = NULL;
  CHECK_STATUS(rn_obj_graph_parse(ctx, "g.obj", nul, sizeof nul - 1, &g), RN_ERR_PARSE);
  CHECK(strcmp(rn_context_last_error(ctx), "g.obj:2: NUL byte in the file") == 0);
  const char noeol[] = "v 0 0 0\nv 1 0 0\nl 1 2";
  CHECK_STATUS(rn_obj_graph_parse(ctx, "g.obj", noeol, sizeof noeol - 1, &g), RN_OK);
  CHECK(rn_obj_graph_num_segments(g) == 1);
  rn_obj_graph_destroy(&g);
  CHECK_STATUS(rn_obj_graph_load(ctx, "/nonexistent/g.obj", &g), RN_ERR_IO);
  CHECK(strstr(rn_context_last_error(ctx), "/nonexistent/g.obj: cannot open") != NULL);
  char path[1024];
  CHECK_STATUS(rn_obj_graph_load(ctx, dir, &g), RN_ERR_IO); /* a directory */
  snprintf(path, sizeof path, "%s: not a regular file", dir);
  CHECK(strcmp(rn_context_last_error(ctx), path) == 0);
  CHECK(g == NULL);
  /* a seed file: the 2 x 2 square grid */
  snprintf(path, sizeof path, "%s/square_2x2.obj", dir);
  CHECK_STATUS(rn_obj_graph_load(ctx, path, &g), RN_OK);
  CHECK(rn_obj_graph_num_vertices(g) == 9);
  CHECK(rn_obj_graph_num_segments(g) == 12);
  int hist[5] = {0};
  for (int v = 0; v < 9; v++) hist[rn_obj_graph_valence(g, v)]++;
  CHECK(hist[2] == 4 && hist[3] == 4 && hist[4] == 1);
  rn_obj_graph_destroy(&g);
}

int main(int argc, char **argv) {
  if (argc < 2) {
    fprintf(stderr, "usage: problems_obj_test DATA_DIR\n");
    return 2;
  }
  rn_context *ctx = NULL;
  CHECK_STATUS(rn_context_create(&ctx), RN_OK);
  check_good(ctx);
  for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) check_case(ctx, &cases[i]);
  check_special(ctx, argv[1]);
  rn_context_destroy(&ctx);
  return rn_test_finish("problems_obj");
}

/* fuzz_obj.c - libFuzzer target for the OBJ line-graph reader
 * (problems/scene/obj.h).  The contract checked on every input:
 *  - rejected: no graph, a negative status, and ONE non-empty line of
 *    message that starts with the label;
 *  - accepted: at least one segment; every segment joins two different
 *    vertices in range, no unordered pair twice, positive finite length;
 *    finite coordinates; the valences count the segment ends; and the graph
 *    built as a network (2 edges per segment, joints at valence >= 2,
 *    rigid and elastic alternating) either finalizes and evaluates to finite
 *    energy and gradient, or is rejected by the library with a one-line
 *    message (e.g. two joints closer than its tolerance).
 * A broken rule aborts, so libFuzzer keeps the input as a crash.
 *
 * Built without -DRN_LIBFUZZER it has a main() that replays files given on
 * the command line through the same check (ctest fuzz_obj_replay, label
 * unit, over the seed corpus tests/data/obj/). */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scene/obj.h"

/* Graphs with more segments are only parsed, not built (fuzzing speed). */
#define FUZZ_MAX_BUILD_SEGMENTS 2000

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static const char *label = "fuzz.obj";

static int broken(const char *rule, const char *msg) {
  fprintf(stderr, "fuzz_obj: %s: broken rule: %s (message: %s)\n", label, rule,
          msg ? msg : "");
  return 1;
}

static int one_line(const char *msg, const char *prefix) {
  return msg && *msg && !strchr(msg, '\n') && strncmp(msg, prefix, strlen(prefix)) == 0;
}

static int check_segments(const rn_obj_graph *g) {
  int nv = rn_obj_graph_num_vertices(g), ns = rn_obj_graph_num_segments(g), bad = 0;
  int *count = calloc((size_t)(nv ? nv : 1), sizeof *count);
  if (!count) return 0;
  for (int s = 0; s < ns && !bad; s++) {
    int e[2];
    double p[3], q[3];
    bad |= rn_obj_graph_segment(g, s, e) != RN_OK || e[0] == e[1] || e[0] < 0 ||
           e[1] < 0 || e[0] >= nv || e[1] >= nv;
    if (bad) break;
    rn_obj_graph_vertex(g, e[0], p);
    rn_obj_graph_vertex(g, e[1], q);
    double l = sqrt((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) +
                    (q[2] - p[2]) * (q[2] - p[2]));
    bad |= !(l > 0) || !isfinite(l);
    count[e[0]]++;
    count[e[1]]++;
    for (int t = 0; t < s && !bad && s < 4000; t++) { /* quadratic: small inputs */
      int f[2];
      rn_obj_graph_segment(g, t, f);
      bad |= (f[0] == e[0] && f[1] == e[1]) || (f[0] == e[1] && f[1] == e[0]);
    }
  }
  for (int v = 0; v < nv && !bad; v++) bad |= count[v] != rn_obj_graph_valence(g, v);
  free(count);
  return bad ? broken("segments: range, self loop, duplicate, length or valence", NULL)
             : 0;
}

/* Rods of 2 edges per segment, joints at valence >= 2; finalize and one
 * energy and gradient at the initial state. */
static int build_network(rn_context *ctx, const rn_obj_graph *g) {
  rn_network *net = NULL;
  rn_material m;
  rn_section sec;
  rn_material_from_E_nu(1, 0.3, 0, &m);
  rn_section_circle(0.01, &sec);
  if (rn_network_create(ctx, &net) != RN_OK) return broken("network_create", NULL);
  int ns = rn_obj_graph_num_segments(g), nv = rn_obj_graph_num_vertices(g), rule = 0;
  rn_status st = RN_OK;
  for (int s = 0; s < ns && !st; s++) {
    int e[2], rod;
    double x[9];
    rn_obj_graph_segment(g, s, e);
    rn_obj_graph_vertex(g, e[0], x);
    rn_obj_graph_vertex(g, e[1], x + 6);
    for (int k = 0; k < 3; k++) x[3 + k] = 0.5 * (x[k] + x[6 + k]);
    st = rn_network_add_rod(net, NULL, 3, x, NULL, &rod);
    if (!st) st = rn_network_set_material(net, rod, -1, &m);
    if (!st) st = rn_network_set_section(net, rod, -1, &sec);
  }
  int *rods = malloc(2 * (size_t)ns * sizeof *rods),
      *ends = malloc(2 * (size_t)ns * sizeof *ends);
  for (int v = 0; v < nv && !st && rods && ends; v++) {
    int n = 0, joint;
    if (rn_obj_graph_valence(g, v) < 2) continue;
    for (int s = 0; s < ns; s++) {
      int e[2];
      rn_obj_graph_segment(g, s, e);
      for (int k = 0; k < 2; k++)
        if (e[k] == v) {
          rods[n] = s;
          ends[n++] = k ? RN_END : RN_START;
        }
    }
    st = rn_network_add_joint(net, NULL, v % 2 ? RN_JOINT_RIGID : RN_JOINT_ELASTIC, n,
                              rods, ends, &joint);
  }
  free(rods);
  free(ends);
  if (!st) st = rn_network_finalize(net);
  if (st < 0 && !one_line(rn_context_last_error(ctx), ""))
    rule = broken("library rejection without a one-line message",
                  rn_context_last_error(ctx));
  if (!st) {
    size_t n = rn_network_num_dofs(net);
    double *x = malloc((n ? n : 1) * sizeof *x), *gr = malloc((n ? n : 1) * sizeof *gr);
    double E = 0;
    if (x && gr && rn_network_get_dofs(net, x) == RN_OK) {
      st = rn_network_gradient(net, x, &E, gr);
      int finite = isfinite(E);
      for (size_t i = 0; i < n && !st; i++) finite &= isfinite(gr[i]) != 0;
      if (st < 0 || (!st && !finite))
        rule = broken("energy and gradient at the initial state",
                      rn_context_last_error(ctx));
    }
    free(x);
    free(gr);
  }
  rn_network_destroy(&net);
  return rule;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  rn_context *ctx = NULL;
  if (rn_context_create(&ctx) != RN_OK) return 0;
  rn_obj_graph *g = NULL;
  rn_status st = rn_obj_graph_parse(ctx, label, (const char *)data, size, &g);
  int bad = 0;
  if (st) {
    bad |= (st > 0 || g != NULL)
               ? broken("rejected with a non-negative status or a graph", NULL)
               : 0;
    bad |= !one_line(rn_context_last_error(ctx), label)
               ? broken("one line starting with the label", rn_context_last_error(ctx))
               : 0;
  } else {
    bad |=
        rn_obj_graph_num_segments(g) < 1 ? broken("accepted without segments", NULL) : 0;
    for (int v = 0; v < rn_obj_graph_num_vertices(g) && !bad; v++) {
      double x[3];
      rn_obj_graph_vertex(g, v, x);
      if (!isfinite(x[0]) || !isfinite(x[1]) || !isfinite(x[2]))
        bad |= broken("finite coordinates", NULL);
    }
    if (!bad) bad |= check_segments(g);
    if (!bad && rn_obj_graph_num_segments(g) <= FUZZ_MAX_BUILD_SEGMENTS)
      bad |= build_network(ctx, g);
  }
  rn_obj_graph_destroy(&g);
  rn_context_destroy(&ctx);
  if (bad) abort();
  return 0;
}

#ifndef RN_LIBFUZZER
/* Replay: fuzz_obj FILE... (each file must keep the contract). */
int main(int argc, char **argv) {
  for (int i = 1; i < argc; i++) {
    FILE *f = fopen(argv[i], "rb");
    if (!f) {
      fprintf(stderr, "fuzz_obj: cannot open %s\n", argv[i]);
      return 1;
    }
    static unsigned char buf[1 << 20];
    size_t n = fread(buf, 1, sizeof buf, f);
    fclose(f);
    label = argv[i];
    LLVMFuzzerTestOneInput(buf, n); /* aborts on a broken rule */
    printf("fuzz_obj: ok: %s\n", argv[i]);
  }
  printf("fuzz_obj: %d file(s) keep the contract\n", argc - 1);
  return 0;
}
#endif

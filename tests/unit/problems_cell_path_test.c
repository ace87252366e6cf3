/* problems_cell_path_test.c - the library's macroscopic load path of a periodic
 * cell through its public C entry (rn_cell_path_run, rodnet_solve.h) without the
 * command: a waypoint path on the honeycomb cell (strain, then stress control,
 * as tests/data/periodic/paths/hc_mixed.json) gives the records `rodnet
 * homogenize --path-file` wrote before the path moved into the library
 * (issue 23); the progress callback sees every step; bad arguments are refused
 * with a message; rn_homogenization_invert inverts and detects singularity.
 * Argument: the scene tests/data/periodic/hc_stress.json. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "rodnet_solve.h"
#include "scene/scene.h"
#include "testutil.h"

typedef struct progress_log {
  int calls, last_done, in_order;
} progress_log;

static void on_step(void *user, const rn_cell_path_result *r) {
  progress_log *log = user;
  log->in_order &= r->done == log->last_done + 1;
  log->last_done = r->done;
  ++log->calls;
}

static void check_invert(void) {
  const double C[9] = {4, 1, 0, 1, 3, 0, 0, 0, 2}, singular[4] = {1, 2, 2, 4};
  double S[9], T[4];
  CHECK(rn_homogenization_invert(3, C, S) == 1);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double p = 0.0;
      for (int k = 0; k < 3; ++k) p += S[i * 3 + k] * C[k * 3 + j];
      CHECK_NEAR(p, i == j ? 1.0 : 0.0, 1e-15);
    }
  CHECK(rn_homogenization_invert(2, singular, T) == 0);
  CHECK(rn_homogenization_invert(7, C, S) == 0);
}

static void check_refusals(rn_context *ctx, rn_network *net) {
  rn_cell_path_segment g;
  rn_cell_path_result r;
  memset(&g, 0, sizeof g);
  CHECK_STATUS(rn_cell_path_run(net, 0, &g, NULL, &r), RN_ERR_ARG);
  CHECK(strstr(rn_context_last_error(ctx), "no segment") != NULL);
  CHECK_STATUS(rn_cell_path_run(net, 1, &g, NULL, NULL), RN_ERR_ARG);
  CHECK_STATUS(rn_cell_path_run(net, 1, &g, NULL, &r), RN_ERR_ARG); /* 0 steps */
  CHECK(strstr(rn_context_last_error(ctx), "segment 0 has no step") != NULL);
  rn_cell_path_result_free(&r);
  rn_cell_path_result_free(NULL);
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  rn_scene *sc = NULL;
  CHECK(argc == 2);
  check_invert();
  if (argc != 2 || rn_context_create(&ctx) || rn_scene_load(ctx, argv[1], &sc)) {
    rn_test_fail(__FILE__, __LINE__, "cannot load the scene: %s",
                 ctx ? rn_context_last_error(ctx) : "no context");
    return rn_test_finish("problems_cell_path");
  }
  rn_network *net = rn_scene_network(sc);
  check_refusals(ctx, net);
  /* hc_mixed.json: E11 to 1e-4 at zero S22, S12 in 2 steps, then every component
   * stress-controlled to (2e-9, 1e-9, 0) in 2 steps */
  rn_cell_path_segment seg[2];
  memset(seg, 0, sizeof seg);
  seg[0].steps = 2;
  seg[0].target[0] = 1e-4;
  seg[0].stress[1] = seg[0].stress[2] = 1;
  seg[1].steps = 2;
  seg[1].stress[0] = seg[1].stress[1] = seg[1].stress[2] = 1;
  seg[1].target[0] = 2e-9;
  seg[1].target[1] = 1e-9;
  rn_cell_path_options o;
  rn_cell_path_options_default(&o);
  CHECK(o.modes == RN_BLOCH_ALL && o.grid == 0 && o.progress == NULL);
  progress_log log = {0, 0, 1};
  o.grid = 2;
  o.progress = on_step;
  o.user = &log;
  rn_cell_path_result r;
  CHECK_STATUS(rn_cell_path_run(net, 2, seg, &o, &r), RN_OK);
  CHECK(r.ns == 3 && r.nseg == 2 && r.steps == 4 && r.done == 4);
  CHECK(r.stopped == NULL && r.limit_end == 0 && !r.inst.found);
  CHECK(log.calls == 4 && log.in_order && log.last_done == 4);
  for (int k = 0; k <= r.done; ++k) {
    CHECK_NEAR(r.step[k].t, 0.5 * k, 1e-15);
    CHECK(r.step[k].converged && r.step[k].stable == 1);
    CHECK(r.step[k].outer == (k ? 2 : 0)); /* mixed iterations */
    CHECK(k == 0 || r.step[k].seg == (k - 1) / 2);
  }
  /* the strain-controlled E11 of the first leg exactly on its line */
  CHECK(r.step[1].strain[0] == 5e-5 && r.step[2].strain[0] == 1e-4);
  /* the second leg starts from the stress reached (as the command wrote it) */
  for (int v = 0; v < 3; ++v) CHECK(r.seg[1].start[v] == r.step[2].stress[v]);
  CHECK_REL(r.seg[1].start[0], 7.361969968679578e-10, 1e-8);
  /* the end: the stresses reached, and the strain the command wrote */
  CHECK_REL(r.step[4].stress[0], 2e-9, 1e-8);
  CHECK_REL(r.step[4].stress[1], 1e-9, 1e-8);
  CHECK_REL(r.step[4].strain[0], 0.0001369287712648894, 1e-8);
  CHECK_REL(r.step[4].strain[1], -0.00013336902315828425, 1e-8);
  CHECK(isfinite(r.step[4].tangent_min) && r.step[4].tangent_min > 0.0);
  CHECK(isnan(r.step[0].tangent_min)); /* no stress control at rest */
  rn_cell_path_result_free(&r);
  CHECK(r.step == NULL && r.seg == NULL && r.done == 0);
  rn_scene_destroy(&sc);
  rn_context_destroy(&ctx);
  return rn_test_finish("problems_cell_path");
}

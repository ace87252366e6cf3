/* problems_cell_post_test.c - past the first instability of a cell path through the
 * library's public C entries, without the command (issue 23: the post-buckling
 * numerics out of the command layer): rn_cell_instability_supercell on wave
 * vectors of known period, rn_scene_load_supercell and rn_scene_supercell_copies
 * (rodnet_scene.h), rn_cell_post_buckling on the 2 x 2 supercell of the honeycomb
 * under equibiaxial compression (the bifurcated branch below the principal one in
 * energy and compressive stress, a verified minimum where the principal state is
 * not, its displacement on the M points: no cell-periodic share), and
 * rn_cell_pattern_state; bad arguments are refused with a message.
 * Argument: the honeycomb cell of `rodnet generate honeycomb --periodic
 * --joint-model rigid --edges-per-rod 8 --slenderness 0.05`. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "rodnet_scene.h"
#include "rodnet_solve.h"
#include "testutil.h"

static void on_step(void *user, const rn_cell_post_result *r) {
  int *calls = user;
  CHECK(r->done == *calls + 1);
  *calls = r->done;
}

/* Periods of synthetic wave vectors: 2D M point, a K point (1/3, 1/3) with its
 * star, an incommensurate one, a 3D X point, and what is not a local instability. */
static void check_supercell_of_wave_vector(void) {
  rn_cell_path_instability in;
  int rep[3];
  memset(&in, 0, sizeof in);
  in.found = 1;
  in.xi[0] = 0.5;
  in.xi[1] = -0.5;
  CHECK(rn_cell_instability_supercell(&in, 2, rep) == 1);
  CHECK(rep[0] == 2 && rep[1] == 2 && rep[2] == 1);
  in.nequiv = 2; /* the star: (1/3, 1/3) and (-2/3, 1/3) */
  in.xi_equiv[0][0] = in.xi_equiv[0][1] = 1.0 / 3.0;
  in.xi_equiv[1][0] = -2.0 / 3.0;
  in.xi_equiv[1][1] = 1.0 / 3.0;
  in.xi[0] = in.xi[1] = 1.0 / 3.0;
  CHECK(rn_cell_instability_supercell(&in, 2, rep) == 1);
  CHECK(rep[0] == 3 && rep[1] == 3 && rep[2] == 1);
  in.nequiv = 0;
  in.xi[0] = 0.1234567;
  CHECK(rn_cell_instability_supercell(&in, 2, rep) == 0);
  in.xi[0] = 0.5;
  in.xi[1] = 0.0;
  in.xi[2] = 0.25;
  CHECK(rn_cell_instability_supercell(&in, 3, rep) == 1);
  CHECK(rep[0] == 2 && rep[1] == 1 && rep[2] == 4);
  in.kind_macroscopic = 1;
  CHECK(rn_cell_instability_supercell(&in, 3, rep) == 0);
  in.kind_macroscopic = 0;
  in.found = 0;
  CHECK(rn_cell_instability_supercell(&in, 2, rep) == 0);
  CHECK(rn_cell_instability_supercell(NULL, 2, rep) == 0);
  in.found = 1;
  CHECK(rn_cell_instability_supercell(&in, 4, rep) == 0);
}

static void check_refusals(rn_context *ctx, rn_network *net, const rn_cell_path_result *p,
                           const char *scene) {
  rn_cell_post_options o;
  rn_cell_post_result r;
  rn_cell_post_options_default(&o);
  CHECK(o.steps == 4 && o.modes == RN_BLOCH_ALL && o.rep[0] == 1 && o.rep[2] == 1);
  CHECK(o.rod_base == NULL && o.progress == NULL);
  rn_cell_path_result none = *p;
  none.inst.found = 0;
  CHECK_STATUS(rn_cell_post_buckling(net, &none, &o, &r), RN_ERR_ARG);
  CHECK(strstr(rn_context_last_error(ctx), "no local instability") != NULL);
  o.steps = 0;
  CHECK_STATUS(rn_cell_post_buckling(net, p, &o, &r), RN_ERR_ARG);
  CHECK(strstr(rn_context_last_error(ctx), "steps 0") != NULL);
  o.steps = 2;
  o.rep[2] = 2; /* past the dimension of a 2D cell */
  CHECK_STATUS(rn_cell_post_buckling(net, p, &o, &r), RN_ERR_ARG);
  CHECK(strstr(rn_context_last_error(ctx), "rep[2] = 2") != NULL);
  CHECK_STATUS(rn_cell_post_buckling(net, p, NULL, &r), RN_ERR_ARG);
  rn_cell_post_result_free(&r);
  rn_cell_post_result_free(NULL);
  double ev, amp;
  int conv;
  CHECK_STATUS(
      rn_cell_pattern_state(net, &p->inst, 0, RN_BLOCH_ALL, 0.05, &ev, &amp, &conv),
      RN_ERR_ARG);
  CHECK_STATUS(
      rn_cell_pattern_state(net, &p->inst, 1, RN_BLOCH_ALL, NAN, &ev, &amp, &conv),
      RN_ERR_ARG);
  rn_scene *sc = NULL;
  const int rep[3] = {2, 0, 1};
  CHECK_STATUS(rn_scene_load_supercell(ctx, scene, 2, rep, 0, &sc), RN_ERR_ARG);
  CHECK(sc == NULL && strstr(rn_context_last_error(ctx), "0 copies in direction 2"));
  CHECK_STATUS(rn_scene_load_supercell(ctx, scene, 3, (const int[3]){1, 1, 1}, 1, &sc),
               RN_ERR_ARG);
  CHECK_STATUS(rn_scene_load_supercell(ctx, "/nonexistent/cell.json", 2,
                                       (const int[3]){2, 2, 1}, 0, &sc),
               RN_ERR_IO);
  CHECK(rn_scene_supercell_copies(NULL, NULL, NULL) == RN_ERR_ARG);
}

/* The bifurcated branch of the pinned 2 x 2 supercell (check_post_buckling.py's
 * assertions on the command's RESULT.json, here on the library's result). */
static void check_post_buckling(rn_context *ctx, const char *scene,
                                const rn_cell_path_result *p) {
  rn_cell_post_options o;
  rn_cell_post_options_default(&o);
  CHECK(rn_cell_instability_supercell(&p->inst, 2, o.rep) == 1);
  CHECK(o.rep[0] == 2 && o.rep[1] == 2 && o.rep[2] == 1);
  rn_scene *sc = NULL;
  CHECK_STATUS(rn_scene_load_supercell(ctx, scene, 2, o.rep, 1, &sc), RN_OK);
  if (!sc) return;
  rn_network *net = rn_scene_network(sc);
  int nrod = rn_network_num_rods(net);
  CHECK(nrod == 12); /* 4 copies of the 3 struts */
  int *base = malloc((size_t)nrod * sizeof *base);
  int *cell = malloc(3 * (size_t)nrod * sizeof *cell);
  CHECK_STATUS(rn_scene_supercell_copies(sc, base, cell), RN_OK);
  int own = 0, coord_sum = 0;
  for (int r = 0; r < nrod; ++r) {
    CHECK(base[r] >= 0 && base[r] < nrod && base[base[r]] == base[r]);
    own += base[r] == r;
    coord_sum += cell[3 * r] + cell[3 * r + 1] + cell[3 * r + 2];
    CHECK(cell[3 * r + 2] == 0);
    if (base[r] == r) CHECK(cell[3 * r] == 0 && cell[3 * r + 1] == 0);
  }
  CHECK(own == 3 && coord_sum == 3 * (0 + 1 + 1 + 2));
  int calls = 0;
  o.steps = 4; /* as the command's test: 3 steps land on a less symmetric minimum */
  o.modes = RN_BLOCH_IN_PLANE;
  o.rod_base = base;
  o.rod_cell = cell;
  o.progress = on_step;
  o.user = &calls;
  rn_cell_post_result r;
  CHECK_STATUS(rn_cell_post_buckling(net, p, &o, &r), RN_OK);
  CHECK(calls == 4 && r.done == 4 && r.steps == 4 && r.copies == 4);
  CHECK(r.rep[0] == 2 && r.rep[1] == 2 && r.rep[2] == 1);
  /* critical there: at round-off against the Bloch eigenvalues past it */
  CHECK(p->inst.neig > 1 && p->inst.eig[0] < 0.0);
  CHECK(fabs(r.mode_eigenvalue) < 1e-8 * p->inst.eig[p->inst.neig - 1]);
  CHECK(r.perturbation > 0.0);
  double gap = 0.0, amp = 0.0;
  for (int j = 0; j < r.done; ++j) {
    const rn_cell_post_step *s = &r.step[j];
    CHECK(s->converged && s->verified && s->lowest > 0.0);
    CHECK(!s->principal_verified && s->principal_lowest < 0.0);
    CHECK(s->energy < s->principal_energy);
    CHECK(s->strain[0] < p->inst.strain[0] && s->strain[0] == s->strain[1]);
    for (int v = 0; v < 2; ++v)
      CHECK(s->principal_stress[v] < s->stress[v] && s->stress[v] < 0.0);
    CHECK(s->stress[0] - s->principal_stress[0] > gap); /* a growing margin */
    CHECK(s->amplitude > amp);
    gap = s->stress[0] - s->principal_stress[0];
    amp = s->amplitude;
  }
  /* the harmonics of a 2 x 2 supercell: (0, 0), (1/2, 0), (0, 1/2), (1/2, 1/2),
   * shares summing to 1, the cell-periodic one (0, 0) negligible, the three M
   * points of the honeycomb's star equal */
  CHECK(r.nharm == 4);
  double total = 0.0, periodic = 1.0;
  for (int h = 0; h < r.nharm; ++h) {
    total += r.harm[h];
    if (fabs(r.harm_xi[h][0]) < 1e-12 && fabs(r.harm_xi[h][1]) < 1e-12)
      periodic = r.harm[h];
    else
      CHECK_NEAR(r.harm[h], 1.0 / 3.0, 1e-3);
  }
  CHECK_NEAR(total, 1.0, 1e-12);
  CHECK(periodic < 1e-3);
  rn_cell_post_result_free(&r);
  CHECK(r.step == NULL && r.done == 0);
  free(base);
  free(cell);
  rn_scene_destroy(&sc);
}

/* The pattern drawn: the principal state at the critical strain (nearly critical
 * there: its lowest eigenvalue close to 0) plus the mode at 5 % of the cell size. */
static void check_pattern_state(rn_context *ctx, const char *scene,
                                const rn_cell_path_result *p) {
  int rep[3];
  CHECK(rn_cell_instability_supercell(&p->inst, 2, rep) == 1);
  rn_scene *sc = NULL;
  CHECK_STATUS(rn_scene_load_supercell(ctx, scene, 2, rep, 0, &sc), RN_OK);
  if (!sc) return;
  rn_network *net = rn_scene_network(sc);
  double ev = NAN, amp = NAN, area = 0.0;
  int conv = 0, dim = 0;
  CHECK_STATUS(
      rn_cell_pattern_state(net, &p->inst, 4, RN_BLOCH_IN_PLANE, 0.05, &ev, &amp, &conv),
      RN_OK);
  rn_network_cell_info(net, &dim, NULL, &area, NULL);
  CHECK(conv == 1 && dim == 2);
  CHECK_REL(amp, 0.05 * sqrt(area / 4.0), 1e-12);
  CHECK(isfinite(ev) && fabs(ev) < 1e-8 * p->inst.eig[p->inst.neig - 1]);
  rn_scene_destroy(&sc);
}

int main(int argc, char **argv) {
  rn_context *ctx = NULL;
  rn_scene *sc = NULL;
  check_supercell_of_wave_vector();
  if (argc != 2 || rn_context_create(&ctx) || rn_scene_load(ctx, argv[1], &sc)) {
    rn_test_fail(__FILE__, __LINE__, "cannot load the scene: %s",
                 ctx ? rn_context_last_error(ctx) : "no context");
    return rn_test_finish("problems_cell_post");
  }
  /* `homogenize --path -0.004,-0.004,0 --steps 8 --modes in-plane --bloch-grid 4` */
  rn_cell_path_segment seg;
  memset(&seg, 0, sizeof seg);
  seg.steps = 8;
  seg.target[0] = seg.target[1] = -0.004;
  rn_cell_path_options po;
  rn_cell_path_options_default(&po);
  po.grid = 4;
  po.modes = RN_BLOCH_IN_PLANE;
  rn_cell_path_result p;
  CHECK_STATUS(rn_cell_path_run(rn_scene_network(sc), 1, &seg, &po, &p), RN_OK);
  CHECK(p.inst.found && !p.inst.kind_macroscopic);
  check_refusals(ctx, rn_scene_network(sc), &p, argv[1]);
  if (p.inst.found && !p.inst.kind_macroscopic) {
    check_post_buckling(ctx, argv[1], &p);
    check_pattern_state(ctx, argv[1], &p);
  }
  rn_cell_path_result_free(&p);
  rn_scene_destroy(&sc);
  rn_context_destroy(&ctx);
  return rn_test_finish("problems_cell_post");
}

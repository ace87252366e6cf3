/* homog_post.c - `rodnet homogenize --path ... --post-buckling P`: the supercell
 * scene the critical wave vector calls for, the library's continuation past the
 * first (local) instability on it (rn_cell_post_buckling, rodnet_solve.h), its
 * progress lines, pattern files and RESULT.json member (homog_path.h;
 * docs/homogenization.md, "Post-buckling"). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/homog_path.h"
#include "scene/scene.h"
#include "scene/vtk.h"

#ifndef RN_RENDER_VTU_SCRIPT
#define RN_RENDER_VTU_SCRIPT "render_vtu.py"
#endif

rn_status hp_write_pattern_files(rn_context *ctx, rn_scene *sc, const char *base,
                                 int quiet, int *vtu_written, int *png_written) {
  char vtu[4096], png[4096];
  snprintf(vtu, sizeof vtu, "%s.vtu", base);
  snprintf(png, sizeof png, "%s.png", base);
  rn_status st = rn_vtk_write(ctx, vtu, sc);
  if (st) return st;
  *vtu_written = 1;
  const char *const args[] = {
      vtu, png, "--view", "xy", "--field", "bending_moment", quiet ? "--quiet" : NULL,
      NULL};
  *png_written =
      rn_cli_run_script_to("RODNET_RENDER_VTU", RN_RENDER_VTU_SCRIPT, args, png) == 0;
  return RN_OK;
}

/* Progress line of post-buckling step res->done of res->steps on stderr. */
static void print_post_step(void *user, const rn_cell_post_result *res) {
  const int ns = *(const int *)user; /* the number of stress components */
  const rn_cell_post_step *s = &res->step[res->done - 1];
  fprintf(stderr, "rodnet homogenize: post-buckling %d/%d  t %.4f  stress ", res->done,
          res->steps, s->t);
  hp_print_vec(stderr, ns, s->stress, 4, 1);
  fputs(" (principal ", stderr);
  hp_print_vec(stderr, ns, s->principal_stress, 4, 1);
  fprintf(stderr, ")  amplitude %.3e  %s\n", s->amplitude,
          s->converged && s->verified ? "verified minimum" : "NOT a verified minimum");
}

rn_status hp_post_buckling(rn_context *ctx, const char *scene, const hp_path *p,
                           const char *out_base, hp_post *po) {
  const rn_cell_path_instability *in = &p->r.inst;
  rn_cell_post_options opt;
  rn_status st;
  rn_scene *sc = NULL;
  int *base = NULL, *cell = NULL;
  int ns = p->ns;
  if (!in->found || in->kind_macroscopic) {
    po->failed = in->found ? "the instability is macroscopic (long wavelength): no "
                             "finite supercell"
                           : "the path stays stable: no post-buckling";
    return RN_OK;
  }
  rn_cell_post_options_default(&opt);
  if (!rn_cell_instability_supercell(in, p->dim, opt.rep)) {
    po->failed = "the wave vector is not commensurate with a supercell of at most 12 "
                 "cells per direction";
    return RN_OK;
  }
  po->pinned = p->dim == 2 && p->modes == RN_BLOCH_IN_PLANE;
  if ((st = rn_scene_load_supercell(ctx, scene, p->dim, opt.rep, po->pinned, &sc)))
    return st;
  rn_network *net = rn_scene_network(sc);
  size_t nrod = (size_t)rn_network_num_rods(net) + 1;
  base = malloc(nrod * sizeof *base);
  cell = malloc(3 * nrod * sizeof *cell);
  if (!base || !cell) {
    st = rn_context_set_error(ctx, RN_ERR_ALLOC, "out of memory");
    goto done;
  }
  rn_scene_supercell_copies(sc, base, cell);
  opt.steps = po->nsteps;
  opt.modes = p->modes;
  opt.rod_base = base;
  opt.rod_cell = cell;
  opt.progress = p->quiet ? NULL : print_post_step;
  opt.user = &ns;
  if ((st = rn_cell_post_buckling(net, &p->r, &opt, &po->r))) goto done;
  /* the pattern: the last bifurcated state */
  st = hp_write_pattern_files(ctx, sc, out_base, p->quiet, &po->written, &po->png);
done:
  free(base);
  free(cell);
  rn_scene_destroy(&sc);
  return st;
}

void hp_post_write_json(FILE *f, const hp_path *p, const hp_post *po) {
  if (!po->requested) return;
  fputs("  \"post_buckling\": ", f);
  if (po->failed) {
    fprintf(f, "{\"error\": \"%s\"},\n", po->failed);
    return;
  }
  const rn_cell_post_result *r = &po->r;
  double rep[3] = {r->rep[0], r->rep[1], r->rep[2]};
  fputs("{\"supercell\": ", f);
  hp_put_vec(f, p->dim, rep);
  fprintf(f,
          ", \"out_of_plane_pinned\": %s, \"critical_mode_eigenvalue\": %.17g, "
          "\"perturbation\": %.17g, \"steps\": [",
          po->pinned ? "true" : "false", r->mode_eigenvalue, r->perturbation);
  for (int j = 0; j < r->done; ++j) {
    const rn_cell_post_step *s = &r->step[j];
    fprintf(f, "%s\n    {\"load_factor\": %.17g, \"strain\": ", j ? "," : "", s->t);
    hp_put_vec(f, p->ns, s->strain);
    fputs(", \"stress\": ", f);
    hp_put_vec(f, p->ns, s->stress);
    fprintf(f,
            ", \"energy_per_cell\": %.17g, \"amplitude\": %.17g, \"converged\": %s, "
            "\"iterations\": %d, \"verified_minimum\": %s, \"lowest_eigenvalue\": %.17g, "
            "\"principal_stress\": ",
            s->energy, s->amplitude, s->converged ? "true" : "false", s->iterations,
            s->verified ? "true" : "false", s->lowest);
    hp_put_vec(f, p->ns, s->principal_stress);
    fprintf(f,
            ", \"principal_energy_per_cell\": %.17g, \"principal_verified_minimum\": %s, "
            "\"principal_lowest_eigenvalue\": %.17g}",
            s->principal_energy, s->principal_verified ? "true" : "false",
            s->principal_lowest);
  }
  fputs("],\n    \"harmonics\": [", f);
  for (int h = 0; h < r->nharm; ++h) {
    fprintf(f, "%s{\"wave_vector\": ", h ? ", " : "");
    hp_put_vec(f, p->dim, r->harm_xi[h]);
    fprintf(f, ", \"share\": %.6g}", r->harm[h]);
  }
  fprintf(f, "], \"pattern_written\": %s, \"png\": %s},\n",
          po->written ? "true" : "false", po->png ? "true" : "false");
}

void hp_post_free(hp_post *po) { rn_cell_post_result_free(&po->r); }

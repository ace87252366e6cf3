/* cli_homogenize.c - `rodnet homogenize SCENE.json -o RESULT.json [--plot PNG]`:
 * linear effective elasticity of a periodic cell (rn_homogenize;
 * docs/homogenization.md). */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <cjson/cJSON.h>

#include "io/atomic_file.h"
#include "io/num_format.h"
#include "cli/cli.h"
#include "cli/cli_dist.h"
#include "cli/homog_path.h"
#include "scene/result_json.h"
#include "rodnet_solve.h"
#include "scene/scene.h"
#include "scene/scene_json.h"

#ifndef RN_PLOT_STIFFNESS_SCRIPT
#define RN_PLOT_STIFFNESS_SCRIPT "plot_stiffness.py"
#endif
#ifndef RN_PYTHON3
#define RN_PYTHON3 "python3"
#endif

static const char homogenize_help[] =
    "Usage: rodnet homogenize SCENE.json -o RESULT.json [--plot PNG]\n"
    "       rodnet homogenize SCENE.json --path E11,E22,E12 [--steps N] -o RESULT.json\n"
    "\n"
    "Effective linear stiffness of a periodic cell (a scene with a top-level\n"
    "\"periodic\" object, e.g. from 'rodnet generate KIND --periodic') at its rest\n"
    "state: the Schur complement of the Hessian onto the macroscopic strain,\n"
    "C (Voigt, engineering shear; 2D: 11, 22, 12, force per length; 3D: 11, 22,\n"
    "33, 23, 13, 12, per unit volume), the engineering constants, the cell area or\n"
    "volume and the relative density, written to RESULT.json (completely or not at\n"
    "all).\n"
    "\n"
    "Options:\n"
    "  -o, --output FILE   result JSON (required)\n"
    "      --plot PNG      polar plot of the directional Young's modulus (in the\n"
    "                      xy plane; 3D cells also xz), by python3 with matplotlib\n"
    "      --path E,E,E    follow the proportional macroscopic strain path from the\n"
    "                      rest state to this strain (2D: E11,E22,E12; 3D: E11,E22,\n"
    "                      E33,E23,E13,E12; engineering shear) and locate its first\n"
    "                      instability by Bloch-Floquet analysis (RESULT.json gains\n"
    "                      \"path\" and \"instability\")\n"
    "      --path E,-,-    mixed control: '-' is a stress-controlled component at\n"
    "                      zero stress, s:VALUE one at that stress, e:VALUE (or a\n"
    "                      number) strain-controlled; e.g. uniaxial stress along x\n"
    "      --path-stress S,S,S  proportional macroscopic stress path (every\n"
    "                      component stress-controlled; 2D force per length)\n"
    "      --path-file P.json  piecewise-linear path through waypoints\n"
    "                      {\"waypoints\": [{\"strain\": [..|null], \"stress\": "
    "[..|null],\n"
    "                      \"steps\": n}, ...]} (docs/homogenization.md); under stress\n"
    "                      control a limit point of the stress ends the path\n"
    "      --steps N       steps of the path (default 20)\n"
    "      --modes M       Bloch modes examined: all (default), in-plane or\n"
    "                      out-of-plane (2D cells at planar states; the planar\n"
    "                      model has the in-plane modes only)\n"
    "      --bloch-grid G  wave vectors per reciprocal direction (default 16 in 2D,\n"
    "                      6 in 3D), refined around the minimum\n"
    "      --bloch-method M  auto (default: dense up to 64 Bloch DOFs, sparse\n"
    "                      beyond), dense (LAPACK, up to 4000: the oracle) or\n"
    "                      sparse (shift-invert Lanczos, any size)\n"
    "      --pattern P     after a local instability: the supercell its wave vector\n"
    "                      calls for at the critical strain plus the critical mode\n"
    "                      (scaled for display), written to P.vtu and drawn to\n"
    "                      P.png (docs/render_vtu.py)\n"
    "      --post-buckling B  after a local instability: continue the path past the\n"
    "                      critical strain on the bifurcated branch of that supercell\n"
    "                      (perturbed along the critical mode, minimised by\n"
    "                      rn_cell_minimize; with --modes in-plane the supercell's\n"
    "                      out-of-plane DOFs are pinned), the principal branch next to\n"
    "                      it; the last post-buckled state to B.vtu and B.png;\n"
    "                      RESULT.json gains \"post_buckling\"\n"
    "      --post-steps N  steps from the critical strain to the path's end (default "
    "10)\n"
    "  -q, --quiet         no summary on stdout\n"
    "  -h, --help          show this help\n"
    "\n";
static const char homogenize_help_tail[] =
    "A path that stops early (the fluctuations or the mixed solve fail) writes its\n"
    "partial result to RESULT.partial.json (\"partial\": true) and leaves RESULT.json\n"
    "as it was (a complete earlier result is kept); exit status 4.\n"
    "\n"
    "Exit status: 0 done, 2 usage error, 3 bad scene (not periodic, prescribed\n"
    "strain) or unwritable output, 4 the cell is a mechanism, the path stopped\n"
    "early or the plot failed.\n";

typedef struct hom_args {
  const char *scene, *output, *plot, *path, *pattern, *post;
  const char *path_stress, *path_file; /* --path-stress, --path-file */
  int quiet, steps, grid, post_steps;
  int has_steps, has_grid, has_modes, has_post_steps; /* given on the command line */
  int has_method;
  rn_bloch_modes modes;
  rn_bloch_method method;
} hom_args;

/* The files the command reads and writes (cli.h); returns their count. */
static int hom_files(const hom_args *a, rn_cli_file *f) {
  const rn_cli_file files[] = {{"the scene file", a->scene, NULL, RN_CLI_IN},
                               {"the --path-file", a->path_file, NULL, RN_CLI_IN},
                               {"-o", a->output, NULL, RN_CLI_OUT},
                               {"--plot", a->plot, NULL, RN_CLI_OUT},
                               {"--pattern", a->pattern, ".vtu", RN_CLI_OUT},
                               {"--pattern", a->pattern, ".png", RN_CLI_OUT},
                               {"--post-buckling", a->post, ".vtu", RN_CLI_OUT},
                               {"--post-buckling", a->post, ".png", RN_CLI_OUT}};
  memcpy(f, files, sizeof files);
  return (int)(sizeof files / sizeof files[0]);
}

/* The option at argv[*i] if it takes a value (advancing *i): 1 matched, 0 not
 * one of them, RN_EXIT_USAGE (message printed) if its value is missing or bad. */
static int valued_option(int argc, char **argv, int *i, hom_args *a) {
  const struct {
    const char *name, *alias;
    const char **dest;
  } strings[] = {{"--output", "-o", &a->output},
                 {"--plot", NULL, &a->plot},
                 {"--path-stress", NULL, &a->path_stress},
                 {"--path-file", NULL, &a->path_file},
                 {"--path", NULL, &a->path},
                 {"--pattern", NULL, &a->pattern},
                 {"--post-buckling", NULL, &a->post}};
  const struct {
    const char *name;
    long hi;
    int *dest, *given;
  } ints[] = {{"--post-steps", 10000, &a->post_steps, &a->has_post_steps},
              {"--steps", 100000, &a->steps, &a->has_steps},
              {"--bloch-grid", 1000, &a->grid, &a->has_grid}};
  const char *v = NULL;
  int m;
  for (size_t k = 0; k < sizeof strings / sizeof strings[0]; ++k)
    if ((m = rn_cli_option_value("homogenize", argc, argv, i, strings[k].name,
                                 strings[k].alias, &v))) {
      if (m < 0) return RN_EXIT_USAGE;
      *strings[k].dest = v;
      return 1;
    }
  for (size_t k = 0; k < sizeof ints / sizeof ints[0]; ++k)
    if ((m = rn_cli_option_value("homogenize", argc, argv, i, ints[k].name, NULL, &v))) {
      if (m < 0 ||
          rn_cli_parse_int("homogenize", ints[k].name, v, 1, ints[k].hi, ints[k].dest))
        return RN_EXIT_USAGE;
      *ints[k].given = 1;
      return 1;
    }
  if ((m = rn_cli_option_value("homogenize", argc, argv, i, "--bloch-method", NULL,
                               &v))) {
    static const char *const names[] = {"auto", "dense", "sparse"};
    if (m < 0) return RN_EXIT_USAGE;
    a->has_method = 1;
    for (int k = 0; k < 3; ++k)
      if (strcmp(v, names[k]) == 0) {
        a->method = (rn_bloch_method)k;
        return 1;
      }
    return rn_cli_usage_error("homogenize",
                              "--bloch-method takes auto, dense or sparse, not '%s'", v);
  }
  if ((m = rn_cli_option_value("homogenize", argc, argv, i, "--modes", NULL, &v))) {
    if (m < 0) return RN_EXIT_USAGE;
    a->has_modes = 1;
    if (strcmp(v, "all") == 0)
      a->modes = RN_BLOCH_ALL;
    else if (strcmp(v, "in-plane") == 0)
      a->modes = RN_BLOCH_IN_PLANE;
    else if (strcmp(v, "out-of-plane") == 0)
      a->modes = RN_BLOCH_OUT_OF_PLANE;
    else
      return rn_cli_usage_error(
          "homogenize", "--modes takes all, in-plane or out-of-plane, not '%s'", v);
    return 1;
  }
  return 0;
}

/* The options that go together (after parsing); 0 or a usage error. */
static int check_combination(hom_args *a) {
  if (!a->scene) return rn_cli_usage_error("homogenize", "missing the scene file");
  if (!a->output) return rn_cli_usage_error("homogenize", "missing -o RESULT.json");
  if ((a->path != NULL) + (a->path_stress != NULL) + (a->path_file != NULL) > 1)
    return rn_cli_usage_error("homogenize",
                              "give one of --path, --path-stress and --path-file");
  if (a->path_stress) a->path = a->path_stress;
  if (a->path_file) a->path = a->path_file;
  if (a->pattern && !a->path)
    return rn_cli_usage_error("homogenize", "--pattern needs --path");
  if (a->post && !a->path)
    return rn_cli_usage_error("homogenize", "--post-buckling needs --path");
  /* options of the path only: without one they would be ignored */
  if (!a->path && (a->has_steps || a->has_grid || a->has_modes || a->has_method))
    return rn_cli_usage_error("homogenize",
                              "%s applies to a path only: give --path, --path-stress or "
                              "--path-file",
                              a->has_steps   ? "--steps"
                              : a->has_grid  ? "--bloch-grid"
                              : a->has_modes ? "--modes"
                                             : "--bloch-method");
  if (a->has_post_steps && !a->post)
    return rn_cli_usage_error("homogenize",
                              "--post-steps applies to --post-buckling only");
  return 0;
}

static int parse_args(int argc, char **argv, hom_args *a) {
  memset(a, 0, sizeof *a);
  a->steps = 20;
  a->post_steps = 10;
  for (int i = 1; i < argc; i++) {
    const char *s = argv[i];
    int m;
    if (strcmp(s, "-h") == 0 || strcmp(s, "--help") == 0) {
      fputs(homogenize_help, stdout);
      fputs(homogenize_help_tail, stdout);
      return -1;
    }
    if (strcmp(s, "-q") == 0 || strcmp(s, "--quiet") == 0) {
      a->quiet = 1;
      continue;
    }
    if ((m = valued_option(argc, argv, &i, a))) {
      if (m != 1) return m;
      continue;
    }
    if (s[0] == '-' && s[1] != '\0')
      return rn_cli_usage_error("homogenize", "unknown option '%s'", s);
    if (a->scene)
      return rn_cli_usage_error("homogenize", "more than one scene given ('%s' and '%s')",
                                a->scene, s);
    a->scene = s;
  }
  static const char *const valued[] = {
      "--output|-o", "--plot",       "--path-stress",   "--path-file",
      "--path",      "--pattern",    "--post-buckling", "--post-steps",
      "--steps",     "--bloch-grid", "--modes",         "--bloch-method",
      NULL};
  int rc = rn_cli_check_repeats("homogenize", argc, argv, valued);
  if (rc) return rc;
  if ((rc = check_combination(a))) return rc;
  rn_cli_file files[8];
  return rn_cli_check_files("homogenize", files, hom_files(a, files));
}

/* S = C^-1 (homog_path.h): the library's, where it is built. */
int rn_homog_invert(int n, const double *C, double *S) {
#ifdef RN_HAVE_SOLVER
  return rn_homogenization_invert(n, C, S);
#else
  (void)n, (void)C, (void)S; /* no rn_homogenize without the solver: no C */
  return 0;
#endif
}

typedef struct hom_out {
  const hom_args *a;
  const rn_homogenization *h;
  const double *S;
  double seconds;
  const hp_path *path; /* NULL without --path */
  const rn_network *net;
  const hp_post *post;            /* --post-buckling */
  const char *dest;               /* the file written (messages) */
  const struct rn_cli_dist *dist; /* under mpirun: the partition, else NULL */
} hom_out;

#ifdef RN_HAVE_SOLVER
/* Directional Young's modulus 1 / (s^T S s), s the Voigt form of the unit
 * uniaxial stress along (cos t, sin t) in the plane of axes i, j. */
static double directional_E(const rn_homogenization *h, const double *S, double t,
                            int plane_xz) {
  double s[6] = {0}, c = cos(t), d = sin(t), q = 0.0;
  int n = h->nstrain;
  if (n == 3) {
    s[0] = c * c, s[1] = d * d, s[2] = c * d;
  } else if (!plane_xz) {
    s[0] = c * c, s[1] = d * d, s[5] = c * d;
  } else {
    s[0] = c * c, s[2] = d * d, s[4] = c * d;
  }
  for (int i = 0; i < n; i++)
    for (int j = 0; j < n; j++) q += s[i] * S[i * n + j] * s[j];
  return 1.0 / q;
}
#endif /* RN_HAVE_SOLVER */

void rn_homog_put_constants(FILE *f, const rn_homogenization *h, const double *S) {
  int n = h->nstrain;
#define SIJ(i, j) S[(i)*n + (j)]
  if (n == 3)
    fprintf(f,
            "  \"constants\": {\"E1\": %.17g, \"E2\": %.17g, \"nu12\": %.17g, \"nu21\": "
            "%.17g, \"G12\": %.17g},\n",
            1.0 / SIJ(0, 0), 1.0 / SIJ(1, 1), -SIJ(0, 1) / SIJ(0, 0),
            -SIJ(0, 1) / SIJ(1, 1), 1.0 / SIJ(2, 2));
  else
    fprintf(
        f,
        "  \"constants\": {\"E1\": %.17g, \"E2\": %.17g, \"E3\": %.17g, \"nu12\": %.17g, "
        "\"nu13\": %.17g, \"nu23\": %.17g, \"nu21\": %.17g, \"nu31\": %.17g, \"nu32\": "
        "%.17g, \"G23\": %.17g, \"G13\": %.17g, \"G12\": %.17g},\n",
        1.0 / SIJ(0, 0), 1.0 / SIJ(1, 1), 1.0 / SIJ(2, 2), -SIJ(0, 1) / SIJ(0, 0),
        -SIJ(0, 2) / SIJ(0, 0), -SIJ(1, 2) / SIJ(1, 1), -SIJ(0, 1) / SIJ(1, 1),
        -SIJ(0, 2) / SIJ(2, 2), -SIJ(1, 2) / SIJ(2, 2), 1.0 / SIJ(3, 3), 1.0 / SIJ(4, 4),
        1.0 / SIJ(5, 5));
#undef SIJ
}

#ifndef RN_HAVE_SOLVER
/* rn_homogenize, rn_cell_relax and rn_cell_bloch are the solver's
 * (shim_cxx/periodic/homogenize.cpp, cell_path.cpp): without it the command parses its
 * options (help, usage errors) and refuses; homog_path.c and homog_post.c are
 * not built. */
int rn_cli_homogenize(int argc, char **argv) {
  hom_args a;
  int rc = parse_args(argc, argv, &a);
  if (rc) return rc < 0 ? RN_EXIT_OK : rc;
  return rn_cli_no_solver("homogenize");
}
#else
static rn_status write_result(FILE *f, void *user, rn_context *ctx) {
  const hom_out *o = user;
  const rn_homogenization *h = o->h;
  int n = h->nstrain;
  (void)ctx;
  fputs("{\n  \"command\": \"homogenize\",\n", f);
  if (o->path && o->path->r.stopped) /* RESULT.partial.json: the path stopped early */
    fputs("  \"partial\": true,\n", f);
  fputs("  \"scene\": ", f);
  rn_put_json_string(f, o->a->scene);
  fprintf(f,
          ",\n  \"dimension\": %d,\n  \"%s\": %.17g,\n  \"relative_density\": %.17g,\n",
          h->dim, h->dim == 2 ? "area" : "volume", h->measure, h->relative_density);
  rn_result_put_model(f, o->net);
  fprintf(f, "  \"voigt\": %s,\n",
          n == 3 ? "[\"11\", \"22\", \"12\"]"
                 : "[\"11\", \"22\", \"33\", \"23\", \"13\", \"12\"]");
  fprintf(f, "  \"units\": \"%s\",\n",
          n == 3 ? "force per length (2D stiffness per unit cell area)"
                 : "force per area (per unit cell volume)");
  fputs("  \"C\": [", f);
  for (int i = 0; i < n; i++) {
    fputs(i ? ",\n        [" : "[", f);
    for (int j = 0; j < n; j++) fprintf(f, "%s%.17g", j ? ", " : "", h->C[i * n + j]);
    fputc(']', f);
  }
  fputs("],\n", f);
  rn_homog_put_constants(f, h, o->S);
  for (int plane = 0; plane < (n == 3 ? 1 : 2); plane++) {
    fprintf(f, "  \"directional_modulus_%s\": [", plane ? "xz" : "xy");
    for (int k = 0; k <= 360; k += 2)
      fprintf(f, "%s%.17g", k ? ", " : "",
              directional_E(h, o->S, k * 3.14159265358979323846 / 180.0, plane));
    fputs("],\n", f);
  }
  fprintf(f, "  \"directional_modulus_angles_deg\": [0, 360, 2],\n");
  if (o->dist)
    rn_result_put_partition(f, o->dist->size, o->dist->dofs, o->dist->stencils,
                            o->dist->edge_cut, o->dist->imbalance);
  if (o->path) hp_write_json(f, o->path);
  if (o->path && o->post) hp_post_write_json(f, o->path, o->post);
  fprintf(f, "  \"fluctuation_dofs\": %zu,\n  \"time_s\": %.6g\n}\n", h->fluctuation_dofs,
          o->seconds);
  return RN_OK;
}

/* write_result, checked before a byte reaches f: the text must read back as
 * JSON, which a number that is not finite ("nan", "inf": the fields that may
 * be unavailable are written as null) does not.  The error names the file and
 * the line and column of the first such number (issue 22: every writer refuses
 * non-finite numbers). */
static rn_status write_result_checked(FILE *f, void *user, rn_context *ctx) {
  const hom_out *o = user;
  char *text = NULL;
  size_t len = 0;
  FILE *m = open_memstream(&text, &len);
  if (!m) return rn_context_set_error(ctx, RN_ERR_ALLOC, "%s: out of memory", o->dest);
  rn_status st = write_result(m, user, ctx);
  if (fclose(m) != 0 && !st)
    st = rn_context_set_error(ctx, RN_ERR_ALLOC, "%s: out of memory", o->dest);
  cJSON *root = NULL;
  if (!st && rn_json_parse_text(ctx, o->dest, text, len, &root) != RN_OK) {
    char why[512];
    snprintf(why, sizeof why, "%s", rn_context_last_error(ctx));
    st = rn_context_set_error(ctx, RN_ERR_NOT_FINITE,
                              "%s: a number is not finite (nan or inf); no file written",
                              why);
  }
  cJSON_Delete(root);
  if (!st && fwrite(text, 1, len, f) != len)
    st = rn_context_set_error(ctx, RN_ERR_IO, "%s: write failed", o->dest);
  free(text);
  return st;
}

/* python3 SCRIPT RESULT.json PNG; 0 on success. */
static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* --pattern: the supercell of the critical wave vector on the principal
 * (cell-periodic) branch at the critical strain plus its critical mode
 * (rn_cell_pattern_state, 5 % of the cell size), written as P.vtu and drawn to P.png.
 * (The post-buckled branch is not computed: see docs.)  Fills pat. */
static int write_pattern(rn_context *ctx, const hom_args *a, const hp_path *path,
                         hp_pattern *pat) {
  const rn_cell_path_instability *in = &path->r.inst;
  rn_scene *sc = NULL;
  rn_status st;
  if (!in->found || in->kind_macroscopic) {
    /* nothing to draw: said in RESULT.json and the summary (not an error) */
    snprintf(pat->why_not, sizeof pat->why_not, "%s",
             in->found ? "the instability is macroscopic (long wavelength): no "
                         "finite supercell"
                       : "the path stays stable: no pattern");
    return RN_EXIT_OK;
  }
  if (!rn_cell_instability_supercell(in, path->dim, pat->rep))
    snprintf(pat->why_not, sizeof pat->why_not, "%s",
             "the wave vector is not commensurate with a supercell of at most 12 cells "
             "per direction");
  else if ((st = rn_scene_load_supercell(ctx, a->scene, path->dim, pat->rep, 0, &sc)))
    snprintf(pat->why_not, sizeof pat->why_not, "%s",
             st == RN_ERR_ARG ? "needs a scene without \"repeat\""
                              : rn_context_last_error(ctx));
  else if (rn_cell_pattern_state(
               rn_scene_network(sc), in, pat->rep[0] * pat->rep[1] * pat->rep[2],
               path->modes, 0.05, &pat->eigenvalue, &pat->amplitude, &pat->converged) ||
           hp_write_pattern_files(ctx, sc, a->pattern, a->quiet, &pat->written,
                                  &pat->png))
    snprintf(pat->why_not, sizeof pat->why_not, "%s", rn_context_last_error(ctx));
  else {
    rn_scene_destroy(&sc);
    return RN_EXIT_OK;
  }
  fprintf(stderr, "rodnet homogenize: --pattern: %s\n", pat->why_not);
  rn_scene_destroy(&sc);
  return RN_EXIT_INTERNAL;
}

/* The cell fits the command: periodic, and the --modes asked for exist; 0 or
 * the exit status (message printed). */
static int check_cell(const hom_args *a, rn_network *net, int dim) {
  if (dim == 0) {
    fprintf(stderr,
            "rodnet homogenize: %s: the scene is not periodic (it has no top-level "
            "\"periodic\" object with lattice vectors; see 'rodnet generate KIND "
            "--periodic')\n",
            a->scene);
    return RN_EXIT_INPUT;
  }
  if (a->path && a->modes == RN_BLOCH_OUT_OF_PLANE && rn_network_is_planar(net) == 1) {
    fprintf(stderr,
            "rodnet homogenize: %s: --modes out-of-plane: the scene uses the planar "
            "model, which has no out-of-plane modes (use \"model\": \"3d\")\n",
            a->scene);
    return RN_EXIT_INPUT;
  }
  if (a->path && a->modes != RN_BLOCH_ALL && dim == 3) { /* found before computing */
    fprintf(stderr,
            "rodnet homogenize: %s: --modes %s: a 3D cell has no in-plane / "
            "out-of-plane split of its modes (use --modes all)\n",
            a->scene, a->modes == RN_BLOCH_IN_PLANE ? "in-plane" : "out-of-plane");
    return RN_EXIT_INPUT;
  }
  return 0;
}

/* The path of --path, --path-stress or --path-file into path (its segments);
 * 0 or the exit status (message printed if loud). */
static int read_path(rn_context *ctx, const hom_args *a, rn_network *net, int dim,
                     hp_path *path, int loud) {
  int count = 0, ns = 0, stress[6] = {0};
  double target[6] = {0};
  rn_status st;
  rn_network_cell_info(net, NULL, &ns, NULL, NULL);
  path->ns = ns;
  if (a->path_file) {
    if ((st = hp_read_path_file(ctx, a->path_file, a->steps, path))) {
      if (loud)
        fprintf(stderr, "rodnet homogenize: --path-file: %s\n",
                rn_context_last_error(ctx));
      return st == RN_ERR_ALLOC ? RN_EXIT_INTERNAL : RN_EXIT_INPUT;
    }
    return 0;
  }
  if (hp_parse_targets(a->path, a->path_stress != NULL, target, stress, &count) ||
      count != ns) {
    if (!loud) {
      /* rank 0 prints it */
    } else if (a->path_stress)
      fprintf(stderr,
              "rodnet homogenize: --path-stress '%s': expected %d comma-separated "
              "numbers (%s) for this %dD cell\n",
              a->path, ns, ns == 3 ? "S11,S22,S12" : "S11,S22,S33,S23,S13,S12", dim);
    else
      fprintf(stderr,
              "rodnet homogenize: --path '%s': expected %d comma-separated numbers "
              "(%s; '-', s:VALUE for stress control) for this %dD cell\n",
              a->path, ns, ns == 3 ? "E11,E22,E12" : "E11,E22,E33,E23,E13,E12", dim);
    return RN_EXIT_USAGE;
  }
  if (hp_single_segment(ctx, path, target, stress, a->steps)) return RN_EXIT_INTERNAL;
  return 0;
}

/* --post-buckling and --pattern after the path; 0 or the exit status (the
 * result is written all the same; messages printed). */
static int after_path(rn_context *ctx, const hom_args *a, hp_path *path, hp_post *post) {
  int rc = 0;
  if (a->post) {
    post->requested = 1;
    post->nsteps = a->post_steps;
    rn_status st = hp_post_buckling(ctx, a->scene, path, a->post, post);
    if (st) {
      fprintf(stderr, "rodnet homogenize: --post-buckling: %s\n",
              rn_context_last_error(ctx));
      rc = RN_EXIT_INTERNAL;
    } else if (post->failed)
      fprintf(stderr, "rodnet homogenize: --post-buckling: %s\n", post->failed);
  }
  if (a->pattern) {
    path->pattern.requested = 1;
    int prc = write_pattern(ctx, a, path, &path->pattern);
    if (prc) rc = prc;
  }
  return rc;
}

/* The summary of the path, its instability and pattern on stdout. */
static void print_path(const hom_args *a, const hp_path *path, const hp_post *post) {
  const rn_cell_path_instability *in = &path->r.inst;
  const hp_pattern *pt = &path->pattern;
  if (in->found) {
    printf("rodnet homogenize: first instability at load factor %.6g of the path: "
           "strain ",
           in->t);
    hp_print_vec(stdout, path->ns, in->strain, 6, 0);
    printf(" (Voigt %s), %s, wave vector ",
           path->ns == 3 ? "11 22 12" : "11 22 33 23 13 12",
           in->stress_limit ? "macroscopic (limit point of the stress)"
           : in->kind_macroscopic ? "macroscopic"
                                  : "local");
    hp_print_vec(stdout, path->dim, in->xi, 4, 0);
    printf(", multiplicity %d, %d equivalent wave vector(s)\n", in->multiplicity,
           in->kind_macroscopic ? 1 : in->nequiv);
  } else if (path->r.stopped)
    printf("rodnet homogenize: the path is stable as far as it went (%d of %d steps)\n",
           path->r.done, path->steps);
  else
    printf("rodnet homogenize: the path stays stable (%d steps)\n", path->r.done);
  char third[16] = "";
  if (path->dim == 3) snprintf(third, sizeof third, " x %d", pt->rep[2]);
  if (pt->written)
    printf("rodnet homogenize: pattern: %d x %d%s supercell at the critical strain, "
           "critical mode eigenvalue %.3e (scaled to %.3g)%s; wrote %s.vtu%s%s%s\n",
           pt->rep[0], pt->rep[1], third, pt->eigenvalue, pt->amplitude,
           pt->converged ? "" : " (NOT converged)", a->pattern, pt->png ? " and " : "",
           pt->png ? a->pattern : "", pt->png ? ".png" : "");
  else if (pt->requested)
    printf("rodnet homogenize: pattern: nothing written: %s\n",
           pt->why_not[0] ? pt->why_not : "not computed");
  if (post->requested && post->failed)
    printf("rodnet homogenize: post-buckling: nothing written: %s\n", post->failed);
}

/* The summary of the post-buckled branch's last step on stdout. */
static void print_post(const hom_args *a, const hp_path *path, const hp_post *post) {
  const rn_cell_post_result *r = &post->r;
  const rn_cell_post_step *ls = &r->step[r->done - 1];
  char third[16] = "";
  if (path->dim == 3) snprintf(third, sizeof third, " x %d", r->rep[2]);
  printf("rodnet homogenize: post-buckling: %d x %d%s supercell, %d steps past the "
         "critical strain; at load factor %.4g stress ",
         r->rep[0], r->rep[1], third, r->done, ls->t);
  hp_print_vec(stdout, path->ns, ls->stress, 6, 0);
  fputs(" (principal ", stdout);
  hp_print_vec(stdout, path->ns, ls->principal_stress, 6, 0);
  printf("), %s; wrote %s.vtu%s%s%s\n",
         ls->verified ? "a verified minimum" : "NOT a verified minimum", a->post,
         post->png ? " and " : "", post->png ? a->post : "", post->png ? ".png" : "");
}

/* The summary of the cell's effective stiffness on stdout. */
static void print_cell(const hom_out *o) {
  const rn_homogenization *h = o->h;
  const double *S = o->S;
  int n = h->nstrain;
  char line[320];
  printf("rodnet homogenize: %s: %dD cell, %s %.6g, relative density %.6g, %zu "
         "fluctuation DOFs, %.3g s\n  C =",
         o->a->scene, h->dim, h->dim == 2 ? "area" : "volume", h->measure,
         h->relative_density, h->fluctuation_dofs, o->seconds);
  for (int i = 0; i < n; i++) {
    printf(i ? "\n      [" : " [");
    for (int j = 0; j < n; j++) printf("%s%13.6e", j ? " " : "", h->C[i * n + j]);
    printf("]");
  }
  printf("\n  model %s", rn_result_model_line(o->net, line, sizeof line));
  printf("\n  E1 = %.6e  E2 = %.6e  nu12 = %.6f  G12 = %.6e\n  wrote %s\n", 1.0 / S[0],
         1.0 / S[n + 1], -S[1] / S[0], 1.0 / S[n * n - 1], o->dest);
}

/* The compliance S of the effective stiffness h, with the warnings on h; 0 or
 * the exit status (message printed). */
static int check_stiffness(const hom_args *a, const rn_homogenization *h, double *S) {
  if (h->relative_density >= 1.0) /* issue 22 item 1 (docs/lattices.md) */
    fprintf(stderr,
            "rodnet homogenize: warning: %s: relative density %.6g >= 1: the struts "
            "overlap, the rod model does not hold for this cell (docs/lattices.md, "
            "\"Admissible sections\")\n",
            a->scene, h->relative_density);
  if (!rn_homog_invert(h->nstrain, h->C, S)) {
    fprintf(stderr,
            "rodnet homogenize: %s: the effective stiffness is singular (a macroscopic "
            "mechanism: some strain costs no energy)\n",
            a->scene);
    return RN_EXIT_INTERNAL;
  }
  return 0;
}

/* The effective stiffness h of the cell and its compliance S, timed; 0 or the
 * exit status (message printed). */
static int homogenize_cell(rn_context *ctx, const hom_args *a, rn_network *net,
                           rn_homogenization *h, double *S, double *seconds) {
  double t0 = now();
  rn_status st = rn_homogenize(net, h);
  *seconds = now() - t0;
  if (st) {
    fprintf(stderr, "rodnet homogenize: %s: %s\n", a->scene, rn_context_last_error(ctx));
    return st == RN_ERR_ARG ? RN_EXIT_INPUT : RN_EXIT_INTERNAL;
  }
  return check_stiffness(a, h, S);
}

/* Writes RESULT.json (or, for a path that stopped early, its partial result
 * beside it, never in place of it: a complete earlier result there is kept),
 * prints the summaries; 0 or the exit status. */
static int write_and_print(rn_context *ctx, hom_out *o, const hp_path *path,
                           const hp_post *post) {
  const hom_args *a = o->a;
  char partial[4096];
  int rc = 0;
  o->dest = a->output;
  if (a->path && path->r.stopped) {
    size_t n = strlen(a->output);
    int json = n > 5 && strcmp(a->output + n - 5, ".json") == 0;
    snprintf(partial, sizeof partial, "%.*s.partial.json", (int)(json ? n - 5 : n),
             a->output);
    o->dest = partial;
  }
  rn_status st = rn_file_write_atomic(ctx, o->dest, write_result_checked, o);
  if (!st && a->path && !a->quiet) print_path(a, path, post);
  if (a->path && path->r.stopped) {
    fprintf(stderr,
            "rodnet homogenize: %s: the path stopped at step %d: %s; the partial result "
            "is in %s (%s is not written)\n",
            a->scene, path->r.done + 1, path->r.stopped, o->dest, a->output);
    rc = RN_EXIT_INTERNAL;
  }
  if (!st && post->r.done && !a->quiet) print_post(a, path, post);
  if (st) {
    fprintf(stderr, "rodnet homogenize: %s\n", rn_context_last_error(ctx));
    return RN_EXIT_INPUT;
  }
  if (!a->quiet) print_cell(o);
  if (a->plot && rn_cli_plot("RODNET_PLOT_STIFFNESS", RN_PLOT_STIFFNESS_SCRIPT, o->dest,
                             a->plot) != 0) {
    fprintf(stderr,
            "rodnet homogenize: the plot %s failed (%s %s with matplotlib; "
            "RODNET_PYTHON and RODNET_PLOT_STIFFNESS override them); %s is written\n",
            a->plot, getenv("RODNET_PYTHON") ? getenv("RODNET_PYTHON") : RN_PYTHON3,
            getenv("RODNET_PLOT_STIFFNESS") ? getenv("RODNET_PLOT_STIFFNESS")
                                            : RN_PLOT_STIFFNESS_SCRIPT,
            a->output);
    rc = RN_EXIT_INTERNAL;
  }
  return rc;
}

/* ---- under mpirun: the cell distributed over the ranks (docs/parallel.md) ---- */

/* The rank-0 steps' exit status shared by every rank. */
static int agree_rc(int rc) {
  rn_dist_allreduce_int(&rc, 1, RN_DIST_MAX);
  return rc;
}

/* One part of the cell per rank (rn_homogenize on the parts: the Schur complement
 * through the distributed solver); rank 0 writes and prints.  Every rank returns
 * the same exit status. */
static int homogenize_distributed(const hom_args *a, rn_cli_dist *d) {
  int rc = 0, dim = 0;
  if (a->pattern || a->post) {
    if (d->rank == 0)
      fprintf(stderr,
              "rodnet homogenize: --pattern and --post-buckling run on one process "
              "(the bifurcated branch is not distributed yet); run them without "
              "mpirun, or give the supercell of the critical mode to 'mpirun rodnet "
              "solve' (docs/parallel.md)\n");
    return RN_EXIT_USAGE;
  }
  rn_cli_file files[8];
  if (d->rank == 0) rc = rn_cli_probe_outputs("homogenize", files, hom_files(a, files));
  if ((rc = agree_rc(rc))) return rc;
  if ((rc = rn_cli_dist_load_graph(d, a->scene)) ||
      (rc = rn_cli_dist_load_part(d, a->scene, "rodnet homogenize")))
    return rc;
  rn_network *net = rn_scene_network(d->part);
  rn_network_cell_info(net, &dim, NULL, NULL, NULL);
  if (d->rank == 0) rc = check_cell(a, net, dim);
  if (!rc && a->path && a->modes != RN_BLOCH_ALL && rn_network_is_planar(net) != 1) {
    if (d->rank == 0)
      fprintf(stderr,
              "rodnet homogenize: %s: --modes %s: under mpirun the path examines "
              "every mode of the cell (for the in-plane ones alone use the planar "
              "model, \"model\": \"planar\" in the scene; docs/parallel.md)\n",
              a->scene, a->modes == RN_BLOCH_IN_PLANE ? "in-plane" : "out-of-plane");
    rc = RN_EXIT_USAGE;
  }
  if ((rc = agree_rc(rc))) return rc;
  hp_path path;
  hp_post post;
  memset(&path, 0, sizeof(path));
  memset(&post, 0, sizeof(post));
  /* every rank reads the path (the same file), rank 0 prints its errors */
  if (a->path) {
    rc = read_path(d->ctx, a, net, dim, &path, d->rank == 0);
    if ((rc = agree_rc(rc))) {
      hp_free(&path);
      return rc;
    }
  }
  rn_homogenization h;
  char prefix[4200];
  double S[36], t0 = now();
  rn_status st = rn_homogenize(net, &h);
  double seconds = now() - t0;
  snprintf(prefix, sizeof prefix, "rodnet homogenize: %s: ", a->scene);
  if ((st = rn_cli_dist_agree(d, st, prefix))) {
    hp_free(&path);
    return st == RN_ERR_ARG ? RN_EXIT_INPUT : RN_EXIT_INTERNAL;
  }
  if (rn_cli_dist_agree(d, rn_cli_dist_partition(d), "rodnet homogenize: ")) {
    hp_free(&path);
    return RN_EXIT_INTERNAL;
  }
  if (a->path) { /* collective: every rank follows the path in lockstep */
    path.dim = h.dim;
    path.modes = RN_BLOCH_ALL;
    path.grid = a->grid;
    path.bloch_method = a->method;
    path.quiet = a->quiet || d->rank != 0;
    st = hp_run(net, &path);
    if ((st = rn_cli_dist_agree(d, st, prefix))) {
      hp_free(&path);
      return st == RN_ERR_ARG ? RN_EXIT_INPUT : RN_EXIT_INTERNAL;
    }
  }
  if (d->rank == 0 && !(rc = check_stiffness(a, &h, S))) {
    hom_out o = {a, &h, S, seconds, a->path ? &path : NULL, net, &post, NULL, d};
    rc = write_and_print(d->ctx, &o, &path, &post);
  }
  hp_free(&path);
  return agree_rc(rc);
}

static int homogenize_mpi(const hom_args *a, int rank, int size) {
  rn_cli_dist d;
  int rc = rn_cli_dist_begin(&d, rank, size, "rodnet homogenize");
  if (!rc) rc = homogenize_distributed(a, &d);
  rn_cli_dist_end(&d);
  return rc;
}

int rn_cli_homogenize(int argc, char **argv) {
  hom_args a;
  int rc = parse_args(argc, argv, &a);
  if (rc) return rc < 0 ? RN_EXIT_OK : rc;
  int rank, size;
  if ((rc = rn_cli_mpi_start("rodnet homogenize", &rank, &size))) return rc;
  if (size > 1) return homogenize_mpi(&a, rank, size);
  rn_context *ctx = NULL;
  if (rn_context_create(&ctx) != RN_OK) {
    fprintf(stderr, "rodnet homogenize: out of memory\n");
    return RN_EXIT_INTERNAL;
  }
  rn_scene *scene = NULL;
  rn_homogenization h;
  double S[36], seconds = 0.0;
  int dim = 0;
  hp_path path;
  hp_post post;
  memset(&path, 0, sizeof(path));
  memset(&post, 0, sizeof(post));
  rn_cli_file files[8];
  rn_status st = RN_OK;
  /* every output writable before anything is computed */
  if ((rc = rn_cli_probe_outputs("homogenize", files, hom_files(&a, files)))) goto done;
  st = rn_scene_load(ctx, a.scene, &scene);
  if (st) {
    fprintf(stderr, "%s\n", rn_context_last_error(ctx));
    rc = rn_cli_load_exit_code(st);
    goto done;
  }
  rn_network *net = rn_scene_network(scene);
  rn_network_cell_info(net, &dim, NULL, NULL, NULL);
  if ((rc = check_cell(&a, net, dim))) goto done;
  if (a.path && (rc = read_path(ctx, &a, net, dim, &path, 1))) goto done;
  if ((rc = homogenize_cell(ctx, &a, net, &h, S, &seconds))) goto done;
  if (a.path) {
    path.dim = h.dim;
    path.modes = a.modes;
    path.grid = a.grid;
    path.bloch_method = a.method;
    path.quiet = a.quiet;
    st = hp_run(net, &path);
    if (st) {
      fprintf(stderr, "rodnet homogenize: %s: %s\n", a.scene, rn_context_last_error(ctx));
      rc = st == RN_ERR_ARG ? RN_EXIT_INPUT : RN_EXIT_INTERNAL;
      goto done;
    }
  }
  rc = after_path(ctx, &a, &path, &post);
  hom_out o = {&a, &h, S, seconds, a.path ? &path : NULL, net, &post, NULL, NULL};
  int wrc = write_and_print(ctx, &o, &path, &post);
  /* the first failure's status, but a failed write of the result wins */
  if (wrc == RN_EXIT_INPUT || !rc) rc = wrc;
  hp_post_free(&post);
done:
  hp_free(&path);
  rn_scene_destroy(&scene);
  rn_context_destroy(&ctx);
  return rc;
}
#endif /* RN_HAVE_SOLVER */

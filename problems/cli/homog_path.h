/* homog_path.h - `rodnet homogenize --path`: macroscopic strain, stress and
 * mixed paths from the rest state (proportional, or piecewise linear through
 * waypoints) with the Bloch-Floquet first instability and, under stress
 * control, the limit point of the stress (docs/homogenization.md, "Strain
 * paths and stability", "Stress and mixed paths").  The library follows the
 * path (rn_cell_path_run, rodnet_solve.h); this module reads the command's
 * path, calls it and writes its result. */
#ifndef RN_HOMOG_PATH_H
#define RN_HOMOG_PATH_H

#include <stdio.h>

#include "rodnet_solve.h"
#include "scene/scene.h"

typedef struct hp_pattern {
  int requested, written, png, converged;
  char why_not[320]; /* requested, not written: why (RESULT.json, summary) */
  int rep[3];
  double eigenvalue; /* lowest Bloch eigenvalue (xi = 0) of the supercell there */
  double amplitude;  /* largest displacement of the mode as drawn */
} hp_pattern;

typedef struct hp_path {
  int ns, dim, steps; /* steps: over all segments */
  double target[6];   /* the last segment's target */
  int nseg;
  rn_cell_path_segment *seg; /* [nseg], as parsed (start unset), owned (hp_free) */
  const char *kind;          /* "strain", "stress", "mixed" or "waypoints" */
  rn_bloch_modes modes;
  int grid;
  rn_bloch_method bloch_method; /* --bloch-method */
  int quiet;
  rn_cell_path_result r; /* rn_cell_path_run (hp_run), owned (hp_free) */
  hp_pattern pattern;    /* --pattern (cli_homogenize.c) */
} hp_path;

/* --post-buckling (homog_post.c): the bifurcated branch in the supercell
 * (rn_cell_post_buckling). */
typedef struct hp_post {
  int requested, nsteps, pinned, written, png;
  rn_cell_post_result r; /* owned (hp_post_free) */
  const char *failed;    /* why it was not computed (NULL if it was) */
} hp_post;

/* The pattern files of a supercell scene sc at its current state: BASE.vtu
 * (rn_vtk_write; its status, recorded in ctx) and BASE.png drawn from it by
 * docs/render_vtu.py (view xy, coloured by the bending moment; --quiet if
 * quiet), through a temporary name; *vtu_written = 1 once the .vtu is there,
 * *png_written = 1 if the drawing succeeded (a failed drawing is not an
 * error: the summary says so). */
rn_status hp_write_pattern_files(rn_context *ctx, rn_scene *sc, const char *base,
                                 int quiet, int *vtu_written, int *png_written);

/* After hp_run found a local instability: the supercell scene of its wave
 * vector (rn_cell_instability_supercell; rn_scene_load_supercell, out-of-plane pins for
 * in-plane modes of a 2D cell), the library's continuation past the critical
 * strain on it (rn_cell_post_buckling, po->nsteps steps; progress lines on
 * stderr unless p->quiet) into po->r; the last bifurcated state written to
 * out_base.vtu and drawn to out_base.png.  po->failed says why nothing was
 * computed (RN_OK then). */
rn_status hp_post_buckling(rn_context *ctx, const char *scene, const hp_path *p,
                           const char *out_base, hp_post *po);
void hp_post_write_json(FILE *f, const hp_path *p, const hp_post *po);
void hp_post_free(hp_post *po);
void hp_put_vec(FILE *f, int n, const double *v);
/* "[v0 v1 ...]" for the console: every one of the n components (Voigt order of
 * RESULT.json), %.*e if exp else %.*g with prec digits. */
void hp_print_vec(FILE *f, int n, const double *v, int prec, int exp);

/* The instability's "kind" ("local", "macroscopic"; "none" if not found) and
 * "criterion" ("bloch", "rank_one_convexity", "stress_limit",
 * "cell_periodic_fluctuations"; "" if not found) as RESULT.json and the sweep's
 * point files and CSV write them. */
const char *hp_instability_kind(const rn_cell_path_instability *in);
const char *hp_instability_criterion(const rn_cell_path_instability *in);

/* Parse a path's targets: comma-separated entries, each a number (a strain, or
 * a stress if stress_default), "-" (stress-controlled at zero stress),
 * "s:VALUE" (stress-controlled) or "e:VALUE" (strain-controlled); at most 6.
 * 0 on success. */
int hp_parse_targets(const char *s, int stress_default, double *target, int *stress,
                     int *count);
/* Make p a one-segment path of steps steps to target (stress flags per
 * component) and set p->kind; RN_ERR_ALLOC in ctx. */
rn_status hp_single_segment(rn_context *ctx, hp_path *p, const double *target,
                            const int *stress, int steps);
/* Read the waypoints file (docs/homogenization.md, "Stress and mixed paths")
 * into p->seg for a cell of p->ns strain components; default_steps for a
 * waypoint without "steps".  Errors name the file, the JSON path and the
 * reason (RN_ERR_IO / RN_ERR_PARSE in ctx). */
rn_status hp_read_path_file(rn_context *ctx, const char *file, int default_steps,
                            hp_path *p);
/* Follow the path on net (the scene's network, at rest; every strain component
 * a DOF) and locate the first instability by rn_cell_path_run into p->r;
 * progress lines on stderr unless quiet.  Returns RN_OK when it ran (the path
 * may have stopped early: p->r.stopped, or ended at a limit point of the
 * stress: p->r.limit_end), an error status otherwise. */
rn_status hp_run(rn_network *net, hp_path *p);
/* Write the "path" and "instability" members (each line ends with ",\n"). */
void hp_write_json(FILE *f, const hp_path *p);
void hp_free(hp_path *p);

/* Shared with `rodnet sweep` (cli_homogenize.c): S = C^-1 (n x n) by
 * rn_homogenization_invert; 0 if singular (always without the solver, where
 * there is no C to invert).  The "constants" member of RESULT.json from C and S (ends
 * ",\n"). */
int rn_homog_invert(int n, const double *C, double *S);
void rn_homog_put_constants(FILE *f, const rn_homogenization *h, const double *S);

#endif

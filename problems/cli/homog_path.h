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
  int quiet;
  rn_cell_path_result r; /* rn_cell_path_run (hp_run), owned (hp_free) */
  hp_pattern pattern;    /* --pattern (cli_homogenize.c) */
} hp_path;

/* --post-buckling (homog_post.c): the bifurcated branch in the supercell. */
typedef struct hp_post_step {
  double t, strain[6];       /* path parameter, prescribed macroscopic strain */
  double stress[6], energy;  /* bifurcated branch: stress, elastic energy per cell */
  double amplitude;          /* largest |x - x_principal| over rod vertices */
  int converged, iterations; /* rn_cell_minimize */
  int verified;              /* rn_network_stability: verified minimum */
  double lowest;             /* its lowest (scaled) eigenvalue */
  double principal_stress[6], principal_energy;
  int principal_converged, principal_verified;
  double principal_lowest;
} hp_post_step;

#define HP_MAX_HARMONICS 64
typedef struct hp_post {
  int requested, nsteps, done, pinned, written, png;
  int rep[3];
  double mode_eigenvalue, perturbation;
  hp_post_step *step; /* [nsteps] */
  int nharm;
  double harm_xi[HP_MAX_HARMONICS][3], harm[HP_MAX_HARMONICS];
  const char *failed; /* why it was not computed (NULL if it was) */
} hp_post;

/* The smallest m <= 12 with m xi an integer (to 1e-3); 0 if none. */
int hp_period_of(double xi);
/* The supercell (cells per direction, rep[dim]) of a local instability: the least
 * common multiple of the periods of its wave vector and of the wave vectors
 * equivalent to it, so that it holds every critical mode and their combinations.
 * 0 if one is not commensurate with at most 12 cells per direction. */
int hp_instability_supercell(const rn_cell_path_instability *in, int dim, int rep[3]);
/* The supercell rep[dim] of the periodic scene file (without "repeat"), every
 * strain component a DOF, no applied stress; pin_out_of_plane: z of every joint
 * and interior vertex and every material angle pinned, the first joint fully. */
/* The pattern files of a supercell scene sc at its current state: BASE.vtu
 * (rn_vtk_write; its status, recorded in ctx) and BASE.png drawn from it by
 * docs/render_vtu.py (view xy, coloured by the bending moment; --quiet if
 * quiet), through a temporary name; *vtu_written = 1 once the .vtu is there,
 * *png_written = 1 if the drawing succeeded (a failed drawing is not an
 * error: the summary says so). */
rn_status hp_write_pattern_files(rn_context *ctx, rn_scene *sc, const char *base,
                                 int quiet, int *vtu_written, int *png_written);

rn_status hp_supercell(rn_context *ctx, const char *scene, const int *rep, int dim,
                       int pin_out_of_plane, rn_scene **out);
/* After hp_run found a local instability: the supercell of its wave vector, the
 * principal branch to the critical strain, the critical mode, then po->nsteps
 * steps of the path past the critical strain on both branches (principal:
 * rn_cell_relax; bifurcated: rn_cell_minimize from the principal state plus the
 * critical mode), each checked by rn_network_stability; the last bifurcated
 * state written to out_base.vtu and drawn to out_base.png.  po->failed says why
 * nothing was computed (RN_OK then). */
rn_status hp_post_buckling(rn_context *ctx, const char *scene, const hp_path *p,
                           const char *out_base, hp_post *po);
void hp_post_write_json(FILE *f, const hp_path *p, const hp_post *po);
void hp_post_free(hp_post *po);
void hp_put_vec(FILE *f, int n, const double *v);
/* "[v0 v1 ...]" for the console: every one of the n components (Voigt order of
 * RESULT.json), %.*e if exp else %.*g with prec digits. */
void hp_print_vec(FILE *f, int n, const double *v, int prec, int exp);

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

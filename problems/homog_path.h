/* homog_path.h - `rodnet homogenize --path`: a proportional macroscopic strain
 * path from the rest state with the Bloch-Floquet first instability
 * (docs/homogenization.md, "Strain paths and stability").  The command prints;
 * this module records. */
#ifndef RN_HOMOG_PATH_H
#define RN_HOMOG_PATH_H

#include <stdio.h>

#include "rodnet_solve.h"
#include "scene.h"

typedef struct hp_step {
  double t;                       /* load factor along the path */
  double strain[6], stress[6];    /* Voigt, engineering shear */
  double energy;                  /* elastic energy of the cell */
  int newton, converged;          /* rn_cell_relax */
  double local_min, acoustic_min; /* rn_cell_bloch at the step */
  int stable;
} hp_step;

typedef struct hp_instability {
  int found;
  double t, strain[6], stress[6];
  double xi[3];
  int kind_macroscopic, multiplicity;
  double eig[8];
  int neig;
  double direction[3], amplitude[3];
  int bisections;
} hp_instability;

typedef struct hp_pattern {
  int requested, written, png, converged;
  int rep[3];
  double eigenvalue; /* lowest Bloch eigenvalue (xi = 0) of the supercell there */
  double amplitude;  /* largest displacement of the mode as drawn */
} hp_pattern;

typedef struct hp_path {
  int ns, dim, steps;
  double target[6];
  rn_bloch_modes modes;
  int grid;
  int quiet;
  hp_step *step;       /* [steps + 1] */
  int done;            /* steps computed (step[0 .. done]) */
  const char *stopped; /* NULL, or why the path stopped early */
  hp_instability inst;
  hp_pattern pattern; /* --pattern (cli_homogenize.c) */
  double seconds;
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
/* The supercell rep[dim] of the periodic scene file (without "repeat"), every
 * strain component a DOF, no applied stress; pin_out_of_plane: z of every joint
 * and interior vertex and every material angle pinned, the first joint fully. */
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

/* Parse "E11,E22,E12" (ns numbers); 0 on success. */
int hp_parse_strain(const char *s, double *out, int *count);
/* Follow the path on net (the scene's network, at rest) and locate the first
 * instability; progress lines on stderr unless quiet.  Returns RN_OK when it ran
 * (the path may have stopped early: p->stopped), an error status otherwise. */
rn_status hp_run(rn_network *net, hp_path *p);
/* Write the "path" and "instability" members (each line ends with ",\n"). */
void hp_write_json(FILE *f, const hp_path *p);
void hp_free(hp_path *p);

/* Shared with `rodnet sweep` (cli_homogenize.c): S = C^-1 (n x n); 0 if
 * singular.  The "constants" member of RESULT.json from C and S (ends ",\n"). */
int rn_homog_invert(int n, const double *C, double *S);
void rn_homog_put_constants(FILE *f, const rn_homogenization *h, const double *S);

#endif

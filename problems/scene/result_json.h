/* result_json.h - the result file of `rodnet solve` (docs/cli.md). */
#ifndef RN_RESULT_JSON_H
#define RN_RESULT_JSON_H

#include <stdio.h>

#include "rodnet.h"
#include "rodnet_model.h"
#include "rodnet_solve.h"
#include "scene/scene.h"

/* What the solve reports (filled by the caller from rn_solve_report). */
/* The stability note of a solve with a couple fixed in space (rodnet_couple.h). */
#define RN_NOTE_NONCONSERVATIVE                                                      \
  "not applicable: a couple fixed in space is a nonconservative load (no energy to " \
  "minimise; the state is a stationary point of the residual)"

typedef struct rn_result_info {
  const char *status;        /* "converged" or the reason it stopped */
  const char *solver;        /* solver name ("tr-minres", ...) */
  const char *factorization; /* factorisation used ("banded", "sparse", ...), or NULL */
  const char *stop;          /* stop test ("gradient", "max_iterations", ...) */
  int converged;
  int iterations, load_steps;
  long energy_evals, gradient_evals, hvp_evals, hessian_evals, krylov_iterations;
  double energy, gradient_norm, initial_gradient_norm, time_s;
  int predictor_steps; /* load steps whose predictor step was accepted */
  /* equilibrium on the physical scale (rn_solve_report): residuals, scales and
   * the tolerances of the gradient test, forces and moments apart */
  double force_residual, force_scale, force_tolerance;
  double moment_residual, moment_scale, moment_tolerance;
  const char *preconditioner; /* tr-krylov's preconditioner ("factor", ...), or NULL */
  /* what the solver looks for: "local minimum" (trust regions that leave
   * saddles), "stationary point, energy decreasing" (ROL kinds: may stop at a
   * saddle) or "stationary point" (NOX: minima, saddles or maxima alike) */
  const char *finds;
  /* the partition over MPI ranks (docs/parallel.md); part_ranks = 0: no block */
  int part_ranks;
  const long *part_dofs, *part_stencils; /* [part_ranks] owned per rank */
  long edge_cut;                         /* rod pairs sharing a joint, separated */
  double imbalance;                      /* max owned DOFs / mean owned DOFs */
  long factorizations; /* numeric Cholesky factorisations (rn_solve_report) */
  /* the time split of rn_solve_report (seconds) */
  double hessian_s, preconditioner_setup_s, preconditioner_apply_s;
  /* of the returned state (rn_solve_report.stability): the "stability" block;
   * stability_note says why it is not checked (checked = 0) */
  rn_stability stability;
  const char *stability_note;
} rn_result_info;

/* The "partition" line of a distributed run (ranks, owned DOFs and stencils per
 * rank, edge cut, imbalance), for the result files of other commands too. */
void rn_result_put_partition(FILE *f, int ranks, const long *dofs, const long *stencils,
                             long edge_cut, double imbalance);

/* The summary fields of *in from the report and the options of an rn_solve call
 * (everything but the partition block, part_ranks = 0); with the solver only. */
void rn_result_info_fill(const rn_solve_report *rep, const rn_solve_options *opt,
                         rn_result_info *in);

/* Write the result JSON for the scene's current state: the summary of info
 * (with "partition": {"ranks", "owned_dofs", "owned_stencils", "edge_cut",
 * "imbalance"} when info->part_ranks > 0),
 * energy by term and load factor (from the network), per rod its name,
 * vertices [[x, y, z], ...] and material angles theta, and per joint its
 * name, model, valence, position [x, y, z] and rotation (3 rows of the
 * rotation matrix, identity at rest), and "stability": {"checked",
 * "lowest_eigenvalue", "scale", "verified_minimum", "zero_modes",
 * "factorizations", "time_s"} ({"checked": false, "verified_minimum": false,
 * "note"} when not checked).  Numbers are printed
 * with %.17g; the file is written atomically (atomic_file.h).
 * RN_ERR_NOT_FINITE (and no file) if any value is NaN or infinite. */
/* The line `  "model": {"used": "planar" or "3d", "planar": QUALIFIES[,
 * "not_planar": WHY]},` of a result file (docs/model.md), and the text of the
 * summary's model line into buf[n] (returned). */
void rn_result_put_model(FILE *f, const rn_network *net);
const char *rn_result_model_line(const rn_network *net, char *buf, size_t n);

rn_status rn_result_write_json(rn_context *ctx, const char *path, const rn_scene *scene,
                               const rn_result_info *info);

#endif

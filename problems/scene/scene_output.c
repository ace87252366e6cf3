/* scene_output.c - the result writers of librodnet_scene (rodnet_scene.h) and
 * the solve summary of RESULT.json from rn_solve's report (result_json.h).  Built
 * with the solver only (it reads rn_solve's report). */
#include <string.h>

#include "scene/result_json.h"
#include "rodnet_registry.h"
#include "rodnet_scene.h"
#include "scene/vtk.h"

void rn_result_info_fill(const rn_solve_report *rep, const rn_solve_options *opt,
                         rn_result_info *in) {
  memset(in, 0, sizeof *in);
  in->status = rep->converged ? "converged" : rn_solve_stop_name(rep->stop);
  in->solver = rn_solver_name(opt->solver);
  in->factorization = rn_factorization_name(rep->factorization);
  /* what the kind can do: its row of the registry (rodnet_registry.h) */
  const rn_solver_info *row = rn_solver_info_of(opt->solver);
  const unsigned flags = row ? row->flags : 0;
  if (flags & RN_SOLVER_TAKES_PRECONDITIONER)
    in->preconditioner = rn_preconditioner_name(rep->preconditioner);
  in->finds = !(flags & RN_SOLVER_DESCENDS) ? "stationary point"
              : !(flags & RN_SOLVER_LEAVES_SADDLES)
                  ? "stationary point, energy decreasing"
                  : "local minimum";
  in->stop = rn_solve_stop_name(rep->stop);
  in->converged = rep->converged;
  in->iterations = rep->iterations;
  in->load_steps = rep->load_steps;
  in->predictor_steps = rep->predictor_steps;
  in->energy_evals = rep->energy_evals;
  in->gradient_evals = rep->gradient_evals;
  in->hvp_evals = rep->hvp_evals;
  in->hessian_evals = rep->hessian_evals;
  in->krylov_iterations = rep->krylov_iterations;
  in->factorizations = rep->factorizations;
  in->energy = rep->energy;
  in->gradient_norm = rep->gradient_norm;
  in->initial_gradient_norm = rep->initial_gradient_norm;
  in->time_s = rep->time_s;
  in->hessian_s = rep->hessian_seconds;
  in->preconditioner_setup_s = rep->preconditioner_setup_seconds;
  in->preconditioner_apply_s = rep->preconditioner_apply_seconds;
  in->stability = rep->stability;
  if (!opt->stability) in->stability_note = "skipped (--no-stability)";
  in->force_residual = rep->force_residual;
  in->force_scale = rep->force_scale;
  in->force_tolerance = rep->force_tolerance;
  in->moment_residual = rep->moment_residual;
  in->moment_scale = rep->moment_scale;
  in->moment_tolerance = rep->moment_tolerance;
}

rn_status rn_scene_write_json(rn_context *ctx, const rn_scene *s,
                              const rn_solve_options *opt, const rn_solve_report *rep,
                              const char *path) {
  if (!ctx) return RN_ERR_ARG;
  if (!s || !opt || !rep || !path)
    return rn_context_set_error(ctx, RN_ERR_ARG, "rn_scene_write_json: NULL argument");
  rn_result_info in;
  rn_part_info pi;
  long dofs, stencils;
  rn_result_info_fill(rep, opt, &in);
  memset(&pi, 0, sizeof pi);
  rn_network_part_info(rn_scene_network(s), &pi);
  dofs = (long)pi.owned_dofs;
  stencils = pi.owned_stencils;
  in.part_ranks = 1;
  in.part_dofs = &dofs;
  in.part_stencils = &stencils;
  in.imbalance = 1.0;
  return rn_result_write_json(ctx, path, s, &in);
}

rn_status rn_scene_write_vtu(rn_context *ctx, const rn_scene *s, const char *path) {
  if (!ctx) return RN_ERR_ARG;
  if (!s || !path)
    return rn_context_set_error(ctx, RN_ERR_ARG, "rn_scene_write_vtu: NULL argument");
  return rn_vtk_write(ctx, path, s);
}

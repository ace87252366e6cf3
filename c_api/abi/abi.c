/* abi.c - the layout of the public structs, for bindings that mirror them
 * without a compiler (the Python package's ctypes structures check every field
 * against this table at import: docs/python.md). */
#include <stddef.h>
#include <string.h>

#include "rodnet.h"
#include "rodnet_solve.h"

typedef struct abi_field {
  const char *type, *field;
  size_t offset;
} abi_field;

typedef struct abi_type {
  const char *type;
  size_t size;
} abi_type;

#define RN_ABI_FIELD(s, f) \
  { #s, #f, offsetof(s, f) }
#define RN_ABI_TYPE(s) \
  { #s, sizeof(s) }

/* Every field of every struct a binding may mirror, in declaration order. */
static const abi_field fields[] = {
    RN_ABI_FIELD(rn_material, E),
    RN_ABI_FIELD(rn_material, G),
    RN_ABI_FIELD(rn_material, density),
    RN_ABI_FIELD(rn_section, A),
    RN_ABI_FIELD(rn_section, I11),
    RN_ABI_FIELD(rn_section, I22),
    RN_ABI_FIELD(rn_section, I12),
    RN_ABI_FIELD(rn_section, J),
    RN_ABI_FIELD(rn_reaction, kind),
    RN_ABI_FIELD(rn_reaction, rod),
    RN_ABI_FIELD(rn_reaction, index),
    RN_ABI_FIELD(rn_reaction, fixed),
    RN_ABI_FIELD(rn_reaction, fixed_rotation),
    RN_ABI_FIELD(rn_reaction, point),
    RN_ABI_FIELD(rn_reaction, force),
    RN_ABI_FIELD(rn_reaction, moment),
    RN_ABI_FIELD(rn_iteration_info, iteration),
    RN_ABI_FIELD(rn_iteration_info, energy),
    RN_ABI_FIELD(rn_iteration_info, gradient_norm),
    RN_ABI_FIELD(rn_iteration_info, radius),
    RN_ABI_FIELD(rn_iteration_info, krylov_iterations),
    RN_ABI_FIELD(rn_iteration_info, seconds),
    RN_ABI_FIELD(rn_iteration_info, load_factor),
    RN_ABI_FIELD(rn_solve_options, solver),
    RN_ABI_FIELD(rn_solve_options, max_iterations),
    RN_ABI_FIELD(rn_solve_options, gtol_rel),
    RN_ABI_FIELD(rn_solve_options, gtol_abs),
    RN_ABI_FIELD(rn_solve_options, step_tol),
    RN_ABI_FIELD(rn_solve_options, energy_tol),
    RN_ABI_FIELD(rn_solve_options, krylov_max_iterations),
    RN_ABI_FIELD(rn_solve_options, krylov_tol),
    RN_ABI_FIELD(rn_solve_options, initial_radius),
    RN_ABI_FIELD(rn_solve_options, load_steps),
    RN_ABI_FIELD(rn_solve_options, max_load_cuts),
    RN_ABI_FIELD(rn_solve_options, progress),
    RN_ABI_FIELD(rn_solve_options, progress_user),
    RN_ABI_FIELD(rn_solve_options, factorization),
    RN_ABI_FIELD(rn_solve_options, predictor),
    RN_ABI_FIELD(rn_solve_options, preconditioner),
    RN_ABI_FIELD(rn_solve_options, stability),
    RN_ABI_FIELD(rn_solve_options, stability_method),
    RN_ABI_FIELD(rn_solve_options, interrupt),
    RN_ABI_FIELD(rn_solve_options, forcing),
    RN_ABI_FIELD(rn_stability, checked),
    RN_ABI_FIELD(rn_stability, lowest_eigenvalue),
    RN_ABI_FIELD(rn_stability, scale),
    RN_ABI_FIELD(rn_stability, verified_minimum),
    RN_ABI_FIELD(rn_stability, zero_modes),
    RN_ABI_FIELD(rn_stability, factorizations),
    RN_ABI_FIELD(rn_stability, time_s),
    RN_ABI_FIELD(rn_stability, method),
    RN_ABI_FIELD(rn_stability, iterations),
    RN_ABI_FIELD(rn_stability, cholesky_flops),
    RN_ABI_FIELD(rn_stability, symmetries),
    RN_ABI_FIELD(rn_stability, soft_modes),
    RN_ABI_FIELD(rn_stability, soft_positive),
    RN_ABI_FIELD(rn_solve_report, status),
    RN_ABI_FIELD(rn_solve_report, stop),
    RN_ABI_FIELD(rn_solve_report, converged),
    RN_ABI_FIELD(rn_solve_report, iterations),
    RN_ABI_FIELD(rn_solve_report, energy_evals),
    RN_ABI_FIELD(rn_solve_report, gradient_evals),
    RN_ABI_FIELD(rn_solve_report, hvp_evals),
    RN_ABI_FIELD(rn_solve_report, hessian_evals),
    RN_ABI_FIELD(rn_solve_report, krylov_iterations),
    RN_ABI_FIELD(rn_solve_report, load_steps),
    RN_ABI_FIELD(rn_solve_report, energy),
    RN_ABI_FIELD(rn_solve_report, gradient_norm),
    RN_ABI_FIELD(rn_solve_report, initial_gradient_norm),
    RN_ABI_FIELD(rn_solve_report, time_s),
    RN_ABI_FIELD(rn_solve_report, factorization),
    RN_ABI_FIELD(rn_solve_report, factorizations),
    RN_ABI_FIELD(rn_solve_report, predictor_steps),
    RN_ABI_FIELD(rn_solve_report, force_residual),
    RN_ABI_FIELD(rn_solve_report, moment_residual),
    RN_ABI_FIELD(rn_solve_report, force_scale),
    RN_ABI_FIELD(rn_solve_report, moment_scale),
    RN_ABI_FIELD(rn_solve_report, force_tolerance),
    RN_ABI_FIELD(rn_solve_report, moment_tolerance),
    RN_ABI_FIELD(rn_solve_report, preconditioner),
    RN_ABI_FIELD(rn_solve_report, hessian_seconds),
    RN_ABI_FIELD(rn_solve_report, preconditioner_setup_seconds),
    RN_ABI_FIELD(rn_solve_report, preconditioner_apply_seconds),
    RN_ABI_FIELD(rn_solve_report, stability),
    RN_ABI_FIELD(rn_homogenization, dim),
    RN_ABI_FIELD(rn_homogenization, nstrain),
    RN_ABI_FIELD(rn_homogenization, measure),
    RN_ABI_FIELD(rn_homogenization, C),
    RN_ABI_FIELD(rn_homogenization, relative_density),
    RN_ABI_FIELD(rn_homogenization, fluctuation_dofs),
    RN_ABI_FIELD(rn_cell_path_segment, steps),
    RN_ABI_FIELD(rn_cell_path_segment, stress),
    RN_ABI_FIELD(rn_cell_path_segment, target),
    RN_ABI_FIELD(rn_cell_path_segment, start),
    RN_ABI_FIELD(rn_cell_path_step, t),
    RN_ABI_FIELD(rn_cell_path_step, seg),
    RN_ABI_FIELD(rn_cell_path_step, strain),
    RN_ABI_FIELD(rn_cell_path_step, stress),
    RN_ABI_FIELD(rn_cell_path_step, energy),
    RN_ABI_FIELD(rn_cell_path_step, newton),
    RN_ABI_FIELD(rn_cell_path_step, converged),
    RN_ABI_FIELD(rn_cell_path_step, outer),
    RN_ABI_FIELD(rn_cell_path_step, jumped),
    RN_ABI_FIELD(rn_cell_path_step, kuu_indefinite),
    RN_ABI_FIELD(rn_cell_path_step, tangent_min),
    RN_ABI_FIELD(rn_cell_path_step, local_min),
    RN_ABI_FIELD(rn_cell_path_step, acoustic_min),
    RN_ABI_FIELD(rn_cell_path_step, stable),
    RN_ABI_FIELD(rn_cell_path_instability, found),
    RN_ABI_FIELD(rn_cell_path_instability, t),
    RN_ABI_FIELD(rn_cell_path_instability, strain),
    RN_ABI_FIELD(rn_cell_path_instability, stress),
    RN_ABI_FIELD(rn_cell_path_instability, xi),
    RN_ABI_FIELD(rn_cell_path_instability, nequiv),
    RN_ABI_FIELD(rn_cell_path_instability, xi_equiv),
    RN_ABI_FIELD(rn_cell_path_instability, kind_macroscopic),
    RN_ABI_FIELD(rn_cell_path_instability, multiplicity),
    RN_ABI_FIELD(rn_cell_path_instability, eig),
    RN_ABI_FIELD(rn_cell_path_instability, neig),
    RN_ABI_FIELD(rn_cell_path_instability, direction),
    RN_ABI_FIELD(rn_cell_path_instability, amplitude),
    RN_ABI_FIELD(rn_cell_path_instability, bisections),
    RN_ABI_FIELD(rn_cell_path_instability, stress_limit),
    RN_ABI_FIELD(rn_cell_path_instability, mode),
    RN_ABI_FIELD(rn_cell_path_instability, cell_periodic),
    RN_ABI_FIELD(rn_cell_path_options, grid),
    RN_ABI_FIELD(rn_cell_path_options, modes),
    RN_ABI_FIELD(rn_cell_path_options, progress),
    RN_ABI_FIELD(rn_cell_path_options, user),
    RN_ABI_FIELD(rn_cell_path_options, bloch_method),
    RN_ABI_FIELD(rn_cell_path_result, ns),
    RN_ABI_FIELD(rn_cell_path_result, nseg),
    RN_ABI_FIELD(rn_cell_path_result, seg),
    RN_ABI_FIELD(rn_cell_path_result, steps),
    RN_ABI_FIELD(rn_cell_path_result, step),
    RN_ABI_FIELD(rn_cell_path_result, done),
    RN_ABI_FIELD(rn_cell_path_result, stopped),
    RN_ABI_FIELD(rn_cell_path_result, limit_end),
    RN_ABI_FIELD(rn_cell_path_result, tangent_scale),
    RN_ABI_FIELD(rn_cell_path_result, c_rest),
    RN_ABI_FIELD(rn_cell_path_result, inst),
};

static const abi_type types[] = {
    RN_ABI_TYPE(rn_material),
    RN_ABI_TYPE(rn_section),
    RN_ABI_TYPE(rn_reaction),
    RN_ABI_TYPE(rn_iteration_info),
    RN_ABI_TYPE(rn_solve_options),
    RN_ABI_TYPE(rn_stability),
    RN_ABI_TYPE(rn_solve_report),
    RN_ABI_TYPE(rn_homogenization),
    RN_ABI_TYPE(rn_cell_path_segment),
    RN_ABI_TYPE(rn_cell_path_step),
    RN_ABI_TYPE(rn_cell_path_instability),
    RN_ABI_TYPE(rn_cell_path_options),
    RN_ABI_TYPE(rn_cell_path_result),
};

enum {
  NFIELDS = sizeof fields / sizeof fields[0],
  NTYPES = sizeof types / sizeof types[0]
};

size_t rn_abi_sizeof(const char *type) {
  if (!type) return 0;
  for (int i = 0; i < NTYPES; ++i)
    if (strcmp(types[i].type, type) == 0) return types[i].size;
  return 0;
}

long rn_abi_offsetof(const char *type, const char *field) {
  if (!type || !field) return -1;
  for (int i = 0; i < NFIELDS; ++i)
    if (strcmp(fields[i].type, type) == 0 && strcmp(fields[i].field, field) == 0)
      return (long)fields[i].offset;
  return -1;
}

int rn_abi_num_fields(const char *type) {
  int n = 0;
  if (!type) return 0;
  for (int i = 0; i < NFIELDS; ++i) n += strcmp(fields[i].type, type) == 0;
  return n;
}

/* cli_registry.h - the command's lists of solver kinds and preconditioners, from the
 * library's registry (rodnet_registry.h): help blocks and "known: ..." lists. */
#ifndef RN_CLI_REGISTRY_H
#define RN_CLI_REGISTRY_H

#include <stddef.h>
#include <stdio.h>

/* "tr-minres, rol-tr-tcg, ..." (every solver kind) into buf[n]. */
void rn_cli_solver_names(char *buf, size_t n);
/* "auto, factor, ..." (every preconditioner) into buf[n]. */
void rn_cli_preconditioner_names(char *buf, size_t n);
/* "tr-krylov and nox": the solver kinds that take a preconditioner. */
void rn_cli_preconditioned_solvers(char *buf, size_t n);
/* The help of `rodnet solve`'s --solver and --preconditioner: one line per row. */
void rn_cli_print_solver_help(FILE *out);

#endif

/* rodnet_registry.h - the registries of preconditioners and solver kinds: one row
 * per value of rn_preconditioner and of rn_solver_kind (rodnet_solve.h), with its
 * name, a one-line help and what it can do.  Everything that lists them reads these
 * rows: the name functions of rodnet_solve.h (rn_preconditioner_name,
 * rn_solver_name, their parses, rn_solver_is_distributed), rn_solve's refusals, the
 * scene reader, the help and errors of `rodnet solve` and `rodnet bench`, and the
 * docs' tables (ctest registry_lists checks them).  Part of the library in every
 * build (also without the solver): no MPI, no Trilinos.
 *
 * Adding a preconditioner: its enum value in rodnet_solve.h (values are ABI: never
 * renumber), one row of RN_PRECONDITIONER_LIST below (in enum order: the library
 * does not compile otherwise) and its folder shim_cxx/pc/impls/<name>/ with the
 * factory make_<enum value> in its register.cpp (the sources in
 * shim_cxx/CMakeLists.txt; shim_cxx/pc/registry.cpp makes its table from this list);
 * a row in the docs' tables (docs/solvers.md, docs/cli.md, docs/scene-format.md: the test
 * names what is missing).  The scene reader, the command, rodnet bench
 * (tr-krylov-<name>, nox-<name>) and the conformance suite (shim_dd_solve,
 * mpi_conformance) take it from the row.  A solver kind likewise: its enum value,
 * one row of RN_SOLVER_LIST, its run_* in shim_cxx/newton/ and its case in
 * shim_cxx/api/solve_api.cpp (solve_load_step), the docs' rows. */
#ifndef RODNET_REGISTRY_H
#define RODNET_REGISTRY_H

#include <stddef.h>

#include "rodnet_solve.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- preconditioners ---------------------------------------------------------- */

/* What a preconditioner can do (rn_preconditioner_info.flags). */
enum {
  /* the whole network on one rank only: refused on a part of a distributed network */
  RN_PC_ONE_RANK = 1u << 0,
  /* needs the MPI runtime in Trilinos 13.2 (mpirun, or RODNET_MPI=1 on one process):
   * RN_ERR_TRILINOS with "MPI runtime" in the message otherwise */
  RN_PC_MPI_RUNTIME = 1u << 1,
  /* exact (M = H, one MINRES iteration) on one rank where H is positive definite */
  RN_PC_EXACT = 1u << 2,
  /* stands for another row (rn_preconditioner_info.resolves_to), which the solve
   * reports (rn_solve_report.preconditioner) */
  RN_PC_ALIAS = 1u << 3
};

/* The rows, in enum order: X(value, name, resolves_to, flags, help). */
#define RN_PRECONDITIONER_LIST(X)                                                       \
  X(RN_PRECOND_AUTO, "auto", RN_PRECOND_DD, RN_PC_ALIAS, "the default: dd")             \
  X(RN_PRECOND_FACTOR, "factor", RN_PRECOND_FACTOR, RN_PC_ONE_RANK | RN_PC_EXACT,       \
    "Cholesky of the shifted Hessian H + sigma D")                                      \
  X(RN_PRECOND_LOCAL, "local", RN_PRECOND_LOCAL, RN_PC_EXACT,                           \
    "block Jacobi: each rank's Cholesky of its own block")                              \
  X(RN_PRECOND_GATHERED, "gathered", RN_PRECOND_GATHERED, RN_PC_EXACT,                  \
    "factor's matrix gathered on rank 0: exact, not scalable")                          \
  X(RN_PRECOND_DD, "dd", RN_PRECOND_DD, RN_PC_EXACT,                                    \
    "rod-level domain decomposition (direct or multigrid coarse solve)")                \
  X(RN_PRECOND_MUELU, "muelu", RN_PRECOND_MUELU, RN_PC_MPI_RUNTIME,                     \
    "algebraic multigrid (MueLu) on the whole Hessian")                                 \
  X(RN_PRECOND_IFPACK2, "ifpack2", RN_PRECOND_IFPACK2, RN_PC_MPI_RUNTIME | RN_PC_EXACT, \
    "Ifpack2 additive Schwarz with local LU")                                           \
  X(RN_PRECOND_FROSCH, "frosch", RN_PRECOND_FROSCH, RN_PC_MPI_RUNTIME,                  \
    "FROSch two-level overlapping Schwarz")                                             \
  X(RN_PRECOND_DD_AMG, "dd-amg", RN_PRECOND_DD_AMG, RN_PC_MPI_RUNTIME,                  \
    "dd with the multigrid coarse solve at any size")

typedef struct rn_preconditioner_info {
  rn_preconditioner value;
  const char *name;              /* as rn_preconditioner_name */
  rn_preconditioner resolves_to; /* what the solver runs: value, or for an alias
                                    (RN_PC_ALIAS) the row it stands for */
  unsigned flags;                /* RN_PC_* */
  const char *help;              /* one line, no final period */
} rn_preconditioner_info;

/* The number of rows; row i (i < count; value i), NULL past the end. */
size_t rn_preconditioner_count(void);
const rn_preconditioner_info *rn_preconditioner_info_at(size_t i);
/* The row of a value; NULL for a value outside the enum. */
const rn_preconditioner_info *rn_preconditioner_info_of(rn_preconditioner p);

/* ---- solver kinds --------------------------------------------------------------- */

/* What a solver kind can do (rn_solver_info.flags). */
enum {
  /* solves a part of a distributed network (rn_solver_is_distributed); the others
   * factor the whole Hessian on one process */
  RN_SOLVER_CAN_DISTRIBUTE = 1u << 0,
  /* takes rn_solve_options.preconditioner (and reports the one it used) */
  RN_SOLVER_TAKES_PRECONDITIONER = 1u << 1,
  /* solves a network with a couple fixed in space (rodnet_couple.h): Newton on the
   * residual; the others are energy minimisers and refuse it */
  RN_SOLVER_FIXED_COUPLES = 1u << 2,
  /* descends the energy (the couples' tilt check applies, rodnet_couple.h) */
  RN_SOLVER_DESCENDS = 1u << 3,
  /* follows negative curvature: leaves saddles (finds a local minimum) */
  RN_SOLVER_LEAVES_SADDLES = 1u << 4,
  /* starts load steps with the load-step predictor (rn_solve_options.predictor);
   * the others use gradients only */
  RN_SOLVER_PREDICTOR = 1u << 5
};

/* The rows, in enum order: X(value, name, flags, help). */
#define RN_SOLVER_LIST(X)                                                               \
  X(RN_SOLVER_TR_MINRES, "tr-minres",                                                   \
    RN_SOLVER_DESCENDS | RN_SOLVER_LEAVES_SADDLES | RN_SOLVER_PREDICTOR,                \
    "trust region, MINRES + Cholesky of the shifted Hessian")                           \
  X(RN_SOLVER_ROL_TR_TCG, "rol-tr-tcg", RN_SOLVER_DESCENDS | RN_SOLVER_PREDICTOR,       \
    "ROL trust region with truncated CG")                                               \
  X(RN_SOLVER_ROL_LS_NEWTON, "rol-ls-newton", RN_SOLVER_DESCENDS | RN_SOLVER_PREDICTOR, \
    "ROL line-search Newton with MINRES")                                               \
  X(RN_SOLVER_TR_KRYLOV, "tr-krylov",                                                   \
    RN_SOLVER_CAN_DISTRIBUTE | RN_SOLVER_TAKES_PRECONDITIONER | RN_SOLVER_DESCENDS |    \
        RN_SOLVER_LEAVES_SADDLES | RN_SOLVER_PREDICTOR,                                 \
    "Newton-Krylov trust region, preconditioned MINRES")                                \
  X(RN_SOLVER_NOX, "nox",                                                               \
    RN_SOLVER_CAN_DISTRIBUTE | RN_SOLVER_TAKES_PRECONDITIONER |                         \
        RN_SOLVER_FIXED_COUPLES | RN_SOLVER_PREDICTOR,                                  \
    "NOX Newton on grad E = 0: stationary points, not a minimiser")                     \
  X(RN_SOLVER_ROL_LBFGS, "rol-lbfgs", RN_SOLVER_DESCENDS,                               \
    "ROL limited-memory BFGS, line search, gradients only")

typedef struct rn_solver_info {
  rn_solver_kind value;
  const char *name; /* as rn_solver_name */
  unsigned flags;   /* RN_SOLVER_* */
  const char *help; /* one line, no final period */
} rn_solver_info;

size_t rn_solver_count(void);
const rn_solver_info *rn_solver_info_at(size_t i);
const rn_solver_info *rn_solver_info_of(rn_solver_kind k);

#ifdef __cplusplus
}
#endif
#endif

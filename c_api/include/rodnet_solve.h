/* rodnet_solve.h - equilibrium solvers (implemented in shim_cxx/ on Trilinos).
 *
 * rn_solve minimises the network energy over the reduced DOFs, starting from
 * the network's current state, and leaves the solution as the current state
 * (with the reference frames updated).  No C++ exception crosses this API.
 * On a whole network rn_solve runs on the calling process alone and is safe to
 * call with or without MPI initialised.  On a part of a network
 * (rn_network_set_part, docs/parallel.md) it is collective over MPI_COMM_WORLD:
 * every rank calls it with its part and the same options, and only solver
 * kinds for which rn_solver_is_distributed() holds can run.
 */
#ifndef RODNET_SOLVE_H
#define RODNET_SOLVE_H

#include "rodnet.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum rn_solver_kind {
  /* rodnet's trust region: (H + lambda D) s = -g (D = |diag H| of the first
   * iteration) solved by Belos MINRES preconditioned by a Cholesky
   * factorisation of H + (lambda + sigma) D (banded or sparse, see
   * rn_factorization); negative curvature handled (leaves saddles). */
  RN_SOLVER_TR_MINRES = 0,
  /* ROL trust region with truncated CG (Steihaug-Toint), preconditioned. */
  RN_SOLVER_ROL_TR_TCG = 1,
  /* ROL line-search Newton-Krylov with Belos MINRES as the Krylov solver. */
  RN_SOLVER_ROL_LS_NEWTON = 2,
  /* Newton-Krylov trust region (issue 7): the step from preconditioned MINRES
   * that stops at the trust-region boundary (in the preconditioner's norm), on
   * nonpositive curvature, or at an inexact-Newton forcing tolerance; any SPD
   * preconditioner (rn_preconditioner); leaves saddles; scales to large and
   * distributed problems.  tr-minres stays the exact reference. */
  RN_SOLVER_TR_KRYLOV = 3,
  /* NOX Newton on grad E = 0 (full steps) with Belos MINRES (Stratimikos),
   * left-preconditioned by the same SPD preconditioner as RN_SOLVER_TR_KRYLOV:
   * finds stationary points (minima, saddles or maxima alike; it neither
   * measures the energy nor follows negative curvature), an alternative for
   * comparisons, not a minimiser. */
  RN_SOLVER_NOX = 4,
  /* ROL limited-memory BFGS (10 pairs) with an Armijo backtracking line search:
   * gradients only (no Hessian, no preconditioner, no Krylov solver, no load-step
   * predictor); a first-order reference for the optimiser benchmark
   * (docs/benchmarking.md): thousands of iterations on stiff rods, where it
   * often stalls (step test) or hits max_iterations. */
  RN_SOLVER_ROL_LBFGS = 5
} rn_solver_kind;

/* SPD preconditioner of the Newton systems of RN_SOLVER_TR_KRYLOV; it defines
 * the trust-region norm (docs/solvers.md). */
typedef enum rn_preconditioner {
  RN_PRECOND_AUTO = 0,     /* the default for the problem: dd */
  RN_PRECOND_FACTOR = 1,   /* Cholesky of H + sigma D (rn_factorization), sigma the
                              smallest shift that factors: exact when H is positive
                              definite (one MINRES iteration); one rank only */
  RN_PRECOND_LOCAL = 2,    /* block Jacobi over the ranks: each rank's sparse
                              Cholesky of its owned block H_pp + sigma_p D_p (the
                              factor preconditioner on one rank); docs/parallel.md */
  RN_PRECOND_GATHERED = 3, /* the factor preconditioner's matrix on any number of
                              ranks: the whole Hessian gathered on rank 0 and
                              factored there (exact; not scalable: for tests and
                              small problems); docs/parallel.md */
  RN_PRECOND_DD = 4,       /* rod-level domain decomposition: banded Cholesky of every
                              rod's interior, exact static condensation onto the
                              joints, the coarse problem by sparse Cholesky (on rank
                              0) or, when that costs more than 5e10 flops, one
                              algebraic-multigrid V-cycle; exact when H is positive
                              definite and the coarse solve direct (one MINRES
                              iteration); any number of ranks */
  RN_PRECOND_MUELU = 5,    /* one MueLu smoothed-aggregation V-cycle on the whole
                              Hessian (rigid-body near-null space); MPI runtime */
  RN_PRECOND_IFPACK2 = 6,  /* Ifpack2 additive Schwarz, one subdomain per rank with
                              overlap 1, local sparse LU (exact on one rank); MPI
                              runtime */
  RN_PRECOND_FROSCH = 7,   /* FROSch two-level overlapping Schwarz: one subdomain per
                              rank (overlap 1, local sparse LU) plus a coarse space of
                              the rigid-body modes on the subdomain interfaces (one
                              rank: the whole network; rigid-body modes of the whole
                              network only); MPI runtime */
  RN_PRECOND_DD_AMG = 8    /* "dd-amg": the rod-level domain decomposition with the
                              algebraic-multigrid coarse solve whatever its size (dd
                              chooses it only past 5e10 flops): to measure and test
                              the large-lattice configuration on small ones; MPI
                              runtime */
} rn_preconditioner;

/* Factorisation of the shifted Hessian H + sigma D used by TR-MINRES (multiplier
 * search, negative curvature) and as the SPD preconditioner of every solver kind
 * (docs/solvers.md). */
typedef enum rn_factorization {
  /* banded if the Hessian's half bandwidth is at most 64 (single rods, networks
   * without joints), sparse otherwise (networks with joints) */
  RN_FACTOR_AUTO = 0,
  /* LAPACK banded Cholesky (dpbtrf): memory n (kd + 1), kd the half bandwidth;
   * refused when that exceeds 4 GiB */
  RN_FACTOR_BANDED = 1,
  /* rodnet's supernodal multifrontal sparse Cholesky with a METIS
   * nested-dissection ordering */
  RN_FACTOR_SPARSE = 2,
  /* SuiteSparse CHOLMOD's supernodal Cholesky with a METIS ordering: the library
   * reference for RN_FACTOR_SPARSE (same results to round-off, slower) */
  RN_FACTOR_CHOLMOD = 3
} rn_factorization;

/* Is a state a verified local minimum?  From the lowest eigenvalues of the
 * reduced Hessian H (fixed DOFs removed) at the state, Jacobi-scaled: those of
 * D^{-1/2} H D^{-1/2}, D = |diag H|, which are dimensionless and do not depend on
 * the units or the size of the structure, and have the signs and zero modes of H
 * (rn_network_stability, docs/solvers.md "Stability"). */
/* rn_solve_options.stability_method, rn_stability.method. */
typedef enum rn_stability_method {
  RN_STABILITY_AUTO = 0,
  RN_STABILITY_CHOLESKY = 1, /* factorisations of H - sigma D (inertia) */
  RN_STABILITY_LOBPCG = 2    /* Anasazi LOBPCG preconditioned by the solver's
                                preconditioner (no factorisation of the whole H) */
} rn_stability_method;

/* The automatic choice's budget: the Cholesky check is used when one numeric
 * factorisation of the whole Hessian takes at most this many flops. */
#define RN_STABILITY_MAX_FLOPS 5e10

typedef struct rn_stability {
  int checked;              /* 1 if computed; 0: skipped (stability = 0), not
                               available (a part of a distributed network, Cholesky
                               forced on one: it needs the whole Hessian) or LOBPCG
                               gave no converged eigenpair (method stays LOBPCG) */
  double lowest_eigenvalue; /* lowest eigenvalue of D^{-1/2} H D^{-1/2} outside the
                               symmetries (the soft modes included; 0 if there is
                               none) */
  double scale;             /* ||D^{-1/2} H D^{-1/2}||_inf, the largest absolute row
                               sum (an upper bound of every |eigenvalue|, >= 1): judge
                               the eigenvalues against it */
  int verified_minimum;     /* 1: the Hessian is positive definite outside the
                               symmetries, established by a Cholesky factorisation
                               (inertia) or by converged Ritz pairs; in
                               rn_solve_report also the solve converged.  0:
                               unstable (a negative eigenvalue), soft modes whose
                               sign the check cannot resolve (a mechanism), or not
                               converged */
  int zero_modes;           /* eigenvalues the check cannot tell from zero: the
                               symmetries plus the soft modes not shown positive
                               (symmetries + soft_modes - soft_positive), counted
                               among the 10 lowest */
  long factorizations;      /* Cholesky factorisations the check took */
  double time_s;            /* its wall time */
  int method;               /* how (rn_stability_method): RN_STABILITY_CHOLESKY or
                               RN_STABILITY_LOBPCG; 0 if skipped */
  int iterations;           /* LOBPCG iterations (0 for the Cholesky check) */
  double cholesky_flops;    /* the cost model: flops of one Cholesky factorisation
                               of the whole Hessian (0 if not estimated: LOBPCG
                               forced, or a distributed network) */
  int symmetries;           /* exact zero modes of the energy at the state: the
                               rigid motions no constraint blocks and the spins of
                               rods' material frames (candidates built from the
                               model, kept when H v = 0 to 1e-8 scale), excluded
                               from the verdict; -1: not separated (LOBPCG on a
                               distributed network: zero_modes counts them) */
  int soft_modes;           /* eigenvalues outside the symmetries with |lambda| <=
                               1e-12 scale: very soft modes (the long-wave bending
                               of a finely discretised rod) or mechanisms; -1: not
                               separated */
  int soft_positive;        /* of the soft modes, how many the check showed to be
                               positive (Cholesky of H itself, or each Ritz value
                               above its residual); verified_minimum needs all */
} rn_stability;

/* Why a solve stopped. */
typedef enum rn_solve_stop {
  RN_STOP_GRADIENT = 0,   /* equilibrium: force and moment residuals within their
                             tolerances on the physical scale (and ||g|| <= gtol_abs
                             if set) */
  RN_STOP_STEP = 1,       /* ||s|| <= step_tol * (1 + ||x||) after an accepted step */
  RN_STOP_ENERGY = 2,     /* |dE| <= energy_tol * (1 + |E|) on an accepted step
                             (off by default) */
  RN_STOP_MAX_ITER = 3,   /* iteration limit: not converged */
  RN_STOP_RADIUS = 4,     /* trust radius collapsed: not converged */
  RN_STOP_FAILED = 5,     /* error (see status / context) */
  RN_STOP_INTERRUPTED = 6 /* rn_solve_options.interrupt was set: stopped at the
                             next iteration check, not converged (no load cut,
                             no stability check) */
} rn_solve_stop;

/* Per-iteration progress (passed to the callback once per Newton iteration). */
typedef struct rn_iteration_info {
  int iteration;
  double energy;
  double gradient_norm;
  double radius;         /* trust radius (0 for line search) */
  int krylov_iterations; /* this iteration */
  double seconds;        /* since the start of the solve */
  double load_factor;
} rn_iteration_info;

typedef struct rn_solve_options {
  rn_solver_kind solver;
  int max_iterations;        /* Newton iterations per load step (default 200) */
  double gtol_rel;           /* default 1e-9: the force (moment) residual relative
                                to the force (moment) scale of the applied loads and
                                reactions (see rn_solve) */
  double gtol_abs;           /* default 0 (off); > 0: ||g|| <= gtol_abs is required
                                as well (not an alternative) */
  double step_tol;           /* default 1e-12 */
  double energy_tol;         /* default 0 (off): a tiny energy change does not
                                certify equilibrium */
  int krylov_max_iterations; /* default 500 */
  double krylov_tol;         /* relative MINRES residual, default 1e-10 */
  double initial_radius;     /* default 0: automatic */
  int load_steps;            /* > 0: fixed number of continuation steps;
                                0 (default): one step, split automatically
                                when a full step fails */
  int max_load_cuts;         /* automatic halvings allowed (default 8; none where
                                nothing depends on the load factor: no loads, no
                                prescribed motions, not a periodic cell) */
  void (*progress)(void *user, const rn_iteration_info *info);
  void *progress_user;
  rn_factorization factorization; /* default RN_FACTOR_AUTO */
  /* 1 (default): each load step from t_prev to t starts with the linearised
   * load-increment predictor: s = -H^{-1} (g(x; t_prev) + dg), dg from
   * rn_network_load_increment, H factored like the solver's preconditioner
   * (shifted if not positive definite); x + s is accepted only if it lowers
   * the energy at t.  0: off (the step starts at x). */
  int predictor;
  rn_preconditioner preconditioner; /* RN_SOLVER_TR_KRYLOV, RN_SOLVER_NOX; default AUTO */
  /* 1 (default): after the solve, check the stability of the returned state
   * (rn_solve_report.stability, rn_network_stability); 0: skip it (benchmarks;
   * the check costs one to a few factorisations of the Hessian) */
  int stability;
  /* How the stability check computes the lowest eigenvalues (docs/solvers.md
   * "Stability"): RN_STABILITY_AUTO (default) Cholesky inertia and subspace
   * iteration on factorisations of the whole Hessian when one costs at most
   * RN_STABILITY_MAX_FLOPS (and always for the solver kinds that factor it),
   * LOBPCG otherwise and always on a distributed network; CHOLESKY or LOBPCG
   * force one (CHOLESKY on a part of a distributed network: not checked,
   * stability.checked = 0; rodnet solve then checks the gathered network). */
  int stability_method;
  /* NULL (default), or a flag the caller may set (from a signal handler or
   * another thread) to stop the solve: it is read at every iteration check
   * (once per Newton iteration, after progress), and a non-zero value stops
   * the solve there with RN_STOP_INTERRUPTED, the network at that iterate. */
  const volatile int *interrupt;
  /* The relative residual each Newton step's Krylov solve is asked for
   * (RN_SOLVER_NOX): 0 (default) Eisenstat-Walker choice 2, at most 0.1 and at
   * least max(krylov_tol, 1e-4) (docs/solvers.md, "Forcing terms"); in (0, 1):
   * that constant forcing for every step.  The cell's relaxation on a part of a
   * distributed periodic cell (rn_cell_relax) asks 1e-6: on the principal branch
   * past an instability an inexact step may leave it for a buckled state. */
  double forcing;
} rn_solve_options;

void rn_solve_options_default(rn_solve_options *opt);

typedef struct rn_solve_report {
  rn_status status;   /* RN_OK if the solver ran (converged or not) */
  rn_solve_stop stop; /* which test stopped it */
  int converged;      /* 1 if stop is GRADIENT, STEP or ENERGY */
  int iterations;     /* Newton iterations, all load steps */
  long energy_evals, gradient_evals, hvp_evals, hessian_evals;
  long krylov_iterations; /* total MINRES/CG iterations */
  int load_steps;         /* continuation steps taken */
  double energy, gradient_norm, initial_gradient_norm;
  double time_s;
  rn_factorization factorization; /* the one used (never RN_FACTOR_AUTO once
                                     the solver ran) */
  long factorizations; /* numeric Cholesky factorisations of H + sigma D, failed
                          ones included (the main cost on large networks) */
  int predictor_steps; /* load steps whose predictor step was accepted */
  /* Equilibrium at the last iterate on the physical scale (the gradient test;
   * docs/solvers.md "Stopping tests"): the largest |g_i| over position DOFs (a
   * force) and over material angles and joint rotations (a moment), the force
   * and moment scales they are measured against (applied loads and support
   * reactions, rn_network_reactions) and the tolerances the gradient test
   * required, max(gtol_rel * scale, 10 * round-off floor).  All 0 when no
   * iteration was checked (no free DOFs). */
  double force_residual, moment_residual;
  double force_scale, moment_scale;
  double force_tolerance, moment_tolerance;
  /* the preconditioner RN_SOLVER_TR_KRYLOV used (never AUTO once it ran);
   * RN_PRECOND_AUTO for the other kinds */
  rn_preconditioner preconditioner;
  /* Where the time went (wall seconds, this process; under MPI rank 0's): Hessian
   * assembly (every solver kind), and the setups and applications of the
   * preconditioner of RN_SOLVER_TR_KRYLOV and RN_SOLVER_NOX, their load-step
   * predictors included (0 for the other kinds, whose factorisations are not
   * split out). */
  double hessian_seconds, preconditioner_setup_seconds, preconditioner_apply_seconds;
  /* of the returned state (every solver kind), unless rn_solve_options.stability
   * is 0; not in time_s and factorizations (it has its own) */
  rn_stability stability;
} rn_solve_report;

/* Name of a stop reason ("gradient", "step", "energy", "max_iterations", "radius",
 * "failed", "interrupted"); name of a solver kind (rodnet_registry.h: "tr-minres",
 * "rol-tr-tcg", "rol-ls-newton", "tr-krylov", "nox", "rol-lbfgs"); parse a solver name
 * (RN_ERR_ARG if unknown). */
const char *rn_solve_stop_name(rn_solve_stop s);
const char *rn_solver_name(rn_solver_kind k);
rn_status rn_solver_from_name(const char *name, rn_solver_kind *k);
/* 1 if the solver kind can solve a network distributed over MPI ranks (its
 * Newton systems never need the whole Hessian on one process), 0 otherwise.
 * TR-KRYLOV and NOX (RN_SOLVER_CAN_DISTRIBUTE in rodnet_registry.h);
 * TR-MINRES and the ROL kinds factor the whole Hessian: one process only. */
int rn_solver_is_distributed(rn_solver_kind k);
/* Name of a factorisation ("auto", "banded", "sparse") and its parse
 * (RN_ERR_ARG if unknown). */
const char *rn_factorization_name(rn_factorization f);
rn_status rn_factorization_from_name(const char *name, rn_factorization *f);
/* Name of a preconditioner (rodnet_registry.h lists them: "auto", "factor", ...,
 * "dd-amg"; "unknown" outside the enum) and its
 * parse (RN_ERR_ARG if unknown). */
const char *rn_preconditioner_name(rn_preconditioner p);
rn_status rn_preconditioner_from_name(const char *name, rn_preconditioner *p);

/* ---- runtime (Kokkos / MPI) ------------------------------------------------
 * The solvers run on Tpetra, whose runtime (Kokkos and, in an MPI job, MPI) must
 * be initialised once per process.  Programs should call
 * rn_runtime_initialize(&argc, &argv) at the start of main() and
 * rn_runtime_finalize() before returning.  If they do not, the first rn_solve
 * initialises it and registers rn_runtime_finalize() with atexit().
 * MPI is used (and initialised by rodnet if the program has not done it) only
 * when the process belongs to an MPI job: MPI is already initialised, or an MPI
 * launcher started the process (OMPI_COMM_WORLD_SIZE, PMIX_RANK, PMI_RANK or
 * PMI_SIZE set in the environment), or RODNET_MPI=1; RODNET_MPI=0 forbids it.
 * Otherwise only Kokkos is initialised and rodnet never calls MPI_Init (a
 * singleton MPI_Init costs a few tenths of a second).  A program that calls MPI
 * itself should initialise MPI before rodnet's runtime: under a launcher rodnet
 * would otherwise have initialised it, and MPI_Init cannot be called twice.
 * Idempotent: initialising twice is a no-op.  rn_runtime_finalize() finalises
 * only what rodnet initialised (never an MPI or Kokkos the caller set up), after
 * which no solve may run (neither MPI nor Tpetra can be initialised again):
 * rn_runtime_initialize and rn_solve then return RN_ERR_STATE.
 * argc/argv may be NULL.  Not thread-safe; call from the main thread. */
rn_status rn_runtime_initialize(int *argc, char ***argv);
void rn_runtime_finalize(void);

/* Solve for equilibrium of a finalized network.  Fills rep (may be NULL);
 * opt NULL means rn_solve_options_default().  Returns RN_OK when the solver
 * ran to a stop (check rep->converged), an error code otherwise (message in
 * the network's context; RN_ERR_ARG for invalid options).
 *
 * Load stepping: the target is the network's load factor at the call (normally
 * 1).  load_steps = N > 0 solves at target*k/N, k = 1..N, stopping at the first
 * step that does not converge.  load_steps = 0 tries the target directly; if
 * that does not converge it goes back to the last converged state (restored
 * exactly from its rn_network_state_save snapshot: DOFs, reference frames,
 * joint rotations) and halves the increment, at most
 * max_load_cuts times, doubling it again after each converged step.  When the
 * solve does not converge the network is left at the last iterate of the last
 * attempt, at that attempt's load factor (rn_network_load_factor tells).
 *
 * Stopping (per load step; rep->stop says which test fired): gradient
 * (equilibrium) when the largest force residual (|g_i| over position DOFs) is
 * at most max(gtol_rel F, 10 f_F) and the largest moment residual (material
 * angles, joint rotations) at most max(gtol_rel M, 10 f_M), where F = max(F0,
 * M0 / L) and M = max(M0, F0 L), F0 and M0 the largest applied force / couple
 * or support reaction force / moment at the iterate, L the size of the
 * structure (bounding-box diagonal), and f_F, f_M the round-off floor of the
 * gradient there; and ||g|| <= gtol_abs if gtol_abs > 0 (rep->force_residual
 * and the fields after it report the values); step and energy (energy off by
 * default) only after an accepted step the globalisation did not shorten (full
 * Newton step: interior trust-region step / unit line-search step).  TR-MINRES applies no
 * convergence test while the Hessian has significant negative curvature (a saddle is not
 * a solution).  rep->krylov_iterations counts MINRES iterations (TR-MINRES,
 * ROL-LS-Newton) or truncated-CG iterations (ROL-TR-TCG, counted as Hessian-
 * vector products); rep->hvp_evals counts matrix-free and CSR Hessian-vector
 * products; rep->load_steps counts load steps attempted (including those cut
 * back).  Only TR-MINRES leaves saddles; the ROL kinds can stop at one (check
 * with rn_hessian_min_eigenvalue).  A network without free DOFs is converged
 * at once (iterations 0). */
rn_status rn_solve(rn_network *net, const rn_solve_options *opt, rn_solve_report *rep);

/* ---- distributed solves (docs/parallel.md) ----------------------------------
 * Partition the rod graph (as rn_network_rod_graph gives it) into nparts:
 * rod_part[nrods] receives each rod's part.  METIS_PartGraphKway on the graph
 * whose vertices are the rods, weighted by their DOF counts (4 nv - 1), and whose
 * edges join rods sharing a joint, with a fixed seed (every rank and every run
 * computes the same partition) and contiguous parts when the graph is connected.
 * nparts = 1: every rod in part 0 (no METIS call); nparts >= nrods: rod r in part
 * r; no shared joints: heaviest rod first into the lightest part.  *edge_cut (may
 * be NULL): rod pairs sharing a joint that the partition separates.  Not
 * collective.  RN_ERR_ARG for a malformed graph. */
rn_status rn_partition_rods(int nrods, const int *rod_nv, int njoints,
                            const int *joint_ptr, const int *joint_rods, int nparts,
                            int *rod_part, long *edge_cut);

/* Rank and number of ranks of MPI_COMM_WORLD once the runtime is initialised
 * (rank 0 of 1 without MPI). */
void rn_runtime_ranks(int *rank, int *size);

/* Collective over MPI_COMM_WORLD: agree on the statuses of one step that every
 * rank ran.  Returns RN_OK if every rank passed RN_OK, else the status of the
 * lowest-numbered rank that did not, whose context message (prefixed "rank R: "
 * on other ranks when there are several) is then recorded in ctx on every rank. */
rn_status rn_dist_agree(rn_context *ctx, rn_status local);

/* Collective over MPI_COMM_WORLD: v[0 .. n-1] reduced elementwise over the ranks
 * in place on every rank (op: RN_DIST_SUM, RN_DIST_MAX or RN_DIST_MIN).  A no-op
 * on one rank.  RN_ERR_ARG for a bad op or n < 0. */
typedef enum rn_dist_op { RN_DIST_SUM = 0, RN_DIST_MAX = 1, RN_DIST_MIN = 2 } rn_dist_op;
rn_status rn_dist_allreduce_int(int *v, int n, int op);
/* The same for doubles (MPI_SUM of the same inputs gives the same result on
 * every rank). */
rn_status rn_dist_allreduce_double(double *v, int n, int op);

/* Notices: small records (n <= RN_DIST_NOTICE_INTS integers and a text of at
 * most RN_DIST_NOTICE_TEXT - 1 bytes) sent from any rank to rank 0 while the
 * ranks work independently (progress of independent tasks, their failures),
 * without a collective.  rn_dist_notice_send (rank > 0) does not wait for rank
 * 0: the record is buffered until it is delivered; rn_dist_notice_poll (rank 0)
 * takes one arrived record if there is one (1, with its ints, text and the
 * sender's rank; 0 if none has arrived; it never waits); rn_dist_notice_flush
 * (rank > 0) waits until this rank's records are delivered, e.g. before a
 * collective that ends the independent work.  Not collective.  On one rank
 * (or rank 0 sending) nothing is sent.  RN_ERR_ARG for bad arguments. */
enum { RN_DIST_NOTICE_INTS = 8, RN_DIST_NOTICE_TEXT = 1024 };
rn_status rn_dist_notice_send(const int *v, int n, const char *text);
int rn_dist_notice_poll(int *v, int n, char *text, size_t text_size, int *from);
rn_status rn_dist_notice_flush(void);

/* Collective: the partition's sizes per rank, gathered on every rank:
 * owned_dofs[ranks] and owned_stencils[ranks] (arrays of at least *ranks entries
 * allocated by the caller: call with owned_dofs = NULL first to get *ranks). */
rn_status rn_dist_part_sizes(const rn_network *net, int *ranks, long *owned_dofs,
                             long *owned_stencils);

/* Collective: the states of every rank's part (rn_network_part_state_pack)
 * installed on rank 0 into whole, a network of the whole scene at the same load
 * factor (ignored, may be NULL, on the other ranks), so that rank 0 can write the
 * results.  The status is rank 0's (use rn_dist_agree to share it). */
rn_status rn_dist_gather_state(const rn_network *part, rn_network *whole);

/* Smallest eigenvalue of the reduced Hessian at the current state; used by
 * stability checks (e.g. buckling).  Half bandwidth kd =
 * rn_network_hessian_bandwidth <= 64 (no joints): LAPACK dsbevx on the banded
 * Hessian, exact up to round-off, memory n (kd + 1).  Otherwise (joints):
 * bisection on the inertia (sparse Cholesky of H - sigma I) to 5 %, then
 * inverse iteration; the Rayleigh quotient is exact up to round-off when the
 * lowest eigenvalue is separated from the next one.  RN_ERR_ARG for a network
 * with a couple fixed in space (rodnet_couple.h: no energy, so no Hessian).
 * Needs no runtime initialisation (no Tpetra). */
rn_status rn_hessian_min_eigenvalue(rn_network *net, double *lambda_min);

/* Stability of the network's current state (see rn_stability), eigenvalues of
 * the pencil (H, D), D = |diag H| floored at 1e-20 of its largest entry: scale =
 * ||D^{-1/2} H D^{-1/2}||_inf.  First the symmetries (rigid motions and frame
 * spins that H maps to zero).  Without any, Cholesky of H - delta D (delta =
 * 1e-12 scale) succeeds: every eigenvalue exceeds delta, verified, the lowest
 * estimated by shift-and-invert Lanczos (an upper bound, 1e-6 relative);
 * otherwise subspace iteration on a block of 10 vectors with (H + s D)^{-1} D
 * on the complement of the symmetries, s the smallest shift that factors, gives
 * the soft modes (|lambda| <= delta) and the lowest eigenvalue; soft modes are
 * shown positive by the Cholesky factorisation of H itself (no symmetries) or by
 * Ritz values above their residuals.  The banded or
 * sparse factorisation as rn_solve's RN_FACTOR_AUTO chooses.  verified_minimum
 * here concerns the Hessian alone (not equilibrium).  A part of a distributed
 * network: the LOBPCG check on the distributed Hessian (as rn_solve's on a part;
 * collective over the ranks, initialises the runtime).  On a whole network not
 * collective and no runtime initialisation (no Tpetra).  out is filled only on
 * RN_OK. */
rn_status rn_network_stability(rn_network *net, rn_stability *out);
/* ---- path following (docs/path-following.md) --------------------------------
 * Pseudo-arclength continuation of the equilibria of a finalized whole network
 * in one parameter mu, past limit points and snap-backs:
 *  - RN_PATH_LOAD: mu is the load factor (loads and prescribed motions scale
 *    with it, rn_network_set_load_factor; mu stays in [0, 1]);
 *  - RN_PATH_DOF: mu is the value of one free reduced DOF (a coordinate of a
 *    vertex or joint: displacement control), the load factor stays fixed, and
 *    the conjugate force dE/dq of that DOF is what holds it there.
 * The unknowns z = (x, mu) satisfy r(x, mu) = 0 (the gradient, without the
 * controlled DOF's row under displacement control) and the arclength equation
 * t' W (z - z_prev) = ds, W the metric of RMS changes: positions / L (L the
 * size of the structure) and angles, each kind averaged over its DOFs, plus
 * the load factor, or the controlled coordinate / L.  Each corrector iteration solves the
 * bordered Newton system [A b; t_x' W  t_mu] by the bordering algorithm: two solves with
 * A (the Hessian, constrained), by Cholesky when A is positive definite and otherwise by
 * Belos MINRES preconditioned by the Cholesky factorisation of A + sigma D (banded or
 * sparse, opt.factorization).  At every point the lowest eigenvalue of A
 * (rn_hessian_min_eigenvalue's methods) gives the stability; a sign change between two
 * points is a limit point if dmu/ds changed sign there and a bifurcation otherwise, and
 * dmu/ds changing sign while the eigenvalue does not is a bifurcation met along the
 * bifurcated branch; each is located by a secant search in the arclength and reported
 * as an extra point.  With branch_switch set the path leaves each bifurcation onto the
 * other branch through it: along the critical eigenvector when it came along the
 * regular direction (the stable branch of a supercritical pitchfork), else along the
 * regular direction.  Serial: one process, whole network; never prints. */
typedef enum rn_path_control {
  RN_PATH_LOAD = 0, /* continuation in the load factor */
  RN_PATH_DOF = 1   /* displacement control of the reduced DOF opt.dof */
} rn_path_control;

typedef enum rn_path_event {
  RN_PATH_POINT = 0,        /* a regular point of the path */
  RN_PATH_LIMIT = 1,        /* a limit point (located): dmu/ds = 0, A singular */
  RN_PATH_BIFURCATION = 2,  /* a bifurcation point (located): A singular with
                               dmu/ds != 0 */
  RN_PATH_BRANCH_SWITCH = 3 /* the first point on the bifurcated branch */
} rn_path_event;

/* One point of the path (passed to the callback). */
typedef struct rn_path_point {
  int step; /* 0 for the start, then 1, 2, ... (located events
               carry the number of the step they were found in) */
  rn_path_event event;
  double load_factor;
  double control;      /* value of the monitored DOF (under RN_PATH_DOF the
                          controlled one): a coordinate or an angle */
  double displacement; /* control minus its value at the start of the path */
  double force;        /* conjugate force of the monitored DOF: dE/dq of the
                          controlled DOF (RN_PATH_DOF); under RN_PATH_LOAD the
                          applied generalised load there, -mu dr_q/dmu */
  double energy;
  double lowest_eigenvalue; /* of A (RN_PATH_DOF: the Hessian without the
                               controlled DOF); NaN if not computed */
  double eigenvalue_scale;  /* largest |diagonal| of A */
  int stability;            /* +1 stable (lowest eigenvalue > 1e-12 scale),
                               -1 unstable (< -1e-12 scale), 0 critical,
                               -2 not computed */
  double arclength;         /* accumulated, in the W norm */
  int corrector_iterations;
} rn_path_point;

typedef struct rn_path_options {
  rn_path_control control;
  size_t dof;                   /* RN_PATH_DOF: reduced DOF index (rn_network_dof_info) */
  long monitor;                 /* RN_PATH_LOAD: reduced DOF reported as control and
                                   force; -1 (default): the position DOF with the largest
                                   load derivative |dr/dmu| at the start */
  int max_steps;                /* default 200 */
  double ds;                    /* first arclength step (W norm), default 0.01 */
  double ds_min;                /* default 1e-8: smaller steps stop the path */
  double ds_max;                /* default 0.05; steps whose tangent turns by more
                                   than 0.5 rad are halved */
  double direction;             /* sign of dmu/ds at the start: +1 (default) or -1 */
  double target;                /* stop when mu reaches it (the last step lands on it):
                                   default NaN = none for RN_PATH_DOF, 1 for RN_PATH_LOAD */
  int max_corrector_iterations; /* default 15 */
  double tol;                   /* corrector: |r_i| <= tol * (the largest force or moment
                                   magnitude balanced at a DOF of that kind,
                                   rn_network_gradient_magnitude, or the load scale),
                                   default 1e-9 */
  int eigenvalues;              /* 1 (default): lowest eigenvalue at every point (needed
                                   for events); 0: off */
  int branch_switch;            /* 1: leave every bifurcation onto the other branch
                                   through it (see above); default 0 */
  double branch_sign;           /* +1 (default) or -1: which way along the eigenvector
                                   (normalised with its largest component positive) */
  rn_factorization factorization; /* default RN_FACTOR_AUTO */
  /* called once per point (start, regular points, located events); a non-zero
   * return stops the path (RN_PATH_STOP_CALLBACK).  May be NULL. */
  int (*callback)(void *user, const rn_path_point *pt);
  void *user;
} rn_path_options;

typedef enum rn_path_stop {
  RN_PATH_STOP_TARGET = 0,    /* mu reached the target */
  RN_PATH_STOP_MAX_STEPS = 1, /* max_steps taken */
  RN_PATH_STOP_STEP_MIN = 2,  /* the corrector failed down to ds_min */
  RN_PATH_STOP_RANGE = 3,     /* RN_PATH_LOAD: the load factor left [0, 1] */
  RN_PATH_STOP_CALLBACK = 4   /* the callback asked to stop */
} rn_path_stop;

typedef struct rn_path_report {
  rn_path_stop stop;
  int steps;  /* accepted steps */
  int points; /* points passed to the callback */
  int limit_points, bifurcations;
  double limit_load_factor; /* load factor at the first limit point (NaN if none) */
  double limit_control, limit_force; /* control and force there */
  double bifurcation_load_factor;    /* at the first bifurcation (NaN if none) */
  double bifurcation_control, bifurcation_force;
  long corrector_iterations, factorizations;
  double time_s;
} rn_path_report;

void rn_path_options_default(rn_path_options *opt);
/* "point", "limit", "bifurcation", "branch-switch"; "target", "max-steps",
 * "step-min", "range", "callback". */
const char *rn_path_event_name(rn_path_event e);
const char *rn_path_stop_name(rn_path_stop s);

/* Follow the equilibrium path from the network's current state, which must
 * be an equilibrium at its load factor (rn_solve first; under RN_PATH_LOAD the
 * path starts at the network's load factor).  The network is left at the last
 * accepted point (state, reference frames, load factor).  Returns RN_OK when
 * the path ran to a stop (rep->stop says which: a target set but not reached
 * stops otherwise than RN_PATH_STOP_TARGET), RN_ERR_ARG for invalid options
 * (a DOF out of range, a part of a distributed network, a target set at or
 * behind the start in the direction opt.direction), RN_ERR_GEOMETRY if the
 * start is degenerate, RN_ERR_SOLVER if the start is not an equilibrium (the
 * first corrector fails), another error code otherwise; the message in the
 * network's context.  rep may be NULL. */
rn_status rn_path_follow(rn_network *net, const rn_path_options *opt,
                         rn_path_report *rep);

/* Linear effective elasticity of a periodic cell (docs/homogenization.md). */
typedef struct rn_homogenization {
  int dim, nstrain;        /* 2 and 3, or 3 and 6 */
  double measure;          /* cell area (2D) or volume (3D) */
  double C[36];            /* effective stiffness, nstrain x nstrain row-major,
                              Voigt with engineering shear, per unit measure:
                              force per length in 2D, stress in 3D */
  double relative_density; /* rn_network_cell_relative_density */
  size_t fluctuation_dofs; /* size of the factored fluctuation block */
} rn_homogenization;
/* Effective stiffness at the current state of a periodic network (normally the
 * rest state) by the Schur complement of the Hessian onto the strain DOFs,
 * C = (K_ee - K_eu K_uu^-1 K_ue) / measure: one sparse Cholesky factorisation of
 * the fluctuation block K_uu (METIS ordering) solves all strain load cases.
 * Every strain component must be a DOF (RN_ERR_ARG otherwise); RN_ERR_SOLVER if
 * K_uu is not positive definite (a mechanism: a zero-energy periodic
 * fluctuation, or an unstable state); RN_ERR_ARG for a network with a couple
 * fixed in space (rodnet_couple.h: no energy).  On a whole network: serial, needs
 * no runtime initialisation.  On a part of a distributed periodic cell
 * (rn_network_set_part; docs/parallel.md, "Periodic cells under mpirun"):
 * collective over the ranks, through the distributed solver (the strain block of
 * the inverse Hessian by block CG with the rod-level DD, C its inverse over the
 * measure); every rank receives the same h (fluctuation_dofs: the whole cell's). */
rn_status rn_homogenize(rn_network *net, rn_homogenization *h);

/* ---- strain paths and stability of periodic cells (docs/homogenization.md) --- */
typedef struct rn_cell_relax_report {
  int converged;         /* 1 if the fluctuations are in equilibrium */
  int iterations;        /* Newton iterations */
  int predictor;         /* 1 if the tangent predictor step was accepted */
  int indefinite;        /* 1 if the fluctuation block was not positive definite at
                            the solution (an unstable cell-periodic state) */
  double residual;       /* largest |dE/du| at the end */
  double residual_scale; /* largest balancing force there (the test is relative);
                            on a part of a distributed cell the residual and
                            this are rn_solve's force_residual and
                            force_tolerance */
  int sparse_solves;     /* Newton steps on an indefinite K_uu solved by the sparse
                            route (MINRES, rn_cell_relax_method) */
} rn_cell_relax_report;
/* Equilibrium of the fluctuations at the prescribed macroscopic strain
 * strain[nstrain] (the strain components that are DOFs of net are held at those
 * values; components the network prescribes keep the network's values and their
 * entries are ignored): from the current state, the tangent predictor
 * du = -K_uu^-1 (g_u + K_ue d eps) (accepted if it lowers the energy), then
 * Newton with the sparse Cholesky factor of K_uu and a backtracking line search
 * on the energy; where K_uu is not positive definite (past an instability on
 * the cell-periodic branch) Newton steps on the gradient norm with a symmetric
 * indefinite solve: dense (LAPACK dsysv) up to 4000 fluctuation DOFs, beyond
 * that sparse (MINRES preconditioned by the Cholesky factor of K_uu + mu D, the
 * smallest shift mu that factors; rn_cell_relax_method chooses).  Reference
 * frames are updated on every accepted step.  Converged when the largest
 * fluctuation force is at most 1e-9 of the largest balancing force
 * (rn_network_gradient_magnitude) or the Newton step stalls at round-off.
 * Leaves the result as the current state; RN_OK when it ran (check
 * rep->converged).  RN_ERR_ARG for a network with a couple fixed in space
 * (rodnet_couple.h; so also rn_cell_minimize, rn_cell_bloch and
 * rn_cell_bloch_eigen).  Serial; needs no runtime initialisation (but on
 * cells beyond 4000 fluctuation DOFs past an instability, where its sparse
 * indefinite solve initialises Kokkos itself). */
rn_status rn_cell_relax(rn_network *net, const double *strain, rn_cell_relax_report *rep);
/* rn_cell_relax with the indefinite solves of method (rn_bloch_method values):
 * RN_BLOCH_AUTO as rn_cell_relax, RN_BLOCH_DENSE always dense (a cell beyond 4000
 * fluctuation DOFs then stops unconverged where K_uu is indefinite),
 * RN_BLOCH_SPARSE always sparse (the route of large cells, on any cell: the
 * tests compare it with the dense one).  The sparse route initialises the solver
 * runtime (Kokkos) itself.  RN_ERR_ARG for another method. */
rn_status rn_cell_relax_method(rn_network *net, const double *strain, int method,
                               rn_cell_relax_report *rep);
/* As rn_cell_relax, but a minimisation of the energy over the fluctuations that
 * may leave the cell-periodic (principal) branch, e.g. onto the bifurcated branch
 * of a supercell after a perturbation along its critical mode: Newton with the
 * sparse Cholesky factor of K_uu + mu D (D = |diag K_uu|; mu = 0 where K_uu is
 * positive definite, else the smallest shift 1e-10 4^k that factors), an Armijo
 * backtracking line search on the energy and, at a stationary point where K_uu is
 * indefinite (a saddle), steps along the lowest mode of (K_uu, D) by inverse
 * iteration.  rep->converged only at an equilibrium with K_uu positive definite
 * (rep->indefinite 0): a local minimum of the fluctuations at that strain.  No
 * tangent predictor.  Serial; needs no runtime initialisation. */
rn_status rn_cell_minimize(rn_network *net, const double *strain,
                           rn_cell_relax_report *rep);

/* Which Bloch modes rn_cell_bloch examines. */
typedef enum rn_bloch_modes {
  RN_BLOCH_ALL = 0,         /* every DOF */
  RN_BLOCH_IN_PLANE = 1,    /* 2D cells at a planar state: x, y positions and the
                               joint rotation about z (what a planar model sees) */
  RN_BLOCH_OUT_OF_PLANE = 2 /* 2D cells at a planar state: z, material angles, joint
                               rotations about x and y */
} rn_bloch_modes;
/* How rn_cell_bloch solves its eigenproblems. */
typedef enum rn_bloch_method {
  RN_BLOCH_AUTO = 0,  /* dense up to 64 Bloch DOFs, sparse beyond (measured faster) */
  RN_BLOCH_DENSE = 1, /* LAPACK zheevr on the dense Bloch Hessian (<= 4000 DOFs) and
                         the dense moments for the acoustic tensor: the oracle */
  RN_BLOCH_SPARSE = 2 /* at any size: rn_cell_bloch_lowest_sparse per wave vector
                         (the lowest neig at the minimum by deflated runs), the
                         acoustic tensor from rn_network_bloch_moment_csr and the
                         sparse Cholesky factor of the fluctuation block */
} rn_bloch_method;
typedef struct rn_bloch_options {
  int grid;   /* wave vectors per reciprocal direction of the Brillouin-zone
                 grid (default 0: 16 in 2D, 6 in 3D) */
  int refine; /* 1 (default): refine the grid minima by a quasi-Newton descent in
                 xi with the Hellmann-Feynman gradient (rn_cell_bloch_gradient) */
  rn_bloch_modes modes;
  const double *xi_hint; /* optional: also start a refinement here (dim) */
  int method; /* an rn_bloch_method (int: any value is checked); default RN_BLOCH_AUTO */
  /* 1: no grid scan, only the refinement from xi_hint (a tracked minimum, e.g.
   * while a critical load is located); without xi_hint no local test (local_min
   * +inf, neig 0) */
  int no_scan;
  int no_acoustic; /* 1: no acoustic test (acoustic_valid -1) */
} rn_bloch_options;
void rn_bloch_options_default(rn_bloch_options *opt);
typedef struct rn_bloch_result {
  /* local (finite-wavelength) stability: the lowest eigenvalue of the Bloch
   * Hessian over the Brillouin zone (rn_network_bloch_hessian; at xi = 0 without
   * the rigid translations, i.e. with the anchor pinned; wave vectors with
   * 0 < |xi|_inf < 1/(4 grid) are left to the long-wavelength test) */
  double local_min;
  double xi[3];  /* where (reciprocal-lattice coordinates, |xi_i| <= 1/2) */
  double eig[8]; /* the lowest neig eigenvalues there */
  int neig;
  double local_scale; /* eigenvalue scale for tolerances: the largest |eig| of
                         the rest of the spectrum examined (>= 0) */
  /* long-wavelength (macroscopic) stability: the lowest eigenvalue over unit
   * directions n of the acoustic tensor A(n)_ab = L_aJbL n_J n_L of the
   * homogenised tangent (with its stress terms), from the second-order
   * expansion of the Bloch Hessian at k = 0 (force per length in 2D, stress
   * in 3D) */
  int acoustic_valid; /* 1; 0 if K_uu is not positive definite (no tangent); -1 not
                         examined (no_acoustic) */
  double acoustic_min;
  double acoustic_scale; /* the largest eigenvalue of A over the directions */
  double direction[3];   /* n at the minimum (Cartesian, reference) */
  double amplitude[3];   /* the eigenvector there */
  size_t bloch_dofs;
  int evaluations; /* Bloch eigenvalue problems solved */
  /* symmetry-equivalent minima (e.g. the three M points of a hexagonal cell
   * under equibiaxial load): the grid wave vectors whose lowest eigenvalue equals
   * local_min to 1e-8 of the grid's eigenvalue range, xi first and the others in
   * grid order (at most 12; nequiv >= 1).  Where they tie, xi is the first in
   * grid order, so the choice does not depend on round-off; a supercell that
   * holds every one of them holds their combinations. */
  int nequiv;
  double xi_equiv[12][3];
} rn_bloch_result;
/* Bloch-Floquet stability of a periodic network at its current state (an
 * equilibrium of the fluctuations, e.g. after rn_cell_relax): the lowest
 * eigenvalue of the Bloch Hessian over a grid of the Brillouin zone (half of it:
 * H(-xi) = conj H(xi)) refined around the minima, and the acoustic tensor over
 * directions (720 in 2D, 2000 on the sphere in 3D, refined).  opt->method:
 * dense LAPACK (zheevr, cells up to 4000 Bloch DOFs, RN_ERR_ARG beyond) or
 * sparse (any size; the same numbers to the eigensolvers' accuracy).  RN_ERR_ARG for
 * in-plane or out-of-plane modes on a 3D cell or at a state where those modes do
 * not decouple.  Serial; needs no runtime initialisation.
 * On a part of a distributed cell (collective): the cell-periodic test alone
 * (xi = 0: local_min the lowest eigenvalue of the Jacobi-scaled fluctuation
 * Hessian by distributed LOBPCG, as rn_network_stability with the strain held;
 * local_scale its scale; neig 1) and the long-wavelength test from the tangent
 * (rn_cell_acoustic_tangent); opt->modes must be RN_BLOCH_ALL, grid, xi_hint,
 * no_scan and method are not used.  A supercell's cell-periodic modes are the
 * primitive cell's Bloch modes on the supercell's wave-vector grid
 * (docs/homogenization.md, "Paths under mpirun"). */
rn_status rn_cell_bloch(rn_network *net, const rn_bloch_options *opt,
                        rn_bloch_result *res);
/* The long-wavelength (macroscopic) test from the homogenised tangent at the
 * current state (whole network or part; collective on a part): C (rn_homogenize)
 * and the stress give the first elasticity tensor L_aJbL = F_aI F_bK CE_IJKL +
 * delta_ab S_JL (F = I + H the cell's deformation gradient, CE and S the tangent
 * and stress of the Green-Lagrange strain E = H + H^2 / 2, by the chain rule) and
 * the acoustic tensor A(n)_ab = L_aJbL n_J n_L; fills res->acoustic_* as
 * rn_cell_bloch does (acoustic_valid 0 if K is not positive definite).  The same
 * numbers as rn_cell_bloch's expansion of the Bloch Hessian (val_bloch
 * check_acoustic_tangent). */
rn_status rn_cell_acoustic_tangent(rn_network *net, rn_bloch_modes modes,
                                   rn_bloch_result *res);
/* The lowest neig (<= 8) Bloch eigenvalues at the current state at the wave
 * vector xi (reciprocal coordinates; xi = 0 without the rigid translations),
 * restricted to modes; eig[neig]; vec (may be NULL) receives the eigenvector of
 * the lowest as 2 n doubles (real, imaginary parts per Bloch DOF; zero outside
 * the modes examined).  Dense (zheevr) up to 4000 Bloch DOFs; beyond, the sparse
 * route of rn_cell_bloch_lowest_sparse (neig > 1 by Lanczos runs deflated by the
 * eigenvectors found before, multiplicities included). */
rn_status rn_cell_bloch_eigen(rn_network *net, const double *xi, rn_bloch_modes modes,
                              int neig, double *eig, double *vec);
/* The lowest Bloch eigenvalue *eig at xi (as rn_cell_bloch_eigen with neig 1; method
 * an rn_bloch_method) and its gradient grad[dim] in xi (reciprocal coordinates) by
 * Hellmann-Feynman, d lambda / d xi_a = v^H (dH/dxi_a) v with v its unit eigenvector
 * and dH/dxi_a from the lattice-shift terms of H (rn_network_bloch_terms): exact for a
 * simple eigenvalue (at a multiple one the derivative along the eigenvector found).
 * rn_cell_bloch's refinement descends along it. */
rn_status rn_cell_bloch_gradient(rn_network *net, const double *xi, rn_bloch_modes modes,
                                 int method, double *eig, double *grad);
/* The lowest Bloch eigenvalue at xi (as rn_cell_bloch_eigen with neig 1) without a
 * dense matrix, at any cell size: the sparse Bloch Hessian
 * (rn_network_bloch_hessian_csr) on the examined DOFs in its real symmetric form
 * [A -B; B A] (each eigenvalue twice), the sparse Cholesky factor of it plus
 * sigma I (sigma 0 where it is positive definite, else the smallest decade of its
 * largest diagonal entry that makes it so), and the largest eigenvalue of the
 * inverse by Lanczos with full reorthogonalisation (Ritz residual 1e-12 of it).
 * *eig the eigenvalue, vec (may be NULL) its eigenvector as for
 * rn_cell_bloch_eigen (unit norm); *steps (may be NULL) the Lanczos steps (each
 * one solve), *shift (may be NULL) sigma.  rn_cell_bloch_eigen takes this route by
 * itself on cells of more than 4000 Bloch DOFs.  RN_ERR_SOLVER if
 * Lanczos does not converge in 400 steps.  Serial. */
rn_status rn_cell_bloch_lowest_sparse(rn_network *net, const double *xi,
                                      rn_bloch_modes modes, double *eig, double *vec,
                                      int *steps, double *shift);

/* ---- macroscopic load paths of periodic cells (docs/homogenization.md, "Strain
 * paths and stability", "Stress and mixed paths") ---- */
/* S = C^-1 of the n x n (n <= 6, row-major) matrix C by Gauss-Jordan elimination
 * with partial pivoting: 1, or 0 if C is singular (a pivot at most 1e-14 |C_00|),
 * e.g. the compliance of rn_homogenization's C.  Needs no network. */
int rn_homogenization_invert(int n, const double *C, double *S);

/* One leg of a path: from the state reached at its start, every strain component
 * v moves linearly in the path parameter from its start value to target[v], the
 * strain (stress[v] == 0) or the homogenised stress (stress[v] == 1; the strain
 * component is then a DOF, found by the mixed solve). */
typedef struct rn_cell_path_segment {
  int steps;        /* steps of the leg (>= 1) */
  int stress[6];    /* 1: component v is stress-controlled on this leg */
  double target[6]; /* its strain or stress at the leg's end */
  double start[6];  /* its strain or stress at the leg's start (set by
                       rn_cell_path_run in the result's copy) */
} rn_cell_path_segment;

/* One step of the path. */
typedef struct rn_cell_path_step {
  double t;                       /* path parameter: segment j spans [j, j + 1] */
  int seg;                        /* the segment */
  double strain[6], stress[6];    /* Voigt, engineering shear */
  double energy;                  /* elastic energy of the cell */
  int newton, converged;          /* rn_cell_relax (Newton summed over the mixed solve) */
  int outer;                      /* mixed solve iterations (0: strain control) */
  int jumped;                     /* the mixed solve's correction exceeded the
                                     predicted step (another branch) */
  int kuu_indefinite;             /* the mixed solve met an indefinite K_uu (an
                                     unstable cell-periodic fluctuation) */
  double tangent_min;             /* lowest eigenvalue of the effective tangent on the
                                     stress-controlled components over the largest
                                     eigenvalue of C at rest (NaN without stress
                                     control) */
  double local_min, acoustic_min; /* rn_cell_bloch at the step (NaN: not examined) */
  int stable;                     /* 1 stable, 0 unstable, -1 not examined (past the
                                     first instability) */
} rn_cell_path_step;

/* The first instability of a path. */
typedef struct rn_cell_path_instability {
  int found;
  double t, strain[6], stress[6]; /* where: path parameter, strain, stress */
  double xi[3];                   /* critical wave vector (0: macroscopic) */
  int nequiv;                     /* symmetry-equivalent wave vectors (rn_bloch_result) */
  double xi_equiv[12][3];         /* xi first */
  int kind_macroscopic, multiplicity;
  double eig[8]; /* the lowest Bloch eigenvalues past it */
  int neig;
  double direction[3], amplitude[3]; /* macroscopic: the acoustic tensor's mode */
  int bisections;
  int stress_limit;  /* 1: the effective tangent on the stress-controlled
                        components lost positive definiteness (a limit point) */
  double mode[6];    /* then: its null vector (strain components) */
  int cell_periodic; /* 1: under stress control, the cell-periodic fluctuations
                        (K_uu) lost positive definiteness in modes the Bloch
                        test does not examine */
} rn_cell_path_instability;

typedef struct rn_cell_path_result rn_cell_path_result;
/* Called after each step of the path (res->done: the step just recorded). */
typedef void (*rn_cell_path_progress)(void *user, const rn_cell_path_result *res);

typedef struct rn_cell_path_options {
  int grid;                       /* rn_bloch_options.grid (0: its default) */
  rn_bloch_modes modes;           /* the Bloch modes examined */
  rn_cell_path_progress progress; /* may be NULL */
  void *user;                     /* progress's first argument */
  int bloch_method;               /* rn_bloch_options.method (default RN_BLOCH_AUTO) */
} rn_cell_path_options;
void rn_cell_path_options_default(rn_cell_path_options *opt);

struct rn_cell_path_result {
  int ns;                    /* strain components */
  int nseg;                  /* segments */
  rn_cell_path_segment *seg; /* [nseg]: a copy of the path with start set */
  int steps;                 /* steps over all segments */
  rn_cell_path_step *step;   /* [steps + 1]; step[0] the rest state */
  int done;                  /* steps computed (step[0 .. done]) */
  const char *stopped;       /* NULL, or why the path stopped early (static text) */
  int limit_end;             /* the path ended under stress control at its first
                                instability: 1 a limit point of the stress, 2 unstable
                                cell-periodic fluctuations (K_uu indefinite); 3 on a
                                part of a distributed cell (any control): with the
                                step past the first instability */
  double tangent_scale;      /* largest eigenvalue of C at rest */
  double c_rest[36];         /* C at rest (ns x ns) */
  rn_cell_path_instability inst;
};

/* Follows the macroscopic load path seg[nseg] (strain, stress or mixed control
 * per component and segment; one segment for a proportional path, several for
 * waypoints) on the periodic network net from its current (rest) state, every
 * strain component a DOF: at each step the fluctuations by rn_cell_relax, under
 * stress control the strain components by Newton with the effective tangent
 * (rn_homogenize), then the Bloch-Floquet test (rn_cell_bloch); the first
 * instability (local, macroscopic, a limit point of the stress, or unstable
 * cell-periodic fluctuations) is located by bisection to 0.1 % of the parameter.
 * Fills res (free it with rn_cell_path_result_free, also after an error).
 * RN_OK when it ran (the path may have stopped early: res->stopped, or ended at a
 * limit point of the stress: res->limit_end); RN_ERR_ARG for bad arguments;
 * another error code otherwise, the message in the network's context.  Leaves
 * the last state computed as the current state.  Serial; prints nothing
 * (opt->progress is called after every step). */
rn_status rn_cell_path_run(rn_network *net, int nseg, const rn_cell_path_segment *seg,
                           const rn_cell_path_options *opt, rn_cell_path_result *res);
/* Frees what rn_cell_path_run allocated in res (NULL-safe; res is left empty). */
void rn_cell_path_result_free(rn_cell_path_result *res);

/* ---- past the first instability: the bifurcated branch in a supercell
 * (docs/homogenization.md, "Post-buckling") ---- */
/* The supercell (cells per direction, rep[dim]; rep[2] = 1 in 2D) of a local
 * instability: the least common multiple of the periods of its wave vector and
 * of the wave vectors equivalent to it (each period the smallest m <= 12 with
 * m xi an integer to 1e-3), so that it holds every critical mode and their
 * combinations.  1, or 0 if one is not commensurate with at most 12 cells per
 * direction (or in is not a local instability).  Needs no network. */
int rn_cell_instability_supercell(const rn_cell_path_instability *in, int dim,
                                  int rep[3]);

/* The state drawn for a pattern: the principal (cell-periodic) branch of the
 * supercell network net (at rest, every strain component a DOF; e.g. rep of
 * rn_cell_instability_supercell copies of the cell of a path) at the critical
 * strain of in, reached by rn_cell_relax in 10 proportional load steps, plus its
 * critical mode (the lowest Bloch mode at xi = 0 of the supercell in modes)
 * scaled so that its largest fluctuation entry is amplitude_fraction of the
 * cell size (the supercell's measure per copy to the power 1/dim).  Sets
 * *eigenvalue (that mode's eigenvalue), *amplitude (the displacement drawn) and
 * *converged (the last relaxation).  Serial; prints nothing. */
rn_status rn_cell_pattern_state(rn_network *net, const rn_cell_path_instability *in,
                                int copies, rn_bloch_modes modes,
                                double amplitude_fraction, double *eigenvalue,
                                double *amplitude, int *converged);

/* One step past the critical strain, on both branches. */
typedef struct rn_cell_post_step {
  double t, strain[6];       /* path parameter, prescribed macroscopic strain */
  double stress[6], energy;  /* bifurcated branch: stress, elastic energy per cell */
  double amplitude;          /* largest |x - x_principal| over rod vertices */
  int converged, iterations; /* rn_cell_minimize */
  int verified;              /* rn_network_stability: a verified minimum */
  double lowest;             /* its lowest (scaled) eigenvalue */
  double principal_stress[6], principal_energy; /* principal branch (rn_cell_relax) */
  int principal_converged, principal_verified;
  double principal_lowest;
} rn_cell_post_step;

#define RN_CELL_POST_MAX_HARMONICS 64
typedef struct rn_cell_post_result rn_cell_post_result;
/* Called after each step (res->done: the steps recorded so far). */
typedef void (*rn_cell_post_progress)(void *user, const rn_cell_post_result *res);

typedef struct rn_cell_post_options {
  int steps;            /* steps from the critical strain to the path's end (>= 1) */
  rn_bloch_modes modes; /* the Bloch modes of the critical mode */
  int rep[3];           /* the supercell: copies of the cell per direction */
  /* For the harmonics (NULL: none computed): rod_base[r] the index of the rod of
   * copy (0, 0, 0) that rod r of the supercell copies (r itself in that copy),
   * rod_cell[3 r .. 3 r + 2] the copy's cell coordinates. */
  const int *rod_base, *rod_cell;
  rn_cell_post_progress progress; /* may be NULL */
  void *user;                     /* progress's first argument */
} rn_cell_post_options;
void rn_cell_post_options_default(rn_cell_post_options *opt);

struct rn_cell_post_result {
  int rep[3], copies;
  double mode_eigenvalue; /* lowest Bloch eigenvalue (xi = 0) of the supercell at the
                             critical strain */
  double perturbation;    /* the critical mode's amplitude added (1e-3 of the cell
                             size at its largest entry) */
  int steps, done;        /* steps asked for; recorded (step[0 .. done - 1]) */
  rn_cell_post_step *step;
  /* the last bifurcated displacement from the principal state over the
   * supercell's harmonics xi = (p / rep[0], q / rep[1](, s / rep[2])) (components
   * folded into (-1/2, 1/2]): the share of sum over base vertices of
   * |sum_copies d exp(-2 pi i xi . c)|^2; nharm 0 without rod_base or past
   * RN_CELL_POST_MAX_HARMONICS harmonics */
  int nharm;
  double harm_xi[RN_CELL_POST_MAX_HARMONICS][3], harm[RN_CELL_POST_MAX_HARMONICS];
};

/* After rn_cell_path_run found a local instability (path->inst) on a cell:
 * the supercell network net (opt->rep copies of that cell, at rest, every strain
 * component a DOF) follows the principal branch through the path's steps to the
 * critical strain (rn_cell_relax), takes the critical mode there, then opt->steps
 * steps of the path past the critical strain to its end, on both branches:
 * principal by rn_cell_relax from the previous principal state, bifurcated by
 * rn_cell_minimize from the previous bifurcated state (first: the principal
 * state plus the critical mode), each checked by rn_network_stability.  Stops
 * after a step whose bifurcated minimisation did not converge.  Leaves the last
 * bifurcated state as net's current state.  Fills res (free it with
 * rn_cell_post_result_free, also after an error).  RN_ERR_ARG for a path
 * without a local instability or bad options.  Serial; prints nothing. */
rn_status rn_cell_post_buckling(rn_network *net, const rn_cell_path_result *path,
                                const rn_cell_post_options *opt,
                                rn_cell_post_result *res);
/* Frees what rn_cell_post_buckling allocated in res (NULL-safe; res left empty). */
void rn_cell_post_result_free(rn_cell_post_result *res);

#ifdef __cplusplus
}
#endif
#endif

/* cli_dist.h - what the distributed commands (solve, homogenize under mpirun;
 * docs/parallel.md) share: the graph pass over the scene, the METIS partition of
 * its rod graph, the part pass, the partition block of RESULT.json and the
 * agreement of statuses over the ranks.  With the solver only. */
#ifndef RODNET_CLI_DIST_H
#define RODNET_CLI_DIST_H

#include "rodnet.h"
#include "scene/scene.h"

/* Everything one distributed run holds on a rank. */
typedef struct rn_cli_dist {
  rn_context *ctx;
  int rank, size;
  rn_scene *graph, *part, *whole;
  int *rod_part;
  long edge_cut;
  long *dofs, *stencils; /* [size] owned per rank (rn_cli_dist_partition) */
  double imbalance;      /* max owned DOFs / mean */
} rn_cli_dist;

/* In an MPI job (an MPI launcher started this process as one of several): starts the
 * runtime first (to know the ranks) and sets *rank, *size; otherwise *rank = 0, *size = 1
 * without starting anything.  0, or an exit status if the runtime does not start
 * (printed, naming cmd). */
int rn_cli_mpi_start(const char *cmd, int *rank, int *size);
/* Agree on a step's status over the ranks; rank 0 prints the (first failing
 * rank's) message with prefix.  Returns the agreed status. */
rn_status rn_cli_dist_agree(rn_cli_dist *d, rn_status st, const char *prefix);
/* The graph pass (d->graph: the rod graph and the scene's options): 0 or an exit
 * status (printed by rank 0). */
int rn_cli_dist_load_graph(rn_cli_dist *d, const char *scene);
/* The partition of the graph, then the part pass (d->part): 0 or an exit status;
 * cmd names the command in messages ("rodnet solve"). */
int rn_cli_dist_load_part(rn_cli_dist *d, const char *scene, const char *cmd);
/* The owned DOFs and stencils of every rank (collective) into d. */
rn_status rn_cli_dist_partition(rn_cli_dist *d);
/* Starts a run on rank `rank` of `size`: d zeroed, its context created (agreed
 * over the ranks; cmd names the command in the message).  0 or an exit status. */
int rn_cli_dist_begin(rn_cli_dist *d, int rank, int size, const char *cmd);
/* Frees what d holds, its context, and finalizes the runtime. */
void rn_cli_dist_end(rn_cli_dist *d);

#endif

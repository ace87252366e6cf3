/* cli_dist.c - the distributed commands' shared steps (cli_dist.h). */
#include "cli/cli_dist.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "rodnet_solve.h"

#ifdef RN_HAVE_SOLVER

/* 1 if an MPI launcher started this process as one of several. */
static int in_mpi_job(void) {
  static const char *const vars[] = {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", NULL};
  for (int i = 0; vars[i]; i++) {
    const char *v = getenv(vars[i]);
    if (v && atoi(v) > 1) return 1;
  }
  return getenv("PMIX_RANK") != NULL;
}

int rn_cli_mpi_start(const char *cmd, int *rank, int *size) {
  *rank = 0;
  *size = 1;
  if (!in_mpi_job()) return 0;
  if (rn_runtime_initialize(NULL, NULL) != RN_OK) {
    fprintf(stderr, "%s: cannot start the MPI runtime\n", cmd);
    return RN_EXIT_INTERNAL;
  }
  rn_runtime_ranks(rank, size);
  return 0;
}

rn_status rn_cli_dist_agree(rn_cli_dist *d, rn_status st, const char *prefix) {
  st = rn_dist_agree(d->ctx, st);
  if (st && d->rank == 0)
    fprintf(stderr, "%s%s\n", prefix, rn_context_last_error(d->ctx));
  return st;
}

int rn_cli_dist_load_graph(rn_cli_dist *d, const char *scene) {
  rn_scene_part sp;
  memset(&sp, 0, sizeof sp);
  sp.mode = RN_SCENE_GRAPH;
  rn_status st = rn_scene_load_part(d->ctx, scene, &sp, &d->graph);
  if ((st = rn_cli_dist_agree(d, st, ""))) return rn_cli_load_exit_code(st);
  return 0;
}

int rn_cli_dist_load_part(rn_cli_dist *d, const char *scene, const char *cmd) {
  rn_scene_part sp;
  const int *nv = NULL, *jp = NULL, *jr = NULL;
  int nr = 0, nj = 0;
  char prefix[64];
  rn_status st;
  snprintf(prefix, sizeof prefix, "%s: ", cmd);
  memset(&sp, 0, sizeof sp);
  rn_network_rod_graph(rn_scene_network(d->graph), &nr, &nv, &nj, &jp, &jr);
  d->rod_part = malloc(((size_t)nr + 1) * sizeof(int));
  st = d->rod_part
           ? rn_partition_rods(nr, nv, nj, jp, jr, d->size, d->rod_part, &d->edge_cut)
           : RN_ERR_ALLOC;
  if (st)
    rn_context_set_error(d->ctx, st, "%s: cannot partition the rod graph (%s)", scene,
                         rn_status_name(st));
  if ((st = rn_cli_dist_agree(d, st, prefix))) return RN_EXIT_INTERNAL;
  sp.mode = RN_SCENE_PART;
  sp.nparts = d->size;
  sp.part = d->rank;
  sp.nrods = nr;
  sp.njoints = nj;
  sp.rod_nv = nv;
  sp.rod_part = d->rod_part;
  sp.joint_ptr = jp;
  sp.joint_rods = jr;
  st = rn_scene_load_part(d->ctx, scene, &sp, &d->part);
  if ((st = rn_cli_dist_agree(d, st, ""))) return rn_cli_load_exit_code(st);
  return 0;
}

rn_status rn_cli_dist_partition(rn_cli_dist *d) {
  int ranks = d->size;
  double sum = 0.0, mx = 0.0;
  free(d->dofs);
  free(d->stencils);
  d->dofs = calloc((size_t)ranks, sizeof(long));
  d->stencils = calloc((size_t)ranks, sizeof(long));
  if (!d->dofs || !d->stencils) return RN_ERR_ALLOC;
  rn_status st =
      rn_dist_part_sizes(rn_scene_network(d->part), &ranks, d->dofs, d->stencils);
  for (int q = 0; q < ranks; q++) {
    sum += (double)d->dofs[q];
    if ((double)d->dofs[q] > mx) mx = (double)d->dofs[q];
  }
  d->imbalance = sum > 0.0 ? mx * ranks / sum : 1.0;
  return st;
}

int rn_cli_dist_begin(rn_cli_dist *d, int rank, int size, const char *cmd) {
  char msg[96];
  memset(d, 0, sizeof *d);
  d->rank = rank;
  d->size = size;
  snprintf(msg, sizeof msg, "%s: out of memory", cmd);
  int rc = rn_context_create(&d->ctx) == RN_OK ? 0 : RN_EXIT_INTERNAL;
  if (rn_cli_dist_agree(d, rc ? RN_ERR_ALLOC : RN_OK, msg)) rc = RN_EXIT_INTERNAL;
  return rc;
}

void rn_cli_dist_end(rn_cli_dist *d) {
  rn_scene_destroy(&d->whole);
  rn_scene_destroy(&d->part);
  rn_scene_destroy(&d->graph);
  free(d->rod_part);
  free(d->dofs);
  free(d->stencils);
  d->rod_part = NULL;
  d->dofs = d->stencils = NULL;
  rn_context_destroy(&d->ctx);
  rn_runtime_finalize();
}
#else
typedef int rn_cli_dist_needs_the_solver; /* (an empty file is not ISO C) */
#endif /* RN_HAVE_SOLVER */

/* partition.h - the record of a network that is a part of a partition, or
 * holds only the rod graph (part.c; docs/parallel.md): shared by the index
 * translation of core/partition.c and the partition calls of parts/part.c.
 * Not installed. */
#ifndef RODNET_PARTITION_H
#define RODNET_PARTITION_H

#include "core/network_internal.h"

enum { MODE_GRAPH = 1, MODE_PART = 2 };

struct rn_part_data {
  int mode;
  int nparts, part;
  /* rods and joints added so far (whole-network indices) */
  int nrods, njoints, nmom;
  int cap_rods, cap_joints, cap_ends;
  int *rod_nv; /* [nrods_total] (graph: grows) */
  /* graph mode: joint ends in CSR, and the joint of each rod end */
  int *jptr, *jrods, *jends; /* [njoints + 1], [ends] */
  int *rod_endj;             /* [2 nrods] */
  double *rod_ends;          /* [8 nrods]: end vertices, terminal edge lengths */
  rn_joint_point *points;    /* [njoints] for the coincidence check */
  char **names;              /* [njoints] their names (owned) */
  int cap_points, cap_names;
  /* part mode: the partition */
  int nrods_total, njoints_total;
  int *rod_part;    /* [nrods_total] */
  int *rod_local;   /* [nrods_total] local index, -1: not here */
  int *joint_owner; /* [njoints_total] */
  int *joint_local; /* [njoints_total] */
  int64_t next_key; /* key of the next rod added */
  int64_t joint_key0;
  int64_t *rod_key; /* [local rods] */
  int nlocal_rods;
  /* finalize */
  unsigned char *entry_owned; /* [nfull] during numbering */
  size_t n_owned;
  int64_t *keys; /* [nred] */
  int *owner;    /* [nred] */
};

#endif

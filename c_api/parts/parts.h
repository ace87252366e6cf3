/* parts.h - parts of a partition (part.c, dof_blocks.c; docs/parallel.md): the
 * steps of finalize that only a part or a graph-only network takes.  The index
 * translation every building call needs is core's (core/partition.c). */
#ifndef RN_PARTS_MODULE_H
#define RN_PARTS_MODULE_H

#include "core/network_internal.h"

/* Graph-only finalize: coincident joints (the check every part cannot make). */
rn_status rn_part_graph_validate(const rn_network *net, const char *where);
/* Finalize of a part: marks the full DOFs no evaluated stencil reads with
 * RN_DOF_ABSENT in net->map (called after fixed and aliased entries are
 * marked, before numbering) and returns 1 if full entry a (canonical) is owned
 * by this part (numbering order: owned first). */
void rn_part_mark_absent(rn_network *net);
int rn_part_entry_owned(const rn_network *net, size_t a);
/* Global keys of the reduced DOFs (after numbering); RN_ERR_ALLOC. */
rn_status rn_part_begin_numbering(rn_network *net);
rn_status rn_part_build_keys(rn_network *net);
void rn_part_free(rn_part_data **p);

#endif

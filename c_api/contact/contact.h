/* contact.h - contact between rods (contact.c; docs/contact.md): the contact
 * edges, candidate pairs and the Hessian pattern's pairs. */
#ifndef RN_CONTACT_MODULE_H
#define RN_CONTACT_MODULE_H

#include "core/network_internal.h"

/* ---- contact (contact.c) ---------------------------------------------------- */
typedef struct rn_contact rn_contact;
/* Pairs of contact edges (indices into the contact edge list), a < b. */
typedef struct rn_contact_list {
  int *pair; /* [2 n] */
  size_t n, cap;
} rn_contact_list;
/* At finalize after the DOF map: the contact edges (RN_OK without contact). */
rn_status rn_contact_build(rn_network *net, const char *where);
void rn_contact_unbuild(rn_network *net);
void rn_contact_free(rn_network *net);
/* The Hessian pattern's contact pairs (docs/contact.md, "Hessian pattern"):
 * the pairs whose boxes, inflated by the radius, dhat / 2 and margin / 2,
 * overlap at the accepted state.  rn_contact_pattern_update keeps them (force
 * 0) if every pair within half the margin at the accepted state is one of
 * them, else rebuilds them there and the CSR pattern with them
 * (pattern_version + 1); the old pattern stays on failure.  Called at
 * finalize and wherever the accepted state changes. */
rn_status rn_contact_pattern_update(rn_network *net, int force, const char *where);
int rn_contact_in_pattern(const rn_network *net, int a, int b);
size_t rn_contact_pattern_count(const rn_network *net);
/* The two contact edges (a < b, indices into the contact's edge list) of pattern
 * pair i: the one decoding of the pattern's keys. */
void rn_contact_pattern_pair(const rn_network *net, size_t i, int *a, int *b);
/* The 12 full indices of pattern pair i. */
void rn_contact_pattern_idx(const rn_network *net, size_t i, size_t idx[12]);
/* 1 if pattern pair i joins two rods or two edges of one rod at least 3 apart
 * (edges j and j + 2, close on every straight rod, stay inside its band). */
int rn_contact_pattern_far(const rn_network *net, size_t i);
/* RN_ERR_GEOMETRY if the initial state interpenetrates. */
rn_status rn_contact_check_initial(const rn_network *net, const char *where);
/* The pairs within the barrier's reach at x (x NULL: the accepted state); with
 * ccd, first the continuous check of the motion from the accepted state to x
 * (RN_DEGENERATE naming the pair if it would cross).  L is freed on error. */
rn_status rn_contact_candidates(const rn_network *net, const double *x, int ccd,
                                const char *where, rn_contact_list *L);
void rn_contact_list_free(rn_contact_list *L);
/* The 12 full indices of pair (a, b): (p0, p1) of edge a, then of edge b. */
void rn_contact_pair_idx(const rn_network *net, int a, int b, size_t idx[12]);
/* The kernel parameters of pair (a, b): radius the sum of the rods' radii. */
rnk_contact_param rn_contact_pair_param(const rn_network *net, int a, int b);
/* rn_fail with a message naming the pair's rods and edges. */
rn_status rn_contact_pair_fail(const rn_network *net, rn_status st, const char *where,
                               int a, int b, const char *what);

#endif

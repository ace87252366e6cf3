/* name_index.h - string -> index hash map for the scene's rod and joint
 * names (lookups by name are constant time, so scenes of 1e5 rods and
 * joints read in linear time).  Keys are borrowed: they must outlive the
 * index and not change.  Internal to problems/. */
#ifndef RN_NAME_INDEX_H
#define RN_NAME_INDEX_H

#include <stddef.h>

typedef struct rn_name_index {
  const char **key; /* NULL: empty slot */
  int *value;
  size_t cap, n; /* cap: 0 or a power of two */
} rn_name_index;

/* Add key -> value (key not present yet); 0 on success, -1 out of memory. */
int rn_name_index_put(rn_name_index *ix, const char *key, int value);
/* The value of key, -1 if absent. */
int rn_name_index_get(const rn_name_index *ix, const char *key);
/* Free the tables (the index is then empty and reusable). */
void rn_name_index_free(rn_name_index *ix);

#endif

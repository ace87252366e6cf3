/* name_index.c - open-addressing string hash map (name_index.h). */
#include "scene/name_index.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static uint64_t hash(const char *s) { /* FNV-1a */
  uint64_t h = 1469598103934665603ull;
  for (; *s; s++) h = (h ^ (unsigned char)*s) * 1099511628211ull;
  return h;
}

static void insert(rn_name_index *ix, const char *key, int value) {
  size_t i = (size_t)hash(key) & (ix->cap - 1);
  while (ix->key[i]) i = (i + 1) & (ix->cap - 1);
  ix->key[i] = key;
  ix->value[i] = value;
  ix->n++;
}

static int grow(rn_name_index *ix) {
  rn_name_index big = {NULL, NULL, ix->cap ? 2 * ix->cap : 64, 0};
  big.key = calloc(big.cap, sizeof *big.key);
  big.value = malloc(big.cap * sizeof *big.value);
  if (!big.key || !big.value) {
    rn_name_index_free(&big);
    return -1;
  }
  for (size_t i = 0; i < ix->cap; i++)
    if (ix->key[i]) insert(&big, ix->key[i], ix->value[i]);
  rn_name_index_free(ix);
  *ix = big;
  return 0;
}

int rn_name_index_put(rn_name_index *ix, const char *key, int value) {
  if (2 * (ix->n + 1) > ix->cap && grow(ix)) return -1;
  insert(ix, key, value);
  return 0;
}

int rn_name_index_get(const rn_name_index *ix, const char *key) {
  if (!ix->cap || !key) return -1;
  for (size_t i = (size_t)hash(key) & (ix->cap - 1); ix->key[i];
       i = (i + 1) & (ix->cap - 1))
    if (strcmp(ix->key[i], key) == 0) return ix->value[i];
  return -1;
}

void rn_name_index_free(rn_name_index *ix) {
  free(ix->key);
  free(ix->value);
  ix->key = NULL;
  ix->value = NULL;
  ix->cap = ix->n = 0;
}

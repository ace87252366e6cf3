/* shim_partition.c - rn_partition_rods (METIS on the rod graph): every rod in a
 * valid part, the same partition twice, balanced parts on a connected lattice-like
 * graph (rods weighted by DOFs: within 10 % of the mean), contiguous parts there, one
 * part without METIS, more parts than rods, no shared joints (greedy), disconnected
 * components with edges, the edge cut counted, malformed graphs rejected. */
#include <stdlib.h>
#include <string.h>

#include "rodnet_solve.h"
#include "testutil.h"

/* A square grid of n x n cells: rods are the bars (horizontal then vertical),
 * joints the nodes.  nv[r] = 3 + r % 4 (unequal weights). */
typedef struct graph {
  int nr, nj, *nv, *jp, *jr;
} graph;

static graph grid(int n) {
  graph g;
  int k = 0;
  g.nr = 2 * n * (n + 1);
  g.nj = (n + 1) * (n + 1);
  g.nv = malloc(sizeof(int) * (size_t)g.nr);
  g.jp = malloc(sizeof(int) * (size_t)(g.nj + 1));
  g.jr = malloc(sizeof(int) * 4 * (size_t)g.nj);
  for (int r = 0; r < g.nr; ++r) g.nv[r] = 3 + r % 4;
  g.jp[0] = 0;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      int node = j * (n + 1) + i;
      if (i > 0) g.jr[k++] = j * n + i - 1;
      if (i < n) g.jr[k++] = j * n + i;
      if (j > 0) g.jr[k++] = n * (n + 1) + i * n + j - 1;
      if (j < n) g.jr[k++] = n * (n + 1) + i * n + j;
      g.jp[node + 1] = k;
    }
  return g;
}

static void graph_free(graph *g) {
  free(g->nv);
  free(g->jp);
  free(g->jr);
}

/* 1 if the rods of part p are connected through joints. */
static int part_connected(const graph *g, const int *part, int p) {
  int *seen = calloc((size_t)g->nr, sizeof(int)),
      *queue = malloc(sizeof(int) * (size_t)g->nr);
  int head = 0, tail = 0, count = 0, first = -1, ok;
  for (int r = 0; r < g->nr; ++r)
    if (part[r] == p) {
      count++;
      if (first < 0) first = r;
    }
  if (first >= 0) {
    queue[tail++] = first;
    seen[first] = 1;
  }
  while (head < tail) {
    int r = queue[head++];
    for (int j = 0; j < g->nj; ++j) {
      int has = 0;
      for (int a = g->jp[j]; a < g->jp[j + 1]; ++a) has |= g->jr[a] == r;
      if (!has) continue;
      for (int a = g->jp[j]; a < g->jp[j + 1]; ++a) {
        int s = g->jr[a];
        if (part[s] == p && !seen[s]) {
          seen[s] = 1;
          queue[tail++] = s;
        }
      }
    }
  }
  ok = tail == count;
  free(seen);
  free(queue);
  return ok;
}

int main(void) {
  graph g = grid(8);
  int *a = malloc(sizeof(int) * (size_t)g.nr), *b = malloc(sizeof(int) * (size_t)g.nr);
  long cut = -1, cut2 = -1;
  for (int np = 1; np <= 4; ++np) {
    long w[4] = {0, 0, 0, 0}, total = 0;
    CHECK_STATUS(rn_partition_rods(g.nr, g.nv, g.nj, g.jp, g.jr, np, a, &cut), RN_OK);
    CHECK_STATUS(rn_partition_rods(g.nr, g.nv, g.nj, g.jp, g.jr, np, b, &cut2), RN_OK);
    CHECK(memcmp(a, b, sizeof(int) * (size_t)g.nr) == 0 && cut == cut2);
    for (int r = 0; r < g.nr; ++r) {
      CHECK(a[r] >= 0 && a[r] < np);
      w[a[r]] += 4 * g.nv[r] - 1;
      total += 4 * g.nv[r] - 1;
    }
    for (int p = 0; p < np; ++p) {
      CHECK(w[p] <= 1.1 * (double)total / np);
      CHECK(part_connected(&g, a, p));
    }
    CHECK(np == 1 ? cut == 0 : cut > 0);
  }
  /* more parts than rods: rod r in part r */
  {
    const int nv[3] = {5, 6, 7}, jp[2] = {0, 3}, jr[3] = {0, 1, 2};
    int p[3];
    CHECK_STATUS(rn_partition_rods(3, nv, 1, jp, jr, 5, p, &cut), RN_OK);
    CHECK(p[0] == 0 && p[1] == 1 && p[2] == 2 && cut == 3);
  }
  /* no shared joints: heaviest first onto the lightest part */
  {
    const int nv[5] = {10, 2, 9, 3, 8};
    int p[5];
    CHECK_STATUS(rn_partition_rods(5, nv, 0, NULL, NULL, 2, p, &cut), RN_OK);
    CHECK(p[0] == 0 && p[2] == 1 && p[4] == 1 && p[3] == 0 && p[1] == 0 && cut == 0);
  }
  /* two components with joints (METIS without the contiguity option) */
  {
    graph h = grid(3);
    int nr = 2 * h.nr, nj = 2 * h.nj, *nv = malloc(sizeof(int) * (size_t)nr);
    int *jp = malloc(sizeof(int) * (size_t)(nj + 1)),
        *jr = malloc(sizeof(int) * 8 * (size_t)h.nj);
    int *p = malloc(sizeof(int) * (size_t)nr), ends = h.jp[h.nj];
    for (int r = 0; r < nr; ++r) nv[r] = h.nv[r % h.nr];
    for (int j = 0; j <= h.nj; ++j) jp[j] = h.jp[j];
    for (int j = 1; j <= h.nj; ++j) jp[h.nj + j] = ends + h.jp[j];
    for (int a2 = 0; a2 < ends; ++a2) {
      jr[a2] = h.jr[a2];
      jr[ends + a2] = h.nr + h.jr[a2];
    }
    CHECK_STATUS(rn_partition_rods(nr, nv, nj, jp, jr, 3, p, &cut), RN_OK);
    for (int r = 0; r < nr; ++r) CHECK(p[r] >= 0 && p[r] < 3);
    free(nv);
    free(jp);
    free(jr);
    free(p);
    graph_free(&h);
  }
  /* malformed graphs */
  {
    const int nv[2] = {5, 1}, jp[2] = {0, 2}, jr[2] = {0, 7};
    int p[2];
    CHECK_STATUS(rn_partition_rods(2, nv, 0, NULL, NULL, 2, p, NULL), RN_ERR_ARG);
    CHECK_STATUS(rn_partition_rods(1, nv, 1, jp, jr, 2, p, NULL), RN_ERR_ARG);
    CHECK_STATUS(rn_partition_rods(1, nv, 0, NULL, NULL, 0, p, NULL), RN_ERR_ARG);
  }
  free(a);
  free(b);
  graph_free(&g);
  return rn_test_finish("shim_partition");
}

// partition.cpp - partition of the rod graph over MPI ranks with METIS (issue 7,
// docs/parallel.md): rn_partition_rods.
//
// The rod graph has one vertex per rod, weighted by the rod's DOF count (4 nv - 1),
// and an edge between two rods that share a joint.  METIS_PartGraphKway with a fixed
// seed (the same partition on every rank and every run) and contiguous parts when
// the graph is connected (METIS_OPTION_CONTIG fails on disconnected graphs).  One
// part: no METIS call (nparts = 1 dies with SIGFPE in METIS 5.1).  At least as many
// parts as rods: rod r goes to part r (the other parts get none).  A graph without
// edges (independent rods): longest-processing-time greedy on the weights.
#include <metis.h>

#include <algorithm>
#include <numeric>
#include <vector>

#include "rodnet_solve.h"

namespace rodnet {
namespace {

struct RodGraph {
  std::vector<idx_t> xadj, adjncy, vwgt;
};

// Adjacency of the rods (unique neighbours, no self loops) from the joints.
RodGraph rod_graph(int nrods, const int *rod_nv, int njoints, const int *joint_ptr,
                   const int *joint_rods) {
  std::vector<std::vector<idx_t>> adj(static_cast<size_t>(nrods));
  for (int j = 0; j < njoints; ++j)
    for (int a = joint_ptr[j]; a < joint_ptr[j + 1]; ++a)
      for (int b = joint_ptr[j]; b < joint_ptr[j + 1]; ++b)
        if (joint_rods[a] != joint_rods[b])
          adj[static_cast<size_t>(joint_rods[a])].push_back(joint_rods[b]);
  RodGraph g;
  g.xadj.assign(1, 0);
  for (int r = 0; r < nrods; ++r) {
    auto &v = adj[static_cast<size_t>(r)];
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
    g.adjncy.insert(g.adjncy.end(), v.begin(), v.end());
    g.xadj.push_back(static_cast<idx_t>(g.adjncy.size()));
    g.vwgt.push_back(static_cast<idx_t>(4 * rod_nv[r] - 1));
  }
  return g;
}

// 1 if the graph is connected (breadth-first search from vertex 0).
bool connected(const RodGraph &g) {
  const size_t n = g.vwgt.size();
  std::vector<char> seen(n, 0);
  std::vector<idx_t> queue{0};
  seen[0] = 1;
  for (size_t h = 0; h < queue.size(); ++h)
    for (idx_t a = g.xadj[static_cast<size_t>(queue[h])];
         a < g.xadj[static_cast<size_t>(queue[h]) + 1]; ++a)
      if (!seen[static_cast<size_t>(g.adjncy[static_cast<size_t>(a)])]) {
        seen[static_cast<size_t>(g.adjncy[static_cast<size_t>(a)])] = 1;
        queue.push_back(g.adjncy[static_cast<size_t>(a)]);
      }
  return queue.size() == n;
}

// Heaviest rod first to the lightest part (ties: lowest index): deterministic.
void greedy(const RodGraph &g, int nparts, int *part) {
  std::vector<int> order(g.vwgt.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
    return g.vwgt[static_cast<size_t>(a)] > g.vwgt[static_cast<size_t>(b)];
  });
  std::vector<long> load(static_cast<size_t>(nparts), 0);
  for (int r : order) {
    const size_t p =
        static_cast<size_t>(std::min_element(load.begin(), load.end()) - load.begin());
    part[r] = static_cast<int>(p);
    load[p] += g.vwgt[static_cast<size_t>(r)];
  }
}

} // namespace
} // namespace rodnet

extern "C" rn_status rn_partition_rods(int nrods, const int *rod_nv, int njoints,
                                       const int *joint_ptr, const int *joint_rods,
                                       int nparts, int *rod_part, long *edge_cut) {
  using namespace rodnet;
  if (nrods < 0 || njoints < 0 || nparts < 1 || (nrods && (!rod_nv || !rod_part)) ||
      (njoints && (!joint_ptr || !joint_rods)))
    return RN_ERR_ARG;
  for (int r = 0; r < nrods; ++r)
    if (rod_nv[r] < 2) return RN_ERR_ARG;
  for (int j = 0; j < njoints; ++j)
    for (int a = joint_ptr[j]; a < joint_ptr[j + 1]; ++a)
      if (joint_rods[a] < 0 || joint_rods[a] >= nrods) return RN_ERR_ARG;
  try {
    RodGraph g = rod_graph(nrods, rod_nv, njoints, joint_ptr, joint_rods);
    if (nparts == 1 || nrods == 0) {
      std::fill(rod_part, rod_part + nrods, 0);
    } else if (nparts >= nrods) {
      std::iota(rod_part, rod_part + nrods, 0);
    } else if (g.adjncy.empty()) {
      greedy(g, nparts, rod_part);
    } else {
      idx_t options[METIS_NOPTIONS];
      METIS_SetDefaultOptions(options);
      options[METIS_OPTION_SEED] = 20261;
      options[METIS_OPTION_NUMBERING] = 0;
      options[METIS_OPTION_CONTIG] = connected(g) ? 1 : 0;
      idx_t nv = nrods, ncon = 1, np = nparts, objval = 0;
      std::vector<idx_t> part(static_cast<size_t>(nrods), 0);
      const int rc = METIS_PartGraphKway(&nv, &ncon, g.xadj.data(), g.adjncy.data(),
                                         g.vwgt.data(), nullptr, nullptr, &np, nullptr,
                                         nullptr, options, &objval, part.data());
      if (rc != METIS_OK) return rc == METIS_ERROR_MEMORY ? RN_ERR_ALLOC : RN_ERR_SOLVER;
      for (int r = 0; r < nrods; ++r)
        rod_part[r] = static_cast<int>(part[static_cast<size_t>(r)]);
    }
    if (edge_cut) {
      long cut = 0;
      for (int r = 0; r < nrods; ++r)
        for (idx_t a = g.xadj[static_cast<size_t>(r)];
             a < g.xadj[static_cast<size_t>(r) + 1]; ++a)
          if (g.adjncy[static_cast<size_t>(a)] > r &&
              rod_part[g.adjncy[static_cast<size_t>(a)]] != rod_part[r])
            ++cut;
      *edge_cut = cut;
    }
    return RN_OK;
  } catch (const std::bad_alloc &) {
    return RN_ERR_ALLOC;
  } catch (...) {
    return RN_ERR_INTERNAL;
  }
}

// amg_coarse.cpp - nodes and near-null space of the DD's coarse matrix for its AMG
// coarse solve (amg_coarse.hpp).
#include "pc/impls/dd/amg_coarse.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

#include "base/shim_error.hpp"
#include "system/dof_blocks.hpp"
#include "system/rigid_body_modes.hpp"

namespace rodnet {
namespace dd {

std::vector<int> coarse_nodes(const DofBlocks &blk, std::vector<double> &points) {
  using Point = std::array<double, 3>;
  std::map<Point, int> at;
  std::vector<Point> where;
  std::vector<std::array<int, 6>> used; // interface index in each slot, -1: free
  std::vector<size_t> angles;
  std::vector<int> slot(blk.interface.size(), -1);
  auto new_node = [&](const Point &p) {
    where.push_back(p);
    used.push_back({-1, -1, -1, -1, -1, -1});
    return static_cast<int>(where.size()) - 1;
  };
  for (size_t k = 0; k < blk.interface.size(); ++k) {
    const DofBlocks::Interface &f = blk.interface[k];
    if (f.kind == kDofAngle) {
      angles.push_back(k);
      continue;
    }
    const Point p{f.point[0], f.point[1], f.point[2]};
    auto it = at.find(p);
    if (it == at.end()) it = at.emplace(p, new_node(p)).first;
    const int n = it->second;
    if (used[static_cast<size_t>(n)][static_cast<size_t>(f.kind)] >= 0)
      throw Error(RN_ERR_INTERNAL,
                  "dd preconditioner: two interface DOFs of one kind at one point");
    used[static_cast<size_t>(n)][static_cast<size_t>(f.kind)] = static_cast<int>(k);
    slot[k] = 6 * n + f.kind;
  }
  // Nearest node with a free rotation slot, searched over the nodes sorted by x.
  std::vector<int> byx(where.size());
  for (size_t i = 0; i < byx.size(); ++i) byx[i] = static_cast<int>(i);
  std::sort(byx.begin(), byx.end(), [&](int a, int b) {
    return where[static_cast<size_t>(a)][0] < where[static_cast<size_t>(b)][0];
  });
  std::vector<double> xs(byx.size());
  for (size_t i = 0; i < byx.size(); ++i) xs[i] = where[static_cast<size_t>(byx[i])][0];
  auto free_slot = [&](size_t n) {
    for (int j = 3; j < 6; ++j)
      if (used[n][static_cast<size_t>(j)] < 0) return j;
    return -1;
  };
  for (size_t k : angles) {
    const double *p = blk.interface[k].point;
    int best = -1;
    double bd = HUGE_VAL;
    const long mid =
        static_cast<long>(std::lower_bound(xs.begin(), xs.end(), p[0]) - xs.begin());
    for (int dir = -1; dir <= 1; dir += 2)
      for (long i = dir < 0 ? mid - 1 : mid; i >= 0 && i < static_cast<long>(xs.size());
           i += dir) {
        const double dx = xs[static_cast<size_t>(i)] - p[0];
        if (dx * dx >= bd) break;
        const size_t n = static_cast<size_t>(byx[static_cast<size_t>(i)]);
        if (free_slot(n) < 0) continue;
        double d = 0.0;
        for (size_t c = 0; c < 3; ++c) d += (where[n][c] - p[c]) * (where[n][c] - p[c]);
        if (d < bd) bd = d, best = static_cast<int>(n);
      }
    if (best < 0) best = new_node(Point{p[0], p[1], p[2]}); // not searched again
    const int j = free_slot(static_cast<size_t>(best));
    used[static_cast<size_t>(best)][static_cast<size_t>(j)] = static_cast<int>(k);
    slot[k] = 6 * best + j;
  }
  points.clear();
  for (const Point &p : where) points.insert(points.end(), p.begin(), p.end());
  return slot;
}

Teuchos::RCP<TMV> coarse_nullspace(const Teuchos::RCP<const TMap> &cmap,
                                   const DofBlocks &blk, const std::vector<int> &slot,
                                   const std::vector<double> &node_points) {
  const size_t nif = cmap->getNodeNumElements();
  std::vector<int> kinds(nif);
  std::vector<double> points(3 * nif), axes(points.size(), 0.0);
  for (size_t c = 0; c < kinds.size(); ++c) {
    kinds[c] = static_cast<int>(c % 6);
    std::copy(node_points.begin() + 3 * (c / 6), node_points.begin() + 3 * (c / 6) + 3,
              points.begin() + 3 * c);
  }
  for (size_t k = 0; k < blk.interface.size(); ++k) {
    const DofBlocks::Interface &f = blk.interface[k];
    const size_t c = static_cast<size_t>(slot[k]);
    kinds[c] = f.kind;
    std::copy(f.point, f.point + 3, points.begin() + 3 * c);
    std::copy(f.axis, f.axis + 3, axes.begin() + 3 * c);
  }
  return rigid_body_modes(cmap, kinds.data(), points.data(), axes.data());
}

} // namespace dd
} // namespace rodnet

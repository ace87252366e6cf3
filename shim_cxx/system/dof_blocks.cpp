// dof_blocks.cpp - DofBlocks from the C API's classification (see dof_blocks.hpp).
#include "system/dof_blocks.hpp"

#include <algorithm>

#include "base/shim_error.hpp"

namespace rodnet {

NetworkDofs network_dofs(const rn_network *net) {
  const size_t n = rn_network_num_dofs(net);
  NetworkDofs d;
  d.block.resize(n);
  d.kind.resize(n);
  d.point.resize(3 * n);
  d.axis.resize(3 * n);
  std::vector<rn_dof_info> info(n);
  if (n == 0) return d;
  check_status(rn_network_dof_blocks(net, d.block.data(), d.point.data(), d.axis.data()),
               "rn_network_dof_blocks");
  check_status(rn_network_dof_info(net, info.data()), "rn_network_dof_info");
  for (size_t i = 0; i < n; ++i)
    d.kind[i] = info[i].kind == RN_DOF_POSITION   ? info[i].component
                : info[i].kind == RN_DOF_ROTATION ? kDofRotation + info[i].component
                                                  : kDofAngle;
  return d;
}

DofBlocks make_dof_blocks(const NetworkDofs &d, const std::vector<GO> &owned) {
  DofBlocks b;
  std::vector<int> local_rod;
  b.block.assign(owned.size(), -1);
  for (size_t l = 0; l < owned.size(); ++l) {
    const size_t i = static_cast<size_t>(owned[l]);
    const int32_t rod = d.block.at(i);
    if (rod >= 0) {
      if (static_cast<size_t>(rod) >= local_rod.size())
        local_rod.resize(static_cast<size_t>(rod) + 1, -1);
      int &lr = local_rod[static_cast<size_t>(rod)];
      if (lr < 0) lr = b.num_rods++;
      b.block[l] = lr;
      continue;
    }
    DofBlocks::Interface f;
    f.local = static_cast<LO>(l);
    f.kind = d.kind[i];
    std::copy(d.point.begin() + 3 * i, d.point.begin() + 3 * i + 3, f.point);
    std::copy(d.axis.begin() + 3 * i, d.axis.begin() + 3 * i + 3, f.axis);
    b.interface.push_back(f);
  }
  return b;
}

} // namespace rodnet

// snapshot.hpp - an owned snapshot of a network's whole mutable state
// (rn_network_state_save / rn_network_state_restore), for going back exactly:
// load-step cuts (solve_api.cpp), path following (path.cpp).  No Trilinos here.
#ifndef RODNET_SHIM_SNAPSHOT_HPP
#define RODNET_SHIM_SNAPSHOT_HPP

#include "rodnet.h"
#include "base/shim_error.hpp"

namespace rodnet {

class Snapshot {
public:
  Snapshot() = default;
  ~Snapshot() { rn_state_destroy(&s_); }
  Snapshot(const Snapshot &) = delete;
  Snapshot &operator=(const Snapshot &) = delete;
  void save(const rn_network *net) {
    rn_state_destroy(&s_);
    check_status(rn_network_state_save(net, &s_), "rn_network_state_save");
  }
  void restore(rn_network *net) const {
    check_status(rn_network_state_restore(net, s_), "rn_network_state_restore");
  }

private:
  rn_state *s_ = nullptr;
};

} // namespace rodnet

#endif

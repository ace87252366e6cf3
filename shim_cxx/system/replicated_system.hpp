// replicated_system.hpp - a System (system.hpp) whose DOFs are distributed over the
// ranks of a communicator while every rank holds and evaluates the whole network.
//
// Each rank owns the reduced DOFs of a contiguous block of rods (rod r on rank
// floor(r P / R)): the interiors of its rods (rn_network_dof_blocks) and the
// interface DOFs whose lowest coupled rod it owns.  Energy and gradient are
// evaluated on the whole network on every rank (the state is gathered with an
// Import); the Hessian is a Tpetra::CrsMatrix of the owned rows.  It exists to test
// and measure distributed preconditioners (the rod-level domain decomposition) on
// several ranks independently of the partitioned network, and serves as a serial
// System on one rank.  Not a scalable System: memory and evaluation are not divided
// by the number of ranks.  All members are collective over the communicator; every
// rank must pass its own copy of the same network.
#ifndef RODNET_SHIM_REPLICATED_SYSTEM_HPP
#define RODNET_SHIM_REPLICATED_SYSTEM_HPP

#include <vector>

#include <Teuchos_Comm.hpp>
#include <Tpetra_Import.hpp>

#include "system/problem.hpp"
#include "system/system.hpp"

namespace rodnet {

struct NetworkDofs;

class ReplicatedSystem : public System {
public:
  // net: finalized (borrowed; must outlive the System).  Throws Error.
  ReplicatedSystem(rn_network *net, const Teuchos::RCP<const Teuchos::Comm<int>> &comm);

  Teuchos::RCP<const TMap> map() const override { return map_; }
  void get_state(TMV &x) const override;
  void set_state(const TMV &x) override;
  rn_status energy(const TMV &x, double *E) override;
  rn_status gradient(const TMV &x, double *E, TMV &g) override;
  void assemble_hessian(const TMV &x) override;
  Teuchos::RCP<const TCrs> hessian() const override { return H_; }
  void accept(TMV &x) override;
  const DofBlocks &blocks() const override { return blocks_; }

  // The Hessian's values may be changed by tests (same graph): resumeFill() first,
  // fillComplete() after.
  Teuchos::RCP<TCrs> hessian_nonconst() { return H_; }
  Problem &problem() { return problem_; }
  // The network's load factor (rn_network_set_load_factor on every rank's copy).
  void set_load_factor(double t);
  // dg = rn_network_load_increment at x from load factor t0 to t1.
  void load_increment(const TMV &x, double t0, double t1, TMV &dg);
  // Rigid-body modes of every owned DOF (rigid_body_modes.hpp).
  Teuchos::RCP<TMV> rigid_body_modes() const;

private:
  void gather(const TMV &x, std::vector<double> &full) const;
  void scatter(const std::vector<double> &full, TMV &x) const;
  void take_owned_dofs(const NetworkDofs &dofs);
  void build_hessian();

  Problem problem_;
  Teuchos::RCP<const TMap> map_, all_;
  Teuchos::RCP<const Tpetra::Import<>> import_;
  Teuchos::RCP<TCrs> H_;
  std::vector<GO> owned_;         // owned GIDs (ascending)
  std::vector<size_t> value_pos_; // CSR entry of each owned row -> local matrix value
  DofBlocks blocks_;
  std::vector<int> kind_;            // of the owned DOFs
  std::vector<double> point_, axis_; // 3 per owned DOF
  mutable std::vector<double> full_, gfull_;
  mutable Teuchos::RCP<TMV> all_vec_;
};

} // namespace rodnet

#endif

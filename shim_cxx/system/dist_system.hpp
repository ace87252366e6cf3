// dist_system.hpp - the System (system.hpp) of a network distributed over MPI ranks:
// each rank holds one part (rn_network_set_part, docs/parallel.md) and evaluates the
// stencils it owns; Tpetra maps, Import and Export join the parts (issue 7).
//
//   owned map     the rank's owned reduced DOFs (contiguous global ids in rank
//                 order: rank 0's owned DOFs first; on each rank the part's order,
//                 owned rods in order with their DOFs contiguous, then owned joints)
//   overlap map   the owned ids first, in map order, then the ghost ids (the part's
//                 local DOF vector: the Import has no permutes)
//   Import        owned -> overlap: the ghost values a part's stencils read
//   Export (ADD)  overlap -> owned: the gradient and Hessian contributions of the
//                 ghost rows go to their owners
//   Hessian       a Tpetra::CrsMatrix on the owned map; its graph is the export of the
//                 parts' CSR patterns, built once in the constructor
//
// The ghost ids are found from the parts' DOF keys (rn_network_part_dofs): each rank
// asks the owner of each ghost DOF for its id (one all-to-all).  A whole network
// (not a part) works on a communicator of one rank.  Every member is collective;
// errors and recoverable statuses are reduced over the ranks (system.hpp).
#ifndef RODNET_SHIM_DIST_SYSTEM_HPP
#define RODNET_SHIM_DIST_SYSTEM_HPP

#include <string>
#include <vector>

#include <Teuchos_Comm.hpp>
#include <Tpetra_Export.hpp>
#include <Tpetra_Import.hpp>

#include "system/equilibrium.hpp"
#include "base/shim_error.hpp"
#include "system/system.hpp"

namespace rodnet {

// Communication and work of one rank, for reports and benchmarks.
struct CommStats {
  double bytes_sent = 0.0; // payload this rank sent in imports / exports / reductions
  long imports = 0, exports = 0, reductions = 0;
};

class DistSystem final : public System {
public:
  // net: a finalized part of a partition over comm's ranks (part index = rank), or a
  // whole network when comm has one rank.  The network is borrowed (must outlive
  // the System); throws Error on every rank if any rank fails.
  DistSystem(rn_network *net, const Teuchos::RCP<const Teuchos::Comm<int>> &comm);
  ~DistSystem() override;

  Teuchos::RCP<const TMap> map() const override { return owned_; }
  Teuchos::RCP<const TMap> overlap_map() const { return overlap_; }
  void get_state(TMV &x) const override;
  void set_state(const TMV &x) override;
  rn_status energy(const TMV &x, double *E) override;
  rn_status gradient(const TMV &x, double *E, TMV &g) override;
  void assemble_hessian(const TMV &x) override;
  Teuchos::RCP<const TCrs> hessian() const override { return h_; }
  void accept(TMV &x) override;
  const DofBlocks &blocks() const override;
  // Snapshots of every part (rn_network_state_save), in lockstep on all ranks.
  bool save_state() override;
  void restore_state() override;
  // f = rn_network_stretch_correction summed over the parts (owned entries).
  bool has_stretch_correction() const override { return true; }
  rn_status stretch_correction(const TMV &x, const TMV &s, TMV &f) override;
  // The residual of equilibrium on the physical scale (equilibrium.hpp) over all
  // ranks: residuals and floors are maxima over the owned DOFs, the reactions of the
  // supports are summed over the parts (each sees the stencils it owns).
  EquilibriumView equilibrium(const TMV &x, const TMV &g) override;

  // dg = rn_network_load_increment summed over the parts (owned entries) at x.
  void load_increment(const TMV &x, double t_prev, double t, TMV &dg);

  rn_network *network() const { return net_; }
  const Teuchos::RCP<const Teuchos::Comm<int>> &comm() const { return comm_; }
  const CommStats &comm_stats() const { return stats_; }
  size_t num_owned() const { return n_owned_; }
  size_t num_ghosts() const { return n_local_ - n_owned_; }

  // Reduces a local status over the ranks: any error (< 0) throws Error on every rank
  // with the first failing rank's message (from msg, or the network's context);
  // otherwise returns the largest recoverable status (RN_OK if none).
  rn_status agree(rn_status local, const std::string &msg = std::string()) const;

private:
  void import_state(const TMV &x) { import_to(x, *xov_); } // x (owned) -> xov_
  void import_to(const TMV &x, TMV &ov);                   // owned -> overlap (INSERT)
  void export_gov(TMV &out); // gov_ summed into out (owned, ADD)
  // A part's evaluation (a rodnet status), its errors caught and agreed over ranks.
  template <class F>
  rn_status evaluate(F &&call, const char *where) {
    rn_status st = RN_OK;
    try {
      st = check_status(call(), where);
    } catch (const Error &e) {
      st = e.status();
    }
    return agree(st);
  }
  void build_maps();
  void build_hessian_graph();

  rn_network *net_;
  Teuchos::RCP<const Teuchos::Comm<int>> comm_;
  size_t n_owned_ = 0, n_local_ = 0;
  Teuchos::RCP<const TMap> owned_, overlap_;
  Teuchos::RCP<const Tpetra::Import<>> importer_;
  Teuchos::RCP<const Tpetra::Export<>> exporter_;
  Teuchos::RCP<TMV> xov_, gov_, sov_; // sov_: a step on the overlap map
  // The Hessian: the owned rows of the part's CSR are summed into h_ directly (their
  // columns in h_'s column map, hcols_), the ghost rows go through hgh_, a matrix on
  // the ghost rows exported (ADD) to their owners.
  Teuchos::RCP<TCrs> hgh_, h_;
  Teuchos::RCP<const Tpetra::Export<>> ghost_exporter_;
  std::vector<LO> hcols_; // [owned-row CSR entries]
  std::vector<double> vals_;
  double ghost_nnz_ = 0.0; // CSR entries in the ghost rows (exported each assembly)
  mutable CommStats stats_;
  mutable DofBlocks blocks_;
  mutable bool blocks_done_ = false;
  rn_state *snapshot_ = nullptr;
  // equilibrium(): DOF kinds (owned first), the size of the structure, the last
  // full measurement
  std::vector<int> kind_;
  double size_ = -1.0;
  EquilibriumView last_eq_;
  void reaction_scales(double *f0, double *m0);
  void build_blocks() const;
};

} // namespace rodnet

#endif

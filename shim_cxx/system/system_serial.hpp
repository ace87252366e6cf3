// system_serial.hpp - the System (system.hpp) of one rn_network on one rank.
//
// SerialSystem wraps a Problem (problem.hpp): vectors live on a map of all reduced DOFs
// over MPI_COMM_SELF, evaluations are the Problem's (counted there), and the Hessian
// is a Tpetra::CrsMatrix whose graph is the network's CSR pattern, built once (again
// when the pattern changes, with contact: Problem::pattern_version; hessian() then
// returns a new matrix); each assemble_hessian() copies the assembled values into it.
// Any communicator of size 1.
#ifndef RODNET_SHIM_SYSTEM_SERIAL_HPP
#define RODNET_SHIM_SYSTEM_SERIAL_HPP

#include <memory>

#include "system/system.hpp"

namespace rodnet {

class SerialSystem : public System {
public:
  explicit SerialSystem(Problem &p); // throws Error
  ~SerialSystem() override;
  SerialSystem(const SerialSystem &) = delete;
  SerialSystem &operator=(const SerialSystem &) = delete;

  Problem &problem() { return p_; }
  Counters &report_counters() override;

  Teuchos::RCP<const TMap> map() const override { return map_; }
  void get_state(TMV &x) const override;
  void set_state(const TMV &x) override;
  rn_status energy(const TMV &x, double *E) override;
  rn_status gradient(const TMV &x, double *E, TMV &g) override;
  void assemble_hessian(const TMV &x) override;
  Teuchos::RCP<const TCrs> hessian() const override { return H_; }
  void accept(TMV &x) override;
  const DofBlocks &blocks() const override { return blocks_; }
  EquilibriumView equilibrium(const TMV &x, const TMV &g) override;
  bool save_state() override;
  void restore_state() override;
  bool has_stretch_correction() const override { return true; }
  rn_status stretch_correction(const TMV &x, const TMV &s, TMV &f) override;

private:
  void build_blocks();
  void build_graph();

  Problem &p_;
  Teuchos::RCP<const TMap> map_;
  Teuchos::RCP<TCrs> H_;
  unsigned long version_ = 0; // the pattern version of H_'s graph
  DofBlocks blocks_;
  std::unique_ptr<Equilibrium> equilibrium_;
  rn_state *snapshot_ = nullptr;
};

} // namespace rodnet

#endif

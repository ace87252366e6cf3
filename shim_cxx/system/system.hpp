// system.hpp - the nonlinear problem as the Newton-Krylov trust region and its
// preconditioners see it, serial or distributed over MPI ranks (issue 7).
//
// A System owns the solver's view of one rn_network (one rank) or of the parts of a
// partitioned network (several ranks): the Tpetra map of the owned reduced DOFs, the
// energy and its gradient on Tpetra vectors over that map, the Hessian as a
// Tpetra::CrsMatrix whose graph is built once, explicit reference updates, and the
// structure that domain-decomposition preconditioners need (which owned DOFs belong
// to the interior of which rod, and which are interface DOFs).
//
// Every member function is collective over the System's communicator: all ranks call
// it with the same arguments in the same order.  Recoverable statuses (RN_DEGENERATE,
// RN_OVERFLOW at a trial point) are the same on every rank (reduced over ranks).
// Errors throw rodnet::Error on every rank (never on one rank only: an error on one
// rank is reduced, so that all ranks throw and none hangs).
//
// Implementations: SerialSystem (one rn_network, any communicator of size 1) and the
// distributed one (partitioned network, Import/Export of ghost DOFs).
#ifndef RODNET_SHIM_SYSTEM_HPP
#define RODNET_SHIM_SYSTEM_HPP

#include <cstdint>
#include <vector>

#include <Teuchos_RCP.hpp>
#include <Tpetra_CrsMatrix.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>

#include "system/equilibrium.hpp"
#include "system/problem.hpp"
#include "rodnet.h"

namespace rodnet {

using TMap = Tpetra::Map<>;
using TMV = Tpetra::MultiVector<>;
using TCrs = Tpetra::CrsMatrix<>;
using LO = TMap::local_ordinal_type;
using GO = TMap::global_ordinal_type;

// What a domain-decomposition preconditioner needs to know about the owned DOFs.
// Rod-interior DOFs of a rod couple (through the Hessian) only with DOFs of the same
// rod and with interface DOFs; interface DOFs are the joints' positions and
// rotations and any rod DOF that a stencil couples with another rod (for example the
// terminal-edge DOFs of rods meeting at an elastic joint, whose rotation fit couples
// all of them).  Eliminating every rod interior exactly (static condensation) leaves
// a problem on the interface DOFs only.
struct DofBlocks {
  // block[i] for owned local DOF i: the local index (0 .. num_rods - 1) of the rod
  // whose interior it belongs to, or -1 for an interface DOF.
  std::vector<int> block;
  int num_rods = 0; // rods owned by this rank
  // Interface DOFs: the point they move (joint or vertex position, for rigid-body
  // near-null-space vectors) and what they are: 0, 1, 2 a position component,
  // 3, 4, 5 a rotation-vector component, 6 a material angle; axis: the unit
  // tangent of a material angle's edge (zero otherwise).  A rigid motion
  // (translation t, rotation w) moves them by t + w x point, w, w . axis
  // (rn_network_dof_blocks).
  struct Interface {
    LO local = 0;
    int kind = 0;
    double point[3] = {0.0, 0.0, 0.0};
    double axis[3] = {0.0, 0.0, 0.0};
  };
  std::vector<Interface> interface;
};

class System {
public:
  virtual ~System() = default;

  // Map of the owned reduced DOFs: the solver's vectors (x, g, steps) live on it.
  virtual Teuchos::RCP<const TMap> map() const = 0;
  // Global number of reduced DOFs.
  GO global_size() const { return static_cast<GO>(map()->getGlobalNumElements()); }

  // The current state of the network(s) (rn_network_get_dofs / set_dofs).
  virtual void get_state(TMV &x) const = 0;
  virtual void set_state(const TMV &x) = 0;

  // Energy (reduced over ranks) at x.  RN_OK or a recoverable status.
  virtual rn_status energy(const TMV &x, double *E) = 0;
  // Energy (may be NULL) and gradient at x.
  virtual rn_status gradient(const TMV &x, double *E, TMV &g) = 0;
  // Assemble the Hessian at x into hessian() (same graph every time, except with
  // contact when the pattern changed: system_serial.hpp); throws if x is
  // degenerate (call it only at accepted states).
  virtual void assemble_hessian(const TMV &x) = 0;
  virtual Teuchos::RCP<const TCrs> hessian() const = 0;

  // Accept x as the new state: explicit reference update (rn_network_update_
  // reference on every part).  x may change (rigid-joint rotation DOFs move into the
  // reference rotation; the energy is unchanged).
  virtual void accept(TMV &x) = 0;

  // Rod / interface structure of the owned DOFs (fixed for the System's life).
  virtual const DofBlocks &blocks() const = 0;

  // Residual of equilibrium on the physical scale at x with gradient g there
  // (equilibrium.hpp: maxima over all ranks); .valid = false if not provided (the
  // stopping test then falls back to a test relative to the first gradient).
  virtual EquilibriumView equilibrium(const TMV & /*x*/, const TMV & /*g*/) {
    return EquilibriumView();
  }
  // One snapshot of the whole mutable state (rn_network_state_save on every part),
  // for the trust region's watchdog (nonmonotone steps it may take back): false if
  // not supported (the trust region then stays monotone).  restore_state() goes
  // back to it exactly (state and reference frames); x must be set by the caller.
  virtual bool save_state() { return false; }
  virtual void restore_state() {}
  // The second-order stretching error f of a step s from x (rn_network_stretch_
  // correction, summed over the parts), for the trust region's second-order
  // correction; false if not provided.  Any other status is the network's (e.g.
  // RN_DEGENERATE where an edge has zero length at x + s).
  virtual bool has_stretch_correction() const { return false; }
  virtual rn_status stretch_correction(const TMV & /*x*/, const TMV & /*s*/,
                                       TMV & /*f*/) {
    return RN_ERR_STATE;
  }

  // Evaluation counts of this rank (energy, gradient, Hessian, HVP, Krylov).
  Counters counters;
  // The counters rn_solve_report reads for this System: counters, or those of the
  // Problem a SerialSystem wraps.
  virtual Counters &report_counters() { return counters; }
  // Adds a Preconditioner's setup and apply seconds to report_counters().
  void add_preconditioner_time(double setup_seconds, double apply_seconds) {
    report_counters().setup_seconds += setup_seconds;
    report_counters().apply_seconds += apply_seconds;
  }
};

} // namespace rodnet

#endif

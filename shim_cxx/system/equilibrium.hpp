// equilibrium.hpp - the residual of equilibrium on a physical scale, for the stopping
// test (monitor.hpp) and the solve report (no Trilinos here).
//
// The gradient of the energy is the out-of-balance generalised force: a force at a
// position DOF, a moment at a material angle or a joint rotation (rn_network_dof_kinds).
// Forces and moments are measured separately so that units do not mix:
//  - residual: the largest |g_i| over the free DOFs of each kind;
//  - scale: F0 = the largest applied force or support reaction force, M0 = the
//    largest applied couple, reaction moment (rn_network_applied_load_max,
//    rn_network_reactions at the iterate) or internal moment of the state
//    (equilibrium_scale.hpp: a self-stressed ring has one); force scale max(F0,
//    M0 / L), moment scale max(M0, F0 L), L the size of the structure (diagonal of
//    the bounding box of its initial vertices: a force F makes moments of about F L,
//    a moment M is carried by forces of about M / L), so that a structure loaded by
//    forces alone has a moment scale and one loaded by couples alone a force scale;
//  - floor: what round-off alone makes of the gradient: |H delta| with delta the
//    rounding error of the DOFs (eps times the largest coordinate for positions, eps
//    for angles, signs alternating pseudo-randomly; one matrix-free Hessian-vector
//    product), plus eps times the sum of the magnitudes of the stencil forces at the
//    DOF (rn_network_gradient_magnitude), the rounding error of summing forces that
//    cancel.  A residual at that level cannot be told from zero.
//  Scales and floors are measured again only when the residual is within 1e-3 of
//  the last scale (they change slowly; far from equilibrium they are not needed).
#ifndef RODNET_SHIM_EQUILIBRIUM_HPP
#define RODNET_SHIM_EQUILIBRIUM_HPP

#include <cmath>
#include <cstdint>
#include <vector>

#include "system/problem.hpp"

namespace rodnet {

// |v| of a 3-vector.
inline double eq_norm3(const double v[3]) {
  return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

// A fixed pseudo-random sign per DOF, by its index (serial) or global id
// (distributed): the probes' rounding errors are not correlated.
inline double eq_sign_of(uint64_t i) {
  uint64_t h = (i + 1) * 0x9E3779B97F4A7C15ull;
  h ^= h >> 31;
  return (h & 1) ? 1.0 : -1.0;
}

struct EquilibriumView {
  bool valid = false; // measured (false: the solver did not provide it)
  double force_residual = 0.0, moment_residual = 0.0;
  double force_scale = 0.0, moment_scale = 0.0;
  double force_floor = 0.0, moment_floor = 0.0;
};

class Equilibrium {
public:
  explicit Equilibrium(Problem &p); // throws Error
  // Residual, scales and floor at the reduced state x with gradient g there (one
  // full-layout gradient for the reactions, one Hessian-vector product).
  EquilibriumView measure(const double *x, const double *g);
  // Size of the structure: the diagonal of the bounding box of its initial vertices.
  double size() const { return size_; }
  // RN_DOF_* kind of every reduced DOF.
  const std::vector<int> &kinds() const { return kind_; }

private:
  Problem &p_;
  std::vector<int> kind_;
  std::vector<rn_reaction> reactions_;
  std::vector<double> delta_, hdelta_, gabs_;
  EquilibriumView last_; // the last full measurement
  static constexpr double kRemeasure = 1e-3;
  double size_ = 0.0; // diagonal of the bounding box of the initial vertices
};

} // namespace rodnet

#endif

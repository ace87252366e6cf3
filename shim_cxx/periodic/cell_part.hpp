// cell_part.hpp - the cell's relaxation and stability tests on a part of a
// distributed periodic cell, and the acoustic tensor from the homogenised tangent
// (cell_part.cpp).  Collective over the ranks on a part; throw Error.
#ifndef RODNET_SHIM_CELL_PART_HPP
#define RODNET_SHIM_CELL_PART_HPP

#include <vector>

#include "periodic/acoustic.hpp"
#include "rodnet_solve.h"

namespace rodnet {

// Strain and stress (and the elastic energy if energy) of the current state; on a
// part the stress and energy summed over the parts (collective).
rn_status cell_state(rn_network *net, double *strain, double *stress, double *energy);

// rn_cell_relax on a part: the fluctuations' equilibrium at strain[nstrain] (the
// components that are DOFs; the network's own for the prescribed ones) by the
// distributed Newton solver (RN_SOLVER_NOX on grad E = 0, so the principal branch
// is followed past an instability too) with the strain DOFs held.
void relax_part(rn_network *net, const double *strain, rn_cell_relax_report &r);

// rn_cell_bloch on a part: the cell-periodic test (xi = 0, the lowest eigenvalue of
// the Jacobi-scaled fluctuation Hessian by distributed LOBPCG with the strain held)
// and, unless o.no_acoustic, the long-wavelength test from the tangent
// (acoustic_tangent).  Every mode (RN_BLOCH_ALL) only.
void bloch_part(rn_network *net, const rn_bloch_options &o, rn_bloch_result *res);

// The long-wavelength test from the homogenised tangent at the current state (a
// whole network or a part): C = rn_homogenize and the stress S give the first
// elasticity tensor L_aJbL = F_aI F_bK CE_IJKL + delta_ab S_JL (F = I + H the
// cell's symmetric deformation gradient, CE and S the tangent and stress of the
// Green-Lagrange strain, from C and the stress by the chain rule of
// E = H + H^2 / 2), and the acoustic tensor A(n)_ab = L_aJbL n_J n_L over the
// modes' amplitude components: fills res->acoustic_* (acoustic_valid 0 if
// rn_homogenize finds K not positive definite).
void acoustic_tangent(rn_network *net, rn_bloch_modes modes, rn_bloch_result *res);

// The AcousticTensor of the tangent C[ns ns] (per measure) and stress[ns] at
// strain[ns] over the amplitude components amp (0, 1, 2).
void acoustic_from_tangent(int dim, double measure, const double *strain,
                           const double *stress, const double *C,
                           const std::vector<int> &amp, AcousticTensor &t);

} // namespace rodnet

#endif

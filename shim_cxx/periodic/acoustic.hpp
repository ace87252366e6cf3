// acoustic.hpp - the acoustic tensor of a periodic cell's long-wavelength
// (macroscopic) stability test and its lowest eigenvalue over the directions
// (cell_path.cpp: from the Bloch Hessian's expansion; cell_part.cpp: from the
// homogenised tangent on a part of a distributed cell).
#ifndef RODNET_SHIM_ACOUSTIC_HPP
#define RODNET_SHIM_ACOUSTIC_HPP

#include <vector>

#include "rodnet_solve.h"

namespace rodnet {

// The acoustic tensor A(n) = (1/V) [-1/2 sum n_J n_L T^T M2_JL T
//                                   - sum n_J n_L (M1_J^T T)^T K^-1 (M1_L^T T)]
// over the amplitude components amp[na] of the modes examined, K the fluctuation
// block (anchor pinned) on those modes: the second-order term of the Bloch
// Hessian's acoustic branches (translations t plus the fluctuation i k w they
// induce).  Q_JL[a][b] holds the bracket per direction pair.
struct AcousticTensor {
  int d = 0, na = 0;
  double measure = 0.0;
  std::vector<int> amp;
  std::vector<double> Q; // [d][d][na][na]
  double &q(int J, int L, int a, int b) {
    return Q[static_cast<size_t>(((J * d + L) * na + a) * na + b)];
  }
  double q(int J, int L, int a, int b) const {
    return Q[static_cast<size_t>(((J * d + L) * na + a) * na + b)];
  }
  // A(n) (na x na) for the unit direction nv.
  void at(const double *nv, double *A) const {
    for (int a = 0; a < na; ++a)
      for (int b = 0; b < na; ++b) {
        double s = 0.0;
        for (int J = 0; J < d; ++J)
          for (int L = 0; L < d; ++L)
            s += nv[J] * nv[L] * 0.5 * (q(J, L, a, b) + q(J, L, b, a));
        A[a * na + b] = s / measure;
      }
  }
};

// The lowest eigenvalue of the acoustic tensor t over the unit directions (720
// of the half circle in 2D, 2000 on the hemisphere in 3D, then refined) into
// res->acoustic_min, acoustic_scale (the largest), direction and amplitude.
void acoustic_search(const AcousticTensor &t, rn_bloch_result *res);

} // namespace rodnet

#endif

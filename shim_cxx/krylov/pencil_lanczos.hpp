// pencil_lanczos.hpp - the lowest eigenpair of a symmetric pencil (H, M), M SPD given
// by M^{-1}, by preconditioned Lanczos (M-orthonormal basis, full
// reorthogonalisation, at most 30 steps, LAPACK dstev) from a fixed pseudo-random
// start.  The trust region's negative-curvature test (tr_krylov.cpp) on the pencil
// of the Hessian and its preconditioner, or on the DD's coarse pencil
// (DdPreconditioner::coarse_pencil).  Written against Tpetra operators only.
#ifndef RODNET_SHIM_PENCIL_LANCZOS_HPP
#define RODNET_SHIM_PENCIL_LANCZOS_HPP

#include <Teuchos_RCP.hpp>
#include <Tpetra_Map.hpp>
#include <Tpetra_MultiVector.hpp>
#include <Tpetra_Operator.hpp>

namespace rodnet {

// The lowest Ritz value mu (the Rayleigh quotient v'Hv of the Ritz vector, an upper
// bound of the lowest eigenvalue), v M-normalised with M v in Mv (both on map, H's
// domain map); *steps: the Lanczos steps taken.  Collective over the map's ranks.
double pencil_lowest(const Tpetra::Operator<> &H, const Tpetra::Operator<> &Minv,
                     const Teuchos::RCP<const Tpetra::Map<>> &map,
                     Tpetra::MultiVector<> &v, Tpetra::MultiVector<> &Mv, int *steps);
// The same on H's domain map.
double pencil_lowest(const Tpetra::Operator<> &H, const Tpetra::Operator<> &Minv,
                     Tpetra::MultiVector<> &v, Tpetra::MultiVector<> &Mv, int *steps);

} // namespace rodnet

#endif

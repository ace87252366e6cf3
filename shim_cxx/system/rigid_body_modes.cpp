// rigid_body_modes.cpp - the rigid-body modes of a network's DOFs
// (rigid_body_modes.hpp).
#include "system/rigid_body_modes.hpp"

#include "system/dof_blocks.hpp"
#include "system/system_serial.hpp"

namespace rodnet {

Teuchos::RCP<TMV> rigid_body_modes(const Teuchos::RCP<const TMap> &map, const int *kind,
                                   const double *point, const double *axis) {
  auto modes = Teuchos::rcp(new TMV(map, 6));
  auto v = modes->getLocalViewHost(Tpetra::Access::OverwriteAll);
  for (size_t k = 0; k < v.extent(0); ++k) {
    const double *p = point + 3 * k;
    for (size_t c = 0; c < 6; ++c) v(k, c) = 0.0;
    if (kind[k] < kDofRotation) { // t + w x p, component a
      const size_t a = static_cast<size_t>(kind[k]);
      const double wxp[3][3] = {
          {0.0, -p[2], p[1]}, {p[2], 0.0, -p[0]}, {-p[1], p[0], 0.0}};
      v(k, a) = 1.0;
      for (size_t c = 0; c < 3; ++c) v(k, 3 + c) = wxp[c][a];
    } else if (kind[k] < kDofAngle) { // w
      v(k, static_cast<size_t>(kind[k])) = 1.0;
    } else { // w . axis
      for (size_t c = 0; c < 3; ++c) v(k, 3 + c) = axis[3 * k + c];
    }
  }
  return modes;
}

Teuchos::RCP<const TMV> network_rigid_body_modes(const System &sys) {
  const auto *serial = dynamic_cast<const SerialSystem *>(&sys);
  if (!serial) return Teuchos::null;
  const NetworkDofs d =
      network_dofs(const_cast<SerialSystem *>(serial)->problem().network());
  return rigid_body_modes(sys.map(), d.kind.data(), d.point.data(), d.axis.data());
}

} // namespace rodnet

// krylov_workspace.cpp - the System and the preconditioner of tr-krylov for one load
// step (KrylovWorkspace, solvers.hpp): a SerialSystem of the whole network unless a
// distributed System is given, the preconditioner from the registry (pc/registry.hpp).
// Apart from tr_krylov.cpp, which is written against the interfaces only.
#include <memory>

#include "newton/solvers.hpp"
#include "pc/preconditioner.hpp"
#include "pc/registry.hpp"
#include "system/system_serial.hpp"

namespace rodnet {

KrylovWorkspace::KrylovWorkspace(Problem &p, System *system, const rn_solve_options &opt)
    : sys_(system) {
  if (!sys_) {
    own_ = std::make_unique<SerialSystem>(p);
    sys_ = own_.get();
  }
  prec_ = make_preconditioner(*sys_, opt, &kind_);
}

KrylovWorkspace::~KrylovWorkspace() = default;

void KrylovWorkspace::account() {
  const PreconditionerStats &st = prec_->stats();
  sys_->add_preconditioner_time(st.setup_seconds - setup_seen_,
                                st.apply_seconds - apply_seen_);
  setup_seen_ = st.setup_seconds;
  apply_seen_ = st.apply_seconds;
}

} // namespace rodnet

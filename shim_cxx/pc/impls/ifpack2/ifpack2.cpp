// ifpack2.cpp - the "ifpack2" preconditioner: Ifpack2 additive Schwarz with a local
// sparse LU (ifpack2.hpp).  The only translation unit with Ifpack2 headers (they
// compile slowly).
#include "pc/impls/ifpack2/ifpack2.hpp"

#include <Amesos2_Details_registerLinearSolverFactory.hpp>
#include <Ifpack2_Factory.hpp>
#include <Teuchos_ParameterList.hpp>

#include "base/clock.hpp"
#include "base/shim_error.hpp"

namespace rodnet {

void SchwarzPreconditioner::setup(System &sys) {
  const Clock::time_point t0 = Clock::now();
  static const bool registered = [] {
    Amesos2::Details::registerLinearSolverFactory();
    return true;
  }();
  (void)registered;
  if (!mpi_backed(*sys.map()->getComm()))
    throw Error(
        RN_ERR_TRILINOS,
        "Ifpack2 additive Schwarz needs the MPI runtime in Trilinos 13.2: run under "
        "mpirun or with RODNET_MPI=1 (docs/solvers.md)");
  guarded_setup(
      sys,
      [](const Teuchos::RCP<TCrs> &A) -> Teuchos::RCP<Tpetra::Operator<>> {
        using RowMatrix = Tpetra::RowMatrix<>;
        Ifpack2::Factory factory;
        auto prec =
            factory.create<RowMatrix>("SCHWARZ", Teuchos::RCP<const RowMatrix>(A));
        Teuchos::ParameterList p;
        p.set("schwarz: overlap level", 1);
        p.set("schwarz: combine mode", "ADD");
        p.set("inner preconditioner name", "AMESOS2");
        Teuchos::ParameterList &inner = p.sublist("inner preconditioner parameters");
        inner.sublist("Amesos2");
        inner.set("Amesos2 solver name", "klu2");
        prec->setParameters(p);
        prec->initialize();
        prec->compute();
        return prec;
      },
      "ifpack2 preconditioner", t0);
}

} // namespace rodnet

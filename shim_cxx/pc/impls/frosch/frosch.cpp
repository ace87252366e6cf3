// frosch.cpp - FROSch (Trilinos ShyLU-DD) two-level overlapping Schwarz as an
// alternative preconditioner measured against the rod-level domain decomposition
// (frosch.hpp, docs/solvers.md).  The only translation unit with FROSch
// and Xpetra headers (they compile slowly).
//
// FROSch is used algebraically: one subdomain per rank (the rank's rows of the
// Hessian, every DOF a "node" of one DOF), overlap 1 grown from the matrix graph, a
// sparse LU of each overlapping subdomain (Amesos2 KLU2 on the rank alone), combined
// additively so that the operator is symmetric.  The coarse space is the IPOU harmonic
// one: the rigid-body modes (the near-null space of the network, given as input)
// restricted to the interface components found from the repeated map and partitioned
// by the GDSW partition of unity, extended harmonically into the subdomains.  The
// coarse matrix is gathered to one rank (FROSch's default) and factored there: never
// a distributed Amesos2 solve (wrong in Trilinos 13.2, TRILINOS.md).
//
// FROSch prints its set-up tables and notices on rank 0's std::cout / std::cerr; the
// library must not print, so those streams are muted around every FROSch call.

// No FROSch notices or warnings on the standard streams (the macros are defaults).
#define FROSCH_WARNING(CLASS, VERBOSE, OUTPUT)
#define FROSCH_NOTIFICATION(CLASS, VERBOSE, OUTPUT)

#include <iostream>
#include <streambuf>
#include <string>

// Xpetra first, then FROSch's tools: the other FROSch headers use their names
// without including them.
#include <Teuchos_ParameterList.hpp>
#include <Xpetra_CrsMatrixWrap.hpp>
#include <Xpetra_ExportFactory.hpp>
#include <Xpetra_ImportFactory.hpp>
#include <Xpetra_MapFactory.hpp>
#include <Xpetra_MatrixFactory.hpp>
#include <Xpetra_MultiVectorFactory.hpp>
#include <Xpetra_TpetraCrsMatrix.hpp>
#include <Xpetra_TpetraMultiVector.hpp>

#include <FROSch_Tools_def.hpp>
#include <FROSch_TwoLevelPreconditioner_def.hpp>

#include "base/clock.hpp"
#include "base/shim_error.hpp"
#include "pc/impls/frosch/frosch.hpp"

namespace rodnet {

namespace {

using NO = Tpetra::Map<>::node_type;
using XMatrix = Xpetra::Matrix<double, LO, GO, NO>;
using XMV = Xpetra::MultiVector<double, LO, GO, NO>;
using XTpetraMV = Xpetra::TpetraMultiVector<double, LO, GO, NO>;
using Frosch = FROSch::TwoLevelPreconditioner<double, LO, GO, NO>;

// Discards everything written to it.
class NullBuffer : public std::streambuf {
protected:
  int overflow(int c) override { return traits_type::not_eof(c); }
  std::streamsize xsputn(const char *, std::streamsize n) override { return n; }
};

// Mutes std::cout and std::cerr for its lifetime (FROSch's set-up output).
class MuteStreams {
public:
  MuteStreams() : out_(std::cout.rdbuf(&null_)), err_(std::cerr.rdbuf(&null_)) {}
  ~MuteStreams() {
    std::cout.rdbuf(out_);
    std::cerr.rdbuf(err_);
  }
  MuteStreams(const MuteStreams &) = delete;
  MuteStreams &operator=(const MuteStreams &) = delete;

private:
  NullBuffer null_;
  std::streambuf *out_, *err_;
};

Teuchos::RCP<XMV> as_xpetra(const TMV &v) {
  return Teuchos::rcp(new XTpetraMV(Teuchos::rcpFromRef(const_cast<TMV &>(v))));
}

Teuchos::RCP<Teuchos::ParameterList> frosch_parameters(bool have_nullspace) {
  auto p = Teuchos::rcp(new Teuchos::ParameterList("FROSch"));
  p->set("Dimension", 3);
  p->set("Overlap", 1);
  p->set("OverlappingOperator Type", "AlgebraicOverlappingOperator");
  p->set("CoarseOperator Type", "IPOUHarmonicCoarseOperator");
  p->set("Level Combination", "Additive");
  p->set("Null Space Type", have_nullspace ? "Input" : "Laplace");
  Teuchos::ParameterList &ov = p->sublist("AlgebraicOverlappingOperator");
  ov.set("Verbosity", "None");
  ov.set("Combine Values in Overlap", "Full"); // additive: a symmetric operator
  ov.sublist("Solver").set("SolverType", "Amesos2");
  ov.sublist("Solver").set("Solver", "Klu");
  Teuchos::ParameterList &co = p->sublist("IPOUHarmonicCoarseOperator");
  co.set("Verbosity", "None");
  Teuchos::ParameterList &block = co.sublist("Blocks").sublist("1");
  block.set("Use For Coarse Space", true);
  block.set("Verbosity", "None");
  block.sublist("InterfacePartitionOfUnity").set("Type", "GDSW");
  block.sublist("InterfacePartitionOfUnity").sublist("GDSW").set("Verbosity", "None");
  co.sublist("ExtensionSolver").set("SolverType", "Amesos2");
  co.sublist("ExtensionSolver").set("Solver", "Klu");
  co.sublist("Distribution").set("Type", "linear");
  co.sublist("Distribution").set("NumProcs", 1);
  co.sublist("CoarseSolver").set("SolverType", "Amesos2");
  co.sublist("CoarseSolver").set("Solver", "Klu");
  return p;
}

// The FROSch operator of one shifted matrix as a Tpetra operator.
class FroschOperator : public Tpetra::Operator<> {
public:
  FroschOperator(const Teuchos::RCP<TCrs> &A, const Teuchos::RCP<const TMV> &nullspace)
      : map_(A->getRowMap()) {
    Teuchos::RCP<Xpetra::CrsMatrix<double, LO, GO, NO>> xcrs =
        Teuchos::rcp(new Xpetra::TpetraCrsMatrix<double, LO, GO, NO>(A));
    Teuchos::RCP<const XMatrix> xA =
        Teuchos::rcp(new Xpetra::CrsMatrixWrap<double, LO, GO, NO>(xcrs));
    Teuchos::RCP<const XMV> xnull;
    if (!nullspace.is_null()) xnull = as_xpetra(*nullspace);
    MuteStreams mute;
    prec_ = Teuchos::rcp(new Frosch(xA, frosch_parameters(!xnull.is_null())));
    // Dimension 3, one DOF per node: FROSch finds the interface from the graph.
    int ret = prec_->initialize(3, 1, 1, xnull, Teuchos::null, FROSch::NodeWise);
    if (ret < 0)
      throw Error(RN_ERR_TRILINOS,
                  "FROSch initialize failed (status " + std::to_string(ret) + ")");
    ret = prec_->compute();
    if (ret < 0)
      throw Error(RN_ERR_TRILINOS,
                  "FROSch compute failed (status " + std::to_string(ret) + ")");
  }
  Teuchos::RCP<const TMap> getDomainMap() const override { return map_; }
  Teuchos::RCP<const TMap> getRangeMap() const override { return map_; }
  void apply(const TMV &X, TMV &Y, Teuchos::ETransp mode, double alpha,
             double beta) const override {
    Teuchos::RCP<XMV> x = as_xpetra(X), y = as_xpetra(Y);
    prec_->apply(*x, *y, mode, alpha, beta);
  }

private:
  Teuchos::RCP<const TMap> map_;
  Teuchos::RCP<Frosch> prec_;
};

} // namespace

void FroschPreconditioner::setup(System &sys) {
  const Clock::time_point t0 = Clock::now();
  if (!mpi_backed(*sys.map()->getComm()))
    throw Error(RN_ERR_TRILINOS,
                "FROSch needs the MPI runtime in Trilinos 13.2: run under mpirun or "
                "with RODNET_MPI=1 (docs/solvers.md)");
  const Teuchos::RCP<const TMV> nullspace = nullspace_;
  try {
    guarded_setup(
        sys,
        [&](const Teuchos::RCP<TCrs> &A) -> Teuchos::RCP<Tpetra::Operator<>> {
          return Teuchos::rcp(new FroschOperator(A, nullspace));
        },
        "frosch preconditioner", t0);
  } catch (const Error &) {
    throw;
  } catch (const std::exception &e) {
    throw Error(RN_ERR_TRILINOS, std::string("FROSch: ") + e.what());
  }
}

} // namespace rodnet

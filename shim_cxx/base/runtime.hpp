// runtime.hpp - the solver's process runtime (Kokkos, and MPI only when the process
// is part of an MPI job) and the Teuchos communicators the shim builds its Tpetra
// maps on.  rn_runtime_initialize / rn_runtime_finalize (rodnet_solve.h) are
// implemented in runtime.cpp.
//
// How rodnet decides whether to use MPI (docs/cli.md, "MPI"):
//   - MPI already initialised by the program (MPI_Init before the first solve or
//     before rn_runtime_initialize): MPI mode, nothing of MPI is initialised or
//     finalised by rodnet.
//   - RODNET_MPI=1 in the environment: MPI mode (MPI_Init through Tpetra::initialize,
//     even as a singleton); RODNET_MPI=0: serial mode even under a launcher.
//   - otherwise MPI mode exactly when an MPI launcher started the process: one of
//     OMPI_COMM_WORLD_SIZE (Open MPI's mpirun), PMIX_RANK (PMIx launchers: Open MPI,
//     Slurm srun --mpi=pmix), PMI_RANK or PMI_SIZE (PMI-1/2: MPICH/Intel MPI hydra,
//     srun --mpi=pmi2) is set.
//   - serial mode otherwise: Kokkos only; MPI_Init is never called (a singleton
//     MPI_Init of Open MPI forks an orted and costs about 0.3 s) and the maps live
//     on a Teuchos::SerialComm.
#ifndef RODNET_SHIM_RUNTIME_HPP
#define RODNET_SHIM_RUNTIME_HPP

#include <Teuchos_Comm.hpp>
#include <Teuchos_RCP.hpp>

namespace rodnet {

// Initialise the runtime if neither the program nor an earlier call did (the first
// rn_solve without rn_runtime_initialize; registers rn_runtime_finalize with
// atexit).  Throws rodnet::Error if it cannot (after rn_runtime_finalize).
void ensure_runtime();

// True if the runtime uses MPI (MPI is initialised and not finalised).
bool runtime_uses_mpi();

// A communicator of this process alone: MPI_COMM_SELF in MPI mode, a
// Teuchos::SerialComm in serial mode.
Teuchos::RCP<const Teuchos::Comm<int>> self_comm();

// The communicator of all the processes of the job: MPI_COMM_WORLD in MPI mode, a
// Teuchos::SerialComm (one process) in serial mode.
Teuchos::RCP<const Teuchos::Comm<int>> world_comm();

} // namespace rodnet

#endif

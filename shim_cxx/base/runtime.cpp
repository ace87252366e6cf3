// runtime.cpp - rn_runtime_initialize / rn_runtime_finalize and the shim's
// communicators (runtime.hpp): MPI only for processes of an MPI job.
#include "base/runtime.hpp"

#include <mpi.h>

#include <cstdlib>
#include <cstring>

#include <Kokkos_Core.hpp>
#include <Teuchos_DefaultMpiComm.hpp>
#include <Teuchos_DefaultSerialComm.hpp>
#include <Tpetra_Core.hpp>

#include "rodnet_solve.h"
#include "base/shim_error.hpp"

namespace rodnet {
namespace {

bool g_tpetra_here = false; // Tpetra::initialize was called by rodnet (MPI mode)
bool g_kokkos_here = false; // Kokkos::initialize was called by rodnet (serial mode)
bool g_serial = false;      // serial mode chosen (Kokkos ready, no MPI)
// rodnet finalised what it initialised: Tpetra (13.2) cannot be initialised again
// after Tpetra::finalize, nor MPI after MPI_Finalize, and Tpetra's objects do not
// survive a Kokkos::finalize / Kokkos::initialize cycle.
bool g_finalized = false;
bool g_atexit_registered = false;

void finalize_at_exit() { rn_runtime_finalize(); }

bool mpi_active() {
  int initialized = 0, finalized = 0;
  MPI_Initialized(&initialized);
  MPI_Finalized(&finalized);
  return initialized && !finalized;
}

bool env_set(const char *name) {
  const char *v = std::getenv(name);
  return v && *v;
}

// Whether this process should run with MPI (runtime.hpp says how it is decided).
bool want_mpi() {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (initialized) return true;
  const char *force = std::getenv("RODNET_MPI");
  if (force && std::strcmp(force, "1") == 0) return true;
  if (force && std::strcmp(force, "0") == 0) return false;
  return env_set("OMPI_COMM_WORLD_SIZE") || env_set("PMIX_RANK") || env_set("PMI_RANK") ||
         env_set("PMI_SIZE");
}

bool runtime_ready() {
  return Tpetra::isInitialized() || (g_serial && Kokkos::is_initialized());
}

} // namespace

void ensure_runtime() {
  if (runtime_ready()) return;
  const rn_status s = rn_runtime_initialize(nullptr, nullptr);
  if (s != RN_OK)
    throw Error(s, "rn_solve: cannot initialise the solver runtime (Kokkos, MPI)");
  if (!g_atexit_registered && std::atexit(finalize_at_exit) == 0)
    g_atexit_registered = true;
}

bool runtime_uses_mpi() { return mpi_active(); }

Teuchos::RCP<const Teuchos::Comm<int>> self_comm() {
  if (mpi_active()) return Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_SELF));
  return Teuchos::rcp(new Teuchos::SerialComm<int>());
}

Teuchos::RCP<const Teuchos::Comm<int>> world_comm() {
  if (mpi_active()) return Teuchos::rcp(new Teuchos::MpiComm<int>(MPI_COMM_WORLD));
  return Teuchos::rcp(new Teuchos::SerialComm<int>());
}

} // namespace rodnet

extern "C" {

rn_status rn_runtime_initialize(int *argc, char ***argv) {
  using namespace rodnet;
  try {
    if (runtime_ready()) return RN_OK;
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (finalized || g_finalized) return RN_ERR_STATE;
    int argc0 = 0;
    char *argv0[] = {nullptr};
    char **argvp = argv0;
    if (!argc || !argv) {
      argc = &argc0;
      argv = &argvp;
    }
    if (want_mpi()) {
      Tpetra::initialize(argc, argv); // MPI_Init unless the program did it
      g_tpetra_here = true;
      return RN_OK;
    }
    if (!Kokkos::is_initialized()) {
      Kokkos::initialize(*argc, *argv);
      g_kokkos_here = true;
    }
    g_serial = true;
    return RN_OK;
  } catch (...) {
    return RN_ERR_TRILINOS;
  }
}

void rn_runtime_finalize(void) {
  using namespace rodnet;
  try {
    if (g_tpetra_here && Tpetra::isInitialized()) {
      g_finalized = true;
      Tpetra::finalize();
    }
    if (g_kokkos_here && Kokkos::is_initialized()) {
      g_finalized = true;
      Kokkos::finalize();
    }
  } catch (...) {
  }
  g_tpetra_here = g_kokkos_here = g_serial = false;
}

} // extern "C"

#pragma once
// The interface between the study processes (processes.cpp) and the MPI module
// (mpi_module.cpp, built as the shared module librodlab_mpi.so when CMake finds MPI). The
// module is loaded with dlopen only by `rodlab study` under an MPI launcher, so no other run
// maps the MPI libraries (OpenMPI and its dependencies: a dozen shared objects, about 2 ms of
// every process start; docs/performance.md "Process start-up").
//
// C linkage and plain C types, so that the table is all the two sides share: the module is the
// only code compiled against mpi.h.

extern "C" {

struct RodlabMpiApi {
  /// MPI_Init_thread (MPI_THREAD_FUNNELED), then this process's rank and the job's size.
  /// Returns 0 on success (MPI's error code otherwise).
  int (*init)(int* rank, int* size);
  /// MPI_Finalize.
  void (*finalize)();
  /// Collective on MPI_COMM_WORLD: every rank's `length` into `lengths` on rank 0 (size()
  /// entries there; may be null elsewhere).
  int (*gather_lengths)(int length, int* lengths);
  /// Collective: every rank's `length` bytes into `all` on rank 0, rank r's at offsets[r].
  int (*gather_bytes)(const char* mine, int length, char* all, const int* lengths,
                      const int* offsets);
};

/// The module's one exported symbol.
const RodlabMpiApi* rodlab_mpi_api();
}

/// Its name, for rodlab::load_module (rodlab/module.hpp).
inline constexpr const char* kRodlabMpiApiSymbol = "rodlab_mpi_api";

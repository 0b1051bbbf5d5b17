// librodlab_mpi.so (validation/CMakeLists.txt): the MPI calls of the study processes
// (studies/mpi_module.hpp), the only code compiled against mpi.h. Loaded by
// studies/processes.cpp under an MPI launcher only.
#include <mpi.h>

#include "studies/mpi_module.hpp"

namespace {

int init(int* rank, int* size) {
  int provided = 0;
  if (const int e = MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
      e != MPI_SUCCESS)
    return e;
  if (const int e = MPI_Comm_rank(MPI_COMM_WORLD, rank); e != MPI_SUCCESS) return e;
  return MPI_Comm_size(MPI_COMM_WORLD, size);
}

void finalize() { MPI_Finalize(); }

int gather_lengths(int length, int* lengths) {
  return MPI_Gather(&length, 1, MPI_INT, lengths, 1, MPI_INT, 0, MPI_COMM_WORLD);
}

int gather_bytes(const char* mine, int length, char* all, const int* lengths,
                 const int* offsets) {
  return MPI_Gatherv(mine, length, MPI_CHAR, all, lengths, offsets, MPI_CHAR, 0, MPI_COMM_WORLD);
}

constexpr RodlabMpiApi kApi{&init, &finalize, &gather_lengths, &gather_bytes};

}  // namespace

extern "C" __attribute__((visibility("default"))) const RodlabMpiApi* rodlab_mpi_api() {
  return &kApi;
}

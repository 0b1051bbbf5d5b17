#include "studies/processes.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>

#ifdef RODLAB_HAVE_MPI
#include <mpi.h>
#endif


namespace rodlab::validation::study {

int launcher_world_size() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_SIZE"}) {
    if (const char* v = std::getenv(name)) {
      const int n = std::atoi(v);
      if (n >= 1) return n;
    }
  }
  return std::getenv("PMIX_RANK") != nullptr ? 2 : 1;
}

namespace {
bool launched_by_mpi() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_SIZE") ||
         std::getenv("PMIX_RANK");
}
}  // namespace

Processes::Processes() {
  if (!launched_by_mpi()) return;
#ifdef RODLAB_HAVE_MPI
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  mpi_ = true;
#else
  if (launcher_world_size() > 1)
    throw std::invalid_argument(
        "launched by mpirun with " + std::to_string(launcher_world_size()) +
        " ranks, but this rodlab was built without MPI: every rank would run the whole study. "
        "Run it without mpirun (use --jobs N for the local cores), or install libopenmpi-dev "
        "and openmpi-bin and rebuild (scripts/bootstrap.sh)");
#endif
}

Processes::~Processes() {
#ifdef RODLAB_HAVE_MPI
  if (mpi_) MPI_Finalize();
#endif
}

std::vector<std::string> Processes::gather(const std::string& mine) const {
  if (!mpi_) return {mine};
#ifdef RODLAB_HAVE_MPI
  const int length = static_cast<int>(mine.size());
  std::vector<int> lengths(root() ? size_ : 0);
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  std::vector<int> offsets(lengths.size(), 0);
  int total = 0;
  for (std::size_t r = 0; r < lengths.size(); ++r) {
    offsets[r] = total;
    total += lengths[r];
  }
  std::string all(static_cast<std::size_t>(total), '\0');
  MPI_Gatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(), MPI_CHAR,
              0, MPI_COMM_WORLD);
  std::vector<std::string> out;
  for (std::size_t r = 0; r < lengths.size(); ++r)
    out.push_back(all.substr(static_cast<std::size_t>(offsets[r]),
                             static_cast<std::size_t>(lengths[r])));
  return out;
#else
  return {mine};
#endif
}

}  // namespace rodlab::validation::study

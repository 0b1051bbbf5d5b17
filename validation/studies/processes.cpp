#include "studies/processes.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>

#include "rodlab/module.hpp"
#include "studies/mpi_module.hpp"

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
  std::string tried;
#ifdef RODLAB_MPI_MODULE  // the module's path in the build tree (validation/CMakeLists.txt)
  mpi_api_ = load_module_api<RodlabMpiApi>(RODLAB_MPI_MODULE, kRodlabMpiApiSymbol, tried);
#endif
  if (!mpi_api_) {
    if (launcher_world_size() <= 1) return;
    throw std::invalid_argument(
        "launched by mpirun with " + std::to_string(launcher_world_size()) + " ranks, but " +
        (tried.empty() ? std::string("this rodlab was built without MPI")
                       : "its MPI module could not be loaded (" + tried + ")") +
        ": every rank would run the whole study. Run it without mpirun (use --jobs N for the "
        "local cores), or install libopenmpi-dev and openmpi-bin and rebuild "
        "(scripts/bootstrap.sh)");
  }
  if (const int e = mpi_api_->init(&rank_, &size_); e != 0)
    throw std::runtime_error("MPI_Init_thread failed with error code " + std::to_string(e));
  mpi_ = true;
}

Processes::~Processes() {
  if (mpi_) mpi_api_->finalize();
}

std::vector<std::string> Processes::gather(const std::string& mine) const {
  if (!mpi_) return {mine};
  const int length = static_cast<int>(mine.size());
  std::vector<int> lengths(root() ? size_ : 0);
  mpi_api_->gather_lengths(length, lengths.data());
  std::vector<int> offsets(lengths.size(), 0);
  int total = 0;
  for (std::size_t r = 0; r < lengths.size(); ++r) {
    offsets[r] = total;
    total += lengths[r];
  }
  std::string all(static_cast<std::size_t>(total), '\0');
  mpi_api_->gather_bytes(mine.data(), length, all.data(), lengths.data(), offsets.data());
  std::vector<std::string> out;
  for (std::size_t r = 0; r < lengths.size(); ++r)
    out.push_back(all.substr(static_cast<std::size_t>(offsets[r]),
                             static_cast<std::size_t>(lengths[r])));
  return out;
}

}  // namespace rodlab::validation::study

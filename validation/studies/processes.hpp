#pragma once
// The processes a study runs on: one, or the ranks of an MPI job (`mpirun -n K rodlab study
// ...`). MPI is initialised only by `rodlab study`, only after its input has been checked, and
// only when the program was launched by an MPI launcher (OMPI_COMM_WORLD_SIZE, PMI_SIZE or
// PMIX_RANK in the environment), so every other command, and a plain `rodlab study`, never
// touches MPI: the MPI calls live in a module loaded then (mpi_module.hpp), and no other run maps
// the MPI libraries. Built without MPI (or with its module missing), a launch by mpirun with
// more than one rank is refused (exit status 2) instead of running the whole study K times.
#include <string>
#include <vector>

struct RodlabMpiApi;

namespace rodlab::validation::study {

class Processes {
 public:
  /// Joins the MPI job if launched by an MPI launcher; otherwise one process. Throws
  /// std::invalid_argument (exit 2) when launched with several ranks by a build without MPI.
  Processes();
  ~Processes();
  Processes(const Processes&) = delete;
  Processes& operator=(const Processes&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool root() const { return rank_ == 0; }
  bool mpi() const { return mpi_; }

  /// Collective: every rank's text, in rank order, on rank 0; an empty list elsewhere.
  std::vector<std::string> gather(const std::string& mine) const;

 private:
  int rank_ = 0;
  int size_ = 1;
  bool mpi_ = false;
  const RodlabMpiApi* mpi_api_ = nullptr;  ///< the MPI module's calls (mpi_module.hpp)
};

/// The number of ranks the launcher announced in the environment (1 when not launched by one).
int launcher_world_size();

}  // namespace rodlab::validation::study

#include "mpi_session.hpp"

#include <cstdlib>

#ifdef STUDY_WITH_MPI
#include <mpi.h>
#endif

namespace study::cli {

#ifdef STUDY_WITH_MPI
MpiSession::MpiSession(int& argc, char**& argv) {
  // Only under a launcher (mpirun sets these): a plain run stays a plain process, with no MPI
  // start-up cost and no dependence on a working MPI runtime.
  if (!std::getenv("OMPI_COMM_WORLD_SIZE") && !std::getenv("PMI_SIZE") && !std::getenv("PMIX_RANK")) return;
  MPI_Init(&argc, &argv);
  initialised_ = true;
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  rank_ = static_cast<std::size_t>(rank);
  size_ = static_cast<std::size_t>(size);
}

MpiSession::~MpiSession() {
  if (initialised_) MPI_Finalize();
}

bool MpiSession::all_succeeded(bool mine) const {
  if (!initialised_) return mine;
  int ok = mine ? 1 : 0, all = 0;
  MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
  return all == 1;
}

std::size_t MpiSession::sum(std::size_t mine) const {
  if (!initialised_) return mine;
  unsigned long long in = mine, out = 0;
  MPI_Allreduce(&in, &out, 1, MPI_UNSIGNED_LONG_LONG, MPI_SUM, MPI_COMM_WORLD);
  return static_cast<std::size_t>(out);
}

bool MpiSession::available() { return true; }
#else
MpiSession::MpiSession(int&, char**&) {}
MpiSession::~MpiSession() = default;
bool MpiSession::all_succeeded(bool mine) const { return mine; }
std::size_t MpiSession::sum(std::size_t mine) const { return mine; }
bool MpiSession::available() { return false; }
#endif

}  // namespace study::cli

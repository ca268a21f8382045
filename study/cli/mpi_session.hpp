#pragma once
// The MPI side of `study sweep`, present only when the build found MPI (STUDY_WITH_MPI). Without
// MPI a process is rank 0 of 1. With it, every rank runs its share of the points into the shared
// result directory, and rank 0 assembles the tables after a barrier.

#include <cstddef>

namespace study::cli {

class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  std::size_t rank() const { return rank_; }
  std::size_t size() const { return size_; }
  // Waits for every rank; returns false when some rank failed (its message is its own).
  bool all_succeeded(bool mine) const;
  // The sum over ranks (every rank calls it).
  std::size_t sum(std::size_t mine) const;
  static bool available();

 private:
  std::size_t rank_ = 0, size_ = 1;
  bool initialised_ = false;
};

}  // namespace study::cli

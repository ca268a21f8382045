#pragma once
// Runs a sweep's unfinished points on a pool of threads, and on MPI ranks when the caller has
// several: the work is split into units (a point for fresh initial conditions, a whole chain for
// continuation), unit u belongs to rank u % ranks, and a rank's threads take its units in order.
// Each finished point is written at once (ResultStore::write), so the only shared state is the
// counter of the next unit. Which thread or rank computes a point never changes its numbers.

#include <cstddef>
#include <functional>

#include "study/result_store.hpp"
#include "study/sweep.hpp"

namespace study {

struct SweepProgress {
  std::size_t done = 0;       // points finished by this process (this run)
  std::size_t to_do = 0;      // points this process had to run
  std::size_t skipped = 0;    // points already finished before this run (resume)
  std::size_t failed = 0;     // points whose simulation did not complete or ended energy_defect (still written)
};

struct SweepExecution {
  std::size_t threads = 1;
  std::size_t rank = 0, ranks = 1;  // MPI rank and size (1 without MPI)
  // Called after each point this process finishes (from the worker threads, serialised).
  std::function<void(const SweepProgress&)> progress;
};

// Runs this rank's share; the caller assembles once every rank is done.
SweepProgress run_sweep(const SweepSpec& spec, const ResultStore& store, const SweepExecution& execution);

}  // namespace study

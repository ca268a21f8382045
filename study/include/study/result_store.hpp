#pragma once
// A sweep's result directory, written so that a killed sweep loses no finished point and resumes
// where it stopped:
//   DIR/spec.txt          the spec's canonical text; a resume must present the same text
//   DIR/points/NNNNNN.tsv one file per finished point, written to a temporary name and renamed
//                         (rename is atomic on POSIX file systems: a file there is complete)
//   DIR/samples.tsv       assembled in point order: one row per point and kept revolution
//   DIR/points.tsv        one row per point: the simulation's status and counters
//   DIR/analysis.tsv      one row per point when the analysis was asked for
//   DIR/timing.tsv        wall seconds per point: the only file that differs between runs
// The assembled files depend only on the point files, never on the order in which points
// finished, so 1 thread, N threads and M MPI ranks write identical files (docs/study.md).

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "study/point.hpp"
#include "study/sweep.hpp"

namespace study {

class ResultStore {
 public:
  // Opens DIR for `spec`: creates it, or reopens it when `resume` is set and its spec.txt matches.
  // Refuses an existing DIR with finished points without `resume`, and a resume whose spec differs
  // (naming the first line that differs).
  ResultStore(std::filesystem::path dir, const SweepSpec& spec, bool resume);

  const std::filesystem::path& dir() const { return dir_; }
  bool finished(std::size_t point) const;
  // The final state stored with a finished point (for continuation chains that resume mid-way).
  std::optional<std::vector<double>> final_state(std::size_t point) const;
  // Writes the point's file atomically. Thread-safe for different points.
  void write(const PointResult& result) const;
  // Writes the assembled tables from the point files; refuses if any point is missing.
  void assemble() const;

 private:
  std::filesystem::path point_path(std::size_t point) const;
  std::filesystem::path dir_;
  const SweepSpec& spec_;
  std::string header_;
};

// Writes `text` to `path` atomically (a temporary file in the same directory, then rename).
void write_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace study

#pragma once
// A sweep's result directory, written so that a killed sweep loses no finished point and resumes
// where it stopped:
//   DIR/lock              held (flock) by the sweep writing DIR: a second sweep into DIR is refused
//   DIR/spec.txt          the spec's canonical text; a resume must present the same text
//   DIR/points/NNNNNN.tsv one file per finished point, written to a temporary name and renamed
//                         (rename is atomic on POSIX file systems); it carries the spec's hash,
//                         its sample count and an end line, so a resume recomputes a point whose
//                         file was cut short, altered or left by another spec
//   DIR/samples.tsv       assembled in point order: one row per point and kept revolution
//   DIR/points.tsv        one row per point: the simulation's status and counters
//   DIR/analysis.tsv      one row per point when the analysis was asked for
//   DIR/lyapunov.tsv      one row per point when the Lyapunov exponents were asked for (1/s)
//   DIR/timing.tsv        wall seconds per point: the only file that differs between runs
// The assembled files depend only on the point files, never on the order in which points
// finished, so 1 thread, N threads and M MPI ranks write identical files (docs/reference/study.md).

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
  // (naming the first line that differs). With `lock` (every process but MPI ranks other than
  // the first, which share rank 0's lock) it first takes DIR/lock, refusing a DIR another sweep
  // holds; on resume it then deletes every point file that fails validation (discarded()).
  ResultStore(std::filesystem::path dir, const SweepSpec& spec, bool resume, bool lock = true);
  ~ResultStore();
  ResultStore(const ResultStore&) = delete;
  ResultStore& operator=(const ResultStore&) = delete;

  const std::filesystem::path& dir() const { return dir_; }
  bool finished(std::size_t point) const;
  // The final state stored with a finished point (for continuation chains that resume mid-way);
  // none when its simulation did not complete (or ended energy_defect), since a live chain does not
  // continue from such a point either, and the resumed sweep must equal the uninterrupted one.
  std::optional<std::vector<double>> final_state(std::size_t point) const;
  // Writes the point's file atomically. Thread-safe for different points.
  void write(const PointResult& result) const;
  // Writes the assembled tables from the point files; refuses if any point is missing or damaged.
  void assemble() const;
  // Why each point file found on resume was deleted, to be recomputed ("point 3: ...").
  const std::vector<std::string>& discarded() const { return discarded_; }

 private:
  std::filesystem::path point_path(std::size_t point) const;
  // Empty when the file of `point` is whole (it ends with `end`, its check line holds the hash of
  // what is above it) and belongs to this spec, else why not.
  std::string check_point_file(std::size_t point, const std::string& text) const;
  std::filesystem::path dir_;
  const SweepSpec& spec_;
  std::string header_;
  std::string spec_hash_;
  int lock_fd_ = -1;
  std::vector<std::string> discarded_;
};

// Writes `text` to `path` atomically (safe_output::write_file: a temporary file in the same
// directory, every write checked, then rename); a failure is a StudyError of kind io naming the path and why.
void write_atomically(const std::filesystem::path& path, const std::string& text);

}  // namespace study

#pragma once
// A zoo run's checkpoint (`chaos zoo --checkpoint FILE`): every finished case is appended to FILE as
// one line of JSON and flushed, so that a run stopped part way (a session's end, Ctrl-C, a killed
// job) resumes with the cases it has not yet run; without a checkpoint nothing of a stopped run is
// left.
//
// A checkpoint belongs to one build and one choice of --fast, --no-grid and --grid-points. Its first line records
// them: the build as a hash of the executable or Python module that holds the suite, so that no
// report mixes results of two versions of the code. A run that differs refuses the file instead of
// discarding it or merging it. One run at a time per file: two processes appending to one file
// could interleave their lines. Files of one build and options can be merged by appending one's
// case lines (all but the first line) to the other.

#include <cstdint>
#include <fstream>
#include <map>
#include <string>

#include <nlohmann/json.hpp>

#include "chaos/models/zoo_suite.hpp"

namespace chaos::cli {

class ZooCheckpoint {
 public:
  // Reads `path` if it exists (a last line cut short by a killed run is dropped from the file) and
  // opens it for appending, writing the first line if it is new or empty. Throws InvalidInput:
  // io when the file cannot be read or written, invalid_parameter when it was written by another
  // build or with other options, or a line is not a case result.
  // grid_points: the grid points per system at N = 10^5 (ZooSuiteOptions), 0 for a run without the grid.
  ZooCheckpoint(const std::string& path, bool fast, std::size_t grid_points);

  // The finished cases it holds, by case name (case_index as stored: the caller renumbers).
  const std::map<std::string, ZooCaseResult>& results() const { return results_; }

  // Appends one finished case and flushes it to the file.
  void append(const std::string& case_name, const ZooCaseResult& result);

  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::ofstream out_;
  std::map<std::string, ZooCaseResult> results_;
};

// A 64-bit FNV-1a hash, as 16 hex digits, of the file (executable or shared library) that holds
// this code: equal builds give equal strings, and any change to the suite's code changes it.
std::string zoo_build_fingerprint();

// A case result as a checkpoint stores it, and back; the round trip is exact (finite doubles are
// written as the shortest text that reads back to the same bits, non-finite ones as strings).
nlohmann::ordered_json zoo_result_to_json(const ZooCaseResult& result);
ZooCaseResult zoo_result_from_json(const nlohmann::ordered_json& json);

}  // namespace chaos::cli

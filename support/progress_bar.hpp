#pragma once
// A progress bar on stderr for the command-line tools: the fraction done, a short detail ("42%",
// "17/120 points") and the time left from the rate so far. It draws only when enabled (the caller
// passes whether stderr is a terminal and the user did not ask for quiet) and only after the first
// two seconds, so short runs print nothing.

#include <chrono>
#include <string>

namespace cli_support {

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled);
  ~ProgressBar();  // ends the line it drew
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  void update(double fraction, const std::string& detail);
  // Starts the time-left estimate afresh, for the next step of a job run in steps; a bar already
  // drawn keeps drawing.
  void restart();

 private:
  bool enabled_, shown_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace cli_support

#pragma once
// How every result file and standard output of the tools (`chaos`, `mechanism`, `study`) and the
// Python package is written: a write error (a full disk, /dev/full, a file size limit) is never
// silent, and a failed write leaves no partial file under the target's name. A file is written to a
// temporary file beside its target, every write, the flush to disk and the close are checked, and
// only then is it renamed over the target. Failures throw WriteError naming the path and the
// system's reason (strerror). Standard library only: the estimator libraries' command layers and
// the study library use it as well as the command-line tools.

#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace safe_output {

class WriteError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Why `path` cannot be written ("cannot create a file in DIR (Permission denied)"), or empty: it is
// checked the way OutputFile will write it (a temporary file created beside it and removed again;
// a device or pipe's write permission), so that the reason is the system's and is found before any work.
std::string refusal(const std::string& path);

// One output under construction. A regular file (or a new one) goes to a temporary file beside it
// (".NAME.tmp.PID.N", the target's permissions) until commit(); a device or pipe that exists
// (/dev/null, /dev/full, /dev/stdout) is written directly, with every write checked. Destroyed
// without commit(), the temporary is removed and the target is left as it was.
class OutputFile {
 public:
  explicit OutputFile(std::string path);  // throws WriteError when the file cannot be created
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  ~OutputFile();
  std::ostream& stream();
  const std::string& path() const { return path_; }
  // Flushes, syncs to disk and closes, then renames over the target; throws WriteError (and
  // removes the temporary) on any failure, including one of an earlier write. A second call does nothing.
  void commit();
  // Removes the temporary; the target is left as it was.
  void discard() noexcept;

 private:
  struct Impl;
  std::string path_;
  std::unique_ptr<Impl> impl_;
};

// Writes `bytes` to `path` through OutputFile: all of them, or throws WriteError and leaves `path`
// as it was.
void write_file(const std::string& path, std::string_view bytes);

// Files whose commit waits for the command to succeed: a command writes its -o file while it works,
// and the command line commits every pending file once the command has finished without an error
// (so a later failure, such as a plot refused, leaves an existing -o file untouched). Returns the
// file, which stays alive until commit_pending() or discard_pending().
OutputFile& open_pending(const std::string& path);
// Commits the pending files in the order they were opened; throws WriteError at the first failure
// (the others are discarded).
void commit_pending();
void discard_pending() noexcept;

// Standard output with every write checked: while one exists, std::cout writes straight to file
// descriptor 1 (flushed after every operation when it is a terminal). finish() flushes and says
// why the output is incomplete ("standard output: ... (No space left on device)"), or returns empty.
class StandardOutput {
 public:
  StandardOutput();
  StandardOutput(const StandardOutput&) = delete;
  StandardOutput& operator=(const StandardOutput&) = delete;
  ~StandardOutput();
  std::string finish();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace safe_output

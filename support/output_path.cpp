#include "output_path.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include <unistd.h>

namespace cli_support {

std::string output_refusal(const std::string& option, const std::string& path, const std::string& input) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const std::string named = option + " " + path;
  if (!input.empty() && input != "-" && (input == path || fs::equivalent(input, path, ec)))
    return named + " is the input file; writing the result there would overwrite the data";
  if (fs::is_directory(path, ec)) return named + " is a directory";
  const fs::path parent = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
  const bool exists = fs::exists(path, ec);
  if (!exists && !fs::is_directory(parent, ec)) return named + ": the directory " + parent.string() + " does not exist";
  if (::access(exists ? path.c_str() : parent.c_str(), exists ? W_OK : W_OK | X_OK) != 0)
    return named + ": cannot write " + (exists ? "the file" : "into " + parent.string()) + " (" + std::strerror(errno) + ")";
  return {};
}

}  // namespace cli_support

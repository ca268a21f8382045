#include "output_path.hpp"

#include <filesystem>

#include "gnuplot.hpp"
#include "safe_output.hpp"

namespace cli_support {

std::string output_refusal(const std::string& option, const std::string& path, const std::string& input) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const std::string named = option + " " + path;
  if (!input.empty() && input != "-" && (input == path || fs::equivalent(input, path, ec)))
    return named + " is the input file; writing the result there would overwrite the data";
  if (fs::is_directory(path, ec)) return named + " is a directory";
  const fs::path parent = fs::path(path).parent_path().empty() ? fs::path(".") : fs::path(path).parent_path();
  if (!fs::exists(path, ec) && !fs::is_directory(parent, ec)) return named + ": the directory " + parent.string() + " does not exist";
  // Opened for writing as the result will be (safe_output.hpp), so that what the system refuses
  // (a read-only or full file system, /proc) is found before the work, with its reason.
  if (const std::string why = safe_output::refusal(path); !why.empty()) return named + ": " + why;
  return {};
}

void check_output_option(CLI::Option* option, const std::string& name, const CLI::Option* input, bool plot,
                         std::function<void(const std::string& why, bool io)> refuse) {
  option->check(CLI::Validator(
      [=](std::string& path) {
        if (plot)
          if (const std::string why = plot_extension_refusal(path, name); !why.empty()) refuse(why, false);
        const std::string in = input && input->count() > 0 ? input->results().front() : std::string();
        if (const std::string why = output_refusal(name, path, in); !why.empty()) refuse(why, true);
        return std::string();
      },
      "", plot ? "FILE.png|FILE.svg" : "FILE"));
}

}  // namespace cli_support

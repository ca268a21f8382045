// The `chaos` command: one subcommand per task, TISEAN's option letters, tab-separated output under
// a '#' header or --json. Exit codes: 0 ok, 1 internal error, 2 usage, 3 invalid input,
// 4 a reference case failed (`validate`). A result that cannot be written (standard output or -o:
// a full disk, /dev/full) is an input/output error, exit 3, as an -o refused before the work.

#include <iostream>

#include "chaos/error.hpp"
#include "common.hpp"
#include "memory_policy.hpp"
#include "option_checks.hpp"
#include "safe_output.hpp"

namespace {

void report_write_error(const std::string& why) { std::cerr << "chaos: error [io]: " << why << "\n"; }

int run(int argc, char** argv) {
  using namespace chaos::cli;
  CLI::App app{"chaos: time-series analysis for chaotic data (embedding, mutual information, Cao, FNN, D2, Lyapunov exponents, surrogates, validation)"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "chaos 0.1.0");
  register_generate(app);
  register_mutual(app);
  register_autocorrelation(app);
  register_cao(app);
  register_fnn(app);
  register_d2(app);
  register_analyze(app);
  register_lyapunov(app);
  register_lyapunov_maps(app);
  register_neighbors(app);
  register_spectrum(app);
  register_surrogates(app);
  register_nonlinearity(app);
  register_section(app);
  register_density(app);
  register_validate(app);
  register_zoo(app);
  cli_support::check_numeric_options(app);
  cli_support::one_value_per_occurrence(app);
  if (const std::string unknown = cli_support::unknown_subcommand(app, argc, argv); !unknown.empty()) {
    std::cerr << "chaos: " << unknown << "\n";
    return usage_error;
  }
  try {
    app.parse(argc, argv);
    // The -o files are renamed into place only now that the command has succeeded.
    safe_output::commit_pending();
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return usage_error;
  } catch (const chaos::InvalidInput& e) {
    std::cerr << "chaos: error [" << chaos::to_string(e.code()) << "]: " << e.what() << "\n";
    return invalid_input;
  } catch (const safe_output::WriteError& e) {
    report_write_error(e.what());
    return invalid_input;
  } catch (const ValidationFailed&) {
    // The report of a failed validation is the result: it is written all the same.
    try {
      safe_output::commit_pending();
    } catch (const safe_output::WriteError& e) {
      report_write_error(e.what());
      return invalid_input;
    }
    return validation_failed;
  } catch (const std::exception& e) {
    std::cerr << "chaos: internal error: " << e.what() << "\n";
    return internal_error;
  }
  return ok;
}

}  // namespace

int main(int argc, char** argv) {
  cli_support::keep_freed_memory_in_heap();
  safe_output::StandardOutput out;
  const int code = run(argc, argv);
  safe_output::discard_pending();  // a failed command leaves its -o targets as they were
  if (const std::string why = out.finish(); !why.empty()) {
    report_write_error(why);
    return code == chaos::cli::ok ? chaos::cli::invalid_input : code;
  }
  return code;
}

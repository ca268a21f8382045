// The parameter table of each command (parameter_table.hpp): the options of `chaos X` and the
// keyword arguments of chaos.X, in the order the command's help lists them. Defaults are the
// parameters structs' own (commands.hpp).

#include "commands.hpp"

namespace chaos::cli {

namespace {

// The help of the embedding parameters that cao, fnn, d2, lyapunov and lyapunov-maps choose when
// they are left out.
const char* const delay_help =
    "delay tau in samples (default: automatic, the first mutual-information minimum or the rule that stands in for "
    "it; the output names the rule)";
const char* const theiler_help =
    "Theiler window in samples (default: automatic, the longer of the autocorrelation 1/e time and half the dominant "
    "oscillation period, at least the delay)";
const char* const dimension_help = "embedding dimension (default: automatic, where Cao's E1 saturates)";
const char* const threads_help = "threads (results identical for any number)";
const char* const end_match_help = "first trim the series to the segment whose ends match best (TISEAN endtoend)";

}  // namespace

const ParameterTable<MutualParams>& mutual_parameters() {
  static const ParameterTable<MutualParams> table{
      {"max_delay", "-D,--max-delay",
       "largest delay (default: automatic, 100 (at most N/10), and where the information has no minimum there, on to "
       "two Theiler windows, as chaos analyze searches)",
       field(&MutualParams::max_delay)},
      {"boxes", "-b,--boxes", "boxes per axis", field(&MutualParams::options, &MutualInformationOptions::boxes)},
      {"estimator", "--estimator", "equal_width (TISEAN) or equiprobable", field(&MutualParams::estimator)},
  };
  return table;
}

const ParameterTable<AutocorrelationParams>& autocorrelation_parameters() {
  static const ParameterTable<AutocorrelationParams> table{
      {"max_lag", "-D,--max-lag", "largest lag (default N/10, at most 1000)", field(&AutocorrelationParams::max_lag)},
  };
  return table;
}

const ParameterTable<CaoParams>& cao_parameters() {
  static const ParameterTable<CaoParams> table{
      {"delay", "-d,--delay", delay_help, field(&CaoParams::delay)},
      {"min_dimension", "-m,--min-dimension", "smallest embedding dimension",
       field(&CaoParams::options, &CaoOptions::min_dimension)},
      {"max_dimension", "-M,--max-dimension", "largest embedding dimension",
       field(&CaoParams::options, &CaoOptions::max_dimension)},
      {"theiler", "-t,--theiler", theiler_help, field(&CaoParams::theiler)},
      {"norm", "--norm", "max or euclidean", field(&CaoParams::norm)},
      {"level", "--level", "E1 must reach this level to count as saturated",
       field(&CaoParams::options, &CaoOptions::saturation_level)},
      {"change", "--change", "and change by at most this per dimension from there on",
       field(&CaoParams::options, &CaoOptions::saturation_change)},
      {"sigmas", "--sigmas", "stochastic when every |E2 - 1| is within this many standard errors",
       field(&CaoParams::options, &CaoOptions::stochastic_sigmas)},
  };
  return table;
}

const ParameterTable<FnnParams>& fnn_parameters() {
  static const ParameterTable<FnnParams> table{
      {"delay", "-d,--delay", delay_help, field(&FnnParams::delay)},
      {"min_dimension", "-m,--min-dimension", "smallest embedding dimension",
       field(&FnnParams::options, &FnnOptions::min_dimension)},
      {"max_dimension", "-M,--max-dimension", "largest embedding dimension",
       field(&FnnParams::options, &FnnOptions::max_dimension)},
      {"theiler", "-t,--theiler", theiler_help, field(&FnnParams::theiler)},
      {"rtol", "--rtol", "distance-ratio threshold (criterion 1)", field(&FnnParams::options, &FnnOptions::rtol)},
      {"atol", "--atol", "size threshold in units of the standard deviation (criterion 2)",
       field(&FnnParams::options, &FnnOptions::atol)},
      {"norm", "--norm", "euclidean (Kennel et al.) or max", field(&FnnParams::norm)},
      {"threshold", "--threshold", "dimension chosen where the false fraction <= this",
       field(&FnnParams::options, &FnnOptions::threshold)},
  };
  return table;
}

}  // namespace chaos::cli

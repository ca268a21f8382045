#pragma once
// `study sweep`'s parameter table (parameter_table.hpp): the options of the command and the keyword
// arguments of chaos.study.sweep, written once. The scene, its overrides (--set), the axes and how
// the sweep runs (threads, output directory, resume, progress) stay each front end's own, as a
// chaos command's input file and output do.

#include <string>

#include "parameter_table.hpp"
#include "study/sweep.hpp"

namespace study {

// What the table sets: the sweep's settings, with the initial conditions by name. The front end
// sets the scene, its overrides and the grid in `spec` itself.
struct SweepParams {
  SweepSpec spec;
  std::string initial = "fresh";
};

const cli_support::ParameterTable<SweepParams>& sweep_parameters();

// The sweep the parameters ask for: the initial conditions read from their name (fresh or
// continuation, else refused) and the signal list without empty names (a trailing comma). The
// other checks are SweepSpec::validate's.
SweepSpec sweep_spec(SweepParams params);

}  // namespace study

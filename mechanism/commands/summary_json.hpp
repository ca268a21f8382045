#pragma once
// The JSON summary of a simulation, as `mechanism simulate --json` writes it; shared by the command
// and the Python package (chaos.mechanism.simulate(...).summary), so the two cannot drift apart.

#include <nlohmann/json.hpp>

#include "mechanism/simulate.hpp"
#include "mechanism/slider_crank.hpp"

namespace mechanism {

nlohmann::ordered_json simulation_summary_json(const SimulationSummary& s, const SliderCrank& system);

}  // namespace mechanism

#include "summary_json.hpp"

namespace mechanism {

nlohmann::ordered_json simulation_summary_json(const SimulationSummary& s, const SliderCrank& system) {
  nlohmann::ordered_json j;
  j["status"] = to_string(s.status);
  j["message"] = s.message;
  j["end_time"] = s.end_time;
  j["steps"] = s.steps;
  j["rejected_steps"] = s.rejected_steps;
  j["rhs_evaluations"] = s.rhs_evaluations;
  j["step"] = s.step;
  j["wall_seconds"] = s.wall_seconds;
  j["max_penetration"] = s.max_penetration;
  j["contact_events"] = s.contact_events;
  j["located_switches"] = s.located_switches;
  j["located_reversals"] = s.located_reversals;
  j["unlocated_reversals"] = s.unlocated_reversals;
  j["energy_balance_error"] = s.energy_balance_error;
  j["energy_balance_relative"] = s.energy_balance_relative;
  j["energy_jump_relative"] = s.energy_jump_relative;
  j["samples"] = s.samples;
  j["stroboscopic_samples"] = s.stroboscopic_samples;
  j["coordinates"] = system.coordinate_names();
  return j;
}

}  // namespace mechanism

#pragma once
// The named output signals of a simulation: one column each in the time series. Which signals
// exist depends on the scene (a journal's eccentricity only when that joint has clearance).

#include <string>
#include <vector>

#include "mechanism/slider_crank.hpp"

namespace mechanism {

struct SignalTable {
  std::vector<std::string> names;  // column names, "t" first
  std::vector<std::string> units;  // SI unit of each column ("-" for a code)
};

// All signals the system can write, in column order:
//   t, crank_angle, slider_x, slider_y, slider_angle, slider_vx, slider_vy, slider_omega,
//   conrod_angle, driving_torque, energy (kinetic + gravity), work_drive, work_contact;
//   with translational clearance: slider_mode (SliderConfiguration code), slider_penetration
//   (deepest corner), slider_normal_upper, slider_normal_lower, slider_friction;
//   per revolute clearance joint J: J_ecc_x, J_ecc_y, J_penetration, J_normal, J_friction.
SignalTable signal_table(const SliderCrank& system);

// The values of signal_table(system) at (t, x) with evaluation ev, in the same order.
void signal_values(const SliderCrank& system, double t, const State& x, const Evaluation& ev,
                   std::vector<double>& out);

}  // namespace mechanism

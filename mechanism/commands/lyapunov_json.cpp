#include "lyapunov_json.hpp"

#include <cmath>

namespace mechanism {

// JSON has no infinity: a collapsed exponent (-inf) is written as null, and the status says why.
namespace {

nlohmann::ordered_json finite_or_null(double v) { return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(); }

}  // namespace

nlohmann::ordered_json scene_lyapunov_json(const SceneLyapunov& r) {
  nlohmann::ordered_json j;
  j["status"] = r.status;
  j["method"] = r.method;
  if (r.method == "saltation") j["latched_variations"] = r.latched_variations_carried ? "carried" : "dropped";
  if (!r.message.empty()) j["message"] = r.message;
  j["exponents"] = nlohmann::ordered_json::array();
  for (double v : r.exponents) j["exponents"].push_back(finite_or_null(v));
  j["standard_error"] = nlohmann::ordered_json::array();
  for (double v : r.standard_error) j["standard_error"].push_back(finite_or_null(v));
  j["exponents_per_period"] = nlohmann::ordered_json::array();
  for (double v : r.exponents_per_period) j["exponents_per_period"].push_back(finite_or_null(v));
  j["resolution_limit"] = r.resolution_limit;
  j["kaplan_yorke"] = finite_or_null(r.kaplan_yorke);
  j["kaplan_yorke_section"] = finite_or_null(r.kaplan_yorke_section);
  j["collapsed"] = r.collapsed;
  j["coordinates"] = r.coordinates;
  j["scale"] = r.scale;
  j["period"] = r.period;
  j["periods"] = r.periods;
  j["perturbation"] = r.perturbation;
  j["perturbation_floor"] = r.perturbation_floor;
  j["steps_per_interval"] = r.steps_per_interval;
  j["largest_scaled_coordinate"] = r.largest_scaled_coordinate;
  j["largest_scaled_name"] = r.largest_scaled_name;
  j["largest_separation"] = r.largest_separation;
  j["wall_seconds"] = r.wall_seconds;
  return j;
}

}  // namespace mechanism

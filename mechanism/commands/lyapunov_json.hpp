#pragma once
// The JSON result of `mechanism lyapunov --json`, in the shared command layer (as summary_json.hpp)
// so that another front end (the Python package) can give the same object.

#include <nlohmann/json.hpp>

#include "mechanism/scene_lyapunov.hpp"

namespace mechanism {

// Every field of SceneLyapunov but the running means; JSON has no infinity, so an exponent of
// -inf (a collapsed direction) and a NaN dimension are written as null.
nlohmann::ordered_json scene_lyapunov_json(const SceneLyapunov& r);

}  // namespace mechanism

#pragma once
// Inside the library: largest_lyapunov_local_maps with what a caller already holds.

#include <optional>
#include <span>

#include "chaos/lyapunov_local_maps.hpp"

namespace chaos::detail {

// largest_lyapunov_local_maps(x, options, dt, tolerance), with two additions that leave its result
// unchanged to the last bit:
//   - known_base, when set, is taken as the base estimate instead of being computed; it must be the
//     estimate local_map_exponent gives for `options` (the m + 1 variant of a run at m - 1 with the
//     same delay, step, cutoff and residual limit, and k = 5 m or the same given k);
//   - next_dimension_base, when set, receives the "m + 1" variant's whole estimate where that
//     variant was computed and equals the base of a run at m + 1 with the same options (the
//     retry of local_maps_with_next_dimension).
LocalMapResult local_maps_run(std::span<const double> x, const LocalMapOptions& options, std::optional<double> dt,
                              double tolerance, const LocalMapEstimate* known_base,
                              std::optional<LocalMapEstimate>* next_dimension_base);

}  // namespace chaos::detail

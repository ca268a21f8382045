#pragma once
// FFTW's planner is not thread-safe (only fftw_execute is), so every place in the library that
// makes or destroys a plan takes this one lock; the transforms themselves run concurrently.

#include <mutex>

namespace chaos::detail {

std::mutex& fftw_planner_mutex();

}  // namespace chaos::detail

#include "fftw.hpp"

namespace chaos::detail {

std::mutex& fftw_planner_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace chaos::detail

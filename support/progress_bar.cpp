#include "progress_bar.hpp"

#include <algorithm>
#include <iomanip>
#include <iostream>

namespace cli_support {

ProgressBar::ProgressBar(bool enabled) : enabled_(enabled), start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() {
  if (shown_) std::cerr << "\n";
}

void ProgressBar::restart() { start_ = std::chrono::steady_clock::now(); }

void ProgressBar::update(double fraction, const std::string& detail) {
  if (!enabled_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  if (!shown_ && elapsed < 2.0 && fraction < 1.0) return;
  fraction = std::clamp(fraction, 0.0, 1.0);
  const int width = 40, filled = static_cast<int>(fraction * width);
  const double remaining = fraction > 0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  std::cerr << "\r[" << std::string(filled, '#') << std::string(width - filled, ' ') << "] " << detail << "  "
            << std::fixed << std::setprecision(0) << remaining << " s left " << std::flush;
  shown_ = true;
}

}  // namespace cli_support

#include "plot.hpp"

#include "chaos/error.hpp"
#include "gnuplot.hpp"

namespace chaos::cli {

void render_plot(const std::string& script, const std::string& path) {
  try {
    cli_support::render(script, path);
  } catch (const cli_support::PlotError& e) {
    throw InvalidInput(e.kind() == cli_support::PlotError::Kind::bad_extension ? ErrorCode::invalid_parameter
                                                                                 : ErrorCode::io,
                       e.what());
  }
}

}  // namespace chaos::cli

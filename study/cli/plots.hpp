#pragma once
// `study plot`: the seed's figure types drawn from a result directory's assembled tables through
// gnuplot (support/gnuplot.hpp). With a second axis, the one-dimensional figures get a panel (or
// a curve) per value of it.
//   bifurcation  the last --last kept samples of --signal against the first axis (seed Fig. 4a)
//   density      the probability density of all kept samples per first-axis value, as a colour
//                map (Fig. 4b, 5); equal-width bins over the pooled range (chaos::probability_density)
//   portrait     --signal2 against --signal for each point (Fig. 6)
//   d2           D2 with its interval against the first axis (Fig. 8b, 12); with --dimension m the
//                per-m estimate D2(m), which exists even where D2 does not saturate (labelled so)
//   e2           max |E2(m) - 1| (Cao's determinism measure) against the first axis (Fig. 8a)
//   d2map        D2 over both axes as a colour map (Fig. 9)

#include <CLI/CLI.hpp>

#include <string>

namespace study::cli {

struct PlotRequest {
  std::string dir;
  std::string figure;
  std::string output;
  std::string signal = "slider_y";
  std::string signal2 = "slider_vy";
  std::size_t last = 50;
  std::size_t bins = 60;
  bool log_density = false;     // density: a logarithmic colour scale (zero cells blank)
  std::size_t dimension = 0;    // d2, d2map: plot D2(m) at this m (an unsaturated estimate) instead of the saturated D2
  double x_scale = 1.0, y_scale = 1.0, z_scale = 1.0;
  std::string x_label, y_label, title;
};

void add_plot_options(CLI::App& cmd, PlotRequest& request);
void draw(const PlotRequest& request);

}  // namespace study::cli

#include "plots.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "chaos/poincare.hpp"
#include "mechanism/scene.hpp"
#include "mechanism/signals.hpp"
#include "mechanism/slider_crank.hpp"
#include "gnuplot.hpp"
#include "outputs.hpp"
#include "study/error.hpp"

namespace study::cli {

namespace {

// An assembled table: the column names from its last '#' line, the rows as numbers ('-' is NaN,
// a missing value the plots leave out) and the text columns kept aside by name.
struct Table {
  std::vector<std::string> names;
  std::vector<std::vector<double>> rows;
  std::vector<std::vector<std::string>> text;
  std::size_t column(const std::string& name, const std::string& file) const {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) {
      std::string all;
      for (const auto& n : names) all += " " + n;
      throw StudyError(file, name, "is not a column; it has:" + all);
    }
    return static_cast<std::size_t>(it - names.begin());
  }
};

// Strict: a row cut short or with a field too many, or a number column holding something that is
// neither a finite number nor '-', is refused naming the file and line. A truncated samples.tsv
// was plotted with its last row read past its end, a garbled value drawn as NaN. The text columns are status, d2_status, nonlinearity and message.
Table read_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw StudyError("study plot", path, "cannot be read (run `study sweep` into this directory first)");
  const auto damaged = [&](std::size_t line, const std::string& why) {
    return StudyError("study plot", path + ":" + std::to_string(line),
                      why + "; the table is damaged (`study sweep ... --resume` with the sweep's options assembles it "
                            "again from the point files)");
  };
  Table t;
  std::size_t number = 0;
  for (std::string line; std::getline(in, line);) {
    ++number;
    if (line.empty()) continue;
    std::vector<std::string> f;
    std::stringstream s(line[0] == '#' ? line.substr(1) : line);
    for (std::string x; std::getline(s, x, '\t');) f.push_back(x);
    if (line.back() == '\t') f.emplace_back();
    if (line[0] == '#') {
      if (line.rfind("# point", 0) == 0) {
        f[0] = "point";
        t.names = f;
      }
      continue;
    }
    if (t.names.empty()) throw damaged(number, "a data row before the '# point' header line");
    if (f.size() != t.names.size())
      throw damaged(number, "has " + std::to_string(f.size()) + " fields where the header names " +
                                std::to_string(t.names.size()));
    std::vector<double> row;
    for (std::size_t k = 0; k < f.size(); ++k) {
      const std::string& x = f[k];
      const bool text = t.names[k] == "status" || t.names[k] == "d2_status" || t.names[k] == "message" ||
                        t.names[k] == "nonlinearity";
      char* end = nullptr;
      const double v = std::strtod(x.c_str(), &end);
      const bool ok = !x.empty() && *end == '\0' && std::isfinite(v);
      if (!text && !ok && x != "-")
        throw damaged(number, "column " + t.names[k] + ": '" + x.substr(0, 40) + "' is not a finite number");
      row.push_back(ok ? v : std::nan(""));
    }
    t.rows.push_back(std::move(row));
    t.text.push_back(std::move(f));
  }
  if (t.names.empty()) throw StudyError("study plot", path, "has no '# point' header line: not a study table");
  // gnuplot given no data fails without a word: the table is refused here, naming it.
  if (t.rows.empty())
    throw StudyError("study plot", path,
                     "has no data rows under its header: nothing to draw (a table cut short loses them; "
                     "`study sweep ... --resume` with the sweep's options assembles it again from the point files)");
  return t;
}

std::string label(const std::string& given, const std::string& fallback) { return given.empty() ? fallback : given; }

// The unit of a sampled signal, as `mechanism simulate` writes it in its table's header (the
// built-in scene with every revolute joint given clearance has every signal a sweep can keep).
std::string signal_unit(const std::string& name) {
  static const mechanism::SignalTable table = mechanism::signal_table(mechanism::SliderCrank(mechanism::read_scene(
      "", {"joint.crank_ground.type=\"clearance\"", "joint.crank_conrod.type=\"clearance\"",
           "joint.conrod_slider.type=\"clearance\""})));
  const auto it = std::find(table.names.begin(), table.names.end(), name);
  if (it == table.names.end()) return "";
  const std::string unit = table.units[static_cast<std::size_t>(it - table.names.begin())];
  return unit == "-" ? "" : unit;
}

// A unit with the scale the values were multiplied by: "m", or "0.001 m" for --x-scale 1e3 ("x 1000"
// for a value without a unit); empty for neither.
std::string unit_text(const std::string& unit, double scale) {
  std::ostringstream s;
  if (scale != 1.0 && unit.empty()) s << "x " << scale;
  else if (scale != 1.0) s << 1.0 / scale << " " << unit;
  else s << unit;
  return s.str();
}

// A default axis label: the name with its unit, so that an axis says what it shows
// ("joint.slider.clearance (m)"; with --x-scale 1e3, "joint.slider.clearance (0.001 m)").
std::string axis_label(const std::string& name, const std::string& unit, double scale) {
  const std::string u = unit_text(unit, scale);
  return u.empty() ? name : name + " (" + u + ")";
}
std::string key_label(const std::string& key, double scale) { return axis_label(key, mechanism::scene_key_unit(key), scale); }
std::string signal_label(const std::string& signal, double scale) { return axis_label(signal, signal_unit(signal), scale); }

// Axis keys are the columns between "point" and the first non-axis column of points.tsv.
std::vector<std::string> axis_keys(const Table& samples) {
  std::vector<std::string> keys;
  for (std::size_t k = 1; k < samples.names.size() && samples.names[k] != "revolution" && samples.names[k] != "status"; ++k)
    keys.push_back(samples.names[k]);
  return keys;
}

// Groups row indices by the second axis value (one group when there is none).
std::map<double, std::vector<std::size_t>> by_second_axis(const Table& t, const std::vector<std::string>& keys) {
  std::map<double, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < t.rows.size(); ++i) groups[keys.size() > 1 ? t.rows[i][2] : 0.0].push_back(i);
  return groups;
}

std::string panel_title(const std::vector<std::string>& keys, double value, const PlotRequest& r) {
  if (keys.size() < 2) return r.title;
  std::ostringstream s;
  s << (r.title.empty() ? "" : r.title + ", ") << keys[1] << " = " << value;
  return s.str();
}

std::string multiplot(std::size_t panels) {
  if (panels <= 1) return "";
  const std::size_t columns = panels <= 2 ? panels : 2;
  return "set multiplot layout " + std::to_string((panels + columns - 1) / columns) + "," + std::to_string(columns) + "\n";
}

}  // namespace

void add_plot_options(CLI::App& cmd, PlotRequest& r) {
  cmd.add_option("dir", r.dir, "result directory of `study sweep`")->required();
  cmd.add_option("--figure", r.figure, "bifurcation, density, portrait, d2, e2 or d2map")
      ->required()
      ->check(CLI::IsMember({"bifurcation", "density", "portrait", "d2", "e2", "d2map"}));
  check_output(cmd.add_option("-o,--output", r.output, "FILE.png or FILE.svg")->required(), "-o", nullptr, true);
  cmd.add_option("--signal", r.signal, "the sampled signal plotted (bifurcation, density; portrait's horizontal axis)");
  cmd.add_option("--signal2", r.signal2, "portrait's vertical axis");
  cmd.add_option("--last", r.last, "bifurcation: the last N kept revolutions of each point (the seed: 50)");
  cmd.add_option("--bins", r.bins, "density: equal-width bins over the pooled range of the signal");
  cmd.add_flag("--log", r.log_density, "density: logarithmic colour scale (cells with no sample are left blank)");
  cmd.add_option("--dimension", r.dimension,
                 "d2, d2map: plot the per-dimension estimate D2(m) at this m instead of the saturated D2 "
                 "(it exists where D2 does not saturate; the plot says so)");
  cmd.add_option("--x-scale", r.x_scale, "multiply the horizontal values (1e3: m to mm)");
  cmd.add_option("--y-scale", r.y_scale, "multiply the vertical values");
  cmd.add_option("--z-scale", r.z_scale, "portrait: multiply --signal2's values");
  cmd.add_option("--x-label", r.x_label, "horizontal axis label");
  cmd.add_option("--y-label", r.y_label, "vertical axis label");
  cmd.add_option("--title", r.title, "figure title");
}

void draw(const PlotRequest& r) {
  std::ostringstream g;
  g << "set grid\nunset key\n";
  const std::string samples_path = r.dir + "/samples.tsv", analysis_path = r.dir + "/analysis.tsv";
  if (r.figure == "bifurcation" || r.figure == "density" || r.figure == "portrait") {
    const Table t = read_table(samples_path);
    const auto keys = axis_keys(t);
    const std::size_t y = t.column(r.signal, samples_path), rev = t.column("revolution", samples_path);
    if (keys.empty() && r.figure != "portrait")
      throw StudyError("--figure", r.figure, "needs a sweep with at least one axis");
    if (r.figure == "portrait") {
      const std::size_t z = t.column(r.signal2, samples_path);
      std::map<double, std::vector<std::size_t>> points;
      for (std::size_t i = 0; i < t.rows.size(); ++i) points[t.rows[i][0]].push_back(i);
      g << multiplot(points.size());
      for (const auto& [p, rows] : points) {
        std::ostringstream title;
        title << r.title;
        for (std::size_t k = 0; k < keys.size(); ++k) title << (k || !r.title.empty() ? ", " : "") << keys[k] << " = " << t.rows[rows[0]][1 + k];
        g << "set title " << cli_support::quoted(title.str() + " (" + std::to_string(rows.size()) + " points)") << "\n"
          << "set xlabel " << cli_support::quoted(label(r.x_label, signal_label(r.signal, r.x_scale))) << "\nset ylabel "
          << cli_support::quoted(label(r.y_label, signal_label(r.signal2, r.z_scale))) << "\n$p << EOD\n";
        for (std::size_t i : rows) g << t.rows[i][y] * r.x_scale << ' ' << t.rows[i][z] * r.z_scale << '\n';
        g << "EOD\nplot $p using 1:2 with dots lc rgb 'black'\n";
      }
    } else {
      const auto groups = by_second_axis(t, keys);
      g << multiplot(groups.size());
      double max_rev = 0;
      for (const auto& row : t.rows) max_rev = std::max(max_rev, row[rev]);
      for (const auto& [value, rows] : groups) {
        g << "set title " << cli_support::quoted(panel_title(keys, value, r)) << "\nset xlabel "
          << cli_support::quoted(label(r.x_label, key_label(keys[0], r.x_scale))) << "\n";
        if (r.figure == "bifurcation") {
          g << "set ylabel " << cli_support::quoted(label(r.y_label, signal_label(r.signal, r.y_scale))) << "\n$b << EOD\n";
          for (std::size_t i : rows)
            if (t.rows[i][rev] > max_rev - static_cast<double>(r.last))
              g << t.rows[i][1] * r.x_scale << ' ' << t.rows[i][y] * r.y_scale << '\n';
          g << "EOD\nplot $b using 1:2 with points pt 7 ps 0.2 lc rgb 'black'\n";
        } else {
          // One histogram per first-axis value over the pooled range of this panel.
          std::map<double, std::vector<double>> values;
          double lo = INFINITY, hi = -INFINITY;
          for (std::size_t i : rows) {
            values[t.rows[i][1]].push_back(t.rows[i][y]);
            lo = std::min(lo, t.rows[i][y]);
            hi = std::max(hi, t.rows[i][y]);
          }
          if (!(hi > lo)) hi = lo + 1e-12 * std::max(1.0, std::abs(lo)) + 1e-300;  // a constant signal: one thin bin
          g << "set ylabel " << cli_support::quoted(label(r.y_label, signal_label(r.signal, r.y_scale))) << "\n"
            << "set cblabel " << cli_support::quoted(signal_unit(r.signal).empty() || !r.y_label.empty()
                                                          ? std::string("probability density")
                                                          : "probability density (per " + unit_text(signal_unit(r.signal), r.y_scale) + ")")
            << "\nset palette rgbformulae 33,13,10\n"
            << (r.log_density ? "set logscale cb\n" : "") << "$d << EOD\n";
          for (const auto& [x, v] : values) {
            const chaos::Histogram h = chaos::probability_density(v, r.bins, lo, hi);
            for (std::size_t b = 0; b < r.bins; ++b)
              g << x * r.x_scale << ' ' << 0.5 * (h.edges[b] + h.edges[b + 1]) * r.y_scale << ' '
                << (r.log_density && h.density[b] == 0.0 ? std::string("NaN") : std::to_string(h.density[b] / r.y_scale)) << '\n';
            g << '\n';
          }
          g << "EOD\nplot $d using 1:2:3 with image\n";
        }
      }
    }
  } else {
    const Table t = read_table(analysis_path);
    const auto keys = axis_keys(t);
    if (keys.empty()) throw StudyError("--figure", r.figure, "needs a sweep with at least one axis");
    const bool per_m = r.dimension > 0;
    if (per_m && r.figure == "e2") throw StudyError("--dimension", std::to_string(r.dimension), "applies to d2 and d2map only");
    const std::size_t d2 = t.column(per_m ? "D2_m" + std::to_string(r.dimension) : std::string("d2"), analysis_path),
                      lo = t.column("d2_low", analysis_path),
                      hi = t.column("d2_high", analysis_path), e2 = t.column("e2_deviation", analysis_path);
    const std::size_t shown = r.figure == "e2" ? e2 : d2;
    const bool any = std::any_of(t.rows.begin(), t.rows.end(), [&](const auto& row) { return !std::isnan(row[shown]); });
    if (!any) {
      // Nothing to draw is refused, saying why: an empty frame with exit 0 passed in scripts for a
      // figure. The statuses counted come from analysis.tsv's d2_status (or status) column.
      const std::size_t why = t.column(r.figure == "e2" ? "status" : "d2_status", analysis_path);
      std::map<std::string, std::size_t> counts;
      for (const auto& row : t.text) ++counts[row[why]];
      std::string statuses;
      for (const auto& [status, n] : counts) statuses += (statuses.empty() ? "" : ", ") + std::to_string(n) + " " + status;
      const std::string what = r.figure == "e2" ? "a max|E2 - 1|"
                               : per_m          ? "a D2(m) at m = " + std::to_string(r.dimension)
                                                : "a saturated D2";
      throw StudyError("--figure", r.figure,
                       "nothing to draw: none of the " + std::to_string(t.rows.size()) + " points has " + what +
                           " (analysis.tsv's " + (r.figure == "e2" ? "status" : "d2_status") + " column: " + statuses + ")" +
                           (r.figure != "e2" && !per_m ? "; --dimension M draws the per-dimension estimate D2(m) instead" : ""));
    }
    if (r.figure == "d2map") {
      if (keys.size() < 2) throw StudyError("--figure", "d2map", "needs a two-axis sweep");
      g << "set xlabel " << cli_support::quoted(label(r.x_label, key_label(keys[0], r.x_scale))) << "\nset ylabel "
        << cli_support::quoted(label(r.y_label, key_label(keys[1], r.y_scale))) << "\nset cblabel "
        << cli_support::quoted(per_m ? "D2(m = " + std::to_string(r.dimension) + "), not saturated" : "D2")
        << "\nset palette rgbformulae 33,13,10\nset title "
        << cli_support::quoted(label(r.title, per_m ? "D2(m) (blank: no flat region at this m)" : "correlation dimension D2 (blank: no saturated D2)"))
        << "\n$m << EOD\n";
      const auto groups = by_second_axis(t, keys);
      for (const auto& [value, rows] : groups) {
        for (std::size_t i : rows)
          g << t.rows[i][1] * r.x_scale << ' ' << value * r.y_scale << ' ' << (std::isnan(t.rows[i][d2]) ? std::string("NaN") : std::to_string(t.rows[i][d2])) << '\n';
        g << '\n';
      }
      g << "EOD\nplot $m using 1:2:3 with image\n";
    } else {
      const auto groups = by_second_axis(t, keys);
      std::size_t missing = 0;
      for (const auto& row : t.rows) missing += std::isnan(row[r.figure == "d2" ? d2 : e2]) ? 1 : 0;
      g << "set xlabel " << cli_support::quoted(label(r.x_label, key_label(keys[0], r.x_scale))) << "\nset ylabel "
        << cli_support::quoted(label(r.y_label, r.figure == "e2" ? "max |E2(m) - 1|" : per_m ? "D2(m = " + std::to_string(r.dimension) + "), not a saturated D2" : "D2")) << "\n"
        << "set title " << cli_support::quoted(label(r.title, r.figure == "d2" ? "correlation dimension" : "Cao's E2") +
                                                (missing ? " (" + std::to_string(missing) + " points without a value)" : ""))
        << "\n";
      if (keys.size() > 1) g << "set key below\n";
      std::string plot_line = "plot ";
      std::size_t k = 0;
      for (const auto& [value, rows] : groups) {
        const std::string block = "$g" + std::to_string(k);
        g << block << " << EOD\n";
        for (std::size_t i : rows) {
          if (std::isnan(t.rows[i][r.figure == "d2" ? d2 : e2])) continue;
          g << t.rows[i][1] * r.x_scale << ' ';
          if (r.figure == "d2" && per_m) g << t.rows[i][d2] << ' ' << t.rows[i][d2] << ' ' << t.rows[i][d2] << '\n';
          else if (r.figure == "d2") g << t.rows[i][d2] << ' ' << t.rows[i][lo] << ' ' << t.rows[i][hi] << '\n';
          else g << t.rows[i][e2] << '\n';
        }
        g << "EOD\n";
        std::ostringstream name;
        name << (keys.size() > 1 ? keys[1] + " = " : std::string()) << value;
        const bool empty = std::all_of(rows.begin(), rows.end(), [&](std::size_t i) { return std::isnan(t.rows[i][shown]); });
        if (empty) {
          ++k;
          continue;
        }
        plot_line += std::string(plot_line == "plot " ? "" : ", ") + block + (r.figure == "d2" ? " using 1:2:3:4 with yerrorlines" : " using 1:2 with linespoints") +
                     " title " + cli_support::quoted(name.str());
        ++k;
      }
      g << plot_line << "\n";
    }
  }
  if (g.str().find("set multiplot") != std::string::npos) g << "unset multiplot\n";
  try {
    cli_support::render(g.str(), r.output);
  } catch (const cli_support::PlotError& e) {
    throw StudyError("--output", r.output, e.what());
  }
}

}  // namespace study::cli

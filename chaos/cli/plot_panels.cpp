#include "plot_panels.hpp"

#include <algorithm>

namespace chaos::cli {

void mutual_information_panel(std::ostream& s, const MutualInformationResult& result,
                              const std::optional<std::size_t>& mark, const std::string& mark_title,
                              const std::string& title,
                              const std::optional<double>& dt, double point_size) {
  const double scale = dt.value_or(1.0);
  s << "set key top right\nset xlabel '" << (dt ? "delay tau (time units)" : "delay tau (samples)")
    << "'\nset ylabel 'I(tau) (nats)'\nset title '" << title << "' noenhanced\n";
  if (mark)
    s << "set arrow 1 from first " << static_cast<double>(*mark) * scale << ", graph 0 to first "
      << static_cast<double>(*mark) * scale << ", graph 1 nohead dt 2\n";
  s << "plot '-' using 1:2 with linespoints pt 7 ps " << point_size << " title 'I(tau)'";
  if (mark) s << ", '-' using 1:2 with points pt 6 ps 2 lw 2 title '" << mark_title << "'";
  s << "\n";
  for (std::size_t k = 0; k < result.delay.size(); ++k)
    s << static_cast<double>(result.delay[k]) * scale << " " << result.information[k] << "\n";
  s << "e\n";
  if (mark) {
    for (std::size_t k = 0; k < result.delay.size(); ++k)
      if (result.delay[k] == *mark) s << static_cast<double>(*mark) * scale << " " << result.information[k] << "\n";
    s << "e\n";
  }
}

void cao_panel(std::ostream& s, const CaoResult& result, const std::string& title, double point_size) {
  s << "set key bottom right\nset xlabel 'embedding dimension m'\nset ylabel 'E1(m), E2(m)'\n"
    << "set xtics 1\nset offsets 0.5, 0.5, 0.1, 0.1\nset title \"" << title << "\" noenhanced\n"
    << "set arrow 1 from graph 0, first 1 to graph 1, first 1 nohead dt 2\n";
  if (result.embedding_dimension)
    s << "set arrow 2 from first " << *result.embedding_dimension << ", graph 0 to first " << *result.embedding_dimension
      << ", graph 1 nohead dt 2 lc rgb 'black'\n"
      << "set label 1 'm = " << *result.embedding_dimension << "' at first " << *result.embedding_dimension
      << ", graph 0.05 offset 0.5, 0\n";
  s << "plot '-' using 1:2 with linespoints pt 7 ps " << point_size << " title 'E1', '-' using 1:2 with linespoints pt 5 ps "
    << point_size << " title 'E2'\n";
  for (std::size_t k = 0; k < result.dimension.size(); ++k) s << result.dimension[k] << " " << result.E1[k] << "\n";
  s << "e\n";
  for (std::size_t k = 0; k < result.dimension.size(); ++k) s << result.dimension[k] << " " << result.E2[k] << "\n";
  s << "e\n";
}

void fnn_panel(std::ostream& s, const FnnResult& result, double threshold, const std::string& title,
               double point_size) {
  s << "set key top right\nset xlabel 'embedding dimension m'\nset ylabel 'false nearest neighbours (fraction)'\n"
    << "set xtics 1\nset offsets 0.5, 0.5, 0, 0\nset yrange [0:*]\nset title '" << title << "' noenhanced\n"
    << "set arrow 1 from graph 0, first " << threshold << " to graph 1, first " << threshold << " nohead dt 2\n";
  if (result.embedding_dimension)
    s << "set arrow 2 from first " << *result.embedding_dimension << ", graph 0 to first " << *result.embedding_dimension
      << ", graph 1 nohead dt 2 lc rgb 'black'\n";
  s << "plot '-' using 1:2 with linespoints pt 7 ps " << point_size << " title 'false fraction'\n";
  for (std::size_t k = 0; k < result.dimension.size(); ++k) s << result.dimension[k] << " " << result.false_fraction[k] << "\n";
  s << "e\n";
}

void local_slopes_panel(std::ostream& s, const CorrelationDimensionResult& d2, const std::string& title,
                        double point_size) {
  s << "set key outside right samplen 1\nset logscale x\nunset logscale y\nset xlabel 'eps'\n"
    << "set ylabel 'd ln C / d ln eps'\nset title '" << title << "' noenhanced\n";
  if (d2.scaling_region)
    s << "set object 1 rect from " << d2.scaling_region->low << ", graph 0 to " << d2.scaling_region->high
      << ", graph 1 fc rgb '#dddddd' fs solid 0.5 behind\n";
  if (d2.d2) s << "set arrow 1 from graph 0, first " << *d2.d2 << " to graph 1, first " << *d2.d2 << " nohead dt 2\n";
  const auto has_slopes = [&](std::size_t m) {
    return std::any_of(d2.local_slope[m].begin(), d2.local_slope[m].end(), [](const auto& v) { return v.has_value(); });
  };
  bool any = false;
  for (std::size_t m = 0; m < d2.dimension.size(); ++m) any = any || has_slopes(m);
  if (!any) {
    s << "set label 1 'no local slopes' at graph 0.5, graph 0.5 center\nplot [1:10] [0:1] NaN notitle\n";
    return;
  }
  s << "plot ";
  bool first = true;
  for (std::size_t m = 0; m < d2.dimension.size(); ++m) {
    if (!has_slopes(m)) continue;
    s << (first ? "" : ", ") << "'-' using 1:2 with linespoints pt 7 ps " << point_size << " title 'm=" << d2.dimension[m] << "'";
    first = false;
  }
  s << "\n";
  for (std::size_t m = 0; m < d2.dimension.size(); ++m) {
    if (!has_slopes(m)) continue;
    for (std::size_t k = 0; k < d2.radius.size(); ++k)
      if (d2.local_slope[m][k]) s << d2.radius[k] << " " << *d2.local_slope[m][k] << "\n";
    s << "e\n";
  }
}

}  // namespace chaos::cli

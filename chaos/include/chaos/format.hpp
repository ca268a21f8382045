#pragma once
// Numbers as text: one formatter, its precision named by what the text is for, so that the same
// kind of output has the same digits wherever it is written (commands, Python, the study).

#include <string>

namespace chaos {

enum class Precision {
  round_trip,  // 17 significant digits: reads back as the same double (data files, values a message names)
  shortest,    // the shortest text that reads back as the same double (0.15, not 0.14999999999999999)
  result,      // 10 significant digits: estimates and parameters in a report
  table,       // 12 significant digits: the study's result tables
  message,     // 6 significant digits: a bound or a magnitude that a refusal names
  title,       // 4 significant digits: plot titles and the numbers inside an explanation
  coarse,      // 3 significant digits: interval ends, percentages and times in the zoo report
};

std::string format_number(double value, Precision precision = Precision::round_trip);

}  // namespace chaos

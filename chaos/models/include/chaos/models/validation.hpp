#pragma once
// The validation-first promise in code: every row of references/references.tsv names a reference
// system, its parameters, the quantity an estimator must reproduce, the accepted band and the
// source. `validate` regenerates the data from the row's conditions, runs the estimator and
// compares. The table is compiled into the library, so `chaos validate` and the reference tests
// read the same rows wherever they run.

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace chaos {

struct Reference {
  std::string id;          // unique, e.g. "henon.x.cao.embedding_dimension"
  std::string system;      // a SystemKind name (generate.hpp)
  std::map<std::string, double> parameters;  // system parameters, including sampling
  std::string component;   // "x", "y", ...
  std::string quantity;    // what is measured, e.g. "cao.embedding_dimension"
  std::optional<double> value;  // the source's value; nullopt where the source gives only a bound
  double low = 0.0;        // accepted band [low, high] for our estimate
  double high = 0.0;
  std::map<std::string, std::string> conditions;  // N, tau, m, w, seed, ... of the estimate
  std::string source;      // bibliography key (references/bibliography.md)
  std::string kind;        // analytic | literature | peer-output
  std::string note;
};

// Parses the tab-separated table; `origin` names it in error messages.
std::vector<Reference> parse_reference_table(std::string_view text, const std::string& origin);
// The table compiled from references/references.tsv.
const std::vector<Reference>& reference_table();

struct ValidationResult {
  Reference reference;
  std::optional<double> measured;  // nullopt when the estimator legitimately found no answer
  bool passed = false;
  std::string detail;              // what was measured, or why there is no value
  double seconds = 0.0;
};

ValidationResult validate(const Reference& reference);

}  // namespace chaos

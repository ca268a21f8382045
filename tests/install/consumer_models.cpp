// Links against the installed chaos::models (and through it the estimators) and checks one analytic
// fact: the Henon map in delay coordinates is two-dimensional, so Cao's method must say 2.
#include <chaos/cao.hpp>
#include <chaos/models/systems.hpp>

int main() {
  const auto x = chaos::henon(5000).components[0];
  chaos::CaoOptions options;
  options.max_dimension = 5;
  const auto result = chaos::cao(x, options);
  return result.embedding_dimension == 2u ? 0 : 1;
}

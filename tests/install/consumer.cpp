// Links against the installed estimator library alone (no chaos::models) and checks one analytic
// fact: the Henon map in delay coordinates is two-dimensional, so Cao's method must say 2. The
// series is iterated here, so nothing of the models component is needed.
#include <chaos/cao.hpp>

#include <vector>

int main() {
  std::vector<double> x;
  double u = 0.1, v = 0.0;  // Henon, a = 1.4, b = 0.3, after 1000 transient iterations
  for (int n = 0; n < 6000; ++n) {
    const double next = 1.0 - 1.4 * u * u + v;
    v = 0.3 * u;
    u = next;
    if (n >= 1000) x.push_back(u);
  }
  chaos::CaoOptions options;
  options.max_dimension = 5;
  const auto result = chaos::cao(x, options);
  return result.embedding_dimension == 2u ? 0 : 1;
}

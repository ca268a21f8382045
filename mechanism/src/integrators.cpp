// The out-of-line parts of the integrators: option validation, the throwing helper the inlined
// steppers call, and event location (which calls g through std::function, so inlining would gain
// nothing there).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>

#include "mechanism/dormand_prince.hpp"
#include "mechanism/error.hpp"
#include "mechanism/event_location.hpp"
#include "mechanism/ode.hpp"

namespace mechanism {
namespace {

// Shortest text that reads back as the same double ("0.1", "1e-14", "inf", "nan").
std::string format(double v) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, result.ptr);
}

// The rule is built only on failure: bracket_crossing runs at every event.
template <class Rule>
void require(bool ok, const char* key, double value, const Rule& rule) {
  if (!ok) throw InvalidParameter(key, format(value), rule());
}

}  // namespace

namespace detail {
void throw_invalid(const char* key, double value, const char* rule) {
  throw InvalidParameter(key, format(value), rule);
}
}  // namespace detail

void AdaptiveOptions::validate() const {
  constexpr double inf = std::numeric_limits<double>::infinity();
  require(relative_tolerance > 0.0 && relative_tolerance < inf, "relative_tolerance", relative_tolerance,
          [&] { return std::string("must be finite and > 0"); });
  require(absolute_tolerance > 0.0 && absolute_tolerance < inf, "absolute_tolerance", absolute_tolerance,
          [&] { return std::string("must be finite and > 0"); });
  require(min_step > 0.0 && min_step < inf, "min_step", min_step,
          [&] { return std::string("must be finite and > 0"); });
  require(max_step > 0.0, "max_step", max_step, [&] { return std::string("must be > 0 (infinity allowed)"); });
  require(min_step <= max_step, "min_step", min_step,
          [&] { return std::string("must be <= max_step (= " + format(max_step) + ")"); });
  require(initial_step >= 0.0 && initial_step < inf, "initial_step", initial_step,
          [&] { return std::string("must be finite and >= 0 (0: automatic)"); });
  require(
      initial_step == 0.0 || (initial_step >= min_step && initial_step <= max_step), "initial_step", initial_step, [&] {
        return std::string("must lie in [min_step, max_step] = [" + format(min_step) + ", " + format(max_step) + "]");
      });
  if (max_steps == 0) throw InvalidParameter("max_steps", "0", "must be >= 1");
  require(safety > 0.0 && safety <= 1.0, "safety", safety, [&] { return std::string("must be in (0, 1]"); });
  require(min_factor > 0.0 && min_factor < 1.0, "min_factor", min_factor,
          [&] { return std::string("must be in (0, 1)"); });
  require(max_factor > 1.0 && max_factor < inf, "max_factor", max_factor,
          [&] { return std::string("must be finite and > 1"); });
  require(controller_beta >= 0.0 && controller_beta <= 0.2, "controller_beta", controller_beta, [&] {
    return std::string("must be in [0, 0.2] (0: standard controller; the exponent 1/5 - 0.75 beta must stay > 0)");
  });
}

CrossingBracket bracket_crossing(const std::function<double(double)>& g, double t0, double t1, double g0, double g1,
                                 double time_tolerance) {
  require(std::isfinite(t0), "t0", t0, [&] { return std::string("must be finite"); });
  require(std::isfinite(t1) && t1 > t0, "t1", t1,
          [&] { return std::string("must be finite and > t0 (= " + format(t0) + ")"); });
  require(time_tolerance > 0.0 && std::isfinite(time_tolerance), "time_tolerance", time_tolerance,
          [&] { return std::string("must be finite and > 0"); });
  require(std::isfinite(g0), "g0", g0, [&] { return std::string("must be finite"); });
  require(std::isfinite(g1), "g1", g1, [&] { return std::string("must be finite"); });

  CrossingBracket r;
  if (g0 == 0.0 || g1 == 0.0) {
    r.before = r.after = g0 == 0.0 ? t0 : t1;
    return r;
  }
  require((g0 > 0.0) != (g1 > 0.0), "g1", g1, [&] {
    return std::string("g(t0) = " + format(g0) +
                       " and g(t1) have the same sign: no crossing is bracketed (a grazing or double crossing inside "
                       "[t0, t1] is invisible at the ends)");
  });

  const bool after_positive = g1 > 0.0;
  double a = t0, b = t1;    // a on g0's side, b on g1's side
  double fa = g0, fb = g1;  // secant values, halved by the Illinois rule
  double ga = g0, gb = g1;  // true values at a and b
  int last_replaced = 0;    // +1: b was replaced last time, -1: a was
  double reference_width = b - a;
  int stalled = 0;  // iterations since the bracket was last halved
  const double half_tolerance = 0.5 * time_tolerance;

  while (b - a > time_tolerance) {
    double c;
    if (stalled >= 3) {
      c = 0.5 * (a + b);
    } else {
      c = b - fb * (b - a) / (fb - fa);  // fa, fb have opposite signs: no cancellation in fb - fa
      // At least half a tolerance inside, so the bracket shrinks even when c sits on the root's
      // side next to an end; then the next trial lands on the other side and closes it.
      c = std::clamp(c, a + half_tolerance, b - half_tolerance);
    }
    if (!(c > a && c < b)) c = 0.5 * (a + b);
    if (!(c > a && c < b)) break;  // a and b are adjacent doubles: the tolerance is below resolution
    const double gc = g(c);
    ++r.evaluations;
    require(std::isfinite(gc), "g", gc, [&] {
      return std::string("the event function must be finite inside the bracket (at t = " + format(c) + ")");
    });
    if (gc == 0.0) {
      r.before = r.after = c;
      return r;
    }
    if ((gc > 0.0) == after_positive) {
      b = c;
      fb = gb = gc;
      if (last_replaced == +1) fa *= 0.5;  // a kept twice in a row: Illinois
      last_replaced = +1;
    } else {
      a = c;
      fa = ga = gc;
      if (last_replaced == -1) fb *= 0.5;
      last_replaced = -1;
    }
    if (b - a <= 0.5 * reference_width) {
      reference_width = b - a;
      stalled = 0;
    } else {
      ++stalled;
    }
  }
  r.before = a;
  r.after = b;
  r.g_before = ga;
  r.g_after = gb;
  return r;
}

double locate_crossing(const std::function<double(double)>& g, double t0, double t1, double g0, double g1,
                       double time_tolerance) {
  return bracket_crossing(g, t0, t1, g0, g1, time_tolerance).after;
}

}  // namespace mechanism

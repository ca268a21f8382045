// The maps of the zoo, written once as generic lambdas over the scalar type (see zoo_flows.cpp).

#include <cmath>
#include <numbers>

#include "zoo_model.hpp"

namespace chaos::detail {

namespace {

using P = std::vector<ZooParameter>;

MapSpectrumOptions map_settings(std::size_t transient, std::size_t iterations) {
  MapSpectrumOptions o;
  o.renormalisation_interval = 1;
  o.transient = transient;
  o.iterations = iterations;
  return o;
}

}  // namespace

std::vector<ZooEntry> zoo_map_entries() {
  std::vector<ZooEntry> out;
  const auto add = [&out](ZooEntry e, std::size_t iterations) {
    e.map_spectrum = map_settings(e.map_transient, iterations);
    out.push_back(std::move(e));
  };
  const auto constant = [](ZooEntry& e, double ln_det) {
    e.constant_divergence = true;
    e.divergence = ln_det;
  };
  constexpr double two_pi = 2.0 * std::numbers::pi;

  {
    const auto f = [](const auto* x, auto* n, const double* p) { n[0] = p[0] * x[0] * (1.0 - x[0]); };
    ZooEntry e = zoo_map("logistic", {"x"}, P{{"r", LogisticParameters{}.r, "growth rate"}}, {}, 1000,
                         "x' = r x (1 - x)", "R. M. May, Nature 261, 459 (1976)",
                         with_delegate(make_model<1>(f), ZooModel::Delegate::logistic));
    add(std::move(e), 1'000'000);
  }
  {
    const HenonParameters d;
    const auto f = [](const auto* x, auto* n, const double* p) {
      n[0] = 1.0 - p[0] * x[0] * x[0] + x[1];
      n[1] = p[1] * x[0];
    };
    ZooEntry e = zoo_map("henon", {"x", "y"}, P{{"a", d.a, ""}, {"b", d.b, ""}}, {0.0, 0.0}, 1000,
                         "x' = 1 - a x^2 + y, y' = b x", "M. Henon, Commun. Math. Phys. 50, 69 (1976)",
                         with_delegate(make_model<2>(f), ZooModel::Delegate::henon));
    constant(e, std::log(d.b));
    add(std::move(e), 1'000'000);
  }
  {
    const IkedaParameters d;
    const auto f = [](const auto* z, auto* n, const double* p) {
      using std::cos;
      using std::sin;
      const auto t = p[1] - p[2] / (1.0 + z[0] * z[0] + z[1] * z[1]);
      const auto c = cos(t);
      const auto s = sin(t);
      n[0] = 1.0 + p[0] * (z[0] * c - z[1] * s);
      n[1] = p[0] * (z[0] * s + z[1] * c);
    };
    ZooEntry e = zoo_map("ikeda", {"x", "y"},
                         P{{"mu", d.mu, "dissipation (Jacobian determinant mu^2)"}, {"a", d.a, ""}, {"b", d.b, ""}},
                         {0.0, 0.0}, 1000, "z' = 1 + mu z exp(i (a - b / (1 + |z|^2))), z = x + i y",
                         "K. Ikeda, Opt. Commun. 30, 257 (1979); form of J. C. Sprott, Chaos and Time-Series Analysis "
                         "(2003)",
                         with_delegate(make_model<2>(f), ZooModel::Delegate::ikeda));
    constant(e, 2.0 * std::log(d.mu));
    add(std::move(e), 1'000'000);
  }
  {
    const auto f = [](const auto* x, auto* n, const double* p) {
      using std::abs;
      n[0] = 1.0 - p[0] * abs(x[0]) + x[1];
      n[1] = p[1] * x[0];
    };
    ZooEntry e = zoo_map("lozi", {"x", "y"}, P{{"a", 1.7, ""}, {"b", 0.5, ""}}, {0.0, 0.0}, 1000,
                         "x' = 1 - a |x| + y, y' = b x", "R. Lozi, J. Phys. Colloq. 39, C5-9 (1978)", make_model<2>(f));
    constant(e, std::log(0.5));
    add(std::move(e), 1'000'000);
  }
  {
    const auto f = [](const auto* x, auto* n, const double* p) {
      n[0] = x[0] * x[0] - x[1] * x[1] + p[0] * x[0] + p[1] * x[1];
      n[1] = 2.0 * x[0] * x[1] + p[2] * x[0] + p[3] * x[1];
    };
    add(zoo_map("tinkerbell", {"x", "y"}, P{{"a", 0.9, ""}, {"b", -0.6013, ""}, {"c", 2.0, ""}, {"d", 0.5, ""}},
                {-0.72, -0.64}, 1000, "x' = x^2 - y^2 + a x + b y, y' = 2 x y + c x + d y",
                "H. E. Nusse & J. A. Yorke, Dynamics: Numerical Explorations (Springer, 1994); parameters of J. C. "
                "Sprott, Chaos and Time-Series Analysis (2003)",
                make_model<2>(f)),
        1'000'000);
  }
  {
    const auto f = [](const auto* x, auto* n, const double* p) {
      n[0] = x[1] + 0.0 * x[0];
      n[1] = -p[1] * x[0] + p[0] * x[1] - x[1] * x[1] * x[1];
    };
    ZooEntry e = zoo_map("holmes_cubic", {"x", "y"}, P{{"a", 2.75, ""}, {"b", 0.2, "Jacobian determinant"}},
                         {0.51, 0.1}, 1000, "x' = y, y' = -b x + a y - y^3",
                         "P. J. Holmes, Phil. Trans. R. Soc. Lond. A 292, 419 (1979)", make_model<2>(f));
    constant(e, std::log(0.2));
    add(std::move(e), 1'000'000);
  }
  {
    const auto f = [](const auto* x, auto* n, const double* p) {
      n[0] = p[0] * x[0] * (1.0 - x[1]);
      n[1] = x[0] + 0.0 * x[1];
    };
    add(zoo_map("delayed_logistic", {"x", "y"}, P{{"A", 2.27, "growth rate"}}, {0.001, 0.001}, 1000,
                "x' = A x (1 - y), y' = x",
                "D. G. Aronson, M. A. Chory, G. R. Hall & R. P. McGehee, Commun. Math. Phys. 83, 303 (1982)",
                make_model<2>(f)),
        1'000'000);
  }
  {
    const auto f = [two_pi](const auto* x, auto* n, const double* p) {
      using std::sin;
      const auto y = wrap(p[0] * x[1] + p[1] * sin(x[0]), two_pi);
      n[1] = y;
      n[0] = wrap(x[0] + y, two_pi);
    };
    ZooEntry e = zoo_map("dissipative_standard", {"x", "y"}, P{{"b", 0.1, "Jacobian determinant"}, {"k", 8.8, "kick"}},
                         {0.1, 0.1}, 1000, "y' = b y + k sin x (mod 2 pi), x' = x + y' (mod 2 pi)",
                         "G. Schmidt & B. W. Wang, Phys. Rev. A 32, 2994 (1985)", make_model<2>(f));
    constant(e, std::log(0.1));
    add(std::move(e), 1'000'000);
  }
  {
    const auto f = [](const auto* x, auto* n, const double* p) {
      n[0] = p[0] * x[0] - x[1] * x[1];
      n[1] = p[1] * x[1] + x[0] * x[1];
    };
    add(zoo_map("burgers", {"x", "y"}, P{{"a", 0.75, ""}, {"b", 1.75, ""}}, {-0.1, 0.1}, 1000,
                "x' = a x - y^2, y' = b y + x y", "R. R. Whitehead & N. MacDonald, Physica D 13, 401 (1984)",
                make_model<2>(f)),
        1'000'000);
  }
  {
    const auto f = [](const auto* x, auto* n, const double* p) {
      using std::sin;
      n[0] = p[0] * sin(std::numbers::pi * x[0]);
    };
    add(zoo_map("sine_map", {"x"}, P{{"mu", 1.0, ""}}, {0.3}, 1000, "x' = mu sin(pi x)",
                "N. Metropolis, M. L. Stein & P. R. Stein, J. Comb. Theory A 15, 25 (1973)", make_model<1>(f)),
        1'000'000);
  }
  {
    const auto f = [](const auto* x, auto* n, const double* p) {
      using std::exp;
      n[0] = x[0] * exp(p[0] * (1.0 - x[0]));
    };
    add(zoo_map("ricker", {"x"}, P{{"r", 3.3, "growth rate"}}, {0.51}, 1000, "x' = x exp(r (1 - x))",
                "W. E. Ricker, J. Fish. Res. Board Can. 11, 559 (1954); parameter of dysts", make_model<1>(f)),
        1'000'000);
  }
  {
    const auto f = [](const auto* x, auto* n, const double* p) {
      using std::exp;
      n[0] = exp(-p[0] * x[0] * x[0]) + p[1];
    };
    add(zoo_map("gauss_map", {"x"}, P{{"alpha", 6.2, ""}, {"beta", -0.5, ""}}, {0.5}, 1000,
                "x' = exp(-alpha x^2) + beta",
                "R. C. Hilborn, Chaos and Nonlinear Dynamics (Oxford, 2000), sec. 5.11", make_model<1>(f)),
        1'000'000);
  }
  {
    const auto f = [](const auto* x, auto* n, const double* p) {
      n[0] = p[0] - x[1] * x[1] - p[1] * x[2];
      n[1] = x[0] + 0.0 * x[1];
      n[2] = x[1] + 0.0 * x[2];
    };
    ZooEntry e = zoo_map("generalized_henon", {"x", "y", "z"}, P{{"a", 1.76, ""}, {"b", 0.1, "|Jacobian determinant|"}},
                         {0.1, 0.1, 0.1}, 1000, "x' = a - y^2 - b z, y' = x, z' = y",
                         "G. Baier & M. Klein, Phys. Lett. A 151, 281 (1990)", make_model<3>(f));
    e.hyperchaotic = true;
    constant(e, std::log(0.1));
    add(std::move(e), 1'000'000);
  }
  {
    const auto f = [](const auto* x, auto* n, const double*) {
      using std::abs;
      n[0] = 1.0 - x[1] + abs(x[0]);
      n[1] = x[0] + 0.0 * x[1];
    };
    ZooEntry e = zoo_map("gingerbreadman", {"x", "y"}, P{}, {-0.1, 0.0}, 1000, "x' = 1 - y + |x|, y' = x",
                         "R. L. Devaney, Physica D 10, 387 (1984)", make_model<2>(f));
    e.conservative = true;
    constant(e, 0.0);
    add(std::move(e), 1'000'000);
  }
  return out;
}

}  // namespace chaos::detail

// The flows of the zoo. Each system is written once, as a generic lambda over the scalar type;
// parameters are p[i] in the order of the entry's parameter list. Defaults are those of the
// original paper, or of the source named, cross-checked with dysts where it has the system
// (references/zoo.tsv records where dysts uses other values).

#include <cmath>
#include <numbers>

#include "zoo_model.hpp"

namespace chaos::detail {

namespace {

using P = std::vector<ZooParameter>;

FlowSpectrumOptions spectrum_settings(double step, double interval, double transient, double time) {
  FlowSpectrumOptions o;
  o.step = step;
  o.renormalisation_interval = interval;
  o.transient = transient;
  o.time = time;
  return o;
}

}  // namespace

std::vector<ZooEntry> zoo_flow_entries() {
  std::vector<ZooEntry> out;
  const auto add = [&out](ZooEntry e, FlowSpectrumOptions s) {
    e.flow_spectrum = s;
    out.push_back(std::move(e));
  };
  const auto constant = [](ZooEntry& e, double trace) {
    e.constant_divergence = true;
    e.divergence = trace;
  };

  {  // Delegates to chaos::lorenz and chaos::lorenz_spectrum; the equations serve the tests.
    const LorenzParameters d;
    const auto f = [](const auto* x, auto* dx, const double* p) {
      dx[0] = p[0] * (x[1] - x[0]);
      dx[1] = x[0] * (p[1] - x[2]) - x[1];
      dx[2] = x[0] * x[1] - p[2] * x[2];
    };
    ZooEntry e = zoo_flow("lorenz", {"x", "y", "z"},
                          P{{"sigma", d.sigma, "Prandtl number"}, {"rho", d.rho, "Rayleigh number"},
                            {"beta", d.beta, "geometric factor"}},
                          {1.0, 1.0, 1.0}, 0.01, 0.001, 100.0,
                          "x' = sigma (y - x), y' = x (rho - z) - y, z' = x y - beta z",
                          "E. N. Lorenz, J. Atmos. Sci. 20, 130 (1963)", with_delegate(make_model<3>(f), ZooModel::Delegate::lorenz));
    constant(e, -(d.sigma + 1.0 + d.beta));
    add(std::move(e), FlowSpectrumOptions{});
  }
  {
    const RosslerParameters d;
    const auto f = [](const auto* x, auto* dx, const double* p) {
      dx[0] = -x[1] - x[2];
      dx[1] = x[0] + p[0] * x[1];
      dx[2] = p[1] + x[2] * (x[0] - p[2]);
    };
    ZooEntry e = zoo_flow("rossler", {"x", "y", "z"}, P{{"a", d.a, ""}, {"b", d.b, ""}, {"c", d.c, ""}}, {1.0, 1.0, 1.0},
                          0.1, 0.01, 500.0, "x' = -y - z, y' = x + a y, z' = b + z (x - c)",
                          "O. E. Rossler, Phys. Lett. A 57, 397 (1976)", with_delegate(make_model<3>(f), ZooModel::Delegate::rossler));
    e.rotating = true;
    add(std::move(e), spectrum_settings(0.01, 0.1, 500.0, 40'000.0));
  }
  {
    const MackeyGlassParameters d;
    ZooEntry e = zoo_flow("mackey_glass", {"x"},
                          P{{"beta", d.beta, ""}, {"gamma", d.gamma, ""}, {"n", d.n, "exponent"},
                            {"tau", d.tau, "delay (time units)"}},
                          {}, 1.0, d.tau / 170.0, 1000.0, "x' = beta x(t - tau) / (1 + x(t - tau)^n) - gamma x",
                          "M. C. Mackey & L. Glass, Science 197, 287 (1977)",
                          delegate_model(ZooModel::Delegate::mackey_glass));
    e.delay = true;
    add(std::move(e), spectrum_settings(d.tau / 170.0, 5.0, 2000.0, 20'000.0));
  }
  {
    ZooEntry e = zoo_flow("mackey_glass_30", {"x"},
                          P{{"beta", 0.2, ""}, {"gamma", 0.1, ""}, {"n", 10.0, "exponent"},
                            {"tau", 30.0, "delay (time units)"}},
                          {}, 1.0, 0.1, 1000.0, "x' = beta x(t - tau) / (1 + x(t - tau)^n) - gamma x",
                          "M. C. Mackey & L. Glass, Science 197, 287 (1977); tau = 30 as in J. D. Farmer, Physica D 4, "
                          "366 (1982)",
                          delegate_model(ZooModel::Delegate::mackey_glass));
    e.delay = true;
    e.hyperchaotic = true;
    add(std::move(e), spectrum_settings(0.1, 5.0, 2000.0, 20'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = -x[1] * x[1] - x[2] * x[2] - p[0] * x[0] + p[0] * p[2];
      d[1] = x[0] * x[1] - p[1] * x[0] * x[2] - x[1] + p[3];
      d[2] = p[1] * x[0] * x[1] + x[0] * x[2] - x[2];
    };
    add(zoo_flow("lorenz84", {"x", "y", "z"},
                 P{{"a", 0.25, "damping of the westerly wind"}, {"b", 4.0, "advection by the westerly"},
                   {"F", 8.0, "symmetric thermal forcing"}, {"G", 1.0, "asymmetric thermal forcing"}},
                 {1.0, 0.0, 0.0}, 0.05, 0.005, 200.0,
                 "x' = -y^2 - z^2 - a x + a F, y' = x y - b x z - y + G, z' = b x y + x z - z",
                 "E. N. Lorenz, Tellus A 36, 98 (1984)", make_model<3>(f)),
        spectrum_settings(0.005, 0.1, 200.0, 20'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = p[0] * (x[1] - x[0]);
      d[1] = (p[2] - p[0]) * x[0] - x[0] * x[2] + p[2] * x[1];
      d[2] = x[0] * x[1] - p[1] * x[2];
    };
    ZooEntry e = zoo_flow("chen", {"x", "y", "z"}, P{{"a", 35.0, ""}, {"b", 3.0, ""}, {"c", 28.0, ""}}, {-10.0, 0.0, 37.0},
                          0.01, 0.001, 100.0, "x' = a (y - x), y' = (c - a) x - x z + c y, z' = x y - b z",
                          "G. Chen & T. Ueta, Int. J. Bifurcation Chaos 9, 1465 (1999)", make_model<3>(f));
    constant(e, -35.0 + 28.0 - 3.0);
    add(std::move(e), spectrum_settings(0.002, 0.1, 100.0, 10'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = p[0] * (x[1] - x[0]);
      d[1] = -x[0] * x[2] + p[2] * x[1];
      d[2] = x[0] * x[1] - p[1] * x[2];
    };
    ZooEntry e = zoo_flow("lu_chen", {"x", "y", "z"}, P{{"a", 36.0, ""}, {"b", 3.0, ""}, {"c", 20.0, ""}}, {1.0, 1.0, 1.0},
                          0.01, 0.001, 100.0, "x' = a (y - x), y' = -x z + c y, z' = x y - b z",
                          "J. Lu & G. Chen, Int. J. Bifurcation Chaos 12, 659 (2002)", make_model<3>(f));
    constant(e, -36.0 + 20.0 - 3.0);
    add(std::move(e), spectrum_settings(0.002, 0.1, 100.0, 10'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      using std::abs;
      const auto h = p[3] * x[0] + 0.5 * (p[2] - p[3]) * (abs(x[0] + 1.0) - abs(x[0] - 1.0));
      d[0] = p[0] * (x[1] - x[0] - h);
      d[1] = x[0] - x[1] + x[2];
      d[2] = -p[1] * x[1];
    };
    add(zoo_flow("chua", {"x", "y", "z"},
                 P{{"alpha", 9.0, ""}, {"beta", 100.0 / 7.0, ""}, {"m0", -8.0 / 7.0, "inner slope of h"},
                   {"m1", -5.0 / 7.0, "outer slope of h"}},
                 {0.0, 0.0, 0.6}, 0.05, 0.005, 200.0,
                 "x' = alpha (y - x - h(x)), y' = x - y + z, z' = -beta y, h(x) = m1 x + (m0 - m1)(|x + 1| - |x - 1|)/2",
                 "T. Matsumoto, IEEE Trans. Circuits Syst. 31, 1055 (1984); L. O. Chua, M. Komuro & T. Matsumoto, IEEE "
                 "Trans. Circuits Syst. 33, 1072 (1986); parameters of J. C. Sprott, Chaos and Time-Series Analysis "
                 "(2003)",
                 make_model<3>(f)),
        spectrum_settings(0.005, 0.1, 200.0, 20'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      using std::sin;
      d[0] = sin(x[1]) - p[0] * x[0];
      d[1] = sin(x[2]) - p[0] * x[1];
      d[2] = sin(x[0]) - p[0] * x[2];
    };
    ZooEntry e = zoo_flow("thomas", {"x", "y", "z"}, P{{"b", 0.18, "damping"}}, {0.1, 0.0, 0.0}, 0.2, 0.02, 500.0,
                          "x' = sin y - b x, y' = sin z - b y, z' = sin x - b z",
                          "R. Thomas, Int. J. Bifurcation Chaos 9, 1889 (1999)", make_model<3>(f));
    constant(e, -3.0 * 0.18);
    add(std::move(e), spectrum_settings(0.02, 0.2, 500.0, 100'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = -p[0] * x[0] - p[1] * x[1] - p[1] * x[2] - x[1] * x[1];
      d[1] = -p[0] * x[1] - p[1] * x[2] - p[1] * x[0] - x[2] * x[2];
      d[2] = -p[0] * x[2] - p[1] * x[0] - p[1] * x[1] - x[0] * x[0];
    };
    ZooEntry e = zoo_flow("halvorsen", {"x", "y", "z"}, P{{"a", 1.4, "damping"}, {"b", 4.0, "coupling"}},
                          {-5.0, 0.0, 0.0}, 0.02, 0.002, 100.0,
                          "x' = -a x - b y - b z - y^2 and its cyclic permutations",
                          "A. Halvorsen, in J. C. Sprott, Elegant Chaos (World Scientific, 2010)", make_model<3>(f));
    constant(e, -3.0 * 1.4);
    add(std::move(e), spectrum_settings(0.002, 0.1, 100.0, 10'000.0));
  }
  // Sprott, Phys. Rev. E 50, R647 (1994): the simplest quadratic flows, cases B, C, E, F, G.
  const char* sprott1994 = "J. C. Sprott, Phys. Rev. E 50, R647 (1994)";
  {
    const auto f = [](const auto* x, auto* d, const double*) {
      d[0] = x[1] * x[2];
      d[1] = x[0] - x[1];
      d[2] = 1.0 - x[0] * x[1];
    };
    ZooEntry e = zoo_flow("sprott_b", {"x", "y", "z"}, P{}, {0.1, 0.0, 0.0}, 0.05, 0.005, 200.0,
                          "x' = y z, y' = x - y, z' = 1 - x y", sprott1994, make_model<3>(f));
    constant(e, -1.0);
    add(std::move(e), spectrum_settings(0.005, 0.1, 200.0, 20'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double*) {
      d[0] = x[1] * x[2];
      d[1] = x[0] - x[1];
      d[2] = 1.0 - x[0] * x[0];
    };
    ZooEntry e = zoo_flow("sprott_c", {"x", "y", "z"}, P{}, {0.1, 0.0, 0.0}, 0.05, 0.005, 200.0,
                          "x' = y z, y' = x - y, z' = 1 - x^2", sprott1994, make_model<3>(f));
    constant(e, -1.0);
    add(std::move(e), spectrum_settings(0.005, 0.1, 200.0, 20'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double*) {
      d[0] = x[1] * x[2];
      d[1] = x[0] * x[0] - x[1];
      d[2] = 1.0 - 4.0 * x[0];
    };
    ZooEntry e = zoo_flow("sprott_e", {"x", "y", "z"}, P{}, {0.1, 0.0, 0.0}, 0.05, 0.005, 200.0,
                          "x' = y z, y' = x^2 - y, z' = 1 - 4 x", sprott1994, make_model<3>(f));
    constant(e, -1.0);
    add(std::move(e), spectrum_settings(0.005, 0.1, 200.0, 40'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = x[1] + x[2];
      d[1] = -x[0] + p[0] * x[1];
      d[2] = x[0] * x[0] - x[2];
    };
    ZooEntry e = zoo_flow("sprott_f", {"x", "y", "z"}, P{{"a", 0.5, ""}}, {0.1, 0.0, 0.0}, 0.05, 0.005, 200.0,
                          "x' = y + z, y' = -x + a y, z' = x^2 - z", sprott1994, make_model<3>(f));
    constant(e, 0.5 - 1.0);
    add(std::move(e), spectrum_settings(0.005, 0.1, 200.0, 20'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = p[0] * x[0] + x[2];
      d[1] = x[0] * x[2] - x[1];
      d[2] = -x[0] + x[1];
    };
    ZooEntry e = zoo_flow("sprott_g", {"x", "y", "z"}, P{{"a", 0.4, ""}}, {0.1, 0.0, 0.0}, 0.05, 0.005, 200.0,
                          "x' = a x + z, y' = x z - y, z' = -x + y", sprott1994, make_model<3>(f));
    constant(e, 0.4 - 1.0);
    add(std::move(e), spectrum_settings(0.005, 0.1, 200.0, 40'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = x[1];
      d[1] = x[2];
      d[2] = -x[0] + x[1] * x[1] - p[0] * x[2];
    };
    ZooEntry e = zoo_flow("sprott_jerk", {"x", "y", "z"}, P{{"A", 2.017, "damping of the jerk"}}, {-0.54, 0.59, 0.45},
                          0.05, 0.005, 200.0, "x' = y, y' = z, z' = -x + y^2 - A z",
                          "J. C. Sprott, Phys. Lett. A 228, 271 (1997)", make_model<3>(f));
    constant(e, -2.017);
    add(std::move(e), spectrum_settings(0.005, 0.1, 200.0, 40'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      using std::abs;
      d[0] = x[1];
      d[1] = x[2];
      d[2] = -p[0] * x[2] - x[1] - abs(x[0]) + 1.0;
    };
    ZooEntry e = zoo_flow("linz_sprott", {"x", "y", "z"}, P{{"A", 0.6, "damping of the jerk"}}, {0.0, 0.0, 0.0}, 0.1,
                          0.01, 200.0, "x' = y, y' = z, z' = -A z - y - |x| + 1",
                          "S. J. Linz & J. C. Sprott, Phys. Lett. A 259, 240 (1999)", make_model<3>(f));
    constant(e, -0.6);
    add(std::move(e), spectrum_settings(0.01, 0.1, 200.0, 40'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = x[1] * (x[2] - 1.0 + x[0] * x[0]) + p[0] * x[0];
      d[1] = x[0] * (3.0 * x[2] + 1.0 - x[0] * x[0]) + p[0] * x[1];
      d[2] = -2.0 * x[2] * (p[1] + x[0] * x[1]);
    };
    add(zoo_flow("rabinovich_fabrikant", {"x", "y", "z"}, P{{"gamma", 0.87, ""}, {"alpha", 1.1, ""}},
                 {-1.0, 0.0, 0.5}, 0.02, 0.002, 200.0,
                 "x' = y (z - 1 + x^2) + gamma x, y' = x (3 z + 1 - x^2) + gamma y, z' = -2 z (alpha + x y)",
                 "M. I. Rabinovich & A. L. Fabrikant, Sov. Phys. JETP 50, 311 (1979)", make_model<3>(f)),
        spectrum_settings(0.002, 0.1, 200.0, 20'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = -p[0] * x[0] + x[1] * x[2];
      d[1] = -p[0] * x[1] + x[0] * (x[2] - p[1]);
      d[2] = 1.0 - x[0] * x[1];
    };
    ZooEntry e = zoo_flow("rikitake", {"x", "y", "z"},
                          P{{"mu", 1.0, "resistive dissipation"}, {"a", 1.0, "difference of the disk speeds"}},
                          {-0.78, -0.63, 2.67}, 0.05, 0.005, 200.0,
                          "x' = -mu x + y z, y' = -mu y + x (z - a), z' = 1 - x y",
                          "T. Rikitake, Proc. Cambridge Philos. Soc. 54, 89 (1958); parameters of dysts", make_model<3>(f));
    constant(e, -2.0);
    add(std::move(e), spectrum_settings(0.005, 0.1, 200.0, 20'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = x[1];
      d[1] = x[2];
      d[2] = -x[2] - (p[0] - p[1] + p[1] * x[0] * x[0]) * x[1] - p[0] * x[0];
    };
    ZooEntry e = zoo_flow("moore_spiegel", {"x", "y", "z"}, P{{"T", 6.0, "thermal relaxation"}, {"R", 20.0, "buoyancy"}},
                          {0.1, 0.0, 0.0}, 0.02, 0.002, 200.0, "x' = y, y' = z, z' = -z - (T - R + R x^2) y - T x",
                          "D. W. Moore & E. A. Spiegel, Astrophys. J. 143, 871 (1966)", make_model<3>(f));
    constant(e, -1.0);
    add(std::move(e), spectrum_settings(0.002, 0.1, 200.0, 20'000.0));
  }
  // Arneodo, Coullet & Tresser, Commun. Math. Phys. 79, 573 (1981): x''' = -a x - b x' - c x'' + d x^3.
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = x[1];
      d[1] = x[2];
      d[2] = -p[0] * x[0] - p[1] * x[1] - p[2] * x[2] + p[3] * x[0] * x[0] * x[0];
    };
    ZooEntry e = zoo_flow("arneodo", {"x", "y", "z"}, P{{"a", -5.5, ""}, {"b", 4.5, ""}, {"c", 1.0, ""}, {"d", -1.0, ""}},
                          {1.0, 0.0, 0.0}, 0.05, 0.005, 200.0, "x' = y, y' = z, z' = -a x - b y - c z + d x^3",
                          "A. Arneodo, P. Coullet & C. Tresser, Commun. Math. Phys. 79, 573 (1981)", make_model<3>(f));
    constant(e, -1.0);
    e.rotating = true;
    add(std::move(e), spectrum_settings(0.005, 0.1, 200.0, 20'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = x[1];
      d[1] = x[2];
      d[2] = -p[2] * x[0] - p[1] * x[1] - p[0] * x[2] + x[0] * x[0];
    };
    ZooEntry e = zoo_flow("genesio_tesi", {"x", "y", "z"}, P{{"a", 0.44, ""}, {"b", 1.1, ""}, {"c", 1.0, ""}},
                          {0.1, 0.1, 0.1}, 0.05, 0.005, 200.0, "x' = y, y' = z, z' = -c x - b y - a z + x^2",
                          "R. Genesio & A. Tesi, Automatica 28, 531 (1992)", make_model<3>(f));
    constant(e, -0.44);
    e.rotating = true;
    add(std::move(e), spectrum_settings(0.005, 0.1, 200.0, 40'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = x[1];
      d[1] = x[0] - p[0] * x[1] - x[0] * x[2];
      d[2] = -p[1] * x[2] + x[0] * x[0];
    };
    ZooEntry e = zoo_flow("shimizu_morioka", {"x", "y", "z"}, P{{"a", 0.75, ""}, {"b", 0.45, ""}}, {0.1, 0.0, 0.0}, 0.05,
                          0.005, 500.0, "x' = y, y' = x - a y - x z, z' = -b z + x^2",
                          "T. Shimizu & N. Morioka, Phys. Lett. A 76, 201 (1980)", make_model<3>(f));
    constant(e, -0.75 - 0.45);
    add(std::move(e), spectrum_settings(0.005, 0.1, 500.0, 40'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = (x[2] - p[1]) * x[0] - p[3] * x[1];
      d[1] = p[3] * x[0] + (x[2] - p[1]) * x[1];
      d[2] = p[2] + p[0] * x[2] - x[2] * x[2] * x[2] / 3.0 - (x[0] * x[0] + x[1] * x[1]) * (1.0 + p[4] * x[2]) +
             p[5] * x[2] * x[0] * x[0] * x[0];
    };
    ZooEntry e = zoo_flow("aizawa", {"x", "y", "z"},
                          P{{"a", 0.95, ""}, {"b", 0.7, ""}, {"c", 0.6, ""}, {"d", 3.5, ""}, {"e", 0.25, ""}, {"f", 0.1, ""}},
                          {0.1, 0.0, 0.0}, 0.02, 0.002, 200.0,
                          "x' = (z - b) x - d y, y' = d x + (z - b) y, "
                          "z' = c + a z - z^3/3 - (x^2 + y^2)(1 + e z) + f z x^3",
                          "Y. Aizawa & T. Uezu, Prog. Theor. Phys. 67, 982 (1982); form and parameters of dysts",
                          make_model<3>(f));
    add(std::move(e), spectrum_settings(0.002, 0.1, 200.0, 20'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = x[1] - p[0] * x[0] + p[1] * x[1] * x[2];
      d[1] = p[2] * x[1] - x[0] * x[2] + x[2];
      d[2] = p[3] * x[0] * x[1] - p[4] * x[2];
    };
    ZooEntry e = zoo_flow("dadras", {"x", "y", "z"},
                          P{{"p", 3.0, ""}, {"o", 2.7, ""}, {"r", 1.7, ""}, {"c", 2.0, ""}, {"e", 9.0, ""}},
                          {1.0, 1.0, 0.0}, 0.02, 0.002, 100.0,
                          "x' = y - p x + o y z, y' = r y - x z + z, z' = c x y - e z",
                          "S. Dadras & H. R. Momeni, Phys. Lett. A 373, 3637 (2009)", make_model<3>(f));
    constant(e, -3.0 + 1.7 - 9.0);
    add(std::move(e), spectrum_settings(0.002, 0.1, 100.0, 10'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = x[2] + (x[1] - p[0]) * x[0];
      d[1] = 1.0 - p[1] * x[1] - x[0] * x[0];
      d[2] = -x[0] - p[2] * x[2];
    };
    add(zoo_flow("finance", {"x", "y", "z"},
                 P{{"a", 0.001, "saving"}, {"b", 0.2, "cost per investment"}, {"c", 1.1, "demand elasticity"}},
                 {-0.5, -4.0, 0.0}, 0.05, 0.005, 500.0, "x' = z + (y - a) x, y' = 1 - b y - x^2, z' = -x - c z",
                 "J.-H. Ma & Y.-S. Chen, Appl. Math. Mech. 22, 1240 (2001); parameters of G. Cai & J. Huang, Int. J. "
                 "Nonlinear Sci. 3, 213 (2007) as in dysts",
                 make_model<3>(f)),
        spectrum_settings(0.005, 0.1, 500.0, 40'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = -p[0] * x[0] + p[1] * x[1] - x[1] * x[2];
      d[1] = x[0];
      d[2] = -x[2] + x[1] * x[1];
    };
    ZooEntry e = zoo_flow("rucklidge", {"x", "y", "z"}, P{{"kappa", 2.0, ""}, {"lambda", 6.7, ""}}, {1.0, 0.0, 4.5}, 0.05,
                          0.005, 200.0, "x' = -kappa x + lambda y - y z, y' = x, z' = -z + y^2",
                          "A. M. Rucklidge, J. Fluid Mech. 237, 209 (1992)", make_model<3>(f));
    constant(e, -3.0);
    add(std::move(e), spectrum_settings(0.005, 0.1, 200.0, 20'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      using std::exp;
      d[0] = x[1];
      d[1] = x[2];
      d[2] = -p[0] * x[2] - x[1] + p[1] - exp(x[0]);
    };
    ZooEntry e = zoo_flow("windmi", {"x", "y", "z"}, P{{"a", 0.7, ""}, {"b", 2.5, ""}}, {0.0, 0.8, 0.0}, 0.1, 0.01, 200.0,
                          "x' = y, y' = z, z' = -a z - y + b - exp(x)",
                          "W. Horton, R. S. Weigel & J. C. Sprott, Phys. Plasmas 8, 2946 (2001); jerk form of J. C. "
                          "Sprott, Chaos and Time-Series Analysis (2003)",
                          make_model<3>(f));
    constant(e, -0.7);
    add(std::move(e), spectrum_settings(0.01, 0.1, 200.0, 40'000.0));
  }
  // Forced oscillators: the phase phi = omega t is the last variable.
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      using std::cos;
      d[0] = x[1];
      d[1] = -p[0] * x[1] - p[1] * x[0] - p[2] * x[0] * x[0] * x[0] + p[3] * cos(x[2]);
      d[2] = 0.0 * x[2] + p[4];
    };
    ZooEntry e = zoo_flow("duffing", {"x", "v", "phi"},
                          P{{"delta", 0.1, "damping"}, {"beta", -1.0, "linear stiffness"},
                            {"alpha", 1.0, "cubic stiffness"}, {"gamma", 0.35, "forcing amplitude"},
                            {"omega", 1.4, "forcing frequency"}},
                          {-1.16, -0.51, 0.0}, 0.05, 0.005, 200.0,
                          "x' = v, v' = -delta v - beta x - alpha x^3 + gamma cos phi, phi' = omega",
                          "G. Duffing (1918); parameters of dysts", make_model<3>(f));
    e.forced = true;
    constant(e, -0.1);
    add(std::move(e), spectrum_settings(0.005, 0.1, 200.0, 40'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      using std::sin;
      d[0] = x[1];
      d[1] = -x[0] * x[0] * x[0] - p[0] * x[1] + p[1] * sin(x[2]);
      d[2] = 0.0 * x[2] + p[2];
    };
    ZooEntry e = zoo_flow("ueda", {"x", "v", "phi"},
                          P{{"k", 0.05, "damping"}, {"B", 7.5, "forcing amplitude"}, {"omega", 1.0, "forcing frequency"}},
                          {2.5, 0.0, 0.0}, 0.05, 0.005, 200.0, "x' = v, v' = -x^3 - k v + B sin phi, phi' = omega",
                          "Y. Ueda, J. Stat. Phys. 20, 181 (1979); parameters of J. C. Sprott, Chaos and Time-Series "
                          "Analysis (2003)",
                          make_model<3>(f));
    e.forced = true;
    constant(e, -0.05);
    add(std::move(e), spectrum_settings(0.005, 0.1, 200.0, 40'000.0));
  }
  // Hyperchaotic flows.
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = -x[1] - x[2];
      d[1] = x[0] + p[0] * x[1] + x[3];
      d[2] = p[1] + x[0] * x[2];
      d[3] = -p[2] * x[2] + p[3] * x[3];
    };
    ZooEntry e = zoo_flow("rossler_hyperchaos", {"x", "y", "z", "w"},
                          P{{"a", 0.25, ""}, {"b", 3.0, ""}, {"c", 0.5, ""}, {"d", 0.05, ""}}, {-10.0, -6.0, 0.0, 10.0},
                          0.05, 0.005, 500.0, "x' = -y - z, y' = x + a y + w, z' = b + x z, w' = -c z + d w",
                          "O. E. Rossler, Phys. Lett. A 71, 155 (1979)", make_model<4>(f));
    e.hyperchaotic = true;
    e.rotating = true;
    add(std::move(e), spectrum_settings(0.005, 0.1, 500.0, 20'000.0));
  }
  {
    const auto f = [](const auto* x, auto* d, const double* p) {
      d[0] = p[0] * (x[1] - x[0]) + p[3] * x[3];
      d[1] = x[0] * (p[2] - x[2]) - x[1];
      d[2] = x[0] * x[1] - p[1] * x[2];
      d[3] = -x[0] - p[0] * x[3];
    };
    ZooEntry e = zoo_flow("lorenz_stenflo", {"x", "y", "z", "w"},
                          P{{"a", 2.0, "Prandtl number"}, {"b", 0.7, "geometric factor"}, {"r", 26.0, "Rayleigh number"},
                            {"s", 1.5, "rotation"}},
                          {1.0, 1.0, 1.0, 1.0}, 0.02, 0.002, 200.0,
                          "x' = a (y - x) + s w, y' = x (r - z) - y, z' = x y - b z, w' = -x - a w",
                          "L. Stenflo, Phys. Scr. 53, 83 (1996)", make_model<4>(f));
    constant(e, -2.0 * 2.0 - 1.0 - 0.7);
    add(std::move(e), spectrum_settings(0.002, 0.1, 200.0, 20'000.0));
  }
  {
    constexpr int n = 6;
    const auto f = [](const auto* x, auto* d, const double* p) {
      for (int i = 0; i < n; ++i)
        d[i] = (x[(i + 1) % n] - x[(i + n - 2) % n]) * x[(i + n - 1) % n] - x[i] + p[0];
    };
    std::vector<double> x0(n, 8.0);
    x0[0] += 0.01;
    ZooEntry e = zoo_flow("lorenz96", {"x1", "x2", "x3", "x4", "x5", "x6"}, P{{"F", 8.0, "forcing"}}, x0, 0.05, 0.005,
                          200.0, "x_i' = (x_{i+1} - x_{i-2}) x_{i-1} - x_i + F, i = 1..6 cyclic",
                          "E. N. Lorenz, Proc. ECMWF Seminar on Predictability 1, 1 (1996)", make_model<n>(f));
    constant(e, -6.0);
    add(std::move(e), spectrum_settings(0.005, 0.1, 200.0, 20'000.0));
  }
  return out;
}

}  // namespace chaos::detail

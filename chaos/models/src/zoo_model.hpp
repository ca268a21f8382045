#pragma once
// The equations behind a zoo entry (private). Each system is one generic lambda
// `f(const T* x, T* out, const double* p)` over the scalar type T: the vector field for flows, the
// next state for maps. make_model instantiates it for double (the values) and for Dual<D> (the
// Jacobian, row-major, J[i * D + j] = d out_i / d x_j).

#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "chaos/models/zoo.hpp"
#include "dual.hpp"

namespace chaos::detail {

struct ZooModel {
  // Entries that delegate to the reference generators and spectra of systems.hpp.
  enum class Delegate { none, lorenz, rossler, henon, logistic, ikeda, mackey_glass };
  Delegate delegate = Delegate::none;
  std::function<void(const double* x, double* out, const double* p)> evaluate;
  std::function<void(const double* x, double* jacobian, const double* p)> jacobian;
};

template <int D, class F>
std::shared_ptr<const ZooModel> make_model(F f) {
  auto m = std::make_shared<ZooModel>();
  m->evaluate = [f](const double* x, double* out, const double* p) { f(x, out, p); };
  m->jacobian = [f](const double* x, double* j, const double* p) {
    Dual<D> xd[D], od[D];
    for (int i = 0; i < D; ++i) xd[i] = Dual<D>::variable(x[i], i);
    f(static_cast<const Dual<D>*>(xd), static_cast<Dual<D>*>(od), p);
    for (int i = 0; i < D; ++i)
      for (int k = 0; k < D; ++k) j[i * D + k] = od[i].d[static_cast<std::size_t>(k)];
  };
  return m;
}

inline std::shared_ptr<const ZooModel> delegate_model(ZooModel::Delegate d) {
  auto m = std::make_shared<ZooModel>();
  m->delegate = d;
  return m;
}

// A delegating entry that also carries its equations (for the Jacobian test and zoo_flow_system).
inline std::shared_ptr<const ZooModel> with_delegate(std::shared_ptr<const ZooModel> m, ZooModel::Delegate d) {
  auto copy = std::make_shared<ZooModel>(*m);
  copy->delegate = d;
  return copy;
}

// Builders used by the entry lists; flags and spectrum settings are set on the result.
ZooEntry zoo_flow(std::string name, std::vector<std::string> variables, std::vector<ZooParameter> parameters,
                  std::vector<double> initial_state, double dt, double step, double transient, std::string equations,
                  std::string citation, std::shared_ptr<const ZooModel> model);
ZooEntry zoo_map(std::string name, std::vector<std::string> variables, std::vector<ZooParameter> parameters,
                 std::vector<double> initial_state, std::size_t transient, std::string equations, std::string citation,
                 std::shared_ptr<const ZooModel> model);

std::vector<ZooEntry> zoo_flow_entries();
std::vector<ZooEntry> zoo_map_entries();

// The leading exponents of a delay entry (zoo_delay.cpp); `p` are beta, gamma, n, tau.
LyapunovSpectrum delay_spectrum(const std::vector<double>& p, std::size_t steps_per_delay, std::size_t exponents,
                                const FlowSpectrumOptions& options);

}  // namespace chaos::detail

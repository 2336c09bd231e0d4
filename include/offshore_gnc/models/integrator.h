#pragma once
// Fixed-step classical Runge-Kutta (RK4) used by the vehicle models. A model step of dt is split into
// ceil(dt / max_step) equal sub-steps so that a large sample time never makes the integration unstable.
#include <algorithm>
#include <cmath>

namespace offshore_gnc {
namespace models {

// Number of equal sub-steps so that each is <= max_step (at least 1).
inline int substeps(double dt, double max_step) {
  return std::max(1, static_cast<int>(std::ceil(dt / max_step - 1e-9)));
}

// One RK4 step of x' = f(x) over h. State is any type with + and scalar * (Eigen vectors).
template <class State, class F>
State rk4(const State& x, double h, F&& f) {
  const State k1 = f(x);
  const State k2 = f(State(x + (0.5 * h) * k1));
  const State k3 = f(State(x + (0.5 * h) * k2));
  const State k4 = f(State(x + h * k3));
  return x + (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
}

}  // namespace models
}  // namespace offshore_gnc

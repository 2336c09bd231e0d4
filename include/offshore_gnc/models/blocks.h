#pragma once
// Simulink-style building blocks of the thesis' models (ROS-free): 1-D and 2-D lookup tables, SISO transfer
// functions discretised exactly (zero-order hold, matrix exponential) and a transport delay.
#include <deque>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace offshore_gnc {
namespace models {

// y = f(x) by linear interpolation over strictly increasing breakpoints; clamped outside (like Simulink's
// "clip" extrapolation). Throws ConfigError naming `name` for unsorted, mismatched or non-finite tables.
class Lookup1D {
 public:
  Lookup1D() = default;
  Lookup1D(std::string name, std::vector<double> x, std::vector<double> y);
  double operator()(double x) const;
  const std::vector<double>& x() const { return x_; }
  const std::vector<double>& y() const { return y_; }

 private:
  std::vector<double> x_, y_;
};

// z = f(x, y) by bilinear interpolation on a grid (z row-major: z[i * y.size() + j] = f(x[i], y[j])); clamped.
class Lookup2D {
 public:
  Lookup2D() = default;
  Lookup2D(std::string name, std::vector<double> x, std::vector<double> y, std::vector<double> z);
  double operator()(double x, double y) const;

 private:
  std::vector<double> x_, y_, z_;
};

// Proper SISO transfer function num(s)/den(s), coefficients highest power first (den[0] != 0). Realised in
// controllable canonical form and discretised exactly for a zero-order-hold input, so a step response equals
// the continuous one at the sample instants for any dt. The discretisation is cached per dt.
class TransferFunction {
 public:
  TransferFunction() = default;
  TransferFunction(std::string name, std::vector<double> num, std::vector<double> den);
  void reset(double steady_input);    // states at the equilibrium for a constant input
  double step(double dt, double u);   // advance dt with u held; returns the output at the end
  double output(double u) const;      // y = C x + D u for the current state
  double dcGain() const;
  int order() const { return static_cast<int>(a_.rows()); }

 private:
  void discretise(double dt);
  Eigen::MatrixXd a_, ad_;
  Eigen::VectorXd b_, bd_, c_, x_;
  double d_ = 0.0, dt_cached_ = -1.0;
};

// Pure delay exp(-T s) on a sampled signal: output(t) = input(t - T) (zero-order hold between samples).
class TransportDelay {
 public:
  explicit TransportDelay(double delay = 0.0, double initial = 0.0);
  void reset(double value);
  // Record u at time t (non-decreasing) and return the delayed value at t.
  double push(double t, double u);
  double delay() const { return delay_; }

 private:
  double delay_, initial_;
  std::deque<std::pair<double, double>> samples_;  // (time, value), oldest first
};

}  // namespace models
}  // namespace offshore_gnc

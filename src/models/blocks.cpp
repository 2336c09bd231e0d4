// Lookup tables, exact ZOH transfer functions and transport delay for the vehicle models.
#include "offshore_gnc/models/blocks.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <unsupported/Eigen/MatrixFunctions>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace models {

namespace {
void requireAxis(const std::string& name, const std::vector<double>& x) {
  if (x.empty()) throw ConfigError("parameter '" + name + "' must not be empty");
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i])) throw ConfigError("parameter '" + name + "' has a non-finite entry");
    if (i > 0 && x[i] <= x[i - 1])
      throw ConfigError("parameter '" + name + "' breakpoints must be strictly increasing");
  }
}
void requireFinite(const std::string& name, const std::vector<double>& v) {
  for (double e : v)
    if (!std::isfinite(e)) throw ConfigError("parameter '" + name + "' has a non-finite entry");
}
// Index i and fraction w with x in [ax[i], ax[i+1]], clamped to the ends.
void locate(const std::vector<double>& ax, double x, std::size_t& i, double& w) {
  if (std::isnan(x)) {  // no comparison holds: upper_bound would return end() and index past the table
    i = 0;
    w = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  if (ax.size() == 1 || x <= ax.front()) {
    i = 0;
    w = 0.0;
    return;
  }
  if (x >= ax.back()) {
    i = ax.size() - 2;
    w = 1.0;
    return;
  }
  i = static_cast<std::size_t>(std::upper_bound(ax.begin(), ax.end(), x) - ax.begin()) - 1;
  w = (x - ax[i]) / (ax[i + 1] - ax[i]);
}
}  // namespace

Lookup1D::Lookup1D(std::string name, std::vector<double> x, std::vector<double> y)
    : x_(std::move(x)), y_(std::move(y)) {
  requireAxis(name, x_);
  if (y_.size() != x_.size()) throw ConfigError("parameter '" + name + "': table sizes differ");
  requireFinite(name, y_);
}

double Lookup1D::operator()(double x) const {
  std::size_t i;
  double w;
  locate(x_, x, i, w);
  if (x_.size() == 1) return y_[0];
  return y_[i] + w * (y_[i + 1] - y_[i]);
}

Lookup2D::Lookup2D(std::string name, std::vector<double> x, std::vector<double> y, std::vector<double> z)
    : x_(std::move(x)), y_(std::move(y)), z_(std::move(z)) {
  requireAxis(name + "/x", x_);
  requireAxis(name + "/y", y_);
  if (x_.size() < 2 || y_.size() < 2 || z_.size() != x_.size() * y_.size())
    throw ConfigError("parameter '" + name + "': grid must be at least 2 x 2 with x.size() * y.size() values");
  requireFinite(name, z_);
}

double Lookup2D::operator()(double x, double y) const {
  std::size_t i, j;
  double wx, wy;
  locate(x_, x, i, wx);
  locate(y_, y, j, wy);
  const std::size_t n = y_.size();
  const double z0 = z_[i * n + j] + wy * (z_[i * n + j + 1] - z_[i * n + j]);
  const double z1 = z_[(i + 1) * n + j] + wy * (z_[(i + 1) * n + j + 1] - z_[(i + 1) * n + j]);
  return z0 + wx * (z1 - z0);
}

TransferFunction::TransferFunction(std::string name, std::vector<double> num, std::vector<double> den) {
  requireFinite(name + "/num", num);
  requireFinite(name + "/den", den);
  while (den.size() > 1 && den.front() == 0.0) den.erase(den.begin());
  if (den.empty() || den.front() == 0.0) throw ConfigError("parameter '" + name + "/den' is zero");
  if (num.empty() || num.size() > den.size())
    throw ConfigError("parameter '" + name + "' must be proper (numerator order <= denominator order)");
  const int n = static_cast<int>(den.size()) - 1;
  const double a0 = den.front();
  for (double& v : den) v /= a0;
  for (double& v : num) v /= a0;
  num.insert(num.begin(), den.size() - num.size(), 0.0);  // same length as den
  d_ = num[0];
  a_ = Eigen::MatrixXd::Zero(n, n);
  b_ = Eigen::VectorXd::Zero(n);
  c_ = Eigen::VectorXd::Zero(n);
  // Controllable canonical form: x1' = x2, ..., xn' = -a_n x1 - ... - a_1 xn + u.
  for (int i = 0; i + 1 < n; ++i) a_(i, i + 1) = 1.0;
  for (int i = 0; i < n; ++i) {
    a_(n - 1, i) = -den[n - i];
    c_(i) = num[n - i] - num[0] * den[n - i];
  }
  if (n > 0) b_(n - 1) = 1.0;
  if (n > 0 && den[n] == 0.0) throw ConfigError("parameter '" + name + "/den' has a pole at s = 0");
  x_ = Eigen::VectorXd::Zero(n);
}

double TransferFunction::dcGain() const {
  if (a_.rows() == 0) return d_;
  return d_ - c_.dot(a_.partialPivLu().solve(b_));
}

void TransferFunction::reset(double u) {
  if (a_.rows() == 0) return;
  x_ = -a_.partialPivLu().solve(b_ * u);  // A x + B u = 0
}

void TransferFunction::discretise(double dt) {
  const int n = static_cast<int>(a_.rows());
  Eigen::MatrixXd aug = Eigen::MatrixXd::Zero(n + 1, n + 1);
  aug.topLeftCorner(n, n) = a_ * dt;
  aug.topRightCorner(n, 1) = b_ * dt;
  const Eigen::MatrixXd e = aug.exp();
  ad_ = e.topLeftCorner(n, n);
  bd_ = e.topRightCorner(n, 1);
  dt_cached_ = dt;
}

double TransferFunction::step(double dt, double u) {
  if (a_.rows() > 0) {
    if (dt != dt_cached_) discretise(dt);
    x_ = ad_ * x_ + bd_ * u;
  }
  return output(u);
}

double TransferFunction::output(double u) const { return (a_.rows() ? c_.dot(x_) : 0.0) + d_ * u; }

TransportDelay::TransportDelay(double delay, double initial) : delay_(delay), initial_(initial) {
  requireRange("delay", delay, 0.0, 60.0);
}

void TransportDelay::reset(double value) {
  initial_ = value;
  samples_.clear();
}

double TransportDelay::push(double t, double u) {
  samples_.emplace_back(t, u);
  const double td = t - delay_ + 1e-9;  // tolerance: delays that are multiples of dt hit a sample exactly
  // Drop samples superseded by a newer one that is already due.
  while (samples_.size() > 1 && samples_[1].first <= td) samples_.pop_front();
  return samples_.front().first <= td ? samples_.front().second : initial_;
}

}  // namespace models
}  // namespace offshore_gnc

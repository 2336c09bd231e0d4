#include "offshore_gnc/control/filters.h"

#include <cmath>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace control {

Biquad Biquad::tustin(double n2, double n1, double n0, double d2, double d1, double d0, double dt, double w_warp) {
  // s = K (1 - z^-1) / (1 + z^-1), K = w / tan(w dt / 2) maps s = j w exactly onto z = e^{j w dt}.
  // Prewarping needs w below Nyquist (w dt < pi); above it the plain bilinear constant is used.
  const double k = (w_warp > 0.0 && w_warp * dt < 3.0) ? w_warp / std::tan(w_warp * dt / 2.0) : 2.0 / dt;
  const double k2 = k * k;
  Biquad b;
  if (n2 == 0.0 && d2 == 0.0) {  // first order: no spurious pole/zero pair at z = -1
    const double a0 = d1 * k + d0;
    b.b0 = (n1 * k + n0) / a0;
    b.b1 = (n0 - n1 * k) / a0;
    b.a1 = (d0 - d1 * k) / a0;
    return b;
  }
  const double a0 = d2 * k2 + d1 * k + d0;
  b.b0 = (n2 * k2 + n1 * k + n0) / a0;
  b.b1 = (2.0 * n0 - 2.0 * n2 * k2) / a0;
  b.b2 = (n2 * k2 - n1 * k + n0) / a0;
  b.a1 = (2.0 * d0 - 2.0 * d2 * k2) / a0;
  b.a2 = (d2 * k2 - d1 * k + d0) / a0;
  return b;
}

double Biquad::step(double x) {
  const double y = b0 * x + z1_;
  z1_ = b1 * x - a1 * y + z2_;
  z2_ = b2 * x - a2 * y;
  return y;
}

void Biquad::reset(double u) {
  const double dc = (b0 + b1 + b2) / (1.0 + a1 + a2);
  const double y = dc * u;
  z2_ = b2 * u - a2 * y;
  z1_ = b1 * u - a1 * y + z2_;
}

std::complex<double> Biquad::response(double w, double dt) const {
  const std::complex<double> zi = std::polar(1.0, -w * dt);
  return (b0 + b1 * zi + b2 * zi * zi) / (1.0 + a1 * zi + a2 * zi * zi);
}

bool Biquad::stable() const {
  // Jury conditions for z^2 + a1 z + a2.
  return std::abs(a2) < 1.0 && 1.0 + a1 + a2 > 0.0 && 1.0 - a1 + a2 > 0.0;
}

const ParamTable<FilterParams>& FilterParams::table() {
  using P = FilterParams;
  static const ParamTable<P> t = ParamTable<P>()
      .number("tf", &P::tf, 0.0, 100.0, "s", "low-pass time constant T_f (eq. 4.15; 0 = off)")
      .number("xi", &P::xi, 0.0, 1.0, "", "notch design parameter xi (eq. 4.16): the depth at the centre")
      .number("notch_width", &P::notch_width, 0.01, 1.0, "",
              "notch width zeta: (s^2 + 2 xi zeta w s + w^2) / (s^2 + 2 zeta w s + w^2); 1 = eq. 4.16")
      .numbers("notch_w", &P::notch_w, 0, 1e-4, 1000.0, "rad/s", "centre frequencies of the notches (empty = off)");
  return t;
}

void FilterParams::validate() const { table().validate(*this, "filter/"); }

FeedbackFilter::FeedbackFilter(const FilterParams& p, double dt) : dt_(dt) {
  p.validate();
  requirePositive("filter/dt", dt);
  if (p.tf > 0.0) sections_.push_back(Biquad::tustin(0, 0, 1, 0, p.tf, 1, dt, 1.0 / p.tf));  // eq. 4.15
  const double z = p.notch_width;
  for (double w : p.notch_w)  // eq. 4.16 for notch_width 1
    sections_.push_back(Biquad::tustin(1, 2 * p.xi * z * w, w * w, 1, 2 * z * w, w * w, dt, w));
}

double FeedbackFilter::step(double x) {
  if (!std::isfinite(x)) return last_;
  if (!primed_) reset(x);
  for (auto& s : sections_) x = s.step(x);
  last_ = x;
  return x;
}

void FeedbackFilter::reset(double x) {
  if (!std::isfinite(x)) return;
  for (auto& s : sections_) s.reset(x);  // every section has unity DC gain
  last_ = x;
  primed_ = true;
}

std::complex<double> FeedbackFilter::response(double w) const {
  std::complex<double> h = 1.0;
  for (const auto& s : sections_) h *= s.response(w, dt_);
  return h;
}

bool FeedbackFilter::stable() const {
  for (const auto& s : sections_)
    if (!s.stable()) return false;
  return true;
}

}  // namespace control
}  // namespace offshore_gnc

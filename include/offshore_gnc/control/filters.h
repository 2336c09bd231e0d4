#pragma once
// Feedback filters of the USV directional control (thesis 4.2.3, eq. 4.15-4.16): a first-order low-pass
// h_lp(s) = 1 / (T_f s + 1) in cascade with three notch filters (s^2 + 2 xi w_i s + w_i^2) / (s + w_i)^2.
// Each section is discretised with the bilinear (Tustin) transform, prewarped at its characteristic frequency
// so the discrete notch sits exactly at w_i whatever the control rate. ROS-free.
#include <complex>
#include <vector>

#include "offshore_gnc/common/param_table.h"

namespace offshore_gnc {
namespace control {

// Direct-form II transposed second-order section: y = (b0 + b1 z^-1 + b2 z^-2) / (1 + a1 z^-1 + a2 z^-2) x.
class Biquad {
 public:
  Biquad() = default;
  // Continuous (n2 s^2 + n1 s + n0) / (d2 s^2 + d1 s + d0), Tustin with prewarping at w_warp [rad/s].
  static Biquad tustin(double n2, double n1, double n0, double d2, double d1, double d0, double dt, double w_warp);
  double step(double x);
  void reset(double steady_input);              // state for a steady input (no start-up transient)
  std::complex<double> response(double w, double dt) const;  // H(e^{j w dt})
  bool stable() const;                          // both poles strictly inside the unit circle
  double b0 = 1, b1 = 0, b2 = 0, a1 = 0, a2 = 0;

 private:
  double z1_ = 0, z2_ = 0;
};

// Each notch is (s^2 + 2 xi zeta w s + w^2) / (s^2 + 2 zeta w s + w^2): depth xi at its centre w whatever its width
// zeta; zeta = 1 is eq. 4.16's (s + w)^2 denominator. Below its centre a notch delays the signal by about
// 2 zeta (1 - xi) / w: with eq. 4.16's three notches at xi = 0.8 that is 7 s of the heading's feedback, inside
// the USV heading loop's own band, where it made the loop ring at ~40 s periods (docs/guidance-control.md).
struct FilterParams {
  double tf = 0.1;                               // T_f low-pass time constant [s]; 0 disables it
  double xi = 0.8;                               // notch design parameter (depth at the centre = xi)
  double notch_width = 1.0;                      // zeta (1 = eq. 4.16)
  std::vector<double> notch_w = {0.1, 0.2, 0.4}; // centre frequencies [rad/s]; empty disables the notches
  static const ParamTable<FilterParams>& table();
  void validate() const;
};

// Low-pass + notch cascade for one feedback signal.
class FeedbackFilter {
 public:
  FeedbackFilter() = default;
  FeedbackFilter(const FilterParams& p, double dt);
  double step(double x);                          // non-finite input is rejected: returns the last output
  void reset(double x);
  std::complex<double> response(double w) const;  // whole cascade
  bool stable() const;
  const std::vector<Biquad>& sections() const { return sections_; }
  bool primed() const { return primed_; }

 private:
  std::vector<Biquad> sections_;
  double dt_ = 0.1;
  double last_ = 0.0;
  bool primed_ = false;
};

}  // namespace control
}  // namespace offshore_gnc

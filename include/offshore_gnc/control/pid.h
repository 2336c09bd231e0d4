#pragma once
// PID with derivative on the measurement rate (no derivative kick on reference steps), output saturation and
// anti-windup (conditional integration + integral clamp). ROS-free.
#include <string>

#include "offshore_gnc/common/param_table.h"

namespace offshore_gnc {
namespace control {

struct PidGains {
  double kp = 0.0, ki = 0.0, kd = 0.0;
  double out_limit = 1e9;   // |output| bound
  double i_limit = 1e9;     // |ki * integral| bound
  static const ParamTable<PidGains>& table();
  void validate(const std::string& name) const;  // throws ConfigError naming `name`/field
};

class Pid {
 public:
  Pid() = default;
  explicit Pid(const PidGains& g) { setGains(g); }
  void setGains(const PidGains& g);  // keeps the integral (bumpless gain changes within the clamp)
  const PidGains& gains() const { return g_; }
  // error = reference - measurement; error_rate = d(error)/dt (e.g. -r for yaw with a constant reference).
  // Non-finite inputs return 0 (a safe, neutral command) and leave the state alone.
  double update(double error, double error_rate, double dt);
  void reset() { integral_ = 0.0; }
  double integral() const { return integral_; }
  bool saturated() const { return saturated_; }

 private:
  PidGains g_;
  double integral_ = 0.0;
  bool saturated_ = false;
};

}  // namespace control
}  // namespace offshore_gnc

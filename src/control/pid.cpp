#include "offshore_gnc/control/pid.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace control {

const ParamTable<PidGains>& PidGains::table() {
  using P = PidGains;
  static const ParamTable<P> t = ParamTable<P>()
      .number("kp", &P::kp, 0.0, 1e6, "", "proportional gain")
      .number("ki", &P::ki, 0.0, 1e6, "", "integral gain")
      .number("kd", &P::kd, 0.0, 1e6, "", "derivative gain (on the measured rate)")
      .number("out_limit", &P::out_limit, 1e-6, 1e9, "", "bound on the output magnitude")
      .number("i_limit", &P::i_limit, 0.0, 1e12, "", "bound on the magnitude of ki * integral (anti-windup)");
  return t;
}

void PidGains::validate(const std::string& name) const { table().validate(*this, name + "/"); }

void Pid::setGains(const PidGains& g) {
  g_ = g;
  if (g_.ki > 0.0) integral_ = std::clamp(integral_, -g_.i_limit / g_.ki, g_.i_limit / g_.ki);
}

double Pid::update(double error, double error_rate, double dt) {
  if (!std::isfinite(error) || !std::isfinite(error_rate) || !std::isfinite(dt) || dt < 0.0) return 0.0;
  const double pd = g_.kp * error + g_.kd * error_rate;
  double candidate = integral_ + error * dt;
  if (g_.ki > 0.0) candidate = std::clamp(candidate, -g_.i_limit / g_.ki, g_.i_limit / g_.ki);
  const double u_try = pd + g_.ki * candidate;
  // Conditional integration: do not integrate further into a saturated output.
  const bool winding = std::abs(u_try) > g_.out_limit && error * u_try > 0.0;
  if (!winding) integral_ = candidate;
  const double u = pd + g_.ki * integral_;
  saturated_ = std::abs(u) > g_.out_limit;
  return std::clamp(u, -g_.out_limit, g_.out_limit);
}

}  // namespace control
}  // namespace offshore_gnc

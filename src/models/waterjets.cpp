#include "offshore_gnc/models/waterjets.h"

#include <algorithm>
#include <cmath>

#include "offshore_gnc/models/usv.h"

namespace offshore_gnc {
namespace models {

JetForces::JetForces(const UsvParams& p)
    : l_pivot_(p.l_pivot),
      jet_y_(p.jet_y),
      reverse_efficiency_(p.reverse_efficiency),
      nozzle_max_(p.nozzle_max),
      nozzle_max_angle_(p.nozzle_max_angle),
      eff_a_(p.nozzle_eff_a),
      eff_b_(p.nozzle_eff_b),
      thrust_(makeThrustTable(p)) {}

double JetForces::grossThrust(double ur, double rpm, double nozzle) const {
  const double eff = eff_a_ * std::exp(eff_b_ * std::abs(nozzle));  // eq. 3.12
  return thrust_(std::max(0.0, ur), std::max(0.0, rpm)) * eff;
}

double JetForces::bucketGain(double b) const { return b >= 0.0 ? b : b * reverse_efficiency_; }

double JetForces::angle(double nozzle) const { return nozzle_max_angle_ * nozzle / nozzle_max_; }

double JetForces::jetY(int i) const { return i == 0 ? -jet_y_ : jet_y_; }

Eigen::Vector3d JetForces::force(const std::array<JetState, 2>& s, double ur) const {
  Eigen::Vector3d tau = Eigen::Vector3d::Zero();
  for (int i = 0; i < 2; ++i) {
    const double t = grossThrust(ur, s[i].rpm, s[i].nozzle), a = angle(s[i].nozzle);
    const double fx = t * std::cos(a) * bucketGain(s[i].bucket), fy = t * std::sin(a);
    tau += Eigen::Vector3d(fx, fy, -l_pivot_ * fy - jetY(i) * fx);  // N = x Fy - y Fx with x = -l_pivot
  }
  return tau;
}

TwinWaterjets::TwinWaterjets(const UsvParams& p)
    : rpm_min_(p.rpm_min), rpm_max_(p.rpm_max), nozzle_max_(p.nozzle_max), bucket_rate_(p.bucket_rate), forces_(p) {
  for (int i = 0; i < 2; ++i) {
    rpm_tf_[i] = TransferFunction("rpm_tf", p.rpm_num, p.rpm_den);
    nozzle_lag_[i] = TransferFunction("nozzle_lag", {1.0}, {p.nozzle_time_constant, 1.0});
    nozzle_delay_[i] = TransportDelay(p.nozzle_delay);
  }
  reset();
}

void TwinWaterjets::reset() {
  for (int i = 0; i < 2; ++i) {
    rpm_tf_[i].reset(rpm_min_);
    nozzle_lag_[i].reset(0.0);
    nozzle_delay_[i].reset(0.0);
    cmd_[i] = JetCommand{rpm_min_, 0.0, 0.0};
    state_[i] = JetState{rpm_min_, 0.0, 0.0, 0.0};
  }
}

void TwinWaterjets::setCommands(const JetCommands& c) {
  for (int i = 0; i < 2; ++i)
    cmd_[i] = JetCommand{std::clamp(c[i].rpm, rpm_min_, rpm_max_), std::clamp(c[i].nozzle, -nozzle_max_, nozzle_max_),
                         std::clamp(c[i].bucket, -1.0, 1.0)};
}

void TwinWaterjets::step(double t0, double dt) {
  for (int i = 0; i < 2; ++i) {
    JetState& s = state_[i];
    s.rpm = std::clamp(rpm_tf_[i].step(dt, cmd_[i].rpm), 0.0, rpm_max_);
    s.nozzle = std::clamp(nozzle_lag_[i].step(dt, nozzle_delay_[i].push(t0, cmd_[i].nozzle)), -nozzle_max_, nozzle_max_);
    const double db = std::clamp(cmd_[i].bucket - s.bucket, -bucket_rate_ * dt, bucket_rate_ * dt);
    s.bucket = std::clamp(s.bucket + db, -1.0, 1.0);  // the bucket's hydraulics move at a limited rate
  }
}

void TwinWaterjets::updateThrust(double ur) {
  for (auto& s : state_)
    s.thrust = forces_.grossThrust(ur, s.rpm, s.nozzle) * std::cos(forces_.angle(s.nozzle)) *
               forces_.bucketGain(s.bucket);
}

}  // namespace models
}  // namespace offshore_gnc

#include "offshore_gnc/control/allocation.h"

#include <Eigen/QR>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace control {

ThrustAllocator::ThrustAllocator(const Eigen::MatrixXd& tcm, const Eigen::VectorXd& max_thrust,
                                 CommandFor command_for)
    : tcm_(tcm), max_(max_thrust), command_for_(std::move(command_for)) {
  if (tcm.size() == 0 || !tcm.allFinite()) throw ConfigError("thruster configuration matrix is empty or non-finite");
  if (max_thrust.size() != tcm.cols())
    throw ConfigError("max_thrust has " + std::to_string(max_thrust.size()) + " entries, the TCM has " +
                      std::to_string(tcm.cols()) + " thrusters");
  for (int i = 0; i < max_.size(); ++i) requirePositive("max_thrust[" + std::to_string(i) + "]", max_[i]);
  pinv_ = tcm_.completeOrthogonalDecomposition().pseudoInverse();
}

AllocationResult ThrustAllocator::allocate(const Eigen::VectorXd& tau) const {
  AllocationResult r;
  r.thrust = Eigen::VectorXd::Zero(tcm_.cols());
  if (tau.size() == tcm_.rows() && tau.allFinite()) r.thrust = pinv_ * tau;
  double scale = 1.0;
  for (int i = 0; i < r.thrust.size(); ++i) scale = std::max(scale, std::abs(r.thrust[i]) / max_[i]);
  r.saturated = scale > 1.0 + 1e-12;
  r.thrust /= scale;
  r.setpoint = r.thrust.cwiseQuotient(max_);
  if (command_for_)
    for (int i = 0; i < r.thrust.size(); ++i) r.setpoint[i] = std::clamp(command_for_(i, r.thrust[i]), -1.0, 1.0);
  return r;
}

}  // namespace control
}  // namespace offshore_gnc

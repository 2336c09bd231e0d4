#pragma once
// Thrust allocation f = T^+ tau (thesis eq. 4.8) with per-thruster saturation. When a thruster saturates the
// whole vector is scaled down so the wrench keeps its direction. ROS-free.
#include <Eigen/Core>

#include <functional>

namespace offshore_gnc {
namespace control {

struct AllocationResult {
  Eigen::VectorXd thrust;    // [N], saturated
  Eigen::VectorXd setpoint;  // thrust / max_thrust, -1..1
  bool saturated = false;
};

class ThrustAllocator {
 public:
  ThrustAllocator() = default;
  // tcm: DOF x thrusters (columns: wrench per newton of each thruster); max_thrust per thruster [N] (> 0).
  // command_for(i, thrust) -> normalised setpoint: the inverse thruster curve (models::AuvModel::commandFor);
  // empty: setpoint = thrust / max_thrust.
  using CommandFor = std::function<double(int, double)>;
  ThrustAllocator(const Eigen::MatrixXd& tcm, const Eigen::VectorXd& max_thrust, CommandFor command_for = {});
  AllocationResult allocate(const Eigen::VectorXd& tau) const;  // non-finite tau -> zero thrust
  const Eigen::MatrixXd& tcm() const { return tcm_; }
  const Eigen::MatrixXd& pinv() const { return pinv_; }
  int thrusters() const { return static_cast<int>(tcm_.cols()); }

 private:
  Eigen::MatrixXd tcm_, pinv_;
  Eigen::VectorXd max_;
  CommandFor command_for_;
};

}  // namespace control
}  // namespace offshore_gnc

#pragma once
// Thrust allocation f = T^+ tau (thesis eq. 4.8) with per-thruster saturation, each direction its own limit (a
// T200-like propeller pushes 51.5 N one way, 40.2 N the other). When a thruster saturates, the
// thrusts of its group are scaled down so that the group's part of the wrench keeps its direction. A group is a
// set of thrusters coupled through the degrees of freedom they act on (the Girona500: surge + yaw, sway, heave):
// the groups act on disjoint degrees of freedom, so the depth is held while the horizontal thrusters saturate
// in a current. ROS-free.
#include <Eigen/Core>

#include <functional>
#include <vector>

namespace offshore_gnc {
namespace control {

struct AllocationResult {
  Eigen::VectorXd thrust;    // [N], saturated
  Eigen::VectorXd setpoint;  // thrust / its direction's limit, -1..1
  bool saturated = false;
};

class ThrustAllocator {
 public:
  ThrustAllocator() = default;
  // tcm: DOF x thrusters (columns: wrench per newton of each thruster); max_thrust per thruster [N] (> 0), the
  // largest positive thrust; max_reverse, the largest negative one's size (empty: max_thrust, symmetric).
  // command_for(i, thrust) -> normalised setpoint: the inverse thruster curve (models::AuvModel::commandFor);
  // empty: setpoint = thrust / its direction's limit.
  using CommandFor = std::function<double(int, double)>;
  ThrustAllocator(const Eigen::MatrixXd& tcm, const Eigen::VectorXd& max_thrust, CommandFor command_for = {},
                  const Eigen::VectorXd& max_reverse = Eigen::VectorXd());
  AllocationResult allocate(const Eigen::VectorXd& tau) const;  // non-finite tau -> zero thrust
  const Eigen::MatrixXd& tcm() const { return tcm_; }
  const Eigen::MatrixXd& pinv() const { return pinv_; }
  int thrusters() const { return static_cast<int>(tcm_.cols()); }
  const std::vector<int>& groups() const { return group_; }  // group index of each thruster

 private:
  Eigen::MatrixXd tcm_, pinv_;
  std::vector<int> group_;  // group index of each thruster
  int groups_ = 0;
  Eigen::VectorXd max_, reverse_;
  double limit(int i, double thrust) const { return thrust >= 0.0 ? max_[i] : reverse_[i]; }
  CommandFor command_for_;
};

}  // namespace control
}  // namespace offshore_gnc

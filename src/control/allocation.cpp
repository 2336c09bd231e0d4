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
                                 CommandFor command_for, const Eigen::VectorXd& max_reverse)
    : tcm_(tcm), max_(max_thrust), reverse_(max_reverse.size() ? max_reverse : max_thrust),
      command_for_(std::move(command_for)) {
  if (tcm.size() == 0 || !tcm.allFinite()) throw ConfigError("thruster configuration matrix is empty or non-finite");
  for (const auto& [name, v] : {std::pair<const char*, const Eigen::VectorXd&>{"max_thrust", max_},
                                std::pair<const char*, const Eigen::VectorXd&>{"max_reverse_thrust", reverse_}}) {
    if (v.size() != tcm.cols())
      throw ConfigError(std::string(name) + " has " + std::to_string(v.size()) + " entries, the TCM has " +
                        std::to_string(tcm.cols()) + " thrusters");
    for (int i = 0; i < v.size(); ++i) requirePositive(std::string(name) + "[" + std::to_string(i) + "]", v[i]);
  }
  pinv_ = tcm_.completeOrthogonalDecomposition().pseudoInverse();
  // Groups: thrusters that act on a common degree of freedom, transitively (T and T^+ are block-diagonal over
  // them, so each group's thrusts depend on its own degrees of freedom only).
  const int n = static_cast<int>(tcm_.cols());
  group_.assign(n, -1);
  groups_ = 0;
  for (int seed = 0; seed < n; ++seed) {
    if (group_[seed] >= 0) continue;
    std::vector<int> todo{seed};
    group_[seed] = groups_;
    while (!todo.empty()) {
      const int j = todo.back();
      todo.pop_back();
      for (int row = 0; row < tcm_.rows(); ++row) {
        if (tcm_(row, j) == 0.0) continue;
        for (int k = 0; k < n; ++k)
          if (group_[k] < 0 && tcm_(row, k) != 0.0) {
            group_[k] = groups_;
            todo.push_back(k);
          }
      }
    }
    ++groups_;
  }
}

AllocationResult ThrustAllocator::allocate(const Eigen::VectorXd& tau) const {
  AllocationResult r;
  r.thrust = Eigen::VectorXd::Zero(tcm_.cols());
  if (tau.size() == tcm_.rows() && tau.allFinite()) r.thrust = pinv_ * tau;
  const int n = static_cast<int>(r.thrust.size());
  std::vector<double> scale(groups_, 1.0);
  for (int i = 0; i < n; ++i)
    scale[group_[i]] = std::max(scale[group_[i]], std::abs(r.thrust[i]) / limit(i, r.thrust[i]));
  for (int i = 0; i < n; ++i) r.thrust[i] /= scale[group_[i]];
  r.saturated = std::any_of(scale.begin(), scale.end(), [](double s) { return s > 1.0 + 1e-12; });
  r.setpoint.resize(n);
  for (int i = 0; i < n; ++i) r.setpoint[i] = r.thrust[i] / limit(i, r.thrust[i]);
  if (command_for_)
    for (int i = 0; i < r.thrust.size(); ++i) r.setpoint[i] = std::clamp(command_for_(i, r.thrust[i]), -1.0, 1.0);
  return r;
}

}  // namespace control
}  // namespace offshore_gnc

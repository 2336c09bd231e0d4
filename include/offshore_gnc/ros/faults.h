#pragma once
// The simulators' side of fault injection (docs/safety.md, "Fault injection"): the plan is the master's
// `/sim/faults` parameter (one per master, set by the vehicle's launch file from its `faults` argument); each
// simulator nodelet hands `plan()` to its core (which silences the sensor at its simulated time) and announces
// every start and end of them on /<vehicle>/sim/faults (offshore_gnc/FaultEvent) for the bag and the report.
#include <ros/node_handle.h>
#include <ros/param.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "offshore_gnc/FaultEvent.h"
#include "offshore_gnc/common/faults.h"

namespace offshore_gnc {
namespace ros_util {

class FaultInjector {
 public:
  // Throws ConfigError when /sim/faults does not parse. `names`: the kinds this simulator injects.
  FaultInjector(ros::NodeHandle& nh, const std::string& vehicle, const std::vector<std::string>& names) {
    std::string text;
    ros::param::param<std::string>("/sim/faults", text, "");
    plan_ = FaultPlan::parse(text).of(vehicle);
    for (const auto& f : plan_.faults())
      if (std::find(names.begin(), names.end(), f.name) != names.end()) own_.push_back({f, false});
    pub_ = nh.advertise<FaultEvent>("/" + vehicle + "/sim/faults", 10);
  }
  // This master's faults, for the simulator's core.
  const FaultPlan& plan() const { return plan_; }

  // Publishes the starts and ends of this simulator's faults up to simulated time t; call once per step.
  // `in_effect(name)`: whether a fault in its window has taken effect yet (the collision fault's obstacle appears
  // only once the USV is under way); none: from the window's start.
  void update(double t, const std::function<bool(const std::string&)>& in_effect = nullptr) {
    for (auto& o : own_) {
      const bool on = o.fault.activeAt(t) && (!in_effect || in_effect(o.fault.name));
      if (on == o.on) continue;
      o.on = on;
      FaultEvent e;
      e.header.stamp = ros::Time(t);
      e.name = o.fault.name;
      e.active = on;
      e.effect = findFaultKind(o.fault.name)->effect;
      pub_.publish(e);
    }
  }

 private:
  struct Own {
    Fault fault;
    bool on;
  };
  std::vector<Own> own_;
  FaultPlan plan_;
  ros::Publisher pub_;
};

}  // namespace ros_util
}  // namespace offshore_gnc

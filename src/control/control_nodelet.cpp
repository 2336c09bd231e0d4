// Control nodelet: GuidanceStatus (the reference) + odometry -> control::ControlLoop -> the vehicle's actuator
// command at the control rate:
//   vehicle: usv       -> JoystickCommand on joystick_cmd (source AUTONOMY; the CAN gateway / simulator applies
//                         the priority of manual input)
//   vehicle: girona500 -> ThrusterSetpoints on thruster_setpoints (T^+ allocation, saturation)
//   vehicle: acolor    -> RcChannels on rc_channels (PWM 1100-1900 us)
// The AUVs also publish commanded_velocity (TwistStamped in the vehicle's base frame, FLU): the velocity through the water
// their command gives, the navigation's speed without a DVL (ActuatorCommand::water_velocity).
// The vehicle's safety supervisor (safety/state) overrides guidance: hold, neutral or surface until it clears.
// Thin: parameters, message conversion, publishing.
#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <geometry_msgs/TwistStamped.h>
#include <nodelet/nodelet.h>
#include <offshore_gnc/ControlConfig.h>
#include <offshore_gnc/GuidanceStatus.h>
#include <offshore_gnc/JoystickCommand.h>
#include <offshore_gnc/RcChannels.h>
#include <offshore_gnc/SafetyState.h>
#include <offshore_gnc/ThrusterSetpoints.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <memory>
#include <mutex>

#include "offshore_gnc/control/control_loop.h"
#include "offshore_gnc/ros/conversions.h"
#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/ros/reconfigure.h"

namespace offshore_gnc {

static_assert(SafetyState::ACTION_NONE == static_cast<int>(control::SupervisorAction::kNone) &&
              SafetyState::ACTION_WARN == static_cast<int>(control::SupervisorAction::kWarn) &&
              SafetyState::ACTION_HOLD == static_cast<int>(control::SupervisorAction::kHold) &&
              SafetyState::ACTION_NEUTRAL == static_cast<int>(control::SupervisorAction::kNeutral) &&
              SafetyState::ACTION_SURFACE == static_cast<int>(control::SupervisorAction::kSurface) &&
              SafetyState::ACTION_ABORT == static_cast<int>(control::SupervisorAction::kAbort),
              "SafetyState.msg's ACTION_* must match control::SupervisorAction");

class ControlNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros::NodeHandle& pnh = getPrivateNodeHandle();
    ros_util::ParamReader p(pnh);
    control::ControlLoopParams cp;
    try {
      ros_util::readParams(p, control::ControlLoopParams::table(), cp);
      if (cp.vehicle == "usv") {
        ros_util::readParams(p, control::UsvControlParams::table(), cp.usv);
        joy_pub_ = nh.advertise<JoystickCommand>("joystick_cmd", 10);
      } else if (cp.vehicle == "girona500") {
        ros_util::readParams(p, control::Girona500ControlParams::table(), cp.girona500);
        control::ThrusterLayout layout = control::ThrusterLayout::of(cp.girona500);  // hardware overrides
        ros_util::readParams(p, control::ThrusterLayout::table(), layout);
        layout.applyTo(cp.girona500);
        thr_pub_ = nh.advertise<ThrusterSetpoints>("thruster_setpoints", 10);
      } else {
        ros_util::readParams(p, control::AcolorControlParams::table(), cp.acolor);
        rc_pub_ = nh.advertise<RcChannels>("rc_channels", 10);
        nav_status_sub_ = nh.subscribe("navigation/status", 1, &ControlNodelet::onNavStatus, this);  // latched
      }
      if (cp.vehicle != "usv") {
        water_pub_ = nh.advertise<geometry_msgs::TwistStamped>("commanded_velocity", 10);
      }
      loop_ = std::make_unique<control::ControlLoop>(cp);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    status_sub_ = nh.subscribe("guidance/status", 10, &ControlNodelet::onStatus, this);
    odom_sub_ = nh.subscribe("odom", 10, &ControlNodelet::onOdom, this);
    safety_sub_ = nh.subscribe("safety/state", 10, &ControlNodelet::onSafety, this);

    reconfigure_ = std::make_unique<dynamic_reconfigure::Server<ControlConfig>>(reconf_mutex_, pnh);
    reconfigure_->updateConfig(toConfig(cp));
    reconfigure_->setCallback([this](ControlConfig& c, uint32_t) { onReconfigure(c); });

    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, pnh, getName());
    updater_->setHardwareID(cp.vehicle + "_control");
    updater_->add("control", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      std::lock_guard<std::mutex> l(mutex_);
      const std::string& why = loop_->why();
      s.summary(why.empty() ? diagnostic_msgs::DiagnosticStatus::OK : diagnostic_msgs::DiagnosticStatus::WARN,
                why.empty() ? "controlling" : "neutral command: " + why);
      ros_util::addCounters(s, loop_->counters(), {"stale_input", "bad_reference"});
      ros_util::addCounters(s, loop_->controllerCounters(), {"nan_state", "bad_reference"});
      if (const control::UsvController* usv = loop_->usvController()) {
        // dynamic positioning's state while it holds (its last step within a second of the last command)
        const control::DpOutput& dp = usv->stationKeeping();
        if (ros::Time::now().toSec() - dp.t < 1.0) {
          s.add("station keeping", dp.weathervaning ? "weathervaning (bow into the current)" : "hold heading");
          s.addf("distance from the hold point [m]", "%.2f", dp.distance);
          s.addf("held heading [deg]", "%.1f", rad2deg(dp.heading));
          s.addf("learnt steady force [N]", "%.0f", dp.steady_force.norm());
        }
      }
    });
    timer_ = nh.createTimer(ros::Duration(1.0 / cp.rate), &ControlNodelet::onTimer, this);
    NODELET_INFO("%s control at %.1f Hz", cp.vehicle.c_str(), cp.rate);
  }

  // The reconfigure server starts from the loaded (yaml) values; the .cfg names are the active vehicle's table's.
  ControlConfig toConfig(const control::ControlLoopParams& cp) const {
    if (cp.vehicle == "usv") return ros_util::toReconfigure<ControlConfig>(control::UsvControlParams::table(), cp.usv);
    if (cp.vehicle == "girona500")
      return ros_util::toReconfigure<ControlConfig>(control::Girona500ControlParams::table(), cp.girona500);
    return ros_util::toReconfigure<ControlConfig>(control::AcolorControlParams::table(), cp.acolor);
  }

  void onReconfigure(const ControlConfig& c) {
    std::lock_guard<std::mutex> l(mutex_);
    control::ControlLoopParams cp = loop_->params();
    cp.usv = ros_util::fromReconfigure(c, control::UsvControlParams::table(), cp.usv);
    cp.girona500 = ros_util::fromReconfigure(c, control::Girona500ControlParams::table(), cp.girona500);
    cp.acolor = ros_util::fromReconfigure(c, control::AcolorControlParams::table(), cp.acolor);
    try {
      loop_->setParams(cp);
    } catch (const ConfigError& e) {
      NODELET_ERROR("reconfigure rejected: %s", e.what());
    }
  }

  void onStatus(const GuidanceStatus::ConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex_);
    loop_->onReference(ros_util::referenceFromStatus(*m), ros::Time::now().toSec());
  }
  void onNavStatus(const std_msgs::String::ConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex_);
    loop_->onFixLost(m->data == ros_util::nav_status::kFixLost);
  }
  void onOdom(const nav_msgs::Odometry::ConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex_);
    loop_->onState(ros_util::stateFromOdom(*m), ros::Time::now().toSec());
  }

  void onTimer(const ros::TimerEvent&) {
    std::lock_guard<std::mutex> l(mutex_);
    const ros::Time now = ros::Time::now();
    const control::ActuatorCommand c = loop_->update(now.toSec());
    if (!c.active) NODELET_WARN_THROTTLE(5.0, "neutral command: %s", loop_->why().c_str());
    if (joy_pub_) {
      JoystickCommand m;
      m.header.stamp = now;
      m.surge = c.joystick.surge, m.sway = c.joystick.sway, m.yaw = c.joystick.yaw;
      m.source = JoystickCommand::SOURCE_AUTONOMY;
      m.priority = JoystickCommand::PRIORITY_AUTONOMY;
      joy_pub_.publish(m);
    } else if (thr_pub_) {
      ThrusterSetpoints m;
      m.header.stamp = now;
      const auto& a = c.thrusters.alloc;
      m.thrust.assign(a.thrust.data(), a.thrust.data() + a.thrust.size());
      m.setpoint.assign(a.setpoint.data(), a.setpoint.data() + a.setpoint.size());
      m.saturated = a.saturated;
      thr_pub_.publish(m);
    } else {
      RcChannels m;
      m.header.stamp = now;
      m.channels = c.rc;
      rc_pub_.publish(m);
    }
    if (water_pub_) {
      geometry_msgs::TwistStamped w;
      w.header.stamp = now;
      // frame_id left empty: the vehicle's base frame, whatever the navigation calls it
      w.twist.linear.x = c.water_velocity.x();
      w.twist.linear.y = -c.water_velocity.y();  // FRD sway -> FLU
      water_pub_.publish(w);
    }
  }

  void onSafety(const SafetyState::ConstPtr& m) {
    const control::SafetyOverride o =
        control::safetyOverrideOf(static_cast<control::SupervisorAction>(m->action), m->manual);
    std::lock_guard<std::mutex> l(mutex_);
    if (o != loop_->safety())
      NODELET_WARN("safety override %s: %s", control::safetyOverrideName(o), m->reason.c_str());
    loop_->setSafety(o, m->active_rule + ": " + m->reason);
  }

  std::unique_ptr<control::ControlLoop> loop_;
  std::mutex mutex_;
  boost::recursive_mutex reconf_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<ControlConfig>> reconfigure_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::Publisher joy_pub_, thr_pub_, rc_pub_, water_pub_;
  ros::Subscriber status_sub_, odom_sub_, safety_sub_, nav_status_sub_;
  ros::Timer timer_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::ControlNodelet, nodelet::Nodelet)

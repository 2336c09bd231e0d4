// Control nodelet (issue 3): GuidanceStatus + odometry -> the vehicle's actuator command at the control rate.
//   vehicle: usv       -> JoystickCommand on joystick_cmd (source AUTONOMY; the CAN gateway / simulator applies
//                         the priority of manual input)
//   vehicle: girona500 -> ThrusterSetpoints on thruster_setpoints (T^+ allocation, saturation)
//   vehicle: acolor    -> RcChannels on rc_channels (PWM 1100-1900 us)
// Thin: the controllers are control::UsvController / Girona500Controller / AcolorController. Stale or bad input
// -> neutral / hold command and a counter, never NaN.
#include <diagnostic_updater/diagnostic_updater.h>
#include <dynamic_reconfigure/server.h>
#include <nav_msgs/Path.h>
#include <nodelet/nodelet.h>
#include <offshore_gnc/ControlConfig.h>
#include <offshore_gnc/GuidanceStatus.h>
#include <offshore_gnc/JoystickCommand.h>
#include <offshore_gnc/RcChannels.h>
#include <offshore_gnc/ThrusterSetpoints.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>

#include <memory>
#include <mutex>

#include "offshore_gnc/control/vehicle_control.h"
#include "offshore_gnc/ros/conversions.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/params.h"

namespace offshore_gnc {

namespace {
// GuidanceStatus -> control reference (the same mapping as control::toReference for the core output).
control::Reference referenceFromStatus(const GuidanceStatus& g, const Eigen::Vector3d& hold,
                                              const Eigen::Vector3d& path_point) {
  control::Reference r;
  r.heading = g.desired_heading;
  r.surge = g.desired_surge;
  r.depth = std::isfinite(g.desired_depth) ? g.desired_depth : 0.0;
  r.path_angle = g.path_angle;
  if (g.mode == GuidanceStatus::MODE_FOLLOW_PATH) {
    r.mode = control::RefMode::kFollow;
    r.point = path_point;
  } else if (g.mode == GuidanceStatus::MODE_STATION_KEEPING || g.mode == GuidanceStatus::MODE_HOLD_FAULT) {
    r.mode = control::RefMode::kHold;
    r.point = hold;
  } else {
    r.mode = control::RefMode::kIdle;
  }
  return r;
}

control::PidGains readPid(const ros_util::ParamReader& p, const std::string& name, const control::PidGains& def) {
  control::PidGains g;
  g.kp = p.number(name + "/kp", def.kp, 0.0, 1e6);
  g.ki = p.number(name + "/ki", def.ki, 0.0, 1e6);
  g.kd = p.number(name + "/kd", def.kd, 0.0, 1e6);
  g.out_limit = p.number(name + "/out_limit", def.out_limit, 1e-6, 1e9);
  g.i_limit = p.number(name + "/i_limit", def.i_limit, 0.0, 1e12);
  return g;
}
}  // namespace

class ControlNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros::NodeHandle& pnh = getPrivateNodeHandle();
    ros_util::ParamReader p(pnh);
    try {
      vehicle_ = p.choice("vehicle", "usv", {"usv", "girona500", "acolor"});
      rate_ = p.number("rate", 10.0, 0.1, 200.0);
      timeout_ = p.number("input_timeout", 1.0, 0.01, 60.0);
      const double dt = 1.0 / rate_;
      if (vehicle_ == "usv") {
        control::UsvControlParams c;
        c.surge = readPid(p, "surge", c.surge);
        c.yaw = readPid(p, "yaw", c.yaw);
        c.max_surge_force = p.number("max_surge_force", c.max_surge_force, 1e-3, 1e7);
        c.filter.tf = p.number("filter/tf", c.filter.tf, 0.0, 100.0);
        c.filter.xi = p.number("filter/xi", c.filter.xi, 0.0, 1.0);
        c.filter.notch_w = p.numbers("filter/notch_w", c.filter.notch_w, 0, 1e-4, 1000.0);
        c.dp_speed_gain = p.number("dp/speed_gain", c.dp_speed_gain, 0.0, 10.0);
        c.dp_max_speed = p.number("dp/max_speed", c.dp_max_speed, 0.0, 10.0);
        c.dp_sway_gain = p.number("dp/sway_gain", c.dp_sway_gain, 0.0, 100.0);
        c.dp_radius = p.number("dp/radius", c.dp_radius, 0.0, 1000.0);
        c.turn_thrust = p.number("turn_thrust", c.turn_thrust, 0.0, 1.0);
        c.dt = dt;
        usv_ = std::make_unique<control::UsvController>(c);
        joy_pub_ = nh.advertise<JoystickCommand>("joystick_cmd", 10);
      } else if (vehicle_ == "girona500") {
        control::Girona500ControlParams c;
        c.north = readPid(p, "north", c.north);
        c.east = readPid(p, "east", c.east);
        c.down = readPid(p, "down", c.down);
        c.yaw = readPid(p, "yaw", c.yaw);
        c.lead = p.number("lead", c.lead, 0.0, 100.0);
        c.cross_ki = p.number("cross_ki", c.cross_ki, 0.0, 10.0);
        c.cross_limit = p.number("cross_limit", c.cross_limit, 0.0, 100.0);
        const int n = p.integer("thrusters", 5, 1, 16);
        using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
        const RowMajor def = c.tcm;  // the yaml lists the 4 rows (X, Y, Z, N) one after the other
        const auto tcm = p.numbers("tcm", pnh.hasParam("tcm") ? std::vector<double>()
                                                             : std::vector<double>(def.data(), def.data() + def.size()),
                                   4 * n, -100.0, 100.0);
        c.tcm = Eigen::Map<const RowMajor>(tcm.data(), 4, n);
        const std::vector<double> def_max(c.max_thrust.data(), c.max_thrust.data() + c.max_thrust.size());
        const auto mx = p.numbers("max_thrust", n == c.max_thrust.size() ? def_max : std::vector<double>(), n, 1e-3,
                                  1e6);
        c.max_thrust = Eigen::Map<const Eigen::VectorXd>(mx.data(), n);
        c.dt = dt;
        g500_ = std::make_unique<control::Girona500Controller>(c);
        thr_pub_ = nh.advertise<ThrusterSetpoints>("thruster_setpoints", 10);
      } else {
        control::AcolorControlParams c;
        c.yaw = readPid(p, "yaw", c.yaw);
        c.heave = readPid(p, "heave", c.heave);
        c.surge_pwm = p.number("surge_pwm", c.surge_pwm, 1100, 1900);
        c.num_channels = p.integer("rc/num_channels", c.num_channels, 1, 18);
        c.channel_heave = p.integer("rc/heave", c.channel_heave, 1, c.num_channels);
        c.channel_yaw = p.integer("rc/yaw", c.channel_yaw, 1, c.num_channels);
        c.channel_surge = p.integer("rc/surge", c.channel_surge, 1, c.num_channels);
        c.dt = dt;
        acolor_ = std::make_unique<control::AcolorController>(c);
        rc_pub_ = nh.advertise<RcChannels>("rc_channels", 10);
      }
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    status_sub_ = nh.subscribe("guidance/status", 10, &ControlNodelet::onStatus, this);
    odom_sub_ = nh.subscribe("odom", 10, &ControlNodelet::onOdom, this);
    path_sub_ = nh.subscribe("guidance/planned_path", 1, &ControlNodelet::onPath, this);

    reconfigure_ = std::make_unique<dynamic_reconfigure::Server<ControlConfig>>(reconf_mutex_, pnh);
    reconfigure_->updateConfig(currentConfig());
    reconfigure_->setCallback([this](ControlConfig& c, uint32_t) { onReconfigure(c); });

    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, pnh, getName());
    updater_->setHardwareID(vehicle_ + "_control");
    updater_->add("control", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      std::lock_guard<std::mutex> l(mutex_);
      s.summary(holding_ ? diagnostic_msgs::DiagnosticStatus::WARN : diagnostic_msgs::DiagnosticStatus::OK,
                holding_ ? "neutral command: " + why_ : "controlling");
      ros_util::addCounters(s, counters_, {"stale_input", "bad_reference"});
      const Counters& core = usv_ ? usv_->counters() : g500_ ? g500_->counters() : acolor_->counters();
      ros_util::addCounters(s, core, {"nan_state", "bad_reference"});
    });
    timer_ = nh.createTimer(ros::Duration(1.0 / rate_), &ControlNodelet::onTimer, this);
    NODELET_INFO("%s control at %.1f Hz", vehicle_.c_str(), rate_);
  }

  // The reconfigure server starts from the loaded (yaml) gains, not the .cfg defaults.
  ControlConfig currentConfig() {
    ControlConfig c = ControlConfig::__getDefault__();
    if (usv_) {
      const auto& p = usv_->params();
      c.usv_surge_kp = p.surge.kp, c.usv_surge_ki = p.surge.ki, c.usv_surge_kd = p.surge.kd;
      c.usv_yaw_kp = p.yaw.kp, c.usv_yaw_ki = p.yaw.ki, c.usv_yaw_kd = p.yaw.kd;
      c.usv_tf = p.filter.tf, c.usv_xi = p.filter.xi;
    } else if (g500_) {
      const auto& p = g500_->params();
      c.g500_north_kp = p.north.kp, c.g500_north_ki = p.north.ki, c.g500_north_kd = p.north.kd;
      c.g500_east_kp = p.east.kp, c.g500_east_ki = p.east.ki, c.g500_east_kd = p.east.kd;
      c.g500_down_kp = p.down.kp, c.g500_down_ki = p.down.ki, c.g500_down_kd = p.down.kd;
      c.g500_yaw_kp = p.yaw.kp, c.g500_yaw_ki = p.yaw.ki, c.g500_yaw_kd = p.yaw.kd;
    } else {
      const auto& p = acolor_->params();
      c.acolor_yaw_kp = p.yaw.kp, c.acolor_yaw_ki = p.yaw.ki, c.acolor_yaw_kd = p.yaw.kd;
      c.acolor_heave_kp = p.heave.kp, c.acolor_surge_pwm = p.surge_pwm;
    }
    return c;
  }

  void onReconfigure(const ControlConfig& c) {
    std::lock_guard<std::mutex> l(mutex_);
    try {
      if (usv_) {
        auto p = usv_->params();
        p.surge.kp = c.usv_surge_kp, p.surge.ki = c.usv_surge_ki, p.surge.kd = c.usv_surge_kd;
        p.yaw.kp = c.usv_yaw_kp, p.yaw.ki = c.usv_yaw_ki, p.yaw.kd = c.usv_yaw_kd;
        p.filter.tf = c.usv_tf, p.filter.xi = c.usv_xi;
        usv_->setParams(p);
      } else if (g500_) {
        auto p = g500_->params();
        p.north.kp = c.g500_north_kp, p.north.ki = c.g500_north_ki, p.north.kd = c.g500_north_kd;
        p.east.kp = c.g500_east_kp, p.east.ki = c.g500_east_ki, p.east.kd = c.g500_east_kd;
        p.down.kp = c.g500_down_kp, p.down.ki = c.g500_down_ki, p.down.kd = c.g500_down_kd;
        p.yaw.kp = c.g500_yaw_kp, p.yaw.ki = c.g500_yaw_ki, p.yaw.kd = c.g500_yaw_kd;
        g500_->setParams(p);
      } else {
        auto p = acolor_->params();
        p.yaw.kp = c.acolor_yaw_kp, p.yaw.ki = c.acolor_yaw_ki, p.yaw.kd = c.acolor_yaw_kd;
        p.heave.kp = c.acolor_heave_kp, p.surge_pwm = c.acolor_surge_pwm;
        acolor_->setParams(p);
      }
    } catch (const ConfigError& e) {
      NODELET_ERROR("reconfigure rejected: %s", e.what());
    }
  }

  void onStatus(const GuidanceStatus::ConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex_);
    status_ = *m;
    status_time_ = ros::Time::now();
    have_status_ = true;
  }
  void onOdom(const nav_msgs::Odometry::ConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex_);
    state_ = ros_util::stateFromOdom(*m);
    odom_time_ = ros::Time::now();
    have_odom_ = true;
    if (state_.position.allFinite() && std::isfinite(state_.yaw)) last_good_ = state_.position;
  }
  void onPath(const nav_msgs::Path::ConstPtr& m) {
    std::lock_guard<std::mutex> l(mutex_);
    if (!m->poses.empty()) {
      const auto& q = m->poses.back().pose.position;
      path_end_ = Eigen::Vector3d(q.x, q.y, q.z);
    }
  }

  void onTimer(const ros::TimerEvent&) {
    std::lock_guard<std::mutex> l(mutex_);
    const ros::Time now = ros::Time::now();
    control::Reference r;  // idle = neutral
    holding_ = true;
    if (!have_status_ || !have_odom_) {
      why_ = "waiting for guidance status and odometry";
    } else if ((now - status_time_).toSec() > timeout_ || (now - odom_time_).toSec() > timeout_) {
      counters_.increment("stale_input");
      why_ = "guidance status or odometry stale";
      NODELET_WARN_THROTTLE(5.0, "%s: neutral command", why_.c_str());
    } else {
      // Station keeping holds the end of the planned path; a guidance fault holds the last good position.
      const Eigen::Vector3d hold =
          status_.mode == GuidanceStatus::MODE_STATION_KEEPING && path_end_.allFinite() ? path_end_ : last_good_;
      const double a = status_.path_angle;
      const Eigen::Vector3d proj =
          state_.position - status_.cross_track_error * Eigen::Vector3d(-std::sin(a), std::cos(a), 0.0);
      r = referenceFromStatus(status_, hold, proj);
      if (!r.valid()) {
        counters_.increment("bad_reference");
        NODELET_WARN_THROTTLE(5.0, "non-finite guidance reference: neutral command");
        r = control::Reference();
        why_ = "bad guidance reference";
      } else {
        holding_ = false;
      }
    }
    publish(r);
  }

  void publish(const control::Reference& r) {
    const ros::Time now = ros::Time::now();
    if (usv_) {
      const auto j = usv_->update(state_, r);
      JoystickCommand m;
      m.header.stamp = now;
      m.surge = j.surge, m.sway = j.sway, m.yaw = j.yaw;
      m.source = JoystickCommand::SOURCE_AUTONOMY;
      m.priority = JoystickCommand::PRIORITY_AUTONOMY;
      joy_pub_.publish(m);
    } else if (g500_) {
      const auto o = g500_->update(state_, r);
      ThrusterSetpoints m;
      m.header.stamp = now;
      m.thrust.assign(o.alloc.thrust.data(), o.alloc.thrust.data() + o.alloc.thrust.size());
      m.setpoint.assign(o.alloc.setpoint.data(), o.alloc.setpoint.data() + o.alloc.setpoint.size());
      m.saturated = o.alloc.saturated;
      thr_pub_.publish(m);
    } else {
      RcChannels m;
      m.header.stamp = now;
      m.channels = acolor_->update(state_, r);
      rc_pub_.publish(m);
    }
  }

  std::string vehicle_, why_;
  double rate_ = 10, timeout_ = 1;
  std::unique_ptr<control::UsvController> usv_;
  std::unique_ptr<control::Girona500Controller> g500_;
  std::unique_ptr<control::AcolorController> acolor_;
  GuidanceStatus status_;
  VehicleState state_;
  Eigen::Vector3d last_good_ = Eigen::Vector3d::Zero(), path_end_ = Eigen::Vector3d::Constant(NAN);
  ros::Time status_time_, odom_time_;
  bool have_status_ = false, have_odom_ = false, holding_ = true;
  Counters counters_;
  std::mutex mutex_;
  boost::recursive_mutex reconf_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<ControlConfig>> reconfigure_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::Publisher joy_pub_, thr_pub_, rc_pub_;
  ros::Subscriber status_sub_, odom_sub_, path_sub_;
  ros::Timer timer_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::ControlNodelet, nodelet::Nodelet)

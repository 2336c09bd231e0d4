// CanGateway: the USV's CAN <-> ROS bridge (thesis 4.3.1, the CCPilot display computer's role). Thin wrapper
// over can::CanGateway: parameters, message conversion, diagnostics; the bus is spun in its own thread.
//   in:  joystick_cmd (offshore_gnc/JoystickCommand, autonomy)        -> per-jet set-point frames on the bus
//   out: /usv_gps (NavSatFix), /usv_heading (QuaternionStamped, ENU), gps/velocity (TwistStamped, ENU),
//        waterjet/status (WaterjetStatus), waterjet/answering (WaterjetAnswering, latched: for the safety
//        supervisor's jet rule), can/bus_state (CanBusState, latched: its bus_off rule), manual_cmd
//        (JoystickCommand seen from the bridge)
#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/QuaternionStamped.h>
#include <geometry_msgs/TwistStamped.h>
#include <nodelet/nodelet.h>
#include <offshore_gnc/CanBusState.h>
#include <offshore_gnc/JoystickCommand.h>
#include <offshore_gnc/WaterjetAnswering.h>
#include <offshore_gnc/WaterjetStatus.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <sensor_msgs/NavSatFix.h>

#include <atomic>
#include <cmath>
#include <memory>
#include <thread>

#include "offshore_gnc/can/gateway.h"
#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/models/params_yaml.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/params.h"

namespace offshore_gnc {

static_assert(CanBusState::STATE_DOWN == static_cast<int>(can::BusState::kDown) &&
              CanBusState::STATE_ERROR_ACTIVE == static_cast<int>(can::BusState::kErrorActive) &&
              CanBusState::STATE_ERROR_WARNING == static_cast<int>(can::BusState::kErrorWarning) &&
              CanBusState::STATE_ERROR_PASSIVE == static_cast<int>(can::BusState::kErrorPassive) &&
              CanBusState::STATE_BUS_OFF == static_cast<int>(can::BusState::kBusOff),
              "CanBusState.msg's STATE_* must match can::BusState");

class CanGatewayNodelet : public nodelet::Nodelet {
 public:
  ~CanGatewayNodelet() override {
    stop_ = true;
    if (spinner_.joinable()) spinner_.join();
  }

 private:
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros_util::ParamReader p(getPrivateNodeHandle());
    can::SocketCanOptions bus;
    can::GatewayConfig cfg;
    models::UsvParams jets;
    try {
      can::GatewayNodeParams np;
      ros_util::readParams(p, can::GatewayNodeParams::table(), np);
      bus = np.bus;
      ros_util::readParams(p, can::GatewayConfig::table(), cfg);
      cfg.validate();
      if (!np.model_params.empty()) jets = models::loadUsvParams(np.model_params);
      gps_frame_ = np.gps_frame;
      world_frame_ = np.world_frame;
      gateway_ = std::make_unique<can::CanGateway>(bus, cfg, jets, counters_);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }

    gps_pub_ = nh.advertise<sensor_msgs::NavSatFix>("/usv_gps", 10);
    heading_pub_ = nh.advertise<geometry_msgs::QuaternionStamped>("/usv_heading", 10);
    velocity_pub_ = nh.advertise<geometry_msgs::TwistStamped>("gps/velocity", 10);
    status_pub_ = nh.advertise<offshore_gnc::WaterjetStatus>("waterjet/status", 10);
    manual_pub_ = nh.advertise<offshore_gnc::JoystickCommand>("manual_cmd", 10);
    answering_pub_ = nh.advertise<offshore_gnc::WaterjetAnswering>("waterjet/answering", 1, true);
    bus_pub_ = nh.advertise<offshore_gnc::CanBusState>("can/bus_state", 1, true);
    cmd_sub_ = nh.subscribe("joystick_cmd", 10, &CanGatewayNodelet::onCommand, this);

    outputs_.position = [this](const can::n2k::PositionRapid& v, std::uint8_t) {
      sensor_msgs::NavSatFix m;
      m.header.stamp = ros::Time::now();
      m.header.frame_id = gps_frame_;
      m.latitude = *v.lat_deg;
      m.longitude = *v.lon_deg;
      m.altitude = 0.0;  // PGN 129025 has none; 0 rather than NaN for the consumers' sake (COVARIANCE unknown)
      m.status.status = sensor_msgs::NavSatStatus::STATUS_FIX;
      m.status.service = sensor_msgs::NavSatStatus::SERVICE_GPS;
      m.position_covariance_type = sensor_msgs::NavSatFix::COVARIANCE_TYPE_UNKNOWN;
      gps_pub_.publish(m);
    };
    outputs_.heading = [this](const can::n2k::VesselHeading& v, std::uint8_t) {
      double heading = *v.heading_rad;
      if (v.reference == 1) {  // magnetic: true needs the variation
        if (!v.variation_rad) {
          counters_.increment("magnetic_heading_without_variation");
          return;
        }
        heading += *v.variation_rad;
      }
      const double yaw = geo::nedYawToEnu(heading);
      geometry_msgs::QuaternionStamped m;
      m.header.stamp = ros::Time::now();
      m.header.frame_id = world_frame_;
      m.quaternion.z = std::sin(yaw / 2.0);
      m.quaternion.w = std::cos(yaw / 2.0);
      heading_pub_.publish(m);
    };
    outputs_.cog_sog = [this](const can::n2k::CogSogRapid& v, std::uint8_t) {
      if (!v.cog_rad || !v.sog_mps) {
        counters_.increment("cog_sog_not_available");
        return;
      }
      geometry_msgs::TwistStamped m;
      m.header.stamp = ros::Time::now();
      m.header.frame_id = world_frame_;
      m.twist.linear.x = *v.sog_mps * std::sin(*v.cog_rad);  // east
      m.twist.linear.y = *v.sog_mps * std::cos(*v.cog_rad);  // north
      velocity_pub_.publish(m);
    };
    outputs_.status = [this](const can::jet::Status& s) {
      offshore_gnc::WaterjetStatus m;
      m.header.stamp = ros::Time::now();
      m.jet = s.jet;
      m.rpm = s.rpm;
      m.nozzle_position = s.nozzle;
      m.bucket_position = s.bucket;
      m.faults = s.faults;
      status_pub_.publish(m);
    };
    outputs_.manual = [this](const can::jet::Command& c) {
      offshore_gnc::JoystickCommand m;
      m.header.stamp = ros::Time::now();
      m.surge = c.surge;
      m.sway = c.sway;
      m.yaw = c.yaw;
      m.source = c.source;
      m.priority = offshore_gnc::JoystickCommand::PRIORITY_MANUAL;
      manual_pub_.publish(m);
    };

    outputs_.answering = [this](const std::array<bool, 2>& a) {
      offshore_gnc::WaterjetAnswering m;
      m.header.stamp = ros::Time::now();
      m.answering = {a[0], a[1]};
      answering_pub_.publish(m);
      for (int i = 0; i < 2; ++i)
        if (!a[i]) NODELET_ERROR("waterjet %s not answering on %s: both jets get the neutral command", can::jetName(i), iface_.c_str());
    };

    outputs_.bus_state = [this](can::BusState st) {
      offshore_gnc::CanBusState m;
      m.header.stamp = ros::Time::now();
      m.state = static_cast<std::uint8_t>(st);
      m.state_name = can::toString(st);
      bus_pub_.publish(m);
    };

    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, getPrivateNodeHandle(), getName());
    updater_->setHardwareID("can:" + bus.iface);
    updater_->add("can gateway", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      const can::BusState st = gateway_->state();
      const can::Mode mode = gateway_->mode();
      std::string silent;
      for (int i = 0; i < 2; ++i) {
        const double quiet = gateway_->jetSilentFor(i);
        const bool answering = gateway_->jetAnswering(i);
        s.add(std::string(can::jetName(i)) + "_jet", answering ? "answering" : "not answering");
        s.addf(std::string(can::jetName(i)) + "_jet_silent_s", "%.2f", quiet);
        if (!answering) silent += std::string(silent.empty() ? "" : ", ") + can::jetName(i);
      }
      if (st == can::BusState::kDown || st == can::BusState::kBusOff)
        s.summary(diagnostic_msgs::DiagnosticStatus::ERROR, std::string("bus ") + can::toString(st));
      else if (!silent.empty())
        s.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "waterjet " + silent + " not answering, " + can::toString(mode));
      else if (st != can::BusState::kErrorActive || mode == can::Mode::kWatchdog)
        s.summary(diagnostic_msgs::DiagnosticStatus::WARN,
                  std::string("bus ") + can::toString(st) + ", " + can::toString(mode));
      else
        s.summary(diagnostic_msgs::DiagnosticStatus::OK, std::string("bus ok, ") + can::toString(mode));
      s.add("bus_state", can::toString(st));
      s.add("mode", can::toString(mode));
      ros_util::addCounters(s, counters_,
                            {"wrong_dlc", "unknown_id", "bad_checksum", "out_of_range", "counter_jumps",
                             "autonomy_out_of_range", "port_jet_timeouts", "starboard_jet_timeouts", "tx_dropped"});
    });
    diag_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_->force_update(); });
    spinner_ = std::thread([this] {
      while (!stop_ && ros::ok()) gateway_->spinOnce(0.02, outputs_);
    });
    iface_ = bus.iface;
    NODELET_INFO("CAN gateway on %s: %s command frames at %.1f Hz, watchdog %.2f s, manual hold %.2f s, jet timeout %.2f s",
                 bus.iface.c_str(), cfg.command_frames.c_str(), cfg.command_rate, cfg.watchdog_timeout, cfg.manual_hold,
                 cfg.jet_timeout);
  }

  void onCommand(const offshore_gnc::JoystickCommand::ConstPtr& m) {
    if (!gateway_->onAutonomy(m->surge, m->sway, m->yaw))
      NODELET_ERROR_THROTTLE(5.0, "joystick_cmd out of range or not finite (%g, %g, %g): ignored", m->surge, m->sway,
                             m->yaw);
  }

  Counters counters_;
  std::unique_ptr<can::CanGateway> gateway_;
  can::GatewayOutputs outputs_;
  std::string gps_frame_, world_frame_, iface_;
  ros::Publisher gps_pub_, heading_pub_, velocity_pub_, status_pub_, manual_pub_, answering_pub_, bus_pub_;
  ros::Subscriber cmd_sub_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::WallTimer diag_timer_;
  std::atomic<bool> stop_{false};
  std::thread spinner_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::CanGatewayNodelet, nodelet::Nodelet)

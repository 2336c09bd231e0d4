// CanEmulator: the USV's bus devices in simulation, on a real (v)can interface: the two waterjet control
// units (act on the gateway's per-jet set-points, answer with status frames) and the GPS-compass (NMEA 2000
// from the simulator's ground truth). With it, simulated commands travel the same CAN path as on the boat.
//   in:  /usv/ground_truth/odom (nav_msgs/Odometry, map ENU / usv/base_link)
//   out: waterjet/applied_setpoints (WaterjetSetpoints the units act on; the USV simulator takes them with
//        ~jet_command_topic, driving its per-jet model)
#include <diagnostic_updater/diagnostic_updater.h>
#include <nav_msgs/Odometry.h>
#include <nodelet/nodelet.h>
#include <offshore_gnc/WaterjetSetpoints.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <tf2/utils.h>

#include <cmath>
#include <memory>
#include <mutex>
#include <optional>

#include "offshore_gnc/can/emulator.h"
#include "offshore_gnc/can/gateway.h"
#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/models/params_yaml.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/ros/site.h"

namespace offshore_gnc {

class CanEmulatorNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros_util::ParamReader p(getPrivateNodeHandle());
    can::SocketCanOptions bus;
    can::EmulatorConfig cfg;
    models::UsvParams jets;
    geo::LatLonAlt origin;  // the GPS-compass reports the simulated truth in the site's frame
    try {
      origin = ros_util::readOrigin();
      ros_util::readParams(p, can::EmulatorConfig::table(), cfg);
      bus.iface = cfg.interface;
      bus.auto_restart = false;  // a simulated device never restarts the controller
      if (!cfg.model_params.empty()) jets = models::loadUsvParams(cfg.model_params);
      jets_ = std::make_unique<can::WaterjetEmulator>(jets, cfg.command_timeout, cfg.addresses, counters_);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    local_ = std::make_unique<geo::LocalNed>(origin);
    bus_ = std::make_unique<can::SocketCan>(bus, counters_);
    if (!bus_->open()) NODELET_WARN("%s (retrying)", bus_->lastError().c_str());
    gps_ = std::make_unique<can::GpsCompassEmulator>(static_cast<std::uint8_t>(cfg.gps_address));

    applied_pub_ = nh.advertise<offshore_gnc::WaterjetSetpoints>("waterjet/applied_setpoints", 10);
    odom_sub_ = nh.subscribe("ground_truth/odom", 10, &CanEmulatorNodelet::onOdom, this);
    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, getPrivateNodeHandle(), getName());
    updater_->setHardwareID("can-emulator:" + bus.iface);
    updater_->add("can emulator", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      std::lock_guard<std::mutex> l(mutex_);
      const can::BusState st = bus_->state();
      s.summary(st == can::BusState::kErrorActive ? diagnostic_msgs::DiagnosticStatus::OK
                                                  : diagnostic_msgs::DiagnosticStatus::ERROR,
                std::string("bus ") + can::toString(st));
      ros_util::addCounters(s, counters_, {"bad_checksum", "out_of_range", "counter_jumps", "odom_invalid"});
    });
    // The bus runs on wall time like the hardware it stands for; devices answer at `rate`.
    period_ = 1.0 / cfg.rate;
    timer_ = nh.createWallTimer(ros::WallDuration(0.01), [this](const ros::WallTimerEvent&) { spin(); });
    diag_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_->force_update(); });
    NODELET_INFO("CAN emulator on %s: waterjets 0x%02X/0x%02X, GPS-compass 0x%02X at %.1f Hz", bus.iface.c_str(),
                 cfg.addresses.jet_base, cfg.addresses.jet_base + 1, cfg.gps_address, cfg.rate);
  }

  void onOdom(const nav_msgs::Odometry::ConstPtr& m) {
    const auto& q = m->pose.pose.orientation;
    const auto& pos = m->pose.pose.position;
    const double yaw_enu = tf2::getYaw(q);
    if (!std::isfinite(pos.x) || !std::isfinite(pos.y) || !std::isfinite(yaw_enu) ||
        !std::isfinite(m->twist.twist.linear.x) || !std::isfinite(m->twist.twist.linear.y)) {
      counters_.increment("odom_invalid");
      NODELET_ERROR_THROTTLE(5.0, "ground truth odometry not finite: ignored");
      return;
    }
    can::GpsCompassSample s;
    const geo::LatLonAlt g = local_->toGeodetic(geo::enuToNed(Eigen::Vector3d(pos.x, pos.y, pos.z)));
    s.lat_deg = g.lat_deg;
    s.lon_deg = g.lon_deg;
    s.heading_rad = wrapTwoPi(geo::enuYawToNed(yaw_enu));
    // Odometry twist is in the body frame (x forward, y left): rotate into ENU, then NED course.
    const double vx = m->twist.twist.linear.x, vy = m->twist.twist.linear.y;
    const double ve = vx * std::cos(yaw_enu) - vy * std::sin(yaw_enu);
    const double vn = vx * std::sin(yaw_enu) + vy * std::cos(yaw_enu);
    s.sog_mps = std::hypot(ve, vn);
    s.cog_rad = wrapTwoPi(std::atan2(ve, vn));
    std::lock_guard<std::mutex> l(mutex_);
    sample_ = s;
  }

  void spin() {
    std::lock_guard<std::mutex> l(mutex_);
    const double t = can::CanGateway::monotonic();
    bus_->poll(t);
    for (const auto& f : bus_->receive(t)) jets_->onFrame(f, t);
    if (t < next_) return;
    next_ = t + period_;
    for (const auto& f : jets_->step(t)) bus_->send(f);
    if (sample_)
      for (const auto& f : gps_->frames(*sample_)) bus_->send(f);
    bus_->flush();
    offshore_gnc::WaterjetSetpoints m;
    m.header.stamp = ros::Time::now();
    for (int i = 0; i < 2; ++i) {
      const models::JetCommand& c = jets_->applied()[i];
      m.rpm[i] = c.rpm;
      m.nozzle[i] = c.nozzle;
      m.bucket[i] = c.bucket;
      m.source[i] = jets_->appliedSource(i);
    }
    applied_pub_.publish(m);
  }

  Counters counters_;
  std::mutex mutex_;
  std::unique_ptr<geo::LocalNed> local_;
  std::unique_ptr<can::SocketCan> bus_;
  std::unique_ptr<can::WaterjetEmulator> jets_;
  std::unique_ptr<can::GpsCompassEmulator> gps_;
  std::optional<can::GpsCompassSample> sample_;
  double period_ = 0.1, next_ = 0.0;
  ros::Publisher applied_pub_;
  ros::Subscriber odom_sub_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::WallTimer timer_, diag_timer_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::CanEmulatorNodelet, nodelet::Nodelet)

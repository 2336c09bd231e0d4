// Cola2Bridge: the Girona500's COLA2 stack <-> ours (docs/hardware.md, "COLA2 mapping").
//   /auv/thruster_setpoints (ThrusterSetpoints.setpoint, -1..1, our order) -> <ns>/controller/thruster_setpoints
//     (cola2_msgs/Setpoints, COLA2's order and signs), published under COLA2's own type name and md5sum;
//   <ns>/navigator/navigation (cola2_msgs/NavSts) -> /auv/odom (map ENU / auv/base_link FLU) + TF, in our origin.
// Watchdog: `neutral_messages` zero setpoints once ours stop for `watchdog_timeout` (then silent, so that COLA2's
// own controller or teleoperation can take the thrusters). No navigation within `startup_timeout` of the start
// is a fatal error naming the topic (run it as its own process: launch/hardware_auv_girona500.launch).
#include <diagnostic_updater/diagnostic_updater.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>
#include <topic_tools/shape_shifter.h>

#include <atomic>
#include <memory>
#include <mutex>

#include "offshore_gnc/ros/conversions.h"
#include "offshore_gnc/Cola2NavSts.h"
#include "offshore_gnc/Cola2Setpoints.h"
#include "offshore_gnc/ThrusterSetpoints.h"
#include "offshore_gnc/cola2/mapping.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/ros/site.h"

namespace offshore_gnc {

class Cola2BridgeNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros_util::ParamReader p(getPrivateNodeHandle());
    geo::LatLonAlt o;
    try {
      cola2::BridgeParams bp;
      ros_util::readParams(p, cola2::BridgeParams::table(), bp);
      ns_ = bp.cola2_namespace;
      map_ = bp.mapping();
      watchdog_ = bp.watchdog_timeout;
      neutral_messages_ = bp.neutral_messages;
      startup_timeout_ = bp.startup_timeout;
      base_frame_ = bp.base_frame;
      o = ros_util::readOrigin();
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    local_ = std::make_unique<geo::LocalNed>(o);
    nav_topic_ = ns_ + "/navigator/navigation";
    setpoints_topic_ = ns_ + "/controller/thruster_setpoints";
    // COLA2's type name, our field-for-field definition (same md5sum): COLA2's tools and bags see cola2_msgs.
    shape_.morph(ros::message_traits::md5sum<Cola2Setpoints>(), "cola2_msgs/Setpoints",
                 ros::message_traits::definition<Cola2Setpoints>(), "false");
    setpoints_pub_ = shape_.advertise(nh, setpoints_topic_, 10);
    odom_pub_ = nh.advertise<nav_msgs::Odometry>("/auv/odom", 20);
    ours_sub_ = nh.subscribe("/auv/thruster_setpoints", 20, &Cola2BridgeNodelet::onOurs, this);
    nav_sub_ = nh.subscribe(nav_topic_, 20, &Cola2BridgeNodelet::onNav, this);
    started_ = ros::WallTime::now();
    timer_ = nh.createWallTimer(ros::WallDuration(0.1), [this](const ros::WallTimerEvent&) { tick(); });
    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, getPrivateNodeHandle(), getName());
    updater_->setHardwareID("cola2:" + ns_);
    updater_->add("cola2", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      std::lock_guard<std::mutex> lock(state_mutex_);
      const double nav_age = have_nav_ ? (ros::WallTime::now() - last_nav_).toSec() : -1.0;
      if (!have_nav_ || nav_age > 2.0)
        s.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "no COLA2 navigation on " + nav_topic_);
      else if (tripped_)
        s.summary(diagnostic_msgs::DiagnosticStatus::WARN, "no thruster setpoints from our control: neutral sent");
      else
        s.summary(diagnostic_msgs::DiagnosticStatus::OK, "bridging");
      s.add("navigation_age_s", nav_age);
      ros_util::addCounters(s, counters_, {"bad_setpoints", "bad_navigation"});
    });
    diag_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_->update(); });
    NODELET_INFO("COLA2 bridge: %s <- /auv/thruster_setpoints, %s -> /auv/odom", setpoints_topic_.c_str(),
                 nav_topic_.c_str());
  }

  void publish(const std::vector<double>& setpoints) {
    Cola2Setpoints m;
    m.header.stamp = ros::Time::now();
    m.setpoints = setpoints;
    const std::uint32_t n = ros::serialization::serializationLength(m);
    std::vector<std::uint8_t> buf(n);
    ros::serialization::OStream os(buf.data(), n);
    ros::serialization::serialize(os, m);
    ros::serialization::IStream is(buf.data(), n);
    std::lock_guard<std::mutex> lock(pub_mutex_);
    shape_.read(is);
    setpoints_pub_.publish(shape_);
  }

  void onOurs(const ThrusterSetpoints::ConstPtr& m) {
    const auto out = map_.apply(m->setpoint);
    if (!out) {
      counters_.increment("bad_setpoints");
      NODELET_ERROR_THROTTLE(5.0, "thruster setpoints refused: need %zu finite values, got %zu", map_.order.size(),
                             m->setpoint.size());
      return;
    }
    {
      std::lock_guard<std::mutex> lock(state_mutex_);
      last_ours_ = ros::WallTime::now();
      have_ours_ = true;
      tripped_ = false;
      neutral_left_ = 0;
    }
    counters_.increment("setpoints_forwarded");
    publish(*out);
  }

  void onNav(const Cola2NavSts::ConstPtr& m) {
    cola2::NavSts n;
    n.stamp = m->header.stamp.toSec();
    n.latitude = m->global_position.latitude;
    n.longitude = m->global_position.longitude;
    n.origin_latitude = m->origin.latitude;
    n.origin_longitude = m->origin.longitude;
    n.north = m->position.north;
    n.east = m->position.east;
    n.depth = m->position.depth;
    n.u = m->body_velocity.x;
    n.v = m->body_velocity.y;
    n.w = m->body_velocity.z;
    n.roll = m->orientation.roll;
    n.pitch = m->orientation.pitch;
    n.yaw = m->orientation.yaw;
    n.p = m->orientation_rate.roll;
    n.q = m->orientation_rate.pitch;
    n.r = m->orientation_rate.yaw;
    const auto s = cola2::toVehicleState(n, *local_);
    if (!s) {
      counters_.increment("bad_navigation");
      NODELET_WARN_THROTTLE(5.0, "COLA2 navigation with non-finite or out-of-range values ignored");
      return;
    }
    auto o = ros_util::toOdometry(*s, "map", base_frame_);
    if (o.header.stamp.isZero()) o.header.stamp = ros::Time::now();
    odom_pub_.publish(o);
    tf_.sendTransform(ros_util::toTransform(o));
    std::lock_guard<std::mutex> lock(state_mutex_);
    last_nav_ = ros::WallTime::now();
    have_nav_ = true;
    counters_.increment("navigation_messages");
  }

  void tick() {
    if (!have_nav_ && startup_timeout_ > 0 && (ros::WallTime::now() - started_).toSec() > startup_timeout_ &&
        !failed_) {
      failed_ = true;
      NODELET_FATAL("COLA2 bridge: no COLA2 navigation on %s within %.0f s; is COLA2's navigator running on this "
                    "master (cola2_namespace '%s')?", nav_topic_.c_str(), startup_timeout_, ns_.c_str());
      ros::requestShutdown();
      return;
    }
    bool send = false;
    {
      std::lock_guard<std::mutex> lock(state_mutex_);
      if (have_ours_ && !tripped_ && (ros::WallTime::now() - last_ours_).toSec() > watchdog_) {
        tripped_ = true;
        neutral_left_ = neutral_messages_;
        counters_.increment("watchdog_trips");
        NODELET_WARN("no thruster setpoints for %.1f s: sending zero to COLA2's thrusters", watchdog_);
      }
      if (neutral_left_ > 0) {
        --neutral_left_;
        send = true;
      }
    }
    if (send) publish(std::vector<double>(map_.order.size(), 0.0));
  }

  std::string ns_, nav_topic_, setpoints_topic_, base_frame_;
  cola2::ThrusterMapping map_;
  double watchdog_ = 1.0, startup_timeout_ = 10.0;
  int neutral_messages_ = 5, neutral_left_ = 0;
  std::unique_ptr<geo::LocalNed> local_;
  std::mutex pub_mutex_, state_mutex_;
  topic_tools::ShapeShifter shape_;
  ros::Publisher setpoints_pub_, odom_pub_;
  ros::Subscriber ours_sub_, nav_sub_;
  tf2_ros::TransformBroadcaster tf_;
  ros::WallTime started_, last_ours_, last_nav_;
  bool have_ours_ = false, tripped_ = false, failed_ = false;
  std::atomic<bool> have_nav_{false};
  Counters counters_;
  ros::WallTimer timer_, diag_timer_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::Cola2BridgeNodelet, nodelet::Nodelet)

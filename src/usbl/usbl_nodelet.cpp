// USBL node: runs usbl::TransceiverSession on the serial line (pings to the AUV's SeaTrac beacon, the acoustic
// data channel), decodes the replies and publishes each fix with the AUV's position in map_ned and WGS84,
// geo-referenced by usbl::Positioner with the USV's GPS position and heading at the time of the fix (buffered
// /usv_gps, /usv_heading) and the transceiver's mounting. Thin: parameters, the I/O thread, messages.
#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/QuaternionStamped.h>
#include <nodelet/nodelet.h>
#include <offshore_gnc/UsblFix.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/NavSatFix.h>
#include <std_msgs/UInt8MultiArray.h>

#include <atomic>
#include <deque>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/ros/site.h"
#include "offshore_gnc/usbl/positioning.h"
#include "offshore_gnc/usbl/seatrac.h"
#include "offshore_gnc/serial/serial_port.h"
#include "offshore_gnc/usbl/session.h"
#include "ros_usbl.h"

namespace offshore_gnc {

class UsblNodelet : public nodelet::Nodelet {
 public:
  ~UsblNodelet() override {
    running_ = false;
    if (io_.joinable()) io_.join();
  }

 private:
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros_util::ParamReader p(getPrivateNodeHandle());
    usbl::QualityLimits lim;
    geo::LatLonAlt o;
    try {
      usbl::UsblNodeParams np;
      ros_util::readParams(p, usbl::UsblNodeParams::table(), np);
      retry_ = np.reconnect_period;
      usbl::SessionParams sp;
      ros_util::readParams(p, usbl::SessionParams::table(), sp);
      session_ = std::make_unique<usbl::TransceiverSession>(sp);
      ros_util::readParams(p, usbl::qualityLimitsTable(), lim);
      pressure_ = np.pressure;
      frame_id_ = np.frame_id;
      o = ros_util::readOrigin();
      positioner_ = std::make_unique<usbl::Positioner>(usbl_ros::readMounting(p), lim);
      port_ = std::make_unique<serial::SerialPort>(np.port, np.baud, retry_);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    local_ = std::make_unique<geo::LocalNed>(o);

    fix_pub_ = nh.advertise<offshore_gnc::UsblFix>("/auv/usbl/fix", 10);
    gps_sub_ = nh.subscribe("/usv_gps", 20, &UsblNodelet::onGps, this);
    heading_sub_ = nh.subscribe("/usv_heading", 20, &UsblNodelet::onHeading, this);
    pressure_sub_ = nh.subscribe("/auv/pressure", 20, &UsblNodelet::onPressure, this);
    // Acoustic data channel: packets out with DAT_SEND (REQ: the remote answers with its queued packet),
    // DAT_RECEIVE payloads in.
    data_in_pub_ = nh.advertise<std_msgs::UInt8MultiArray>("/auv/usbl/data_in", 10);
    data_out_sub_ = nh.subscribe("/auv/usbl/data_out", 10, &UsblNodelet::onDataOut, this);

    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, getPrivateNodeHandle(), getName());
    updater_->setHardwareID("seatrac:" + port_->path());
    updater_->add("usbl", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      if (port_open_)
        s.summary(diagnostic_msgs::DiagnosticStatus::OK, "serial open");
      else
        s.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "serial closed: " + last_port_error());
      ros_util::addCounters(s, counters_, {"bad_gps", "bad_heading", "bad_pressure"});
      {
        std::lock_guard<std::mutex> lock(session_mutex_);
        ros_util::addCounters(s, session_->counters(), {"ping_errors", "no_reply", "data_too_long", "data_dropped"});
      }
      ros_util::addCounters(s, port_->counters(), {"hangups", "io_errors"});
      ros_util::addCounters(s, decoder_.counters(),
                            {"bad_crc", "odd_hex_length", "non_hex", "unknown_cid", "truncated", "trailing_bytes",
                             "too_many_channels", "line_too_long", "bad_value"});
      std::lock_guard<std::mutex> lock(mutex_);
      ros_util::addCounters(s, positioner_->counters());
    });
    // fixes whose USV pose never comes (relay down) leave the queue as stale after max_pose_wait
    pending_timer_ = nh.createTimer(ros::Duration(0.2), [this](const ros::TimerEvent&) {
      std::lock_guard<std::mutex> lock(pending_mutex_);
      flushPending();
    });
    diag_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_->update(); });
    running_ = true;
    io_ = std::thread([this] { ioLoop(); });
    NODELET_INFO("USBL on %s: pinging beacon %d every %.2f s", port_->path().c_str(), session_->params().remote_id,
                 1.0 / session_->params().ping_rate);
  }

  std::string last_port_error() {
    std::lock_guard<std::mutex> lock(err_mutex_);
    return last_error_;
  }

  // The only thread touching the serial port: reads replies into the session, writes what it says is due.
  void ioLoop() {
    std::uint8_t buf[512];
    std::vector<usbl::StreamDecoder::Event> events;
    while (running_ && ros::ok()) {
      const std::size_t n = port_->read(buf, sizeof buf, 20);
      const bool open = port_->isOpen();
      if (open != port_open_) {
        port_open_ = open;
        if (!open) NODELET_WARN("serial %s lost (%s); reopening", port_->path().c_str(), port_->lastError().c_str());
        else NODELET_INFO("serial %s open", port_->path().c_str());
      }
      if (!open) {
        std::lock_guard<std::mutex> lock(err_mutex_);
        last_error_ = port_->lastError();
        NODELET_WARN_THROTTLE(10.0, "serial %s not available (%s); retrying every %.1f s", port_->path().c_str(),
                              last_error_.c_str(), retry_);
      }
      const ros::Time now = ros::Time::now();
      if (n > 0) {
        events.clear();
        decoder_.feed(buf, n, events);
        for (const auto& e : events) handle(e, now);
      }
      if (!port_->isOpen()) continue;
      std::optional<usbl::Message> m;
      {
        std::lock_guard<std::mutex> lock(session_mutex_);
        m = session_->due(now.toSec());
      }
      if (m && port_->write(usbl::encodeFrame(*m))) {
        std::lock_guard<std::mutex> lock(session_mutex_);
        session_->sent(*m, now.toSec());
      }
    }
  }

  void handle(const usbl::StreamDecoder::Event& e, const ros::Time& now) {
    if (!e.message) {
      NODELET_WARN_THROTTLE(5.0, "USBL frame rejected (%s): %.60s", e.reason.c_str(), e.line.c_str());
      return;
    }
    if (auto st = std::get_if<usbl::StatusReply>(&e.message->body); st && st->status != usbl::kStatusOk)
      NODELET_WARN_THROTTLE(5.0, "%s refused with status 0x%02X", usbl::cidName(st->cid), st->status);
    usbl::SessionEvent ev;
    {
      std::lock_guard<std::mutex> lock(session_mutex_);
      ev = session_->handle(e, now.toSec());
    }
    if (ev.kind == usbl::SessionEvent::kData) {
      std_msgs::UInt8MultiArray m;
      m.data = ev.data;
      data_in_pub_.publish(m);
    }
    if (ev.kind != usbl::SessionEvent::kNone) publishFix(ev.fix, now);
  }

  // A fix waits (in arrival order) until the USV's relayed GPS and heading have reached its time: they come
  // over the relay, later than the reply. Called on each reply and each GPS / heading sample.
  void publishFix(const usbl::AcoFix& f, const ros::Time& now) {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    pending_.emplace_back(f, now);
    flushPending();
  }
  void flushPending() {  // pending_mutex_ held
    while (!pending_.empty()) {
      bool ready;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        ready = positioner_->ready(pending_.front().second.toSec(), ros::Time::now().toSec());
      }
      if (!ready) return;
      place(pending_.front().first, pending_.front().second);
      pending_.pop_front();
    }
  }

  void place(const usbl::AcoFix& f, const ros::Time& now) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    usbl::FixResult r;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      r = positioner_->process(f, now.toSec(), ros::Time::now().toSec());
    }
    offshore_gnc::UsblFix m;
    m.header.stamp = ros::Time(std::max(0.0, r.stamp));
    m.header.frame_id = frame_id_;
    m.local_beacon_id = f.dest_id;
    m.remote_beacon_id = f.src_id;
    m.flags = f.flags;
    m.quality = r.quality;
    const bool ranged = f.has(usbl::AcoFix::RANGE), angled = f.has(usbl::AcoFix::USBL);
    m.range = ranged ? f.rangeM() : nan;
    m.range_time = ranged ? f.rangeTimeS() : nan;
    m.azimuth = angled ? f.azimuthRad() : nan;
    m.elevation = angled ? f.elevationRad() : nan;
    m.fit_error = angled ? f.fitError() : nan;
    m.rssi = f.rssi * 0.1;
    m.sound_speed = f.vos * 0.1;
    m.local_depth = f.depth_local * 0.1;
    m.local_yaw = deg2rad(f.yaw * 0.1);
    m.local_pitch = deg2rad(f.pitch * 0.1);
    m.local_roll = deg2rad(f.roll * 0.1);
    auto set = [](geometry_msgs::Point& pt, const std::optional<Eigen::Vector3d>& v) {
      pt.x = v ? v->x() : nan;
      pt.y = v ? v->y() : nan;
      pt.z = v ? v->z() : nan;
    };
    set(m.position_local, r.local);
    set(m.position_ned, r.ned);
    m.latitude = m.longitude = nan;
    if (r.ned) {
      const geo::LatLonAlt g = local_->toGeodetic(*r.ned);
      m.latitude = g.lat_deg;
      m.longitude = g.lon_deg;
    }
    if (r.quality != usbl::Q_OK)
      NODELET_WARN_THROTTLE(5.0, "USBL fix rejected: %s", usbl::qualityName(r.quality));
    fix_pub_.publish(m);
  }

  void onDataOut(const std_msgs::UInt8MultiArray& m) {
    std::lock_guard<std::mutex> lock(session_mutex_);
    if (!session_->queueData(m.data))
      NODELET_WARN_THROTTLE(5.0, "acoustic packet of %zu bytes dropped (1..%zu)", m.data.size(), usbl::kMaxDataPacket);
  }

  void onGps(const sensor_msgs::NavSatFix& g) {
    if (g.status.status < sensor_msgs::NavSatStatus::STATUS_FIX || !std::isfinite(g.latitude) ||
        !std::isfinite(g.longitude) || !std::isfinite(g.altitude)) {
      counters_.increment("bad_gps");
      NODELET_WARN_THROTTLE(5.0, "ignoring /usv_gps without a valid fix");
      return;
    }
    const Eigen::Vector3d ned = local_->toNed({g.latitude, g.longitude, g.altitude});
    {
      std::lock_guard<std::mutex> lock(mutex_);
      positioner_->addUsvPosition(g.header.stamp.toSec(), ned);
    }
    std::lock_guard<std::mutex> lock(pending_mutex_);
    flushPending();
  }

  void onHeading(const geometry_msgs::QuaternionStamped& q) {
    const Eigen::Quaterniond e(q.quaternion.w, q.quaternion.x, q.quaternion.y, q.quaternion.z);
    if (!std::isfinite(e.norm()) || std::abs(e.norm() - 1.0) > 0.01) {
      counters_.increment("bad_heading");
      NODELET_WARN_THROTTLE(5.0, "ignoring /usv_heading with a non-unit quaternion");
      return;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      positioner_->addUsvAttitude(q.header.stamp.toSec(), usbl::enuFluToNedFrd(e));
    }
    std::lock_guard<std::mutex> lock(pending_mutex_);
    flushPending();
  }

  void onPressure(const sensor_msgs::FluidPressure& p) {
    if (!std::isfinite(p.fluid_pressure)) {
      counters_.increment("bad_pressure");
      return;
    }
    const double depth = pressure_.depthOf(p.fluid_pressure);
    std::lock_guard<std::mutex> lock(mutex_);
    positioner_->addRemoteDepth(p.header.stamp.toSec(), depth);
  }

  std::mutex session_mutex_;  // session (the I/O thread vs the data_out callback)
  std::unique_ptr<usbl::TransceiverSession> session_;
  ros::Publisher data_in_pub_;
  ros::Subscriber data_out_sub_;
  double retry_ = 1.0;
  geo::PressureDepth pressure_;
  std::string frame_id_;
  std::unique_ptr<geo::LocalNed> local_;
  std::unique_ptr<serial::SerialPort> port_;
  usbl::StreamDecoder decoder_;
  std::mutex mutex_;  // positioner (ROS callbacks vs the I/O thread)
  std::mutex pending_mutex_;  // fixes waiting for the USV's pose (taken before mutex_, never inside it)
  std::deque<std::pair<usbl::AcoFix, ros::Time>> pending_;
  ros::Timer pending_timer_;
  std::unique_ptr<usbl::Positioner> positioner_;
  Counters counters_;
  std::atomic<bool> running_{false}, port_open_{false};
  std::mutex err_mutex_;
  std::string last_error_;
  std::thread io_;
  ros::Publisher fix_pub_;
  ros::Subscriber gps_sub_, heading_sub_, pressure_sub_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::WallTimer diag_timer_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::UsblNodelet, nodelet::Nodelet)

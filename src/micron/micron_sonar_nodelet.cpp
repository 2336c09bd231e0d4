// MicronSonar: the Tritech Micron on its serial line -> /auv/sonar/beam (offshore_gnc/SonarBeam, frame
// auv/sonar), the head's mounting as a static transform, diagnostics (state, head info, counters). Thin wrapper:
// the protocol and its recovery are micron::Session, the line is serial::SerialPort (reopens a vanished device),
// the parameters micron::DriverConfig's table.
// The device must exist when the node starts (within `device_wait`): a missing port is a clear fatal error naming
// it. Run it as its own process (`nodelet standalone`): the wait must not hold up a shared manager's loading.
#include <diagnostic_updater/diagnostic_updater.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <chrono>
#include <memory>
#include <mutex>

#include "offshore_gnc/ros/conversions.h"
#include "offshore_gnc/SonarBeam.h"
#include "offshore_gnc/micron/session.h"
#include "offshore_gnc/ros/device_node.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/serial/serial_port.h"

namespace offshore_gnc {

class MicronSonarNodelet : public nodelet::Nodelet {
  // Device time: the head runs on the wall clock, also under simulated /clock.
  static double monotonic() { return serial::monotonic(); }

  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    try {
      ros_util::readParams(ros_util::ParamReader(getPrivateNodeHandle()), micron::DriverConfig::table(), cfg_);
      cfg_.sonar.validate();
      session_ = std::make_unique<micron::Session>(cfg_.sonar);
      port_ = std::make_unique<serial::SerialPort>(cfg_.port, cfg_.baud, cfg_.reconnect_period);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    // A hardware node that cannot find its device at start fails at once, naming it (a device lost later is
    // reopened every reconnect_period).
    // (USB adapters can take a moment to enumerate: up to device_wait seconds.)
    const double give_up = monotonic() + cfg_.device_wait;
    while (!port_->ensureOpen() && monotonic() < give_up && ros::ok()) ros::WallDuration(0.1).sleep();
    if (!port_->isOpen()) {
      NODELET_FATAL("Micron sonar: cannot open serial device '%s' (%s); check the cable / USB adapter and the "
                    "'port' parameter", port_->path().c_str(), port_->lastError().c_str());
      throw std::runtime_error("Micron sonar device missing: " + port_->path());
    }
    beam_pub_ = nh.advertise<SonarBeam>("/auv/sonar/beam", 50);
    if (cfg_.publish_mount_tf) {  // the head's axes are the body's (FRD), only offset
      const Eigen::Isometry3d mount(Eigen::Translation3d(cfg_.mount[0], cfg_.mount[1], cfg_.mount[2]));
      static_tf_.sendTransform(ros_util::mountTransform(cfg_.base_frame, cfg_.frame_id, mount));
    }
    diag_ = std::make_unique<ros_util::WallDiagnostics>(
        nh, getPrivateNodeHandle(), getName(), "tritech_micron:" + port_->path(), "micron",
        [this](diagnostic_updater::DiagnosticStatusWrapper& s) { diagnose(s); });
    io_.start([this] { ioRound(); });
    const auto& st = session_->settings();
    NODELET_INFO("Micron sonar on %s: %.1f m, %.0f deg sector, %.2f deg step, %d bins", port_->path().c_str(), st.range,
                 rad2deg(st.sector), rad2deg(st.step), st.bins);
  }

  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& s) {
    std::lock_guard<std::mutex> lock(mutex_);
    const double now = monotonic();
    const auto state = session_->state();
    if (!port_->isOpen())
      s.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "serial closed: " + port_->lastError());
    else if (session_->silent(now))
      s.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "no packet from the head (power, wiring, baud rate?)");
    else if (state != micron::Session::State::Scanning)
      s.summary(diagnostic_msgs::DiagnosticStatus::WARN, micron::Session::stateName(state));
    else
      s.summary(diagnostic_msgs::DiagnosticStatus::OK, "scanning");
    s.add("state", micron::Session::stateName(state));
    s.add("head_inf", static_cast<int>(session_->lastAlive().head_inf));
    s.add("software_version", static_cast<int>(session_->version().software_version));
    ros_util::addCounters(s, session_->counters(), {"data_timeouts", "reconfigures", "head_resets", "motor_errors",
                                                    "power_loss", "empty_beams"});
    ros_util::addCounters(s, session_->decoderCounters(),
                          {"garbage_bytes", "bad_hex_length", "length_mismatch", "too_short", "too_long",
                           "bad_terminator"});
    ros_util::addCounters(s, port_->counters(), {"hangups", "io_errors"});
  }

  static std::uint32_t timeOfDayMs() {
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(
        std::chrono::system_clock::now().time_since_epoch()).count();
    return static_cast<std::uint32_t>(ms % 86400000);
  }

  // A round of the only thread touching the serial line.
  void ioRound() {
    std::uint8_t buf[2048];
    beams_.clear();
    ros::Time stamp;
    {
      // Held while reading (10 ms at most): diagnostics see a consistent port and session.
      std::lock_guard<std::mutex> lock(mutex_);
      const std::size_t n = port_->read(buf, sizeof buf, 10);
      stamp = ros::Time::now();
      const double now = monotonic();
      const bool open = port_->isOpen();
      if (open != was_open_) {
        if (!open) NODELET_WARN("Micron serial %s lost (%s); reopening", port_->path().c_str(), port_->lastError().c_str());
        else NODELET_INFO("Micron serial %s open again; restarting the head", port_->path().c_str());
        if (open) session_->reset();
        was_open_ = open;
      }
      if (n > 0) session_->feed(buf, n, now, beams_);
      if (open) {
        const std::string out = session_->poll(now, timeOfDayMs());
        if (!out.empty()) port_->write(out);
      }
    }
    for (const auto& b : beams_) publish(b, stamp);
  }

  void publish(const micron::Beam& b, const ros::Time& stamp) {
    SonarBeam m;
    m.header.stamp = stamp;
    m.header.frame_id = cfg_.frame_id;
    m.bearing = b.bearing;
    m.beam_width = b.beam_width;
    m.range_resolution = b.range_resolution;
    m.range_offset = b.range_offset;
    m.head_status = b.status;
    m.intensities = b.intensities;
    beam_pub_.publish(m);
  }

  micron::DriverConfig cfg_;
  std::mutex mutex_;  // session and port state: I/O thread vs diagnostics
  std::unique_ptr<micron::Session> session_;
  std::unique_ptr<serial::SerialPort> port_;
  std::vector<micron::Beam> beams_;  // the I/O thread's
  bool was_open_ = true;             // the I/O thread's
  ros::Publisher beam_pub_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
  std::unique_ptr<ros_util::WallDiagnostics> diag_;
  ros_util::IoThread io_;  // last: stopped before the members its rounds use go
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::MicronSonarNodelet, nodelet::Nodelet)

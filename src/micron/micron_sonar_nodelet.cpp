// MicronSonar: the Tritech Micron on its serial line -> /auv/sonar/beam (offshore_gnc/SonarBeam, frame
// auv/sonar), the head's mounting as a static transform, diagnostics (state, head info, counters). Thin wrapper:
// the protocol and its recovery are micron::Session, the line is usbl::SerialPort (reopens a vanished device).
// The device must exist when the node starts (within `device_wait`): a missing port is a clear fatal error naming
// it. Run it as its own process (`nodelet standalone`): the wait must not hold up a shared manager's loading.
#include <diagnostic_updater/diagnostic_updater.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <mutex>
#include <thread>

#include "offshore_gnc/ros/conversions.h"
#include "offshore_gnc/SonarBeam.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/sim/sensors.h"
#include "offshore_gnc/usbl/serial_port.h"
#include "ros_micron.h"

namespace offshore_gnc {

class MicronSonarNodelet : public nodelet::Nodelet {
 public:
  ~MicronSonarNodelet() override {
    running_ = false;
    if (io_.joinable()) io_.join();
  }

 private:
  static double monotonic() { return micron_ros::monotonic(); }

  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros_util::ParamReader p(getPrivateNodeHandle());
    Eigen::Vector3d mount;
    try {
      const std::string port = p.text("port", "/dev/ttyUSB1");
      const int baud = p.integer("baud", 115200, 9600, 230400);
      retry_ = p.number("reconnect_period", 1.0, 0.05, 60);
      session_ = std::make_unique<micron::Session>(micron_ros::readSettings(p));
      frame_id_ = p.text("frame_id", "auv/sonar");
      base_frame_ = p.text("base_frame", "auv/base_link");
      const auto m = p.numbers("mount", {0.6, 0.0, -0.2}, 3, -10, 10);  // head in body FRD [m]
      mount = {m[0], m[1], m[2]};
      publish_mount_ = p.flag("publish_mount_tf", true);
      device_wait_ = p.number("device_wait", 3.0, 0, 120);
      port_ = std::make_unique<usbl::SerialPort>(port, baud, retry_);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    // A hardware node that cannot find its device at start fails at once, naming it (a device lost later is
    // reopened every reconnect_period).
    // (USB adapters can take a moment to enumerate: up to device_wait seconds.)
    const double give_up = monotonic() + device_wait_;
    while (!port_->ensureOpen() && monotonic() < give_up && ros::ok()) ros::WallDuration(0.1).sleep();
    if (!port_->isOpen()) {
      NODELET_FATAL("Micron sonar: cannot open serial device '%s' (%s); check the cable / USB adapter and the "
                    "'port' parameter", port_->path().c_str(), port_->lastError().c_str());
      throw std::runtime_error("Micron sonar device missing: " + port_->path());
    }
    beam_pub_ = nh.advertise<SonarBeam>("/auv/sonar/beam", 50);
    if (publish_mount_) static_tf_.sendTransform(ros_util::mountTransform(base_frame_, frame_id_, sim::sensorMount(mount, 0.0, true)));
    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, getPrivateNodeHandle(), getName());
    updater_->setHardwareID("tritech_micron:" + port_->path());
    updater_->add("micron", [this](diagnostic_updater::DiagnosticStatusWrapper& s) { diagnose(s); });
    diag_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_->update(); });
    running_ = true;
    io_ = std::thread([this] { ioLoop(); });
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

  // The only thread touching the serial line.
  void ioLoop() {
    std::uint8_t buf[2048];
    std::vector<micron::Beam> beams;
    bool was_open = true;
    while (running_ && ros::ok()) {
      beams.clear();
      ros::Time stamp;
      {
        // Held while reading (10 ms at most): diagnostics see a consistent port and session.
        std::lock_guard<std::mutex> lock(mutex_);
        const std::size_t n = port_->read(buf, sizeof buf, 10);
        stamp = ros::Time::now();
        const double now = monotonic();
        const bool open = port_->isOpen();
        if (open != was_open) {
          if (!open) NODELET_WARN("Micron serial %s lost (%s); reopening", port_->path().c_str(), port_->lastError().c_str());
          else NODELET_INFO("Micron serial %s open again; restarting the head", port_->path().c_str());
          if (open) session_->reset();
          was_open = open;
        }
        if (n > 0) session_->feed(buf, n, now, beams);
        if (open) {
          const std::string out = session_->poll(now, timeOfDayMs());
          if (!out.empty()) port_->write(out);
        }
      }
      for (const auto& b : beams) publish(b, stamp);
    }
  }

  void publish(const micron::Beam& b, const ros::Time& stamp) {
    SonarBeam m;
    m.header.stamp = stamp;
    m.header.frame_id = frame_id_;
    m.bearing = b.bearing;
    m.beam_width = b.beam_width;
    m.range_resolution = b.range_resolution;
    m.range_offset = b.range_offset;
    m.head_status = b.status;
    m.intensities = b.intensities;
    beam_pub_.publish(m);
  }

  double retry_ = 1.0, device_wait_ = 3.0;
  bool publish_mount_ = true;
  std::string frame_id_, base_frame_;
  std::mutex mutex_;  // session and port state: I/O thread vs diagnostics
  std::unique_ptr<micron::Session> session_;
  std::unique_ptr<usbl::SerialPort> port_;
  std::atomic<bool> running_{false};
  std::thread io_;
  ros::Publisher beam_pub_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::WallTimer diag_timer_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::MicronSonarNodelet, nodelet::Nodelet)

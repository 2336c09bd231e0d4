// MicronEmulator: a Tritech Micron on a pseudo-terminal. The MicronSonar driver opens `port` (a symlink to the
// pty's slave) as if it were the head's serial line; the bytes are answered by micron::HeadEmulator, which draws
// each beam with the simulator's sonar model from the scenario's world and the AUV's ground truth.
#include <diagnostic_updater/diagnostic_updater.h>
#include <nav_msgs/Odometry.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <poll.h>
#include <pty.h>
#include <ros/ros.h>
#include <termios.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <memory>
#include <mutex>
#include <thread>

#include "offshore_gnc/micron/emulator.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/sim/scenario.h"
#include "ros_micron.h"

namespace offshore_gnc {

class MicronEmulatorNodelet : public nodelet::Nodelet {
 public:
  ~MicronEmulatorNodelet() override {
    running_ = false;
    if (io_.joinable()) io_.join();
    if (master_ >= 0) ::close(master_);
    if (slave_ >= 0) ::close(slave_);
    if (!link_.empty()) ::unlink(link_.c_str());
  }

 private:
  static double monotonic() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  }

  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros_util::ParamReader p(getPrivateNodeHandle());
    micron::EmulatorConfig cfg;
    sim::World world;
    try {
      link_ = p.text("port", "/tmp/micron_sim");
      const std::string scenario = p.text("scenario", "");
      if (scenario.empty()) throw ConfigError("parameter '~scenario' (the world the emulated head sees) is missing");
      world = sim::loadScenario(scenario).world;
      cfg.geometry = micron_ros::readGeometry(p);
      cfg.sound_speed = p.number("sound_speed", cfg.sound_speed, 1300, 1700);
      cfg.recentre_time = p.number("recentre_time", cfg.recentre_time, 0, 60);
      cfg.ping_period = p.number("ping_period", cfg.ping_period, 0.001, 5);
      cfg.model.noise_level = p.number("noise_level", cfg.model.noise_level, 0, 255);
      const auto m = p.numbers("mount", {0.6, 0.0, -0.2}, 3, -10, 10);  // the same head mount as the driver's
      cfg.model.mount = {m[0], m[1], m[2]};
      cfg.seed = static_cast<std::uint64_t>(p.integer("seed", 1, 0, 1 << 30));
      emu_ = std::make_unique<micron::HeadEmulator>(cfg, world);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    if (::openpty(&master_, &slave_, nullptr, nullptr, nullptr) != 0) {
      NODELET_FATAL("openpty failed: %s", std::strerror(errno));
      throw std::runtime_error("openpty failed");
    }
    termios t{};
    tcgetattr(slave_, &t);
    cfmakeraw(&t);  // binary protocol: nothing may be translated or echoed
    tcsetattr(slave_, TCSANOW, &t);
    char name[256] = {};
    ttyname_r(slave_, name, sizeof name);
    ::unlink(link_.c_str());
    if (::symlink(name, link_.c_str()) != 0) {
      NODELET_FATAL("cannot create %s -> %s: %s", link_.c_str(), name, std::strerror(errno));
      throw std::runtime_error("symlink failed");
    }
    truth_sub_ = nh.subscribe("/auv/ground_truth/odom", 20, &MicronEmulatorNodelet::onTruth, this);
    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, getPrivateNodeHandle(), getName());
    updater_->setHardwareID("micron_emulator:" + link_);
    updater_->add("micron_emulator", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      s.summary(diagnostic_msgs::DiagnosticStatus::OK, "emulating on " + link_);
      ros_util::addCounters(s, emu_->counters(), {"bad_head_commands", "no_vehicle_state"});
      ros_util::addCounters(s, emu_->decoder().counters(), {"garbage_bytes", "bad_terminator", "length_mismatch"});
      ros_util::addCounters(s, counters_, {"write_errors", "bad_ground_truth"});
    });
    diag_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_->update(); });
    running_ = true;
    io_ = std::thread([this] { ioLoop(); });
    NODELET_INFO("Micron emulator on %s (%s), %zu targets in the world", link_.c_str(), name, world.targets.size());
  }

  void onTruth(const nav_msgs::Odometry& o) {
    VehicleState s;
    if (!micron_ros::toVehicleState(o, s)) return counters_.increment("bad_ground_truth");
    std::lock_guard<std::mutex> lock(mutex_);
    emu_->setVehicle(s);
  }

  void write(const std::string& s) {
    if (!s.empty() && ::write(master_, s.data(), s.size()) != static_cast<ssize_t>(s.size()))
      counters_.increment("write_errors");
  }

  void ioLoop() {
    std::uint8_t buf[512];
    while (running_ && ros::ok()) {
      pollfd pfd{master_, POLLIN, 0};
      std::string out;
      const bool readable = ::poll(&pfd, 1, 2) > 0 && (pfd.revents & POLLIN);
      const ssize_t n = readable ? ::read(master_, buf, sizeof buf) : 0;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        const double now = monotonic();
        if (n > 0) out = emu_->receive(buf, static_cast<std::size_t>(n), now);
        out += emu_->poll(now);
      }
      write(out);
    }
  }

  std::string link_;
  int master_ = -1, slave_ = -1;
  std::mutex mutex_;
  std::unique_ptr<micron::HeadEmulator> emu_;
  Counters counters_;
  std::atomic<bool> running_{false};
  std::thread io_;
  ros::Subscriber truth_sub_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::WallTimer diag_timer_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::MicronEmulatorNodelet, nodelet::Nodelet)

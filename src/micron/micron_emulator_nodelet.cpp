// MicronEmulator: a Tritech Micron on a pseudo-terminal. The MicronSonar driver opens `port` (a symlink to the
// pty's slave) as if it were the head's serial line; the bytes are answered by micron::HeadEmulator, which draws
// each beam with the simulator's sonar model from the scenario's world and the AUV's ground truth.
#include <diagnostic_updater/diagnostic_updater.h>
#include <nav_msgs/Odometry.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>

#include <atomic>
#include <memory>
#include <mutex>
#include <thread>

#include "offshore_gnc/micron/emulator.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/sim/scenario.h"
#include "offshore_gnc/usbl/pseudo_terminal.h"
#include "ros_micron.h"

namespace offshore_gnc {

class MicronEmulatorNodelet : public nodelet::Nodelet {
 public:
  ~MicronEmulatorNodelet() override {
    running_ = false;
    if (io_.joinable()) io_.join();
  }

 private:
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
    try {
      pty_ = std::make_unique<usbl::PseudoTerminal>(link_);
    } catch (const std::runtime_error& e) {
      NODELET_FATAL("%s", e.what());
      throw;
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
    NODELET_INFO("Micron emulator on %s (%s), %zu targets in the world", link_.c_str(), pty_->slaveName().c_str(),
                 world.targets.size());
  }

  void onTruth(const nav_msgs::Odometry& o) {
    VehicleState s;
    if (!micron_ros::toVehicleState(o, s)) return counters_.increment("bad_ground_truth");
    std::lock_guard<std::mutex> lock(mutex_);
    emu_->setVehicle(s);
  }

  void ioLoop() {
    std::uint8_t buf[512];
    while (running_ && ros::ok()) {
      const std::size_t n = pty_->read(buf, sizeof buf, 2);
      std::string out;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        const double now = micron_ros::monotonic();
        if (n > 0) out = emu_->receive(buf, n, now);
        out += emu_->poll(now);
      }
      if (!pty_->write(out)) counters_.increment("write_errors");
    }
  }

  std::string link_;
  std::unique_ptr<usbl::PseudoTerminal> pty_;
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

// MicronEmulator: a Tritech Micron on a pseudo-terminal. The MicronSonar driver opens `port` (a symlink to the
// pty's slave) as if it were the head's serial line; the bytes are answered by micron_sim::HeadEmulator, which
// draws each beam with the simulator's sonar model from the scenario's world and the AUV's ground truth.
#include <nav_msgs/Odometry.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <tf2/LinearMath/Matrix3x3.h>
#include <tf2/LinearMath/Quaternion.h>

#include <cmath>
#include <memory>
#include <mutex>

#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/micron_sim/emulator.h"
#include "offshore_gnc/ros/device_node.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/serial/pseudo_terminal.h"
#include "offshore_gnc/serial/serial_port.h"
#include "offshore_gnc/sim/scenario.h"

namespace offshore_gnc {

class MicronEmulatorNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    micron_sim::EmulatorConfig cfg;
    sim::World world;
    try {
      ros_util::readParams(ros_util::ParamReader(getPrivateNodeHandle()), micron_sim::EmulatorConfig::table(), cfg);
      if (cfg.scenario.empty()) throw ConfigError("parameter '~scenario' (the world the emulated head sees) is missing");
      world = sim::loadScenario(cfg.scenario).world;
      emu_ = std::make_unique<micron_sim::HeadEmulator>(cfg, world);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    try {
      pty_ = std::make_unique<serial::PseudoTerminal>(cfg.port);
    } catch (const std::runtime_error& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    truth_sub_ = nh.subscribe("/auv/ground_truth/odom", 20, &MicronEmulatorNodelet::onTruth, this);
    diag_ = std::make_unique<ros_util::WallDiagnostics>(
        nh, getPrivateNodeHandle(), getName(), "micron_emulator:" + cfg.port, "micron_emulator",
        [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
          s.summary(diagnostic_msgs::DiagnosticStatus::OK, "emulating on " + pty_->link());
          ros_util::addCounters(s, emu_->counters(), {"bad_head_commands", "no_vehicle_state"});
          ros_util::addCounters(s, emu_->decoder().counters(), {"garbage_bytes", "bad_terminator", "length_mismatch"});
          ros_util::addCounters(s, counters_, {"write_errors", "bad_ground_truth"});
        });
    io_.start([this] { ioRound(); });
    NODELET_INFO("Micron emulator on %s (%s), %zu targets in the world", cfg.port.c_str(), pty_->slaveName().c_str(),
                 world.targets.size());
  }

  // Ground truth (map ENU, base_link FLU) as the simulator's state (NED, body FRD).
  void onTruth(const nav_msgs::Odometry& o) {
    const auto& q = o.pose.pose.orientation;
    const auto& p = o.pose.pose.position;
    const double norm = std::sqrt(q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w);
    const Eigen::Vector3d enu(p.x, p.y, p.z);
    if (!enu.allFinite() || !std::isfinite(norm) || norm < 0.5) return counters_.increment("bad_ground_truth");
    double roll = 0.0, pitch = 0.0, yaw = 0.0;
    tf2::Matrix3x3(tf2::Quaternion(q.x, q.y, q.z, q.w).normalized()).getRPY(roll, pitch, yaw);
    VehicleState s;
    s.t = o.header.stamp.toSec();
    s.position = geo::enuToNed(enu);
    s.roll = roll;    // about x: forward in both FLU and FRD
    s.pitch = -pitch;  // about y: left in FLU, right in FRD
    s.yaw = geo::enuYawToNed(yaw);
    std::lock_guard<std::mutex> lock(mutex_);
    emu_->setVehicle(s);
  }

  void ioRound() {
    std::uint8_t buf[512];
    const std::size_t n = pty_->read(buf, sizeof buf, 2);
    std::string out;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      const double now = serial::monotonic();  // the head's clock: wall time, also under simulated /clock
      if (n > 0) out = emu_->receive(buf, n, now);
      out += emu_->poll(now);
    }
    if (!pty_->write(out)) counters_.increment("write_errors");
  }

  std::unique_ptr<serial::PseudoTerminal> pty_;
  std::mutex mutex_;
  std::unique_ptr<micron_sim::HeadEmulator> emu_;
  Counters counters_;
  ros::Subscriber truth_sub_;
  std::unique_ptr<ros_util::WallDiagnostics> diag_;
  ros_util::IoThread io_;  // last: stopped before the members its rounds use go
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::MicronEmulatorNodelet, nodelet::Nodelet)

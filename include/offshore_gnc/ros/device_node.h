#pragma once
// What every device nodelet (a driver on a serial line, an emulator on a pseudo-terminal) has around its core:
// the one thread that touches the line, and diagnostics published every second of wall time (so also while a
// simulated /clock is paused). Declare the IoThread member last: it is destroyed first, so its loop has stopped
// before anything the loop uses goes.
#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include <atomic>
#include <functional>
#include <string>
#include <thread>
#include <utility>

namespace offshore_gnc {
namespace ros_util {

class IoThread {
 public:
  IoThread() = default;
  ~IoThread() { stop(); }
  IoThread(const IoThread&) = delete;
  IoThread& operator=(const IoThread&) = delete;
  // Runs `round` again and again until stop() or ROS shuts down; a round waits on its line (a read with a timeout).
  void start(std::function<void()> round) {
    running_ = true;
    thread_ = std::thread([this, round = std::move(round)] {
      while (running_ && ros::ok()) round();
    });
  }
  void stop() {
    running_ = false;
    if (thread_.joinable()) thread_.join();
  }

 private:
  std::atomic<bool> running_{false};
  std::thread thread_;
};

// A diagnostic_updater with one task, updated every `period` seconds of wall time.
class WallDiagnostics {
 public:
  using Fill = std::function<void(diagnostic_updater::DiagnosticStatusWrapper&)>;
  WallDiagnostics(ros::NodeHandle& nh, ros::NodeHandle& pnh, const std::string& node, const std::string& hardware_id,
                  const std::string& task, Fill fill, double period = 1.0)
      : updater_(nh, pnh, node) {
    updater_.setHardwareID(hardware_id);
    updater_.add(task, std::move(fill));
    timer_ = nh.createWallTimer(ros::WallDuration(period), [this](const ros::WallTimerEvent&) { updater_.update(); });
  }

 private:
  diagnostic_updater::Updater updater_;
  ros::WallTimer timer_;
};

}  // namespace ros_util
}  // namespace offshore_gnc

#pragma once
// ROS side shared by the simulator nodelets: their run settings and the simulation thread that owns /clock
// (state <-> message conversions: offshore_gnc/ros/conversions.h).
#include <geometry_msgs/Quaternion.h>
#include <geometry_msgs/TransformStamped.h>
#include <nav_msgs/Odometry.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>
#include <std_msgs/UInt32.h>
#include <tf2/LinearMath/Quaternion.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/models/state.h"
#include "offshore_gnc/ros/conversions.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/ros/site.h"
#include "offshore_gnc/sim/scenario.h"
#include "offshore_gnc/sim/simulator_params.h"

namespace offshore_gnc {
namespace sim_ros {

// The parameters every simulator nodelet reads (sim::RunParams), the scenario loaded.
struct RunSettings {
  sim::Scenario scenario;
  double rate = 1.0, dt = 0.01;
  bool lockstep = false;
  std::uint64_t seed = 1;
};
inline RunSettings readRunSettings(const ros_util::ParamReader& p, int default_seed) {
  sim::RunParams rp;
  rp.seed = default_seed;
  ros_util::readParams(p, sim::RunParams::table(), rp);
  RunSettings r;
  const std::string& path = rp.scenario;
  if (path.empty()) throw ConfigError("parameter '~scenario' (path of the scenario file) is missing");
  r.scenario = sim::loadScenario(path);
  // The simulated world is placed by the scenario's origin, every other node by the site's: both must be one.
  const geo::LatLonAlt site = ros_util::readOrigin();
  const double apart = geo::surfaceDistance(site, r.scenario.origin);
  if (apart > 1.0) {
    char msg[320];
    std::snprintf(msg, sizeof msg,
                  "scenario '%s' has its origin at (%.6f, %.6f) but the site's /site/origin is (%.6f, %.6f), %.0f m "
                  "apart: in simulation leave origin:= and site:= unset (the scenario is the site) or set them to it",
                  path.c_str(), r.scenario.origin.lat_deg, r.scenario.origin.lon_deg, site.lat_deg, site.lon_deg, apart);
    throw ConfigError(msg);
  }
  r.rate = rp.rate;
  r.lockstep = rp.lockstep;
  r.dt = rp.dt;
  r.seed = static_cast<std::uint64_t>(rp.seed);
  return r;
}

// Runs the simulation step on its own thread and owns /clock. rate > 0: that many times real time; rate = 0:
// as fast as the CPU allows; lockstep: only the steps requested on `sim/step` (std_msgs/UInt32), for tests
// that need every step to be seen. `step` is called with the simulation mutex held.
class SimRunner {
 public:
  SimRunner(ros::NodeHandle& nh, double dt, double rate, bool lockstep, std::function<double()> step)
      : dt_(dt), rate_(rate), lockstep_(lockstep), step_(std::move(step)) {
    // latched: a node that starts while the simulation waits in lockstep still learns the current time
    clock_pub_ = nh.advertise<rosgraph_msgs::Clock>("/clock", 10, true);
    if (lockstep_) {
      // Steps arrive on a queue and thread of their own: in a nodelet manager a worker thread can sit in
      // another nodelet's callback that waits for simulated time (a tf lookup with a timeout), and the
      // clock's source must never queue behind it.
      ros::NodeHandle step_nh(nh);
      step_nh.setCallbackQueue(&step_queue_);
      step_sub_ = step_nh.subscribe<std_msgs::UInt32>("sim/step", 100, [this](const std_msgs::UInt32ConstPtr& m) {
        std::lock_guard<std::mutex> l(wake_mutex_);
        pending_ += m->data;
        wake_.notify_all();
      });
      step_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &step_queue_);
      step_spinner_->start();
    }
  }
  ~SimRunner() { stop(); }
  void start() { thread_ = std::thread([this] { run(); }); }
  void stop() {
    running_ = false;
    wake_.notify_all();
    if (thread_.joinable()) thread_.join();
  }
  std::mutex& mutex() { return mutex_; }
  double realTimeFactor() const { return rtf_.load(); }

 private:
  void run() {
    using clk = std::chrono::steady_clock;
    const auto w0 = clk::now();
    double t = 0.0;
    auto last_report = w0;
    double t_report = 0.0;
    publishClock(0.0);
    while (running_ && ros::ok()) {
      if (lockstep_) {
        std::unique_lock<std::mutex> l(wake_mutex_);
        wake_.wait_for(l, std::chrono::milliseconds(100), [this] { return pending_ > 0 || !running_; });
        if (pending_ == 0) continue;
        --pending_;
      }
      {
        std::lock_guard<std::mutex> l(mutex_);
        t = step_();
      }
      publishClock(t);
      if (rate_ > 0 && !lockstep_) {
        std::this_thread::sleep_until(w0 + std::chrono::duration_cast<clk::duration>(std::chrono::duration<double>(t / rate_)));
      } else if (rate_ > 0) {
        // lockstep at a rate: granted steps are spread evenly (a burst would leave the control loop behind
        // the simulated vehicle); time spent waiting for steps is not made up afterwards.
        const auto step_wall = std::chrono::duration_cast<clk::duration>(std::chrono::duration<double>(dt_ / rate_));
        paced_ = std::max(paced_ + step_wall, clk::now());
        std::this_thread::sleep_until(paced_);
      }
      const auto now = clk::now();
      const double wall = std::chrono::duration<double>(now - last_report).count();
      if (wall > 1.0) {
        rtf_ = (t - t_report) / wall;
        last_report = now;
        t_report = t;
      }
    }
  }
  void publishClock(double t) {
    rosgraph_msgs::Clock c;
    c.clock = ros::Time(t);
    clock_pub_.publish(c);
  }

  double dt_, rate_;
  bool lockstep_;
  std::function<double()> step_;
  ros::Publisher clock_pub_;
  ros::CallbackQueue step_queue_;
  ros::Subscriber step_sub_;
  std::unique_ptr<ros::AsyncSpinner> step_spinner_;
  std::thread thread_;
  std::mutex mutex_, wake_mutex_;
  std::condition_variable wake_;
  unsigned long pending_ = 0;
  std::chrono::steady_clock::time_point paced_{};
  std::atomic<bool> running_{true};
  std::atomic<double> rtf_{0.0};
};

}  // namespace sim_ros
}  // namespace offshore_gnc

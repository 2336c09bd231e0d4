// SeaTrac beacon-pair simulator on a pseudo-terminal: the USBL node opens `port` (a symlink to the pty's slave)
// as if it were the X150's serial line; commands are decoded with the real codec and answered by the core
// BeaconSimulator from both vehicles' ground truth (map ENU odometry), with the two-way acoustic delay.
#include <diagnostic_updater/diagnostic_updater.h>
#include <nav_msgs/Odometry.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <std_msgs/UInt8MultiArray.h>

#include <algorithm>
#include <atomic>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/faults.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/usbl/beacon_sim.h"
#include "offshore_gnc/serial/pseudo_terminal.h"
#include "ros_usbl.h"

namespace offshore_gnc {

class UsblSimNodelet : public nodelet::Nodelet {
 public:
  ~UsblSimNodelet() override {
    running_ = false;
    if (io_.joinable()) io_.join();
  }

 private:
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros_util::ParamReader p(getPrivateNodeHandle());
    usbl::BeaconSimConfig cfg;
    try {
      usbl::BeaconSimNodeParams np;
      ros_util::readParams(p, usbl::BeaconSimNodeParams::table(), np);
      link_ = np.port;
      cfg.local_id = static_cast<std::uint8_t>(np.local_beacon_id);
      cfg.remote_id = static_cast<std::uint8_t>(np.remote_beacon_id);
      cfg.mount = usbl_ros::readMounting(p);
      // The mounting is relative to the point /usv_gps reports (what the USBL node places fixes with), the
      // poses here are the hull's reference point: the transceiver is the GPS antenna's lever arm further.
      // Without it every simulated fix came out 2.5 m too shallow and the 3 m depth gate refused about 20 %.
      cfg.mount.offset += np.gps_antenna;
      ros_util::readParams(p, usbl::beaconSimTable(), cfg);
      cfg.seed = static_cast<unsigned>(np.seed);
      faults_ = std::make_unique<ros_util::FaultInjector>(nh, "auv", std::vector<std::string>{"usbl"});
      cfg.faults = faults_->plan();
      sim_ = std::make_unique<usbl::BeaconSimulator>(cfg);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    mount_ = cfg.mount;
    try {
      pty_ = std::make_unique<serial::PseudoTerminal>(link_);
    } catch (const std::runtime_error& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    usv_sub_ = nh.subscribe<nav_msgs::Odometry>("/usv/ground_truth/odom", 20,
                                                [this](const nav_msgs::OdometryConstPtr& o) { onTruth(usv_, *o); });
    auv_sub_ = nh.subscribe<nav_msgs::Odometry>("/auv/ground_truth/odom", 20,
                                                [this](const nav_msgs::OdometryConstPtr& o) { onTruth(auv_, *o); });
    // What the AUV's beacon has queued for the next data request (the AUV side's DAT_QUEUE_SET).
    queue_sub_ = nh.subscribe("/auv/usbl/sim_remote_queue", 5, &UsblSimNodelet::onQueue, this);
    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, getPrivateNodeHandle(), getName());
    updater_->setHardwareID("seatrac_sim:" + link_);
    updater_->add("usbl_sim", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      s.summary(diagnostic_msgs::DiagnosticStatus::OK, "simulating on " + link_);
      ros_util::addCounters(s, sim_->counters());
      ros_util::addCounters(s, decoder_.counters(), {"bad_crc", "non_hex", "unknown_cid"});
      ros_util::addCounters(s, counters_, {"write_errors"});
    });
    diag_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_->update(); });
    running_ = true;
    io_ = std::thread([this] { ioLoop(); });
    NODELET_INFO("SeaTrac simulator on %s (%s)", link_.c_str(), pty_->slaveName().c_str());
  }

  // A vehicle's latest ground truth with its stamp and body rates, carried to the time it is used (backwards
  // too: the two simulators run in lockstep rounds up to a second apart); at most kMaxPredict, older truth is
  // not carried further. The USV's reaches this master late (in the main job through its simulated acoustic
  // channel), so a turning USV's transceiver points where it really does; the AUV's arrives after the callback
  // latency, tens of milliseconds of wall time at 20x: taken as the position at the reply, the fixes lagged the
  // AUV by 0.5 s of simulated time (0.3 m at the aColor's speed).
  struct Truth {
    usbl::Pose pose;
    Eigen::Vector3d v = Eigen::Vector3d::Zero(), w = Eigen::Vector3d::Zero();  // body FRD
    double t = 0.0;
    bool have = false;
    bool set(const nav_msgs::Odometry& o) {  // false: not a usable pose
      const auto& q = o.pose.pose.orientation;
      const Eigen::Quaterniond e(q.w, q.x, q.y, q.z);
      const Eigen::Vector3d enu(o.pose.pose.position.x, o.pose.pose.position.y, o.pose.pose.position.z);
      if (!enu.allFinite() || !std::isfinite(e.norm()) || e.norm() < 0.5) return false;
      pose.ned = geo::enuToNed(enu);
      pose.q = usbl::enuFluToNedFrd(e);
      const auto& lv = o.twist.twist.linear;
      const auto& av = o.twist.twist.angular;
      const Eigen::Vector3d v_frd(lv.x, -lv.y, -lv.z), w_frd(av.x, -av.y, -av.z);  // FLU -> FRD
      if (v_frd.allFinite() && w_frd.allFinite()) v = v_frd, w = w_frd;
      t = o.header.stamp.toSec();
      have = true;
      return true;
    }
    usbl::Pose at(double when) const {
      constexpr double kMaxPredict = 2.0;  // [s]
      return usbl::predictPose(pose, v, w, std::clamp(when - t, -kMaxPredict, kMaxPredict));
    }
  };
  void onTruth(Truth& truth, const nav_msgs::Odometry& o) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!truth.set(o)) counters_.increment("bad_ground_truth");
  }

  void onQueue(const std_msgs::UInt8MultiArray& m) {
    if (m.data.size() > usbl::kMaxDataPacket) return counters_.increment("bad_remote_queue");
    std::lock_guard<std::mutex> lock(mutex_);
    sim_->setRemoteQueue(m.data);
  }

  void write(const std::string& s) {
    if (!pty_->write(s)) counters_.increment("write_errors");
  }

  void ioLoop() {
    std::uint8_t buf[256];
    std::vector<usbl::StreamDecoder::Event> events;
    while (running_ && ros::ok()) {
      const std::size_t n = pty_->read(buf, sizeof buf, 5);
      if (n > 0) {
        events.clear();
        decoder_.feed(buf, n, events);
        for (const auto& e : events) {
          if (!e.message) continue;
          std::lock_guard<std::mutex> lock(mutex_);
          // Without both poses the beacon is out of reach: the ping times out.
          const double now = ros::Time::now().toSec();
          sim_->setCurrentRange(usv_.have && auv_.have ? usbl::transceiverRange(mount_, usv_.at(now), auv_.at(now).ned)
                                                       : std::numeric_limits<double>::infinity());
          write(sim_->handle(*e.message, now));
        }
      }
      std::lock_guard<std::mutex> lock(mutex_);
      const double now = ros::Time::now().toSec();
      faults_->update(now);
      write(sim_->poll(now, usv_.at(now), auv_.at(now).ned));
    }
  }

  std::string link_;
  std::unique_ptr<serial::PseudoTerminal> pty_;
  usbl::Mounting mount_;
  std::mutex mutex_;
  std::unique_ptr<usbl::BeaconSimulator> sim_;
  std::unique_ptr<ros_util::FaultInjector> faults_;
  Truth usv_, auv_;
  usbl::StreamDecoder decoder_;
  Counters counters_;
  std::atomic<bool> running_{false};
  std::thread io_;
  ros::Subscriber usv_sub_, auv_sub_, queue_sub_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::WallTimer diag_timer_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::UsblSimNodelet, nodelet::Nodelet)

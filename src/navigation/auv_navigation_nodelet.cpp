// AuvNavigation: the AUV's navigation filter (navigation::AuvNavigator) in the AUV's master. USBL fixes
// (/auv/usbl/fix, placed on the USV and relayed, stamped when taken), depth from /auv/pressure, yaw and yaw rate
// from the AHRS (/auv/imu), and the DVL (/auv/dvl, Girona500) or the velocity through the water the commands give
// (/auv/commanded_velocity from Control: the aColor, a Girona500 whose DVL is silent), and the Girona500's GPS at
// the surface (/auv/gps/fix, placed by /site/origin) -> /auv/odom + TF
// map -> auv/base_link at a fixed rate on the ROS (simulation) clock, once the first fix has initialised the
// filter and while it has a heading (no_heading: its dead reckoning has stopped, so it publishes no estimate rather
// than a frozen one, and the safety supervisor's navigation rule sees the silence); /auv/navigation/status
// (latched), the QUALITY_OK fixes the filter refused (gated or too old) on /auv/navigation/refused_fixes, and
// diagnostics. Replaces the simulator's INS-like /auv/odom with `navigation:=usbl`. Thin: parameters, message
// conversion, publishing.
#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/TwistWithCovarianceStamped.h>
#include <nav_msgs/Odometry.h>
#include <nodelet/nodelet.h>
#include <geometry_msgs/TwistStamped.h>
#include <offshore_gnc/UsblFix.h>
#include <pluginlib/class_list_macros.hpp>
#include <ros/ros.h>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/NavSatFix.h>
#include <std_msgs/String.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2/utils.h>
#include <tf2_ros/transform_broadcaster.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/models/state.h"
#include "offshore_gnc/navigation/auv_navigation_params.h"
#include "offshore_gnc/navigation/auv_navigator.h"
#include "offshore_gnc/ros/conversions.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/params.h"
#include "offshore_gnc/ros/site.h"

namespace offshore_gnc {

namespace {

constexpr double kNoFixGraceS = 60.0;  // kNoFix is an ERROR in diagnostics only after this long [s, ROS time]

const char* statusName(navigation::NavStatus s) {
  switch (s) {
    case navigation::NavStatus::kNoFix: return ros_util::nav_status::kNoFix;
    case navigation::NavStatus::kOk: return ros_util::nav_status::kOk;
    case navigation::NavStatus::kFixLost: return ros_util::nav_status::kFixLost;
    case navigation::NavStatus::kNoHeading: return ros_util::nav_status::kNoHeading;
  }
  return "unknown";
}

const char* qualityName(std::uint8_t q) {
  switch (q) {
    case UsblFix::QUALITY_OK: return "ok";
    case UsblFix::QUALITY_FILTER_ERROR: return "filter_error";
    case UsblFix::QUALITY_FIT_ERROR: return "fit_error";
    case UsblFix::QUALITY_STALE: return "stale";
    case UsblFix::QUALITY_DEPTH: return "depth";
    case UsblFix::QUALITY_NO_POSITION: return "no_position";
  }
  return "unknown";
}

// A ROS covariance (row-major, -1 in the first element: unknown) is usable when finite and not flagged unknown.
template <std::size_t N>
bool usableCovariance(const boost::array<double, N>& c) {
  return c[0] >= 0.0 && std::all_of(c.begin(), c.end(), [](double v) { return std::isfinite(v); });
}

}  // namespace

class AuvNavigationNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros::NodeHandle& pnh = getPrivateNodeHandle();
    ros_util::ParamReader p(pnh);
    navigation::AuvNavigatorConfig cfg;
    try {
      ros_util::readParams(p, navigation::AuvNavigatorConfig::table(), cfg);
      ros_util::readParams(p, navigation::AuvNavigationParams::table(), params_);
      base_frame_ = params_.base_frame;
      nav_ = std::make_unique<navigation::AuvNavigator>(cfg);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }

    odom_pub_ = nh.advertise<nav_msgs::Odometry>("/auv/odom", 10);
    refused_pub_ = nh.advertise<UsblFix>("/auv/navigation/refused_fixes", 10);
    status_pub_ = nh.advertise<std_msgs::String>("/auv/navigation/status", 1, true);
    std_msgs::String initial;
    initial.data = statusName(navigation::NavStatus::kNoFix);
    status_pub_.publish(initial);  // latched: the state before the first fix
    fix_sub_ = nh.subscribe("/auv/usbl/fix", 10, &AuvNavigationNodelet::onFix, this);
    pressure_sub_ = nh.subscribe("/auv/pressure", 20, &AuvNavigationNodelet::onPressure, this);
    imu_sub_ = nh.subscribe("/auv/imu", 100, &AuvNavigationNodelet::onImu, this);
    if (params_.use_dvl) dvl_sub_ = nh.subscribe("/auv/dvl", 20, &AuvNavigationNodelet::onDvl, this);
    // the vehicle's own GPS at the surface (the Girona500's), placed in the site's frame: without /site/origin
    // its fixes are refused, counted and said (the USBL fixes come placed already)
    try {
      site_.emplace(ros_util::readOrigin());
    } catch (const ConfigError& e) {
      site_error_ = e.what();
    }
    gps_sub_ = nh.subscribe("/auv/gps/fix", 10, &AuvNavigationNodelet::onGps, this);
    // the commands' velocity always: the filter uses it only while no DVL sample is fresh (dvl_timeout)
    command_sub_ = nh.subscribe("/auv/commanded_velocity", 10, &AuvNavigationNodelet::onCommand, this);

    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, pnh, getName());
    updater_->setHardwareID("auv_navigation");
    updater_->add("navigation", [this](diagnostic_updater::DiagnosticStatusWrapper& s) { diagnose(s); });
    diag_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_->force_update(); });
    timer_ = nh.createTimer(ros::Duration(1.0 / params_.rate), &AuvNavigationNodelet::onTimer, this);
    NODELET_INFO("AUV navigation at %.1f Hz, velocity from %s; no /auv/odom until the first USBL fix", params_.rate,
                 params_.use_dvl ? "the DVL (/auv/dvl)" : "the commands (/auv/commanded_velocity)");
  }

  // ---- inputs ----

  void onGps(const sensor_msgs::NavSatFix::ConstPtr& m) {
    if (m->status.status < sensor_msgs::NavSatStatus::STATUS_FIX) return;  // no fix: nothing to fuse
    if (!site_) {
      counters_.increment("gps_without_site");
      NODELET_ERROR_THROTTLE(10.0, "ignoring /auv/gps/fix: %s", site_error_.c_str());
      return;
    }
    const double sigma = usableCovariance(m->position_covariance) ? std::sqrt(std::max(m->position_covariance[0],
                                                                                         m->position_covariance[4]))
                                                                  : params_.fix_min_sigma;
    if (!std::isfinite(m->latitude) || !std::isfinite(m->longitude) || std::abs(m->latitude) > 90.0 ||
        std::abs(m->longitude) > 180.0 || m->header.stamp.isZero() || !std::isfinite(sigma)) {
      counters_.increment("bad_gps");
      NODELET_WARN_THROTTLE(5.0, "ignoring a GPS fix without a finite position, covariance or stamp");
      return;
    }
    const Eigen::Vector3d ned = site_->toNed(geo::LatLonAlt{m->latitude, m->longitude, 0.0});
    std::lock_guard<std::mutex> l(mutex_);
    nav_->gpsFix(m->header.stamp.toSec(), ned.head<2>(), sigma);  // gated like a USBL fix (the core counts it)
  }

  void onFix(const UsblFix::ConstPtr& m) {
    if (m->quality != UsblFix::QUALITY_OK) {
      counters_.increment(std::string("fix_not_ok_") + qualityName(m->quality));
      return;
    }
    const Eigen::Vector3d ned(m->position_ned.x, m->position_ned.y, m->position_ned.z);
    if (!ned.allFinite() || !std::isfinite(m->range) || m->range < 0.0 || m->header.stamp.isZero()) {
      counters_.increment("bad_fix");
      NODELET_WARN_THROTTLE(5.0, "ignoring a USBL fix without a finite position_ned, range or stamp");
      return;
    }
    std::lock_guard<std::mutex> l(mutex_);
    if (!nav_->usblFix(m->header.stamp.toSec(), ned, params_.fixCovariance(m->range)))
      refused_pub_.publish(m);  // gated (an outlier) or too old: the counters say which; the report scores them
  }

  void onPressure(const sensor_msgs::FluidPressure::ConstPtr& m) {
    if (!std::isfinite(m->fluid_pressure) || m->header.stamp.isZero()) {
      counters_.increment("bad_pressure");
      return;
    }
    std::lock_guard<std::mutex> l(mutex_);
    nav_->depth(m->header.stamp.toSec(), params_.depthOf(m->fluid_pressure));
  }

  // REP-103: orientation of the FLU body in ENU, angular velocity in FLU (z counter-clockwise).
  void onImu(const sensor_msgs::Imu::ConstPtr& m) {
    const auto& q = m->orientation;
    const auto& w = m->angular_velocity;
    const double n2 = q.x * q.x + q.y * q.y + q.z * q.z + q.w * q.w;
    if (!std::isfinite(n2) || n2 < 1e-6 || !std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z) ||
        m->header.stamp.isZero()) {
      counters_.increment("bad_imu");
      NODELET_WARN_THROTTLE(5.0, "ignoring /auv/imu: not a finite, non-zero quaternion and rate, or no stamp");
      return;
    }
    tf2::Quaternion tq(q.x, q.y, q.z, q.w);
    tq.normalize();
    double yaw_enu, pitch_flu, roll;
    tf2::getEulerYPR(tq, yaw_enu, pitch_flu, roll);
    const double yaw = geo::enuYawToNed(tf2::getYaw(tq));
    std::lock_guard<std::mutex> l(mutex_);
    // inverse of ros_util::enuQuaternion: roll the same, pitch negated (FLU y = -FRD y)
    roll_ = roll;
    pitch_ = -pitch_flu;
    rate_pq_ = Eigen::Vector2d(w.x, -w.y);  // FLU -> FRD
    if (usableCovariance(m->orientation_covariance)) orientation_cov_ = m->orientation_covariance;
    if (usableCovariance(m->angular_velocity_covariance)) rate_cov_ = m->angular_velocity_covariance;
    nav_->heading(m->header.stamp.toSec(), yaw, -w.z);  // FLU z up, counter-clockwise -> NED rate clockwise
  }

  // Velocity over ground of the FLU base frame (REP-103), from the DVL.
  void onDvl(const geometry_msgs::TwistWithCovarianceStamped::ConstPtr& m) {
    const auto& v = m->twist.twist.linear;
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z) || m->header.stamp.isZero()) {
      counters_.increment("bad_dvl");
      return;
    }
    if (!m->header.frame_id.empty() && m->header.frame_id != base_frame_)
      NODELET_WARN_ONCE("/auv/dvl is in frame '%s', used as if in '%s' (no mounting rotation applied)",
                        m->header.frame_id.c_str(), base_frame_.c_str());
    std::lock_guard<std::mutex> l(mutex_);
    nav_->dvl(m->header.stamp.toSec(), Eigen::Vector3d(v.x, -v.y, -v.z));  // FLU -> FRD
  }

  void onCommand(const geometry_msgs::TwistStamped::ConstPtr& m) {
    // the command is in force from now (control stamps it when sent; the simulated clock may run ahead of it)
    const ros::Time t = ros::Time::now();
    if (t.isZero()) return;  // the clock has not started
    std::lock_guard<std::mutex> l(mutex_);
    nav_->commandedVelocity(t.toSec(), m->twist.linear.x, -m->twist.linear.y);  // FLU -> FRD; NaN refused, counted
  }

  // ---- output ----

  void onTimer(const ros::TimerEvent&) {
    const ros::Time now = ros::Time::now();
    if (now.isZero()) return;  // simulated time not running yet
    navigation::AuvNavEstimate e;
    double roll, pitch;
    Eigen::Vector2d pq;
    boost::array<double, 9> orientation_cov, rate_cov;
    navigation::NavStatus before;
    bool repeated;
    {
      std::lock_guard<std::mutex> l(mutex_);
      if (start_.isZero() || now < start_) start_ = now;  // first tick, or the clock went back
      e = nav_->estimate(now.toSec());
      status_ = e.status;
      before = published_status_;
      published_status_ = e.status;
      repeated = now == last_stamp_;  // the clock did not move since the last tick: TF would warn
      last_stamp_ = now;
      roll = roll_;
      pitch = pitch_;
      pq = rate_pq_;
      orientation_cov = orientation_cov_;
      rate_cov = rate_cov_;
    }
    if (e.status != before) publishStatus(e.status, before);
    // nothing before the first fix, nor without a heading (the dead reckoning has stopped: no estimate to give)
    using navigation::NavStatus;
    if (e.status == NavStatus::kNoFix || e.status == NavStatus::kNoHeading || repeated) return;

    // NED/FRD state. R_nb: body FRD -> NED, the same roll, pitch and yaw as the published orientation.
    const Eigen::Matrix3d R_nb = (Eigen::AngleAxisd(e.yaw, Eigen::Vector3d::UnitZ()) *
                                  Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                                  Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
                                     .toRotationMatrix();
    VehicleState s;
    s.t = now.toSec();
    s.position = e.position;
    s.roll = roll;
    s.pitch = pitch;
    s.yaw = e.yaw;
    s.velocity = R_nb.transpose() * e.velocity;  // NED velocity -> body (u, v, w)
    s.angular_rate = Eigen::Vector3d(pq.x(), pq.y(), e.yaw_rate);
    nav_msgs::Odometry o = ros_util::toOdometry(s, "map", base_frame_);
    o.header.stamp = now;

    // Covariances. Position: ENU = T NED with T the NED<->ENU permutation (north/east swapped, down negated), so
    // P_enu = T P_ned T' (swaps the north/east rows and columns, negates the cross terms with z).
    Eigen::Matrix3d T;
    T << 0, 1, 0, 1, 0, 0, 0, 0, -1;
    const Eigen::Matrix3d P_pos = T * e.covariance.topLeftCorner<3, 3>() * T.transpose();
    // Velocity in the child frame: v_flu = F R_nb' v_ned with F = diag(1, -1, -1) (FRD -> FLU).
    const Eigen::Matrix3d J = Eigen::Vector3d(1.0, -1.0, -1.0).asDiagonal() * R_nb.transpose();
    const Eigen::Matrix3d P_vel = J * e.covariance.bottomRightCorner<3, 3>() * J.transpose();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        o.pose.covariance[6 * i + j] = P_pos(i, j);
        o.twist.covariance[6 * i + j] = P_vel(i, j);
        // attitude and rates are the AHRS's (REP-103 frames already)
        o.pose.covariance[6 * (i + 3) + j + 3] = orientation_cov[3 * i + j];
        o.twist.covariance[6 * (i + 3) + j + 3] = rate_cov[3 * i + j];
      }
    odom_pub_.publish(o);
    tf_.sendTransform(ros_util::toTransform(o));
  }

  void publishStatus(navigation::NavStatus s, navigation::NavStatus before) {
    std_msgs::String m;
    m.data = statusName(s);
    status_pub_.publish(m);
    if (s == navigation::NavStatus::kOk)
      NODELET_INFO("navigation status: %s (was %s)", statusName(s), statusName(before));
    else
      NODELET_WARN("navigation status: %s (was %s)", statusName(s), statusName(before));
  }

  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& s) {
    const ros::Time now = ros::Time::now();
    std::lock_guard<std::mutex> l(mutex_);
    using D = diagnostic_msgs::DiagnosticStatus;
    switch (status_) {
      case navigation::NavStatus::kOk: s.summary(D::OK, "ok"); break;
      case navigation::NavStatus::kFixLost: s.summary(D::WARN, "no USBL fix accepted lately: dead reckoning"); break;
      case navigation::NavStatus::kNoHeading: s.summary(D::WARN, "no AHRS heading: dead reckoning stopped"); break;
      case navigation::NavStatus::kNoFix:
        if (start_.isZero())
          s.summary(D::WARN, "waiting for the clock");
        else if ((now - start_).toSec() > kNoFixGraceS)
          s.summary(D::ERROR, "no USBL fix yet: no /auv/odom");
        else
          s.summary(D::WARN, "waiting for the first USBL fix");
        break;
    }
    s.add("status", statusName(status_));
    s.add("velocity_source", params_.use_dvl ? "dvl" : "commands");
    ros_util::addCounters(s, nav_->counters(), {"bad_input"});
    ros_util::addCounters(s, counters_, {"bad_fix", "bad_pressure", "bad_imu", "bad_dvl", "bad_gps"});
  }

  std::mutex mutex_;  // nav_ and the AHRS attitude below; callbacks run concurrently
  std::unique_ptr<navigation::AuvNavigator> nav_;
  Counters counters_;  // this nodelet's own (thread-safe)
  navigation::AuvNavigationParams params_;
  std::string base_frame_;
  std::optional<geo::LocalNed> site_;  // /site/origin's frame, for the GPS fixes
  std::string site_error_;
  // the latest AHRS attitude and rates (orientation of the published pose; yaw is the filter's)
  double roll_ = 0.0, pitch_ = 0.0;
  Eigen::Vector2d rate_pq_ = Eigen::Vector2d::Zero();
  boost::array<double, 9> orientation_cov_{}, rate_cov_{};
  navigation::NavStatus status_ = navigation::NavStatus::kNoFix;            // latest, for diagnostics
  navigation::NavStatus published_status_ = navigation::NavStatus::kNoFix;  // on /auv/navigation/status
  ros::Time start_, last_stamp_;
  ros::Publisher odom_pub_, status_pub_, refused_pub_;
  ros::Subscriber fix_sub_, pressure_sub_, imu_sub_, dvl_sub_, command_sub_, gps_sub_;
  tf2_ros::TransformBroadcaster tf_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::WallTimer diag_timer_;
  ros::Timer timer_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::AuvNavigationNodelet, nodelet::Nodelet)

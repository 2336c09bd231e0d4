// AuvSim: the AUV simulator for the AUV's own master. Owns /clock, integrates the AUV, publishes ground truth
// (metrics only), the AHRS (/auv/imu), the depth sensor (/auv/pressure), the Micron-like sonar beams and the
// navigation estimate /auv/odom + TF (a DVL-aided INS stand-in: truth + noise + drift, simulation only; off with
// ~odom/enabled false, when the navigation nodelet publishes both) and, on a Girona500, the DVL (/auv/dvl) and its
// GPS while at the surface (/auv/gps/fix).
// Takes /auv/thruster_setpoints (Girona500) or /auv/rc_channels (aColor AUV).
#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/TwistWithCovarianceStamped.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/FluidPressure.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/NavSatFix.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include <memory>

#include "offshore_gnc/RcChannels.h"
#include "offshore_gnc/SonarBeam.h"
#include "offshore_gnc/ThrusterSetpoints.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/faults.h"
#include "offshore_gnc/ros/nav_sat_fix.h"
#include "offshore_gnc/models/params_yaml.h"
#include "offshore_gnc/sim/simulation.h"
#include "ros_sim.h"

namespace offshore_gnc {

class AuvSimNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros_util::ParamReader p(getPrivateNodeHandle());
    sim::AuvSimulation::Config cfg;
    double rate = 1.0;
    bool lockstep = false;
    try {
      sim_ros::RunSettings run = sim_ros::readRunSettings(p, 2);
      scenario_ = std::move(run.scenario);
      rate = run.rate;
      lockstep = run.lockstep;
      cfg.dt = run.dt;
      cfg.seed = run.seed;
      ros_util::readParams(p, sim::AuvSimulation::Config::table(), cfg);
      ros_util::readParams(p, sim::DepthConfig::table(), cfg.depth);
      ros_util::readParams(p, sim::AhrsConfig::table(), cfg.ahrs);
      ros_util::readParams(p, sim::DvlConfig::table(), cfg.dvl);
      ros_util::readParams(p, sim::SurfaceGpsConfig::table(), cfg.surface_gps);
      sim::AuvSimNodeParams np;
      ros_util::readParams(p, sim::AuvSimNodeParams::table(), np);
      odom_on_ = np.odom_enabled;
      cfg.auv = np.vehicle_model == "acolor" ? models::AuvParams::aColor() : models::AuvParams::girona500();
      if (!np.model_params.empty()) cfg.auv = models::loadAuvParams(np.model_params);
      base_frame_ = np.base_frame;
      faults_ = std::make_unique<ros_util::FaultInjector>(nh, "auv",
                                                          std::vector<std::string>{"sonar", "depth", "dvl", "nav"});
      cfg.faults = faults_->plan();
      sim_ = std::make_unique<sim::AuvSimulation>(scenario_, cfg);
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }
    runner_ = std::make_unique<sim_ros::SimRunner>(getPrivateNodeHandle(), cfg.dt, rate, lockstep, [this] { return step(); });
    truth_pub_ = nh.advertise<nav_msgs::Odometry>("/auv/ground_truth/odom", 10);
    if (odom_on_) odom_pub_ = nh.advertise<nav_msgs::Odometry>("/auv/odom", 10);
    if (sim_->hasDvl()) dvl_pub_ = nh.advertise<geometry_msgs::TwistWithCovarianceStamped>("/auv/dvl", 10);
    if (sim_->hasDvl()) gps_pub_ = nh.advertise<sensor_msgs::NavSatFix>("/auv/gps/fix", 10);  // the Girona500's
    imu_pub_ = nh.advertise<sensor_msgs::Imu>("/auv/imu", 20);
    pressure_pub_ = nh.advertise<sensor_msgs::FluidPressure>("/auv/pressure", 10);
    sonar_pub_ = nh.advertise<SonarBeam>("/auv/sonar/beam", 50);
    setpoint_sub_ = nh.subscribe("/auv/thruster_setpoints", 10, &AuvSimNodelet::onSetpoints, this);
    rc_sub_ = nh.subscribe("/auv/rc_channels", 10, &AuvSimNodelet::onRc, this);
    static_tf_.sendTransform(ros_util::mountTransform(base_frame_, "auv/sonar", sim::sensorMount(cfg.sonar.mount, 0.0, true, -cfg.sonar.tilt)));

    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, getPrivateNodeHandle(), getName());
    updater_->setHardwareID("auv_simulator");
    updater_->add("simulation", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      s.summary(diagnostic_msgs::DiagnosticStatus::OK, "running");
      s.add("real_time_factor", runner_->realTimeFactor());
      ros_util::addCounters(s, sim_->counters(), {"rejected_commands"});
      ros_util::addCounters(s, sim_->modelCounters(), {"rejected_commands", "clamped_commands"});
    });
    diag_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_->force_update(); });
    runner_->start();
    NODELET_INFO("AUV simulator: scenario '%s', %zu targets, %zu walls, rate %g%s%s%s", scenario_.name.c_str(),
                 scenario_.world.targets.size(), scenario_.world.walls.size(), rate, lockstep ? " (lockstep)" : "",
                 sim_->hasDvl() ? ", DVL" : "", odom_on_ ? "" : ", no INS-like odom (navigation publishes it)");
  }

  ~AuvSimNodelet() override {
    if (runner_) runner_->stop();
  }

  // NaN, a wrong thruster count or invalid RC pulses are rejected and counted (never integrated).
  void onSetpoints(const ThrusterSetpoints::ConstPtr& m) {
    std::lock_guard<std::mutex> l(runner_->mutex());
    if (!sim_->setThrusters(m->setpoint))
      NODELET_ERROR_THROTTLE(1.0, "rejected thruster setpoints: need %d finite values", sim_->model().thrusters());
  }
  void onRc(const RcChannels::ConstPtr& m) {
    std::lock_guard<std::mutex> l(runner_->mutex());
    if (!sim_->setRcChannels(m->channels))
      NODELET_ERROR_THROTTLE(1.0, "rejected RC channels: need >= 6 channels, 3..6 within 1100..1900 us");
  }

  double step() {
    const auto& out = sim_->step();
    faults_->update(sim_->state().t);
    const auto& s = sim_->state();
    const ros::Time stamp(s.t);
    if (++truth_count_ % 5 == 0) truth_pub_.publish(ros_util::toOdometry(s, "map", base_frame_));
    if (odom_on_ && out.odom) {
      const auto o = ros_util::toOdometry(*out.odom, "map", base_frame_);
      odom_pub_.publish(o);
      tf_.sendTransform(ros_util::toTransform(o));
    }
    if (out.ahrs) {
      const auto& a = *out.ahrs;
      sensor_msgs::Imu m;
      m.header.stamp = stamp;
      m.header.frame_id = base_frame_;
      m.orientation = ros_util::enuQuaternion(a.roll, a.pitch, a.yaw);
      m.angular_velocity.x = a.angular_rate.x();  // FRD -> FLU
      m.angular_velocity.y = -a.angular_rate.y();
      m.angular_velocity.z = -a.angular_rate.z();
      m.linear_acceleration.x = a.specific_force.x();
      m.linear_acceleration.y = -a.specific_force.y();
      m.linear_acceleration.z = -a.specific_force.z();
      const double va = a.attitude_sigma * a.attitude_sigma, vh = a.heading_sigma * a.heading_sigma;
      m.orientation_covariance = {va, 0, 0, 0, va, 0, 0, 0, vh};
      const double vg = a.gyro_sigma * a.gyro_sigma, vl = a.accel_sigma * a.accel_sigma;
      m.angular_velocity_covariance = {vg, 0, 0, 0, vg, 0, 0, 0, vg};
      m.linear_acceleration_covariance = {vl, 0, 0, 0, vl, 0, 0, 0, vl};
      imu_pub_.publish(m);
    }
    if (out.depth) {
      sensor_msgs::FluidPressure m;
      m.header.stamp = stamp;
      m.header.frame_id = base_frame_;
      m.fluid_pressure = out.depth->pressure_pa;
      m.variance = out.depth->sigma_pa * out.depth->sigma_pa;
      pressure_pub_.publish(m);
    }
    if (out.dvl) {
      // FRD -> FLU (ROS body frame): y and z negated; the noise is independent per axis
      geometry_msgs::TwistWithCovarianceStamped m;
      m.header.stamp = stamp;
      m.header.frame_id = base_frame_;
      m.twist.twist.linear.x = out.dvl->velocity.x();
      m.twist.twist.linear.y = -out.dvl->velocity.y();
      m.twist.twist.linear.z = -out.dvl->velocity.z();
      const double vv = out.dvl->velocity_sigma * out.dvl->velocity_sigma;
      m.twist.covariance[0] = m.twist.covariance[7] = m.twist.covariance[14] = vv;  // angular: not measured (0)
      dvl_pub_.publish(m);
    }
    if (out.gps)
      gps_pub_.publish(
          ros_util::navSatFix(out.gps->fix, out.gps->sigma, stamp, "auv/gps", sensor_msgs::NavSatStatus::STATUS_FIX));
    if (out.sonar) {
      const auto& b = sim_->beam();
      SonarBeam m;
      m.header.stamp = stamp;
      m.header.frame_id = "auv/sonar";
      m.bearing = b.bearing;
      m.beam_width = b.beam_width;
      m.range_resolution = b.range_resolution;
      m.range_offset = b.range_offset;
      m.head_status = b.head_status;
      m.intensities = b.intensities;
      sonar_pub_.publish(m);
    }
    return s.t;
  }

  sim::Scenario scenario_;
  std::unique_ptr<sim::AuvSimulation> sim_;
  std::unique_ptr<sim_ros::SimRunner> runner_;
  std::unique_ptr<ros_util::FaultInjector> faults_;
  std::string base_frame_;
  unsigned long truth_count_ = 0;
  bool odom_on_ = true;
  ros::Publisher truth_pub_, odom_pub_, imu_pub_, pressure_pub_, sonar_pub_, dvl_pub_, gps_pub_;
  ros::Subscriber setpoint_sub_, rc_sub_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
  tf2_ros::TransformBroadcaster tf_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::WallTimer diag_timer_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::AuvSimNodelet, nodelet::Nodelet)

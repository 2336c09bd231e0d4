// UsvSim: the USV simulator for the USV's own master. Owns /clock, integrates the USV on a fixed step,
// publishes ground truth (metrics only), the GPS-compass (/usv_gps, /usv_heading), the LiDAR point cloud and
// the scenario's map grid; takes /usv/joystick_cmd, with /usv/manual_cmd taking priority while it is fresh, or
// with the CAN chain in the loop the per-jet set-points the emulated units act on (~jet_command_topic).
// Without the CAN chain it also stands in for the CAN gateway's reports of the bus: each unit's status
// (/usv/waterjet/status), whether it answers (/usv/waterjet/answering, latched) and the bus state
// (/usv/can/bus_state, latched), on which the jet and bus_off faults show (docs/safety.md).
#include <diagnostic_updater/diagnostic_updater.h>
#include <geometry_msgs/QuaternionStamped.h>
#include <geometry_msgs/TwistStamped.h>
#include <nav_msgs/OccupancyGrid.h>
#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/NavSatFix.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2/LinearMath/Quaternion.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "offshore_gnc/CanBusState.h"
#include "offshore_gnc/JoystickCommand.h"
#include "offshore_gnc/WaterjetAnswering.h"
#include "offshore_gnc/WaterjetSetpoints.h"
#include "offshore_gnc/WaterjetStatus.h"
#include "offshore_gnc/ros/diagnostics.h"
#include "offshore_gnc/ros/faults.h"
#include "offshore_gnc/ros/nav_sat_fix.h"
#include "offshore_gnc/models/params_yaml.h"
#include "offshore_gnc/sim/simulation.h"
#include "ros_sim.h"

namespace offshore_gnc {

class UsvSimNodelet : public nodelet::Nodelet {
  void onInit() override {
    ros::NodeHandle& nh = getNodeHandle();
    ros_util::ParamReader p(getPrivateNodeHandle());
    sim::UsvSimulation::Config cfg;
    double rate = 1.0;
    bool lockstep = false;
    try {
      sim_ros::RunSettings run = sim_ros::readRunSettings(p, 1);
      scenario_ = std::move(run.scenario);
      rate = run.rate;
      lockstep = run.lockstep;
      cfg.dt = run.dt;
      cfg.seed = run.seed;
      ros_util::readParams(p, sim::UsvSimulation::Config::table(), cfg);
      ros_util::readParams(p, sim::GpsCompassConfig::table(), cfg.gps);
      sim::UsvSimNodeParams np;
      ros_util::readParams(p, sim::UsvSimNodeParams::table(), np);
      if (!np.model_params.empty()) cfg.usv = models::loadUsvParams(np.model_params);
      cfg.usv.type = np.model == "nomoto" ? models::UsvModelType::Nomoto : models::UsvModelType::Dynamic3Dof;
      manual_timeout_ = np.manual_timeout;
      command_topic_ = np.command_topic;
      // /usv/waterjet/applied_setpoints behind the CAN gateway + emulator: the units already chose manual or autonomy
      jet_command_topic_ = np.jet_command_topic;
      base_frame_ = np.base_frame;
      faults_ = std::make_unique<ros_util::FaultInjector>(
          nh, "usv", std::vector<std::string>{"gps", "lidar", "jet", "bus_off", "collision"});
      cfg.faults = faults_->plan();
      sim_ = std::make_unique<sim::UsvSimulation>(scenario_, cfg);
      cfg_lidar_imu_sigma_ = cfg.lidar.sea.imu_sigma;
    } catch (const ConfigError& e) {
      NODELET_FATAL("%s", e.what());
      throw;
    }

    runner_ = std::make_unique<sim_ros::SimRunner>(getPrivateNodeHandle(), cfg.dt, rate, lockstep, [this] { return step(); });
    truth_pub_ = nh.advertise<nav_msgs::Odometry>("/usv/ground_truth/odom", 10);
    gps_pub_ = nh.advertise<sensor_msgs::NavSatFix>("/usv_gps", 10);
    heading_pub_ = nh.advertise<geometry_msgs::QuaternionStamped>("/usv_heading", 10);
    vel_pub_ = nh.advertise<geometry_msgs::TwistStamped>("/usv/gps/velocity", 10);
    lidar_pub_ = nh.advertise<sensor_msgs::PointCloud2>("/usv/lidar/points", 2);
    lidar_imu_pub_ = nh.advertise<sensor_msgs::Imu>("/usv/lidar/imu", 10);
    map_pub_ = nh.advertise<nav_msgs::OccupancyGrid>("/usv/map", 1, true);
    jet_pub_ = nh.advertise<WaterjetStatus>("/usv/waterjet/status", 10);
    if (jet_command_topic_.empty()) {  // the gateway's reports; with the CAN chain in the loop the gateway's own
      answering_pub_ = nh.advertise<WaterjetAnswering>("/usv/waterjet/answering", 1, true);
      bus_pub_ = nh.advertise<CanBusState>("/usv/can/bus_state", 1, true);
    }
    if (!jet_command_topic_.empty()) {
      auto_sub_ = nh.subscribe(jet_command_topic_, 10, &UsvSimNodelet::onJets, this);
    } else {
      auto_sub_ = nh.subscribe(command_topic_, 10, &UsvSimNodelet::onCommand, this);
      manual_sub_ = nh.subscribe("/usv/manual_cmd", 10, &UsvSimNodelet::onManual, this);
    }
    if (!scenario_.map.empty()) map_pub_.publish(gridMessage());

    static_tf_.sendTransform({ros_util::mountTransform(base_frame_, "usv/lidar", sim::sensorMount(cfg.lidar.mount, cfg.lidar.mount_yaw, false)),
                              ros_util::mountTransform(base_frame_, "usv/gps", sim::sensorMount(cfg.gps.antenna, 0.0, false))});

    updater_ = std::make_unique<diagnostic_updater::Updater>(nh, getPrivateNodeHandle(), getName());
    updater_->setHardwareID("usv_simulator");
    updater_->add("simulation", [this](diagnostic_updater::DiagnosticStatusWrapper& s) {
      s.summary(diagnostic_msgs::DiagnosticStatus::OK, "running");
      s.add("real_time_factor", runner_->realTimeFactor());
      ros_util::addCounters(s, sim_->counters(), {"rejected_commands", "clamped_commands"});
      ros_util::addCounters(s, counters_, {});
    });
    diag_timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_->force_update(); });

    runner_->start();
    NODELET_INFO("USV simulator: scenario '%s', %zu buoys, %zu vessels, %zu shoreline polygons, rate %g%s",
                 scenario_.name.c_str(), scenario_.world.buoys.size(), scenario_.world.vessels.size(),
                 scenario_.world.shorelines.size(), rate, lockstep ? " (lockstep)" : "");
  }

  ~UsvSimNodelet() override {
    if (runner_) runner_->stop();
  }

  // Manual wins over autonomy while its last message is younger than manual_timeout (simulated time).
  void onManual(const JoystickCommand::ConstPtr& m) {
    std::lock_guard<std::mutex> l(runner_->mutex());
    if (apply(*m)) last_manual_ = sim_->state().t;
  }
  void onCommand(const JoystickCommand::ConstPtr& m) {
    std::lock_guard<std::mutex> l(runner_->mutex());
    if (sim_->state().t - last_manual_ < manual_timeout_) {
      counters_.increment("autonomy_overridden_by_manual");
      return;
    }
    apply(*m);
  }
  void onJets(const WaterjetSetpoints::ConstPtr& m) {
    models::JetCommands c;
    for (int i = 0; i < 2; ++i) c[i] = {m->rpm[i], m->nozzle[i], m->bucket[i]};
    std::lock_guard<std::mutex> l(runner_->mutex());
    if (!sim_->setJetCommands(c))
      NODELET_ERROR_THROTTLE(1.0, "rejected per-jet set-points (rpm %g/%g): not finite, or the lumped model", c[0].rpm,
                             c[1].rpm);
  }
  bool apply(const JoystickCommand& m) {
    if (sim_->setCommand({m.surge, m.sway, m.yaw})) return true;
    NODELET_ERROR_THROTTLE(1.0, "rejected joystick command (surge %g, sway %g, yaw %g): not finite", m.surge, m.sway,
                           m.yaw);
    return false;
  }

  double step() {
    const auto& out = sim_->step();
    // the collision fault is in effect once its obstacle is in the world (the first time under way in its window)
    faults_->update(sim_->state().t, [this](const std::string& name) {
      return name != "collision" || sim_->faultObstacle().has_value();
    });
    const auto& s = sim_->state();
    const ros::Time stamp(s.t);
    if (++truth_count_ % 5 == 0) truth_pub_.publish(ros_util::toOdometry(s, "map", base_frame_));  // 20 Hz
    if (out.gps) {
      // heading and velocity first: the navigation pairs each fix with the latest of both
      geometry_msgs::QuaternionStamped h;
      h.header.stamp = stamp;
      h.header.frame_id = "map";
      h.quaternion = ros_util::enuQuaternion(0.0, 0.0, out.gps->heading);
      heading_pub_.publish(h);
      // as the CAN gateway's: ENU ground velocity (Doppler SOG/COG); angular.z = rate of turn, counter-clockwise
      geometry_msgs::TwistStamped v;
      v.header.stamp = stamp;
      v.header.frame_id = "map";
      v.twist.linear.x = out.gps->velocity_ned.y();
      v.twist.linear.y = out.gps->velocity_ned.x();
      v.twist.angular.z = -out.gps->rate_of_turn;
      vel_pub_.publish(v);
      gps_pub_.publish(ros_util::navSatFix(out.gps->fix, out.gps->position_sigma, stamp, "usv/gps",
                                           sensor_msgs::NavSatStatus::STATUS_SBAS_FIX));
    }
    const auto& p = sim_->model().params();
    for (int i = 0; i < 2; ++i) {  // each unit's status frame, as the gateway decodes it
      if (!out.jet_status[i]) continue;
      const auto j = sim_->model().jet(i);
      WaterjetStatus w;
      w.header.stamp = stamp;
      w.jet = static_cast<std::uint8_t>(i);
      w.rpm = j.rpm;
      w.nozzle_position = std::clamp(-j.nozzle / p.nozzle_max, -1.0, 1.0);  // P < 0 turns to starboard
      w.bucket_position = j.bucket;
      jet_pub_.publish(w);
    }
    if (out.gateway_changed && answering_pub_) {
      const sim::GatewayReport& g = sim_->gateway();
      WaterjetAnswering a;
      a.header.stamp = stamp;
      a.answering = {g.answering[0], g.answering[1]};
      answering_pub_.publish(a);
      CanBusState b;
      b.header.stamp = stamp;
      b.state = g.bus_off ? CanBusState::STATE_BUS_OFF : CanBusState::STATE_ERROR_ACTIVE;
      b.state_name = g.bus_off ? "bus_off" : "error_active";
      bus_pub_.publish(b);
    }
    if (out.lidar && lidar_pub_.getNumSubscribers() > 0) {
      // the MRS1000's built-in IMU: the sensor's attitude with each frame (REP-103 FLU: the FRD pitch negated)
      sensor_msgs::Imu imu;
      imu.header.stamp = stamp;
      imu.header.frame_id = "usv/lidar";
      tf2::Quaternion q;
      q.setRPY(sim_->scan().roll, -sim_->scan().pitch, 0.0);  // the heading is not the IMU's to give
      imu.orientation.x = q.x(), imu.orientation.y = q.y(), imu.orientation.z = q.z(), imu.orientation.w = q.w();
      const double var = std::pow(cfg_lidar_imu_sigma_, 2);
      imu.orientation_covariance = {var, 0, 0, 0, var, 0, 0, 0, -1};  // no yaw
      imu.angular_velocity_covariance[0] = imu.linear_acceleration_covariance[0] = -1;  // not given
      lidar_imu_pub_.publish(imu);
      lidar_pub_.publish(cloudMessage(sim_->scan(), stamp));
    }
    return s.t;
  }

  // sim::packCloud's bytes (organised, usv/lidar FLU, NaN for no return) with their field description.
  sensor_msgs::PointCloud2 cloudMessage(const sim::LidarScan& scan, const ros::Time& stamp) {
    sim::packCloud(scan, packed_);
    sensor_msgs::PointCloud2 c;
    c.header.stamp = stamp;
    c.header.frame_id = "usv/lidar";
    auto field = [](const char* name, std::uint32_t offset, std::uint8_t type) {
      sensor_msgs::PointField f;
      f.name = name;
      f.offset = offset;
      f.datatype = type;
      f.count = 1;
      return f;
    };
    using P = sim::PackedCloud;
    c.fields = {field("x", P::kX, sensor_msgs::PointField::FLOAT32), field("y", P::kY, sensor_msgs::PointField::FLOAT32),
                field("z", P::kZ, sensor_msgs::PointField::FLOAT32),
                field("ring", P::kRing, sensor_msgs::PointField::UINT16)};
    c.height = packed_.height;
    c.width = packed_.width;
    c.point_step = P::kPointStep;
    c.row_step = c.width * c.point_step;
    c.is_bigendian = false;
    c.is_dense = false;
    c.data = packed_.data;
    return c;
  }

  nav_msgs::OccupancyGrid gridMessage() const {
    const auto& m = scenario_.map;
    nav_msgs::OccupancyGrid g;
    g.header.frame_id = "map";  // ENU: grid x = east, y = north, the layout of sim::MapGrid
    g.info.resolution = static_cast<float>(m.resolution);
    g.info.width = m.width;
    g.info.height = m.height;
    g.info.origin.position.x = m.east;
    g.info.origin.position.y = m.north;
    g.info.origin.orientation.w = 1.0;
    g.data = m.data;
    return g;
  }

  sim::Scenario scenario_;
  std::unique_ptr<sim::UsvSimulation> sim_;
  std::unique_ptr<sim_ros::SimRunner> runner_;
  std::unique_ptr<ros_util::FaultInjector> faults_;
  Counters counters_;
  std::string base_frame_, command_topic_, jet_command_topic_;
  double manual_timeout_ = 1.0, last_manual_ = -1e9;
  unsigned long truth_count_ = 0;
  sim::PackedCloud packed_;
  ros::Publisher jet_pub_, answering_pub_, bus_pub_, truth_pub_, gps_pub_, heading_pub_, vel_pub_, lidar_pub_, map_pub_;
  ros::Publisher lidar_imu_pub_;
  double cfg_lidar_imu_sigma_ = 0.0;
  ros::Subscriber auto_sub_, manual_sub_;
  tf2_ros::StaticTransformBroadcaster static_tf_;
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::WallTimer diag_timer_;
};

}  // namespace offshore_gnc

PLUGINLIB_EXPORT_CLASS(offshore_gnc::UsvSimNodelet, nodelet::Nodelet)

#include "ros_perception.h"

#include <sensor_msgs/PointField.h>
#include <tf2/exceptions.h>
#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/perception/sensor_frame.h"
#include "offshore_gnc/ros/diagnostics.h"

namespace offshore_gnc {
namespace perception_ros {

namespace {
constexpr double kPoseSilentS = 1.0;  // a pose this much older than a message: its source has stopped [s]
constexpr double kArrowS = 5.0;       // a track's velocity arrow: where it would be this much later [s]
constexpr double kMovingMps = 0.1;    // slower: no arrow (a buoy's would be a dot) [m/s]
}  // namespace

perception::CloudView cloudView(const sensor_msgs::PointCloud2& m) {
  perception::CloudView v;
  v.data = m.data.data();
  v.size = m.data.size();
  v.width = m.width;
  v.height = m.height;
  v.point_step = m.point_step;
  v.row_step = m.row_step;
  v.big_endian = m.is_bigendian;
  for (const auto& f : m.fields) {
    perception::CloudField* dst = nullptr;
    if (f.name == "x") dst = &v.x;
    else if (f.name == "y") dst = &v.y;
    else if (f.name == "z") dst = &v.z;
    else if (f.name == "ring") dst = &v.ring;
    if (!dst) continue;
    dst->present = true;
    dst->offset = f.offset;
    dst->datatype = f.datatype;
    dst->count = f.count;
  }
  return v;
}

perception::SonarBeamView beamView(const offshore_gnc::SonarBeam& m) {
  perception::SonarBeamView v;
  v.stamp = m.header.stamp.toSec();
  v.bearing = m.bearing;
  v.beam_width = m.beam_width;
  v.range_resolution = m.range_resolution;
  v.range_offset = m.range_offset;
  v.status = m.head_status;
  v.bins = m.intensities.data();
  v.num_bins = m.intensities.size();
  return v;
}

bool lookupPose(const tf2_ros::Buffer& tf, const std::string& target, const std::string& source,
                const ros::Time& stamp, double timeout, Eigen::Isometry3d& pose, std::string& error) {
  try {
    // Without any transform between the frames yet (the AUV's navigation before its first USBL fix) waiting
    // would only block the manager's threads for `timeout` per message: fail at once.
    if (!tf.canTransform(target, source, ros::Time(0))) {
      error = "no transform " + target + " <- " + source + " yet";
      return false;
    }
    // Likewise once the pose has stopped (the navigation without an estimate: its `nav` fault, docs/safety.md):
    // every message waited `timeout` for it, and at the simulation's speed-up that starved the manager's timers
    // (the supervisor's and the controller's ticks came seconds late).
    const ros::Time latest = tf.lookupTransform(target, source, ros::Time(0)).header.stamp;
    if (!latest.isZero() && stamp - latest > ros::Duration(std::max(kPoseSilentS, 10.0 * timeout))) {
      error = "no transform " + target + " <- " + source + " for " + std::to_string((stamp - latest).toSec()) + " s";
      return false;
    }
    const auto t = tf.lookupTransform(target, source, stamp, ros::Duration(timeout));
    pose = tf2::transformToEigen(t);
    return true;
  } catch (const tf2::TransformException& e) {
    error = e.what();
    return false;
  }
}

BeamFed SonarFeed::feed(const offshore_gnc::SonarBeam& msg, const std::string& who) {
  perception::SonarTargetExtractor& ex = *extractor;
  const perception::SonarBeamView beam = beamView(msg);
  if (!ex.check(beam)) {
    ROS_ERROR_THROTTLE(5.0, "%s: rejected sonar beam: %zu bins, bearing %.3f rad, resolution %.3f m (counters in "
                       "diagnostics)", who.c_str(), beam.num_bins, beam.bearing, beam.range_resolution);
    return BeamFed::Rejected;
  }
  Eigen::Isometry3d pose;
  std::string err;
  if (!lookupPose(*tf, target_frame, msg.header.frame_id, msg.header.stamp, tf_timeout, pose, err)) {
    ex.counters().increment("no_transform");
    ex.breakRun();
    ROS_WARN_THROTTLE(5.0, "%s: dropping sonar beam: no transform %s <- %s at %.3f: %s", who.c_str(),
                      target_frame.c_str(), msg.header.frame_id.c_str(), msg.header.stamp.toSec(), err.c_str());
    return BeamFed::NoPose;
  }
  // the head's depth for the surface gate: the world frames' origin lies on the water surface (z down in map_ned,
  // up in map)
  const double z = pose.translation().z();
  ex.addBeam(beam, pose, target_frame == "map" ? -z : z);
  return BeamFed::Added;
}

geometry_msgs::Point toPoint(const Eigen::Vector3d& v) {
  geometry_msgs::Point p;
  p.x = v.x();
  p.y = v.y();
  p.z = v.z();
  return p;
}

offshore_gnc::Target toTarget(const perception::TargetGeometry& sensor_frame, const Eigen::Isometry3d& T,
                              std::uint8_t source, double bearing_cw) {
  const perception::TargetGeometry g = perception::transformed(sensor_frame, T);
  offshore_gnc::Target t;
  t.source = source;
  t.origin = toPoint(g.origin);
  t.centroid = toPoint(g.centroid);
  t.nearest = toPoint(g.nearest);
  t.length = g.length;
  t.axis.x = g.axis.x();
  t.axis.y = g.axis.y();
  t.axis.z = g.axis.z();
  t.width = g.width;
  t.height = g.height;
  t.range = g.range;
  t.bearing = bearing_cw;
  t.num_points = static_cast<std::uint32_t>(g.num_points);
  t.confidence = 1.0f;
  t.latitude = t.longitude = t.depth = std::numeric_limits<double>::quiet_NaN();
  return t;
}

std::vector<visualization_msgs::Marker> targetMarkers(const std::vector<offshore_gnc::Target>& targets, float r,
                                                    float g, float b) {
  std::vector<visualization_msgs::Marker> a;
  for (const auto& t : targets) {
    visualization_msgs::Marker m;
    m.type = visualization_msgs::Marker::CYLINDER;
    m.pose.position = t.origin;
    m.pose.orientation.w = 1.0;
    const double d = std::max({t.length, t.width, 0.3});
    m.scale.x = m.scale.y = d;
    m.scale.z = std::max(t.height, 0.5);
    m.color.r = r;
    m.color.g = g;
    m.color.b = b;
    m.color.a = 0.8f;
    a.push_back(m);
  }
  return a;
}

offshore_gnc::Track toTrack(const perception::Track& tr, double now) {
  offshore_gnc::Track m;
  m.id = tr.id;
  m.status = tr.confirmed ? offshore_gnc::Track::CONFIRMED : offshore_gnc::Track::TENTATIVE;
  m.position.x = tr.x(0);
  m.position.y = tr.x(1);
  m.velocity.x = tr.x(2);
  m.velocity.y = tr.x(3);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) m.covariance[4 * i + j] = tr.P(i, j);
  m.length = tr.length;
  m.width = tr.width;
  m.hits = static_cast<std::uint32_t>(tr.hits);
  m.age = now - tr.born;
  m.unseen = now - tr.last_seen;
  return m;
}

std::vector<visualization_msgs::Marker> trackMarkers(const std::vector<perception::Track>& tracks) {
  std::vector<visualization_msgs::Marker> a;
  for (const auto& tr : tracks) {
    if (!tr.confirmed) continue;
    const double speed = tr.velocity().norm();
    visualization_msgs::Marker text;
    text.type = visualization_msgs::Marker::TEXT_VIEW_FACING;
    text.pose.position = toPoint(Eigen::Vector3d(tr.x(0), tr.x(1), -2.5));  // above the water (z down)
    char b[48];
    std::snprintf(b, sizeof b, "#%u %.1f m/s", tr.id, speed);
    text.text = b;
    text.scale.z = 1.0;
    text.color.r = text.color.g = text.color.b = 1.0f;
    text.color.a = 1.0f;
    a.push_back(text);
    if (speed < kMovingMps) continue;
    visualization_msgs::Marker arrow;
    arrow.type = visualization_msgs::Marker::ARROW;
    arrow.points = {toPoint(Eigen::Vector3d(tr.x(0), tr.x(1), -1.0)),
                    toPoint(Eigen::Vector3d(tr.x(0) + kArrowS * tr.x(2), tr.x(1) + kArrowS * tr.x(3), -1.0))};
    arrow.scale.x = 0.2;  // shaft diameter, head diameter and length [m]
    arrow.scale.y = 0.6;
    arrow.scale.z = 0.8;
    arrow.color.r = 0.0f;
    arrow.color.g = 0.8f;
    arrow.color.b = 1.0f;
    arrow.color.a = 0.9f;
    a.push_back(arrow);
  }
  return a;
}

void SonarFeed::readParams(const ros_util::ParamReader& p) {
  perception::SonarConfig c;
  ros_util::readParams(p, perception::SonarConfig::table(), c);
  extractor = std::make_unique<perception::SonarTargetExtractor>(c);
  perception::SensorFrameParams f;
  ros_util::readParams(p, perception::SensorFrameParams::table(), f);
  target_frame = f.target_frame;
  tf_timeout = f.tf_timeout;
  extractor->setWorldZUp(target_frame == "map");
}

void SonarFeed::connect(ros::NodeHandle& nh) {
  tf = std::make_unique<tf2_ros::Buffer>();
  listener = std::make_unique<tf2_ros::TransformListener>(*tf, nh);
}

Diagnostics::Diagnostics(ros::NodeHandle& nh, ros::NodeHandle& pnh, const std::string& name,
                         const Counters& counters,
                         std::function<void(diagnostic_updater::DiagnosticStatusWrapper&)> extra) {
  updater_ = std::make_unique<diagnostic_updater::Updater>(nh, pnh, name);
  updater_->setHardwareID(name);
  updater_->add("perception", [&counters, extra](diagnostic_updater::DiagnosticStatusWrapper& s) {
    s.summary(diagnostic_msgs::DiagnosticStatus::OK, "running");
    if (extra) extra(s);
    ros_util::addCounters(s, counters,
                          {"empty_cloud", "missing_xyz", "bad_field", "size_mismatch", "big_endian", "no_transform",
                           "empty_beam", "bad_bearing", "bad_beam_geometry", "bad_pose", "non_finite_point",
                           "wrong_frame"});
  });
  timer_ = nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_->force_update(); });
}

}  // namespace perception_ros
}  // namespace offshore_gnc

// Rosbag -> identification log: each topic's samples on one time axis (header stamps), commands held.
#include "ros_identification_bag.h"

#include <geometry_msgs/QuaternionStamped.h>
#include <geometry_msgs/TwistStamped.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/NavSatFix.h>
#include <tf2/utils.h>

#include <cmath>
#include <limits>
#include <map>

#include "offshore_gnc/JoystickCommand.h"
#include "offshore_gnc/ThrusterSetpoints.h"
#include "offshore_gnc/WaterjetStatus.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/geo/geo.h"

namespace offshore_gnc {
namespace identification_ros {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct Sample {
  std::map<std::string, double> values;
};

double stamp(const ros::Time& header, const rosbag::MessageInstance& m) {
  return header.isZero() ? m.getTime().toSec() : header.toSec();
}

template <class Msg>
std::vector<std::pair<double, typename Msg::ConstPtr>> read(rosbag::Bag& bag, const std::string& topic) {
  std::vector<std::pair<double, typename Msg::ConstPtr>> out;
  rosbag::View view(bag, rosbag::TopicQuery(topic));
  for (const auto& m : view)
    if (const auto p = m.instantiate<Msg>()) out.emplace_back(stamp(p->header.stamp, m), p);
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  return out;
}

// The rows: union of all stamps (ns resolution), values per row; commands held from their own stamps.
identification::IdentLog assemble(const std::string& path, const std::vector<std::string>& cmd_names,
                          const std::vector<std::pair<double, std::vector<double>>>& commands,
                          std::map<std::int64_t, Sample>& rows) {
  identification::IdentLog log;
  log.source = path;
  log.command_names = cmd_names;
  if (commands.empty()) throw ConfigError(path + ": the bag has no command messages");
  for (const auto& c : commands) rows[std::llround(c.first * 1e9)];
  const double t0 = commands.front().first;
  std::size_t dropped = 0;
  std::vector<std::int64_t> keys;
  for (const auto& kv : rows) {
    if (kv.first < std::llround(t0 * 1e9)) {
      ++dropped;
      continue;
    }
    keys.push_back(kv.first);
  }
  if (dropped) log.notes.push_back(std::to_string(dropped) + " samples before the first command were left out");
  const std::size_t n = keys.size();
  log.t.resize(n);
  log.commands.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(cmd_names.size()));
  std::size_t c = 0;
  for (std::size_t i = 0; i < n; ++i) {
    log.t[i] = keys[i] * 1e-9;
    while (c + 1 < commands.size() && std::llround(commands[c + 1].first * 1e9) <= keys[i]) ++c;
    for (std::size_t k = 0; k < cmd_names.size(); ++k)
      log.commands(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) = commands[c].second[k];
    for (const auto& kv : rows[keys[i]].values) {
      auto& v = log.measured[kv.first];
      if (v.empty()) v.assign(n, kNaN);
      v[i] = kv.second;
    }
  }
  return log;
}

}  // namespace

identification::IdentLog readIdentLogBag(const std::string& path, identification::FitVehicle v, int thrusters, const BagOptions& opt) {
  rosbag::Bag bag;
  try {
    bag.open(path, rosbag::bagmode::Read);
  } catch (const std::exception& e) {
    throw ConfigError(path + ": cannot read the bag: " + e.what());
  }
  std::map<std::int64_t, Sample> rows;
  auto put = [&](double t, const std::string& s, double value) { rows[std::llround(t * 1e9)].values[s] = value; };
  std::vector<std::pair<double, std::vector<double>>> commands;

  if (v == identification::FitVehicle::Usv) {
    // Commands as the simulator applies them: the CAN chain's applied command if recorded, else manual
    // (while fresh) over autonomy.
    auto applied = read<JoystickCommand>(bag, "/usv/waterjet/applied_cmd");
    if (!applied.empty()) {
      for (const auto& m : applied) commands.push_back({m.first, {m.second->surge, m.second->sway, m.second->yaw}});
    } else {
      const auto autonomy = read<JoystickCommand>(bag, "/usv/joystick_cmd");
      const auto manual = read<JoystickCommand>(bag, "/usv/manual_cmd");
      std::size_t a = 0, m = 0;
      double last_manual = -1e300;
      while (a < autonomy.size() || m < manual.size()) {
        const bool take_manual = m < manual.size() && (a >= autonomy.size() || manual[m].first <= autonomy[a].first);
        const auto& msg = take_manual ? manual[m++] : autonomy[a++];
        if (take_manual) last_manual = msg.first;
        else if (msg.first - last_manual < opt.manual_timeout) continue;  // overridden by the operator
        commands.push_back({msg.first, {msg.second->surge, msg.second->sway, msg.second->yaw}});
      }
    }
    const auto gps = read<sensor_msgs::NavSatFix>(bag, "/usv_gps");
    if (gps.empty()) throw ConfigError(path + ": the bag has no /usv_gps fixes");
    const geo::LocalNed frame(geo::LatLonAlt{gps.front().second->latitude, gps.front().second->longitude, 0.0});
    for (const auto& g : gps) {
      if (!std::isfinite(g.second->latitude) || !std::isfinite(g.second->longitude)) continue;
      const Eigen::Vector3d p = frame.toNed(geo::LatLonAlt{g.second->latitude, g.second->longitude, 0.0});
      put(g.first, "north", p.x());
      put(g.first, "east", p.y());
    }
    std::vector<std::pair<double, double>> headings;
    for (const auto& h : read<geometry_msgs::QuaternionStamped>(bag, "/usv_heading")) {
      const double yaw = geo::enuYawToNed(tf2::getYaw(h.second->quaternion));
      headings.emplace_back(h.first, yaw);
      put(h.first, "yaw_rad", yaw);
    }
    std::size_t h = 0;
    for (const auto& tw : read<geometry_msgs::TwistStamped>(bag, "/usv/gps/velocity")) {
      // ENU ground velocity into body axes with the latest heading; angular.z is the rate of turn (ENU)
      while (h + 1 < headings.size() && headings[h + 1].first <= tw.first) ++h;
      const double vn = tw.second->twist.linear.y, ve = tw.second->twist.linear.x;
      if (!headings.empty()) {
        const double c = std::cos(headings[h].second), s = std::sin(headings[h].second);
        put(tw.first, "u", c * vn + s * ve);
        put(tw.first, "v", -s * vn + c * ve);
      }
      put(tw.first, "r_rad_s", -tw.second->twist.angular.z);
    }
    for (const auto& w : read<WaterjetStatus>(bag, "/usv/waterjet/status")) {
      if (w.second->jet != 0) continue;  // both jets get the same command; the port one is logged
      put(w.first, "rpm", w.second->rpm);
      put(w.first, "nozzle", -w.second->nozzle_position * opt.nozzle_max);  // P < 0 turns to starboard
    }
    return assemble(path, {"surge", "sway", "yaw"}, commands, rows);
  }
  if (v == identification::FitVehicle::AColor)
    throw ConfigError(path + ": aColor bags carry RC channels (/auv/rc_channels), which the flight controller "
                             "mixes; convert them to per-thruster commands in a CSV (docs/model-identification.md)");
  for (const auto& s : read<ThrusterSetpoints>(bag, "/auv/thruster_setpoints")) {
    if (static_cast<int>(s.second->setpoint.size()) != thrusters) continue;
    commands.push_back({s.first, s.second->setpoint});
  }
  for (const auto& o : read<nav_msgs::Odometry>(bag, "/auv/odom")) {
    const auto& p = o.second->pose.pose.position;
    const auto& t = o.second->twist.twist;
    put(o.first, "north", p.y);
    put(o.first, "east", p.x);
    put(o.first, "down", -p.z);
    put(o.first, "yaw_rad", geo::enuYawToNed(tf2::getYaw(o.second->pose.pose.orientation)));
    put(o.first, "u", t.linear.x);  // base_link FLU -> FRD
    put(o.first, "v", -t.linear.y);
    put(o.first, "w", -t.linear.z);
    put(o.first, "r_rad_s", -t.angular.z);
  }
  std::vector<std::string> names;
  for (int i = 0; i < thrusters; ++i) names.push_back("c" + std::to_string(i + 1));
  return assemble(path, names, commands, rows);
}

}  // namespace identification_ros
}  // namespace offshore_gnc

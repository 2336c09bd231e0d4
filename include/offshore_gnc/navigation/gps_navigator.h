#pragma once
// USV navigation from the GPS-compass (simulation and hardware alike): WGS84 fix + heading -> local NED pose;
// body velocity and yaw rate from the receiver's Doppler velocity and rate of turn when it reports them, else
// from successive fixes and headings (low-pass filtered; far noisier). ROS-free; the GpsNavigation nodelet wraps it.
#include <optional>
#include <string>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/models/state.h"

namespace offshore_gnc {
namespace navigation {

struct GpsNavigatorConfig {
  Eigen::Vector3d antenna{0, 0, -2.5};  // antenna in body FRD [m], removed from the fix
  double heading_timeout = 1.0;         // a fix needs a heading at most this old [s]
  double velocity_filter = 0.5;         // first-order filter time constant on differenced velocity [s]
  static const ParamTable<GpsNavigatorConfig>& table();
};

// The GpsNavigation nodelet's own parameters around the navigator.
struct GpsNavigationParams {
  // angular.z of the velocity message is the receiver's rate of turn (simulator); false for receivers that report
  // none (NMEA 2000 COG/SOG through the CAN gateway): the rate then comes from differenced headings
  bool use_rate_of_turn = true;
  std::string base_frame = "usv/base_link", world_frame = "map";
  static const ParamTable<GpsNavigationParams>& table();
};

class GpsNavigator {
 public:
  GpsNavigator(const geo::LatLonAlt& origin, const GpsNavigatorConfig& cfg);
  // Heading (NED yaw) at time t; false and counted when not finite.
  bool heading(double t, double yaw);
  // A fix at time t: the new state estimate, or nothing (counted) when the fix is unusable or no recent heading.
  std::optional<VehicleState> fix(double t, const geo::LatLonAlt& p);
  // The receiver's velocity over ground (NED, at the antenna) and rate of turn at time t (NaN: the receiver
  // reports none; the rate then comes from differenced headings); used by the fixes that follow within
  // heading_timeout. False and counted when not finite.
  bool velocity(double t, const Eigen::Vector2d& v_ned, double rate_of_turn);
  const Counters& counters() const { return counters_; }
  const geo::LocalNed& frame() const { return frame_; }

 private:
  geo::LocalNed frame_;
  GpsNavigatorConfig cfg_;
  double heading_t_ = -1e300, yaw_ = 0.0, yaw_rate_ = 0.0;
  double velocity_t_ = -1e300, rate_of_turn_ = 0.0;
  Eigen::Vector2d v_ned_ = Eigen::Vector2d::Zero();
  std::optional<VehicleState> last_;
  Counters counters_;
};

}  // namespace navigation
}  // namespace offshore_gnc

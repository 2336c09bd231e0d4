#pragma once
// Geodesy for the whole stack (WGS84, ETRS-TM35FIN, local NED), computed with GeographicLib.
#include <Eigen/Core>
#include <memory>

#include "offshore_gnc/common/param_table.h"

namespace GeographicLib {
class LocalCartesian;
}

namespace offshore_gnc {
namespace geo {

struct LatLonAlt {
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double alt_m = 0.0;  // ellipsoidal height
  // latitude, longitude, altitude: the names of an `origin` in vehicle configs and scenarios.
  static const ParamTable<LatLonAlt>& table();
};

// Projected coordinates in ETRS-TM35FIN (EPSG:3067: transverse Mercator, UTM zone 35N on ETRS89;
// ETRS89 and WGS84 agree to well under a metre, which we accept).
struct Tm35 {
  double easting_m = 0.0;
  double northing_m = 0.0;
};

Tm35 toTm35fin(const LatLonAlt& p);
LatLonAlt fromTm35fin(const Tm35& p, double alt_m = 0.0);

// Distance along the WGS84 ellipsoid between two points' latitude and longitude [m] (heights ignored).
double surfaceDistance(const LatLonAlt& a, const LatLonAlt& b);

// Local tangent plane around a fixed origin. NED: x north, y east, z down (thesis convention).
class LocalNed {
 public:
  explicit LocalNed(const LatLonAlt& origin);
  ~LocalNed();
  LocalNed(const LocalNed& other);
  LocalNed& operator=(const LocalNed& other);

  Eigen::Vector3d toNed(const LatLonAlt& p) const;
  LatLonAlt toGeodetic(const Eigen::Vector3d& ned) const;
  const LatLonAlt& origin() const { return origin_; }

 private:
  LatLonAlt origin_;
  std::unique_ptr<GeographicLib::LocalCartesian> lc_;
};

// NED <-> ENU (REP-103 'map' frame) swap, used wherever a ROS frame meets the NED maths.
inline Eigen::Vector3d nedToEnu(const Eigen::Vector3d& v) { return {v.y(), v.x(), -v.z()}; }
inline Eigen::Vector3d enuToNed(const Eigen::Vector3d& v) { return {v.y(), v.x(), -v.z()}; }
// NED yaw (clockwise from north) <-> ENU yaw (counter-clockwise from east).
double nedYawToEnu(double yaw_ned);
double enuYawToNed(double yaw_enu);

// Pyhäjärvi lake, Tampere: where the thesis' field tests ran; default simulation origin.
constexpr LatLonAlt kPyhajarviOrigin{61.4507, 23.7270, 0.0};

}  // namespace geo
}  // namespace offshore_gnc

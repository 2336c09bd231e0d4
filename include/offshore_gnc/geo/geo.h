#pragma once
// Geodesy for the whole stack, valid anywhere on Earth (GeographicLib): WGS84, local NED about the operation's
// origin (the GNC maths), UTM/UPS in the origin's own zone (the map grid reported to operators), and the
// thesis' national grid ETRS-TM35FIN only where it applies.
#include <Eigen/Core>
#include <memory>
#include <string>

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

// The WorldFrames nodelet's parameters: the ENU and NED frames it publishes about the origin, and the national grid
// it reports beside the origin's UTM/UPS zone ("none" or "etrs-tm35fin").
struct WorldFramesParams {
  std::string world_frame = "map", ned_frame = "map_ned", national_grid = "none";
  static const ParamTable<WorldFramesParams>& table();
};

// "LAT,LON[,ALT]" (degrees, degrees, metres; the launch argument origin:=...) -> a checked point; throws
// ConfigError quoting the text when it is not three (or two) finite numbers in range.
LatLonAlt parseLatLonAlt(const std::string& text);
// Throws ConfigError naming `what` when the point is not finite or out of range.
void checkLatLonAlt(const LatLonAlt& p, const std::string& what = "origin");

// Projected coordinates of the UTM/UPS system. zone 1-60: UTM; zone 0: UPS (polar stereographic).
struct GridPoint {
  int zone = 0;
  bool north = true;
  double easting_m = 0.0;
  double northing_m = 0.0;
};
// The point's standard zone (UTM with the Norway and Svalbard exceptions; 0 = UPS beyond 84 N and 80 S).
int standardZone(const LatLonAlt& p);
// In `zone` (-1: the point's own). A point a little across a zone edge stays in the zone asked for (a site's
// grid is its origin's zone); one too far for the projection throws ConfigError naming zone and point.
GridPoint toUtmUps(const LatLonAlt& p, int zone = -1);
LatLonAlt fromUtmUps(const GridPoint& g, double alt_m = 0.0);
std::string gridName(const GridPoint& g);  // "UTM 35N", "UPS S"

// ETRS-TM35FIN (EPSG:3067: transverse Mercator, UTM zone 35N on ETRS89, which agrees with WGS84 to well under a
// metre), the Finnish national grid of the thesis. Defined for EPSG:3067's area of use only (Finland and its
// waters, inTm35finArea); elsewhere toTm35fin throws ConfigError.
bool inTm35finArea(const LatLonAlt& p);
GridPoint toTm35fin(const LatLonAlt& p);
LatLonAlt fromTm35fin(const GridPoint& p, double alt_m = 0.0);

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

// Pyhäjärvi lake, Tampere: where the thesis' field tests ran (the default scenario's origin; tests and benches).
constexpr LatLonAlt kPyhajarviOrigin{61.4507, 23.7270, 0.0};

}  // namespace geo
}  // namespace offshore_gnc

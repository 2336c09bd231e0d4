#include "offshore_gnc/geo/geo.h"

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/LocalCartesian.hpp>
#include <GeographicLib/UTMUPS.hpp>

#include <cstdio>
#include <sstream>
#include <vector>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace geo {

const ParamTable<LatLonAlt>& LatLonAlt::table() {
  using P = LatLonAlt;
  static const ParamTable<P> t = ParamTable<P>()
      .number("latitude", &P::lat_deg, -90.0, 90.0, "deg", "WGS84 latitude of the local frames' origin")
      .number("longitude", &P::lon_deg, -180.0, 180.0, "deg", "WGS84 longitude of the origin")
      .number("altitude", &P::alt_m, -1000.0, 10000.0, "m", "ellipsoidal height of the origin");
  return t;
}

const ParamTable<WorldFramesParams>& WorldFramesParams::table() {
  using P = WorldFramesParams;
  static const ParamTable<P> t = ParamTable<P>()
      .string("world_frame", &P::world_frame, "the ENU frame at the origin")
      .string("ned_frame", &P::ned_frame, "the NED frame at the origin (the GNC's)")
      .choice("national_grid", &P::national_grid, {"none", "etrs-tm35fin"}, "a national grid reported beside UTM/UPS");
  return t;
}

namespace {
constexpr int kTm35Zone = 35;
// EPSG:3067's area of use (Finland, onshore and offshore) [deg]
constexpr double kTm35South = 58.84, kTm35North = 70.09, kTm35West = 19.08, kTm35East = 31.59;

void checkLatLon(const LatLonAlt& p) {
  requireRange("latitude", p.lat_deg, -90.0, 90.0);
  requireRange("longitude", p.lon_deg, -180.0, 180.0);
}

std::string describe(const LatLonAlt& p) {
  char b[64];
  std::snprintf(b, sizeof b, "(%.6f, %.6f)", p.lat_deg, p.lon_deg);
  return b;
}
}  // namespace

void checkLatLonAlt(const LatLonAlt& p, const std::string& what) {
  for (const auto& s : LatLonAlt::table().specs()) {
    LatLonAlt q = p;
    requireRange(what + "/" + s.name, s.number(q), s.lo, s.hi);
  }
}

LatLonAlt parseLatLonAlt(const std::string& text) {
  std::vector<double> v;
  std::stringstream ss(text);
  std::string item;
  bool ok = true;
  while (std::getline(ss, item, ',')) {
    std::size_t used = 0;
    try {
      v.push_back(std::stod(item, &used));
    } catch (const std::exception&) {
      ok = false;
    }
    ok = ok && item.find_first_not_of(" \t", used) == std::string::npos;
  }
  if (!ok || v.size() < 2 || v.size() > 3)
    throw ConfigError("origin '" + text + "' is not LAT,LON[,ALT] (degrees, degrees, metres), e.g. 61.4507,23.7270,0");
  LatLonAlt p{v[0], v[1], v.size() > 2 ? v[2] : 0.0};
  checkLatLonAlt(p);
  return p;
}

int standardZone(const LatLonAlt& p) {
  checkLatLon(p);
  return GeographicLib::UTMUPS::StandardZone(p.lat_deg, p.lon_deg);
}

GridPoint toUtmUps(const LatLonAlt& p, int zone) {
  checkLatLon(p);
  GridPoint g;
  try {
    GeographicLib::UTMUPS::Forward(p.lat_deg, p.lon_deg, g.zone, g.north, g.easting_m, g.northing_m,
                                   zone < 0 ? GeographicLib::UTMUPS::STANDARD : zone);
  } catch (const GeographicLib::GeographicErr& e) {
    throw ConfigError("point " + describe(p) + " cannot be projected in " +
                      (zone == 0 ? std::string("UPS") : "UTM zone " + std::to_string(zone)) + ": " + e.what());
  }
  return g;
}

LatLonAlt fromUtmUps(const GridPoint& g, double alt_m) {
  LatLonAlt out;
  try {
    GeographicLib::UTMUPS::Reverse(g.zone, g.north, g.easting_m, g.northing_m, out.lat_deg, out.lon_deg);
  } catch (const GeographicLib::GeographicErr& e) {
    throw ConfigError("grid point " + gridName(g) + " " + std::to_string(g.easting_m) + " E " +
                      std::to_string(g.northing_m) + " N is outside the grid: " + e.what());
  }
  out.alt_m = alt_m;
  return out;
}

std::string gridName(const GridPoint& g) {
  return (g.zone == 0 ? std::string("UPS ") : "UTM " + std::to_string(g.zone)) + (g.north ? "N" : "S");
}

bool inTm35finArea(const LatLonAlt& p) {
  return p.lat_deg >= kTm35South && p.lat_deg <= kTm35North && p.lon_deg >= kTm35West && p.lon_deg <= kTm35East;
}

GridPoint toTm35fin(const LatLonAlt& p) {
  checkLatLon(p);
  if (!inTm35finArea(p))
    throw ConfigError("ETRS-TM35FIN is defined for Finland only (latitude 58.84-70.09, longitude 19.08-31.59); " +
                      describe(p) + " is outside it: use the site's UTM/UPS grid");
  // Zone 35 also for the parts of Finland in zones 34 and 36: that is what the national grid is.
  return toUtmUps(p, kTm35Zone);
}

LatLonAlt fromTm35fin(const GridPoint& p, double alt_m) {
  GridPoint g = p;
  g.zone = kTm35Zone;
  g.north = true;
  return fromUtmUps(g, alt_m);
}

double surfaceDistance(const LatLonAlt& a, const LatLonAlt& b) {
  double s12 = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(a.lat_deg, a.lon_deg, b.lat_deg, b.lon_deg, s12);
  return s12;
}

LocalNed::LocalNed(const LatLonAlt& origin) : origin_(origin) {
  checkLatLonAlt(origin);
  lc_ = std::make_unique<GeographicLib::LocalCartesian>(origin.lat_deg, origin.lon_deg, origin.alt_m);
}
LocalNed::~LocalNed() = default;
LocalNed::LocalNed(const LocalNed& other) : LocalNed(other.origin_) {}
LocalNed& LocalNed::operator=(const LocalNed& other) {
  if (this != &other) {
    origin_ = other.origin_;
    lc_ = std::make_unique<GeographicLib::LocalCartesian>(*other.lc_);
  }
  return *this;
}

Eigen::Vector3d LocalNed::toNed(const LatLonAlt& p) const {
  checkLatLon(p);
  double e = 0, n = 0, u = 0;
  lc_->Forward(p.lat_deg, p.lon_deg, p.alt_m, e, n, u);
  return {n, e, -u};
}

LatLonAlt LocalNed::toGeodetic(const Eigen::Vector3d& ned) const {
  LatLonAlt out;
  lc_->Reverse(ned.y(), ned.x(), -ned.z(), out.lat_deg, out.lon_deg, out.alt_m);
  return out;
}

double nedYawToEnu(double yaw_ned) { return wrapAngle(kPi / 2.0 - yaw_ned); }
double enuYawToNed(double yaw_enu) { return wrapAngle(kPi / 2.0 - yaw_enu); }

}  // namespace geo
}  // namespace offshore_gnc

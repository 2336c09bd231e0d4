#include "offshore_gnc/geo/geo.h"

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/LocalCartesian.hpp>
#include <GeographicLib/UTMUPS.hpp>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace geo {

const ParamTable<LatLonAlt>& LatLonAlt::table() {
  using P = LatLonAlt;
  static const ParamTable<P> t = ParamTable<P>()
      .number("latitude", &P::lat_deg, -89.0, 89.0, "deg", "WGS84 latitude of the local frames' origin")
      .number("longitude", &P::lon_deg, -180.0, 180.0, "deg", "WGS84 longitude of the origin")
      .number("altitude", &P::alt_m, -1000.0, 10000.0, "m", "ellipsoidal height of the origin");
  return t;
}

namespace {
constexpr int kTm35Zone = 35;

void checkLatLon(const LatLonAlt& p) {
  requireRange("latitude", p.lat_deg, -90.0, 90.0);
  requireRange("longitude", p.lon_deg, -180.0, 180.0);
}
}  // namespace

Tm35 toTm35fin(const LatLonAlt& p) {
  checkLatLon(p);
  int zone = 0;
  bool north = true;
  Tm35 out;
  // Force zone 35 so points in neighbouring zones still land in the national grid.
  GeographicLib::UTMUPS::Forward(p.lat_deg, p.lon_deg, zone, north, out.easting_m, out.northing_m, kTm35Zone);
  return out;
}

LatLonAlt fromTm35fin(const Tm35& p, double alt_m) {
  LatLonAlt out;
  GeographicLib::UTMUPS::Reverse(kTm35Zone, true, p.easting_m, p.northing_m, out.lat_deg, out.lon_deg);
  out.alt_m = alt_m;
  return out;
}

double surfaceDistance(const LatLonAlt& a, const LatLonAlt& b) {
  double s12 = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(a.lat_deg, a.lon_deg, b.lat_deg, b.lon_deg, s12);
  return s12;
}

LocalNed::LocalNed(const LatLonAlt& origin)
    : origin_(origin),
      lc_(std::make_unique<GeographicLib::LocalCartesian>(origin.lat_deg, origin.lon_deg, origin.alt_m)) {
  checkLatLon(origin);
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

#include <gtest/gtest.h>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/geo/geo.h"

using namespace offshore_gnc;
using namespace offshore_gnc::geo;

TEST(Geo, OriginMapsToZero) {
  LocalNed f(kPyhajarviOrigin);
  EXPECT_NEAR(f.toNed(kPyhajarviOrigin).norm(), 0.0, 1e-6);
}

TEST(Geo, NorthAndEastOffsets) {
  LocalNed f(kPyhajarviOrigin);
  // Small offsets scale with the WGS84 radii of curvature at the origin's latitude (computed here, not
  // by GeographicLib): meridional M = a(1-e^2)/(1-e^2 sin^2)^1.5, prime vertical N = a/sqrt(1-e^2 sin^2).
  const double a = 6378137.0, fl = 1.0 / 298.257223563, e2 = fl * (2 - fl);
  const double phi = deg2rad(kPyhajarviOrigin.lat_deg), s2 = std::sin(phi) * std::sin(phi);
  const double M = a * (1 - e2) / std::pow(1 - e2 * s2, 1.5), N = a / std::sqrt(1 - e2 * s2);
  const double dlat = 1e-4, dlon = 1e-4;  // degrees: ~11 m and ~5 m
  LatLonAlt p = kPyhajarviOrigin;
  p.lat_deg += dlat;
  Eigen::Vector3d ned = f.toNed(p);
  EXPECT_NEAR(ned.x(), M * deg2rad(dlat), 1e-3);
  EXPECT_NEAR(ned.y(), 0.0, 1e-6);
  p = kPyhajarviOrigin;
  p.lon_deg += dlon;
  ned = f.toNed(p);
  EXPECT_NEAR(ned.y(), N * std::cos(phi) * deg2rad(dlon), 1e-3);
  EXPECT_NEAR(ned.x(), 0.0, 1e-3);
  EXPECT_GT(ned.z(), 0.0);  // the curved earth drops away below the tangent plane
}

TEST(Geo, RoundTrip) {
  LocalNed f(kPyhajarviOrigin);
  Eigen::Vector3d ned(123.4, -56.7, 8.9);
  Eigen::Vector3d back = f.toNed(f.toGeodetic(ned));
  EXPECT_NEAR((back - ned).norm(), 0.0, 1e-6);
}

TEST(Geo, Tm35finKnownPoint) {
  // Zone 35 central meridian 27 E, false easting 500 km: a point on it has easting 500000.
  Tm35 t = toTm35fin({61.0, 27.0, 0.0});
  EXPECT_NEAR(t.easting_m, 500000.0, 1e-3);
  // On the central meridian the northing is k0 = 0.9996 times the meridian arc, integrated here
  // independently of GeographicLib: M = int_0^phi a (1 - e^2) / (1 - e^2 sin^2)^(3/2).
  const double a = 6378137.0, f = 1.0 / 298.257223563, e2 = f * (2 - f);
  const double phi = deg2rad(61.0);
  const int n = 20000;
  double arc = 0.0;
  for (int i = 0; i < n; ++i) {  // midpoint rule, error << 1 mm
    const double p = (i + 0.5) * phi / n, s = std::sin(p);
    arc += a * (1 - e2) / std::pow(1 - e2 * s * s, 1.5) * phi / n;
  }
  EXPECT_NEAR(t.northing_m, 0.9996 * arc, 0.01);
  LatLonAlt back = fromTm35fin(t);
  EXPECT_NEAR(back.lat_deg, 61.0, 1e-9);
  EXPECT_NEAR(back.lon_deg, 27.0, 1e-9);
}

TEST(Geo, Tm35finOutsideZoneStillProjects) {
  // Tampere (23.7 E) lies in UTM zone 35 already, Åland (19.9 E) in zone 34: both must use zone 35.
  Tm35 t = toTm35fin({60.1, 19.9, 0.0});
  EXPECT_LT(t.easting_m, 200000.0);
  LatLonAlt back = fromTm35fin(t);
  EXPECT_NEAR(back.lon_deg, 19.9, 1e-8);
}

TEST(Geo, BadInputThrows) {
  EXPECT_THROW(LocalNed({95.0, 0.0, 0.0}), ConfigError);
  LocalNed f(kPyhajarviOrigin);
  EXPECT_THROW(f.toNed({std::nan(""), 23.0, 0.0}), ConfigError);
}

TEST(Geo, FrameSwaps) {
  Eigen::Vector3d ned(1, 2, 3);
  EXPECT_EQ(enuToNed(nedToEnu(ned)), ned);
  EXPECT_NEAR(nedYawToEnu(0.0), kPi / 2, 1e-12);       // north in NED = +90 deg in ENU
  EXPECT_NEAR(nedYawToEnu(kPi / 2), 0.0, 1e-12);       // east
  EXPECT_NEAR(enuYawToNed(nedYawToEnu(0.3)), 0.3, 1e-12);
}

TEST(Geo, SurfaceDistanceOnTheEllipsoid) {
  // One degree along the equator is a * pi / 180; one degree of meridian from the equator is shorter (flattening).
  EXPECT_NEAR(surfaceDistance({0, 0, 0}, {0, 1, 0}), 6378137.0 * M_PI / 180.0, 1e-3);
  EXPECT_NEAR(surfaceDistance({0, 0, 0}, {1, 0, 0}), 110574.3, 1.0);
  EXPECT_NEAR(surfaceDistance(kPyhajarviOrigin, kPyhajarviOrigin), 0.0, 1e-9);
  EXPECT_NEAR(surfaceDistance({0, 0, 0}, {0, 1, 500}), surfaceDistance({0, 0, 0}, {0, 1, 0}), 1e-9);  // heights ignored
}

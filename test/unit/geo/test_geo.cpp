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
  GridPoint t = toTm35fin({61.0, 27.0, 0.0});
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
  // Tampere (23.7 E) and Åland (19.9 E) lie in UTM zone 34: the national grid puts both in zone 35.
  GridPoint t = toTm35fin({60.1, 19.9, 0.0});
  EXPECT_LT(t.easting_m, 200000.0);
  LatLonAlt back = fromTm35fin(t);
  EXPECT_NEAR(back.lon_deg, 19.9, 1e-8);
}

TEST(Geo, Tm35finOnlyWhereItApplies) {
  EXPECT_TRUE(inTm35finArea(kPyhajarviOrigin));
  for (const LatLonAlt& p : {LatLonAlt{-42.8821, 147.3514, 0}, LatLonAlt{36.6, -121.9, 0}, LatLonAlt{78.23, 15.6, 0}}) {
    EXPECT_FALSE(inTm35finArea(p));
    try {
      toTm35fin(p);
      ADD_FAILURE() << "no error for " << p.lat_deg << ", " << p.lon_deg;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("UTM/UPS"), std::string::npos) << e.what();
    }
  }
}

// The shipped sites (config/scenarios/) and a polar one: the GNC maths' local frame is exact wherever the site is.
struct Site {
  const char* name;
  LatLonAlt origin;
  int zone;    // its standard UTM zone (0: UPS)
  bool north;
};
const Site kSites[] = {
    {"Pyhajarvi, Finland", kPyhajarviOrigin, 34, true},  // UTM 34 (18-24 E); the national grid is zone 35
    {"Monterey Bay, California (N, W)", {36.6002, -121.8947, 0}, 10, true},
    {"Derwent, Tasmania (S, E)", {-42.8821, 147.3514, 0}, 55, false},
    {"Stanley, Falklands (S, W)", {-51.6900, -57.8500, 0}, 21, false},
    {"Taveuni, Fiji (on the antimeridian)", {-16.7850, 179.9990, 0}, 60, false},
    {"Isfjorden, Svalbard (78 N, the 33X exception)", {78.2300, 15.6000, 0}, 33, true},
    {"Hammerfest, Norway (70.7 N)", {70.6634, 23.6821, 0}, 34, true},
    {"near the North Pole (UPS)", {85.5, 40.0, 0}, 0, true},
    {"Ross Ice Shelf edge (UPS S)", {-80.5, 170.0, 0}, 0, false},
};

TEST(Geo, AnySiteRoundTripsUnderAMillimetre) {
  for (const Site& s : kSites) {
    const LocalNed f(s.origin);
    for (const Eigen::Vector3d& ned : {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(500, 800, 5),
                                       Eigen::Vector3d(-2000, -3000, 10), Eigen::Vector3d(45, 3, 5)}) {
      const LatLonAlt p = f.toGeodetic(ned);
      EXPECT_LT((f.toNed(p) - ned).norm(), 1e-3) << s.name;
      EXPECT_LT(surfaceDistance(f.toGeodetic(f.toNed(p)), p), 1e-3) << s.name;
      EXPECT_GE(p.lon_deg, -180.0) << s.name;
      EXPECT_LT(p.lon_deg, 180.0 + 1e-12) << s.name;
    }
    // north is north: 100 m north of the origin is 100 m along the meridian
    LatLonAlt n = f.toGeodetic({100, 0, 0});
    EXPECT_NEAR(surfaceDistance(s.origin, n), 100.0, 0.01) << s.name;
    EXPECT_GT(n.lat_deg, s.origin.lat_deg) << s.name;
  }
}

TEST(Geo, TheAntimeridianIsJustAnotherLine) {
  const Site& fiji = kSites[4];
  const LocalNed f(fiji.origin);
  // 300 m east of 179.999 E lies at about -179.9982: east in the local frame, however the longitude wraps
  const LatLonAlt east = f.toGeodetic({0, 300, 0});
  EXPECT_LT(east.lon_deg, -179.99);
  EXPECT_NEAR(f.toNed(east).y(), 300.0, 1e-3);
  EXPECT_NEAR(surfaceDistance(fiji.origin, east), 300.0, 0.01);
  // the site's grid is its origin's zone: the point across the line stays in zone 60, east of the origin
  const GridPoint o = toUtmUps(fiji.origin), g = toUtmUps(east, o.zone);
  EXPECT_EQ(g.zone, 60);
  EXPECT_NEAR(g.easting_m - o.easting_m, 300.0, 1.0);
  EXPECT_EQ(standardZone(east), 1);
}

TEST(Geo, GridIsTheOriginsOwnZone) {
  for (const Site& s : kSites) {
    const GridPoint g = toUtmUps(s.origin);
    EXPECT_EQ(g.zone, s.zone) << s.name;
    EXPECT_EQ(g.north, s.north) << s.name;
    EXPECT_EQ(standardZone(s.origin), s.zone) << s.name;
    const LatLonAlt back = fromUtmUps(g);
    EXPECT_LT(surfaceDistance(back, s.origin), 1e-3) << s.name;
  }
  EXPECT_EQ(gridName(toUtmUps(kSites[2].origin)), "UTM 55S");
  EXPECT_EQ(gridName(toUtmUps(kSites[7].origin)), "UPS N");
  // a point far outside the zone asked for cannot be projected in it: said, not a garbage coordinate
  try {
    toUtmUps(kSites[2].origin, 35);
    ADD_FAILURE() << "Hobart projected in zone 35";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("zone 35"), std::string::npos) << e.what();
  }
}

TEST(Geo, OriginText) {
  LatLonAlt p = parseLatLonAlt("61.4507,23.7270");
  EXPECT_DOUBLE_EQ(p.lat_deg, 61.4507);
  EXPECT_DOUBLE_EQ(p.lon_deg, 23.7270);
  EXPECT_DOUBLE_EQ(p.alt_m, 0.0);
  p = parseLatLonAlt(" -42.88, 147.35 , 12.5");
  EXPECT_DOUBLE_EQ(p.alt_m, 12.5);
  for (const char* bad : {"", "61.45", "61.45;23.7", "north,east", "61.45,23.7,0,1", "95,23", "61,190", "nan,23",
                          "61.45,23.7x"}) {
    try {
      parseLatLonAlt(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("origin"), std::string::npos) << e.what();
    }
  }
}

TEST(Geo, BadInputThrows) {
  EXPECT_THROW(LocalNed({95.0, 0.0, 0.0}), ConfigError);
  EXPECT_THROW(LocalNed({std::nan(""), 0.0, 0.0}), ConfigError);
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

// The hull's clearance from the true shapes: turning with the boat, buoys, vessels' boxes, shorelines.
#include <gtest/gtest.h>

#include <string>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/sim/contact.h"

using namespace offshore_gnc;
using namespace offshore_gnc::sim;

namespace {
HullFootprint box(double fwd, double aft, double half_beam) {  // a plain rectangle, easy to reason about
  HullFootprint h;
  h.outline = {fwd, half_beam, -aft, half_beam, -aft, -half_beam, fwd, -half_beam};
  return h;
}
}  // namespace

TEST(HullContact, ABuoyAbeamAndAheadAsTheHullTurns) {
  const HullFootprint h = box(5.0, 3.0, 1.0);
  World w;
  w.buoys.push_back({Eigen::Vector2d(0.0, 4.0), 0.5, 1.0});  // 4 m east of the reference point
  EXPECT_NEAR(hullClearance(h, {0, 0}, 0.0, w, 0.0), 4.0 - 1.0 - 0.5, 1e-9);       // heading north: the beam faces it
  EXPECT_NEAR(hullClearance(h, {0, 0}, kPi / 2, w, 0.0), -0.5, 1e-9);            // heading east: it is under the bow
  EXPECT_NEAR(hullClearance(h, {0, -2.0}, kPi / 2, w, 0.0), 6.0 - 5.0 - 0.5, 1e-9);  // 2 m further west: 0.5 m off the bow
  EXPECT_NEAR(hullClearance(h, {0, 4.0}, 0.0, w, 0.0), -0.5, 1e-9);              // its centre inside the hull
}

TEST(HullContact, VesselsAndShorelinesByTheirShapes) {
  const HullFootprint h = box(4.0, 4.0, 1.0);
  World w;
  Vessel v;
  v.centre = {0.0, 10.0};
  v.length = 8.0;
  v.width = 2.0;
  v.yaw = 0.0;  // lying north-south, its side 9 m east
  w.vessels.push_back(v);
  EXPECT_NEAR(hullClearance(h, {0, 0}, 0.0, w, 0.0), 9.0 - 1.0, 1e-9);
  EXPECT_NEAR(hullClearance(h, {0, 7.5}, 0.0, w, 0.0), 0.5, 1e-9);  // alongside, 0.5 m off
  EXPECT_NEAR(hullClearance(h, {0, 8.5}, 0.0, w, 0.0), 0.0, 1e-9);  // overlapping by 0.5 m: contact
  w.vessels.clear();
  w.shorelines.push_back({{20, -50}, {20, 50}, {80, 50}, {80, -50}});  // land from 20 m north
  EXPECT_NEAR(hullClearance(h, {0, 0}, 0.0, w, 0.0), 16.0, 1e-9);
  EXPECT_NEAR(hullClearance(h, {10, 0}, kPi / 4, w, 0.0), 20.0 - 10.0 - (4.0 + 1.0) / std::sqrt(2.0), 1e-9);
  EXPECT_TRUE(std::isinf(hullClearance(h, {0, 0}, 0.0, World(), 0.0)));
}

TEST(HullContact, AVesselUnderWayWhereItIsAtThatTime) {
  const HullFootprint h = box(4.0, 4.0, 1.0);
  World w;
  Vessel v;  // 6 m x 2 m, from 20 m west of the hull heading east at 2 m/s
  v.centre = {0.0, -20.0};
  v.length = 6.0;
  v.width = 2.0;
  v.motion.kind = VesselMotion::Kind::kCourse;
  v.motion.course = kPi / 2;
  v.motion.speed = 2.0;
  w.vessels.push_back(v);
  std::string what;
  EXPECT_NEAR(hullClearance(h, {0, 0}, 0.0, w, 0.0, {}, &what), 20.0 - 3.0 - 1.0, 1e-9);
  EXPECT_NE(what.find("N 0.0 E -20.0"), std::string::npos) << what;
  EXPECT_NEAR(hullClearance(h, {0, 0}, 0.0, w, 5.0, {}, &what), 10.0 - 3.0 - 1.0, 1e-9);
  EXPECT_NE(what.find("N 0.0 E -10.0"), std::string::npos) << what;  // named where it is then
  EXPECT_NEAR(hullClearance(h, {0, 0}, 0.0, w, 10.0), 0.0, 1e-9);  // over the hull: contact
}

TEST(HullContact, TheShippedOutlineAndBadOnes) {
  HullFootprint h;  // config/usv.yaml's: 8 m long, 2.6 m beam
  h.validate();
  const Polygon p = h.placed({0, 0}, 0.0);
  double len_max = -1e9, len_min = 1e9;
  for (const auto& c : p) len_max = std::max(len_max, c.x()), len_min = std::min(len_min, c.x());
  EXPECT_NEAR(len_max - len_min, 8.0, 1e-9);
  h.outline = {1.0, 0.0, 0.0, 1.0};  // two corners
  EXPECT_THROW(h.validate(), ConfigError);
  h.outline = {1.0, 0.0, 0.0, 1.0, -1.0, std::nan("")};
  EXPECT_THROW(h.validate(), ConfigError);
}

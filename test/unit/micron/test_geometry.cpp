// Bearings over the Micron's whole head range (issue 36, item 5): every head angle of the protocol (0..6399, 1/16
// gradian) for every mount the driver supports (boot up or down, the head's forward at any angle of its scale), each
// beam's bearing in [0, 2 pi), clockwise from the vehicle's forward axis (docs/hardware.md, "Beam conventions"), one
// head step from its neighbour, and back to its head angle; through the whole driver session too.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/micron/session.h"

using namespace offshore_gnc;
using namespace offshore_gnc::micron;

namespace {
constexpr double kUnit = 2.0 * kPi / kAngleUnitsPerTurn;

// Mount yaws: every 7th head unit (on the protocol's grid, 0 included); whole steps written in degrees
// (forward_offset_deg 0.45 is 8 head units, a rounding apart: upright, head angle 8 came out as 360 degrees before
// common/angles.h's wrapTwoPi kept a hair below 0 off 2 pi); degrees off the grid, the range's ends, random.
std::vector<double> mountYaws() {
  std::vector<double> yaws;
  for (int u = 0; u < kAngleUnitsPerTurn; u += 7) yaws.push_back(unitsToRad(u));
  for (int k = 0; k < 800; ++k) yaws.push_back(deg2rad(0.45 * k));
  for (double deg : {0.0, 1e-9, 0.01, 45.0, 90.0, 135.0, 179.99, 180.0, 180.01, 270.0, 359.99, 360.0 - 1e-9, 360.0})
    yaws.push_back(deg2rad(deg));
  std::mt19937 rng(36);
  std::uniform_real_distribution<double> any(0.0, 360.0);
  for (int i = 0; i < 100; ++i) yaws.push_back(deg2rad(any(rng)));
  return yaws;
}

void send(Session& s, Body b, std::vector<Beam>& beams) {
  const std::string w = encode(fromSonar(std::move(b)));
  s.feed(reinterpret_cast<const std::uint8_t*>(w.data()), w.size(), 0.0, beams);
}
}  // namespace

TEST(MicronGeometry, EveryHeadAngleOfEveryMountIsABearingInRangeOneStepFromTheNext) {
  long checked = 0;
  for (bool inverted : {false, true})
    for (double yaw : mountYaws()) {
      HeadGeometry g;
      g.forward_offset = yaw;
      g.inverted = inverted;
      const bool on_grid = std::abs(yaw / kUnit - std::round(yaw / kUnit)) < 1e-6;
      for (int u = 0; u < kAngleUnitsPerTurn; ++u) {
        const double b = g.bearingOf(u);
        ASSERT_TRUE(b >= 0.0 && b < 2.0 * kPi) << "head " << u << " mount " << rad2deg(yaw) << " deg, inverted "
                                               << inverted << ": bearing " << rad2deg(b) << " deg";
        // clockwise from forward: the head's own scale runs clockwise, boot down anticlockwise
        const double step = angleDiff(g.bearingOf((u + 1) % kAngleUnitsPerTurn), b);
        ASSERT_NEAR(step, inverted ? -kUnit : kUnit, 1e-9) << "head " << u << " mount " << rad2deg(yaw);
        if (on_grid) {
          ASSERT_EQ(g.unitsOf(b), u) << "mount " << rad2deg(yaw);
        }
        ++checked;
      }
      // the head angle of forward looks along the vehicle's x axis (within half a step of it off the grid)
      EXPECT_LE(std::abs(angleDiff(g.bearingOf(g.unitsOf(0.0)), 0.0)), 0.5 * kUnit + 1e-12) << rad2deg(yaw);
    }
  EXPECT_GT(checked, 10000000);
}

TEST(MicronGeometry, EveryBeamOfTheDriverOverTheWholeHeadRangeIsConsistent) {
  for (bool inverted : {false, true})
    for (double deg : {0.0, 90.0, 180.0, 359.99, 360.0}) {
      SonarSettings st;
      st.geometry.forward_offset = deg2rad(deg);
      st.geometry.inverted = inverted;
      Session s(st);
      std::vector<Beam> beams;
      s.poll(0.0);  // the bring-up, answered as a head would
      send(s, Alive{}, beams);
      send(s, VersionData{}, beams);
      Alive configured;
      configured.head_inf = kSentCfg;
      send(s, configured, beams);
      ASSERT_EQ(s.state(), Session::State::Scanning);
      for (int u = 0; u < kAngleUnitsPerTurn; ++u) {  // a continuous sweep, the head's scale increasing
        HeadData h;
        h.hd_ctrl = kAdc8On | kHasMot;
        h.ad_interval = 104;
        h.bearing = static_cast<std::uint16_t>(u);
        h.data.assign(200, static_cast<std::uint8_t>(u % 256));
        send(s, h, beams);
      }
      ASSERT_EQ(beams.size(), static_cast<std::size_t>(kAngleUnitsPerTurn));
      for (std::size_t i = 0; i < beams.size(); ++i) {
        const Beam& b = beams[i];
        ASSERT_TRUE(b.bearing >= 0.0 && b.bearing < 2.0 * kPi) << i << " mount " << deg << " inverted " << inverted;
        EXPECT_DOUBLE_EQ(b.beam_width, st.beam_width);
        EXPECT_DOUBLE_EQ(b.range_resolution, st.binSize(104));
        EXPECT_DOUBLE_EQ(b.range_offset, b.range_resolution / 2);
        ASSERT_EQ(b.intensities.size(), 200u);
        EXPECT_TRUE((b.status & kHeadReady) && (b.status & kMotorOnBit));
        // the scan direction from the bearings: clockwise for an upright head, the other way boot down
        if (i > 0) {
          EXPECT_EQ(static_cast<bool>(b.status & kScanCw), !inverted) << i;
        }
        EXPECT_FALSE(b.status & kSectorReverse) << i;  // one way round, never a reversal
      }
    }
}

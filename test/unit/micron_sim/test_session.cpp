// The Micron driver session against the head emulator, in process with a fake clock: bring-up sequence, the
// paper's sector scan, a target drawn by the simulator's sonar model, and recovery from a head reset, lost
// replies and a serial reconnect.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/micron_sim/emulator.h"
#include "offshore_gnc/micron/session.h"

using namespace offshore_gnc;
using namespace offshore_gnc::micron;
using namespace offshore_gnc::micron_sim;

namespace {
struct Bench {
  SonarSettings settings;
  EmulatorConfig ecfg;
  sim::World world;
  std::unique_ptr<Session> session;
  std::unique_ptr<HeadEmulator> head;
  std::vector<Beam> beams;
  double t = 0.0;
  bool link = true;  // false: bytes are lost both ways
  explicit Bench(const sim::World& w = {}) : world(w) {
    ecfg.recentre_time = 0.5;
    session = std::make_unique<Session>(settings);
    head = std::make_unique<HeadEmulator>(ecfg, world);
    head->setVehicle(VehicleState{});
  }
  void run(double seconds, double dt = 0.01) {
    for (double end = t + seconds; t < end; t += dt) {
      std::string to_head = session->poll(t);
      std::string to_pc;
      if (link) to_pc = head->receive(reinterpret_cast<const std::uint8_t*>(to_head.data()), to_head.size(), t);
      to_pc += head->poll(t);
      if (link) session->feed(reinterpret_cast<const std::uint8_t*>(to_pc.data()), to_pc.size(), t, beams);
    }
  }
};
}  // namespace

TEST(MicronSession, BringUpThenScansThePaperSector) {
  Bench b;
  b.run(0.05);
  EXPECT_EQ(b.head->counters().get("reboots"), 1u);  // mtReBoot first
  b.run(3.0);
  EXPECT_EQ(b.session->state(), Session::State::Scanning);
  EXPECT_EQ(b.head->counters().get("version_requests"), 1u);
  EXPECT_EQ(b.head->counters().get("head_commands"), 1u);
  ASSERT_GT(b.beams.size(), 20u);
  double lo = 10, hi = -10;
  int reversals = 0;
  for (const auto& beam : b.beams) {
    EXPECT_EQ(beam.intensities.size(), 200u);
    EXPECT_NEAR(beam.range_resolution, 104 * 640e-9 * 1500 / 2, 1e-12);
    EXPECT_TRUE(beam.status & kHeadReady);
  }
  b.run(5.0);
  for (std::size_t i = 1; i < b.beams.size(); ++i) {
    const double step = std::abs(angleDiff(b.beams[i].bearing, b.beams[i - 1].bearing));
    EXPECT_NEAR(step, deg2rad(1.8), 1e-3) << i;
    if (b.beams[i].status & kSectorReverse) ++reversals;
  }
  for (const auto& beam : b.beams) {
    lo = std::min(lo, wrapAngle(beam.bearing));
    hi = std::max(hi, wrapAngle(beam.bearing));
  }
  EXPECT_NEAR(lo, -deg2rad(45), deg2rad(1.0));
  EXPECT_NEAR(hi, deg2rad(45), deg2rad(1.0));
  EXPECT_GE(reversals, 2);
  EXPECT_EQ(b.session->decoderCounters().total(), b.session->decoderCounters().get("packets"));  // nothing bad
}

TEST(MicronSession, TheEmulatedTargetShowsAtItsRangeAndBearing) {
  sim::World w;
  sim::Target tg;
  // Head at (0.6, 0, -0.2) in body FRD; target 7 m ahead of the head, 2 m to starboard, same depth.
  tg.position = {0.6 + 7.0, 2.0, -0.2};
  tg.radius = 0.5;
  w.targets.push_back(tg);
  Bench b(w);
  b.run(8.0);
  const double expected_bearing = std::atan2(2.0, 7.0), expected_range = std::hypot(7.0, 2.0) - 0.5;
  int hits = 0;
  for (const auto& beam : b.beams) {
    if (std::abs(angleDiff(beam.bearing, expected_bearing)) > deg2rad(1.0)) continue;
    const auto it = std::max_element(beam.intensities.begin() + 40, beam.intensities.end());
    const double r = beam.range_offset + (it - beam.intensities.begin()) * beam.range_resolution;
    EXPECT_NEAR(r, expected_range, 0.15);
    EXPECT_GT(*it, 150);
    ++hits;
  }
  EXPECT_GE(hits, 2);
}

TEST(MicronSession, RecoversFromAHeadResetLostRepliesAndAReconnect) {
  Bench b;
  b.run(3.0);
  ASSERT_EQ(b.session->state(), Session::State::Scanning);
  // The head reboots on its own (power glitch): NoParams in its mtAlive -> the bring-up runs again.
  const std::string reboot = encode(fromPc(Command{mtReBoot}));
  b.head->receive(reinterpret_cast<const std::uint8_t*>(reboot.data()), reboot.size(), b.t);
  b.run(4.0);
  EXPECT_EQ(b.session->counters().get("head_resets"), 1u);
  EXPECT_EQ(b.session->state(), Session::State::Scanning);
  EXPECT_EQ(b.head->counters().get("head_commands"), 2u);
  // The line goes dead: requests time out, then the head command is sent again until the head answers.
  const auto before = b.beams.size();
  b.link = false;
  b.run(8.0);
  EXPECT_GE(b.session->counters().get("data_timeouts"), 5u);
  EXPECT_GE(b.session->counters().get("reconfigures"), 1u);
  EXPECT_TRUE(b.session->silent(b.t));
  b.link = true;
  b.run(4.0);
  EXPECT_EQ(b.session->state(), Session::State::Scanning);
  EXPECT_GT(b.beams.size(), before + 20);
  // The serial port was reopened: start over with mtReBoot.
  b.session->reset();
  b.run(4.0);
  EXPECT_EQ(b.head->counters().get("reboots"), 3u);
  EXPECT_EQ(b.session->state(), Session::State::Scanning);
}

TEST(MicronSession, InvertedHeadKeepsStarboardAtStarboard) {
  sim::World w;
  sim::Target tg;
  tg.position = {0.6 + 5.0, 3.0, 2.8};  // starboard ahead, at the head's depth
  tg.radius = 0.5;
  w.targets.push_back(tg);
  Bench b(w);
  b.settings.geometry.inverted = true;
  b.ecfg.geometry.inverted = true;
  b.session = std::make_unique<Session>(b.settings);
  b.head = std::make_unique<HeadEmulator>(b.ecfg, b.world);
  VehicleState at_depth;  // 3 m down: at the surface the sonar model's surface echo is all round the head
  at_depth.position.z() = 3.0;
  b.head->setVehicle(at_depth);
  b.run(8.0);
  ASSERT_GT(b.beams.size(), 50u);
  const double expected = std::atan2(3.0, 5.0);
  // the echo's centre: the mean bearing of the beams at the strongest peak (the beam is wider than a step, so
  // several beams saturate; the first of them is a step or two off the centre whichever way the head turns)
  int best = -1;
  for (const auto& beam : b.beams)
    best = std::max(best, static_cast<int>(*std::max_element(beam.intensities.begin() + 40, beam.intensities.end())));
  double sx = 0.0, sy = 0.0;
  for (const auto& beam : b.beams)
    if (*std::max_element(beam.intensities.begin() + 40, beam.intensities.end()) == best)
      sx += std::cos(beam.bearing), sy += std::sin(beam.bearing);
  // starboard at starboard (a sign error would put it 62 degrees off). Known: since the rough world's sonar model
  // (issue 32) the inverted head's echo centre comes 3.1 degrees short of the truth where the upright head's is
  // within 1 (TheEmulatedTargetShowsAtItsRangeAndBearing): not yet found whether in the emulator or the model.
  EXPECT_NEAR(angleDiff(std::atan2(sy, sx), expected), 0.0, deg2rad(5.0));
}

TEST(MicronSettings, NonsenseIsRefusedWithTheParameterName) {
  SonarSettings s;
  s.range = 200;
  EXPECT_THROW({
    try { s.validate(); } catch (const ConfigError& e) { EXPECT_NE(std::string(e.what()).find("'range'"), std::string::npos); throw; }
  }, ConfigError);
  s = SonarSettings{};
  s.step = deg2rad(20);
  EXPECT_THROW(s.validate(), ConfigError);
  s = SonarSettings{};
  s.bins = 1500;
  s.range = 0.5;  // a sampling interval below the head's minimum
  EXPECT_THROW(s.validate(), ConfigError);
  s = SonarSettings{};
  s.gain = std::nan("");
  EXPECT_THROW(s.validate(), ConfigError);
}

// can::CanGateway on a scripted bus with a simulated clock, the emulated waterjet units answering on the same
// bus: the per-jet frames, the allocation they carry, manual takeover, the watchdog, a jet that stops answering
// and bus-off handling as plain gtests (the same gateway runs on a real vcan0 in test/unit/can/vcan/).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "offshore_gnc/can/emulator.h"
#include "offshore_gnc/can/gateway.h"
#include "offshore_gnc/models/environment.h"
#include "offshore_gnc/models/params_yaml.h"
#include "offshore_gnc/models/usv.h"
#include "can/scripted_bus.h"

using namespace offshore_gnc;
using namespace offshore_gnc::can;

namespace {
const models::UsvParams& jets() {
  static const models::UsvParams p = models::loadUsvParams("config/models/usv.yaml");  // the tests run in the package
  return p;
}

// The gateway and the two waterjet units (the real emulator, status frames at 10 Hz) on one scripted bus.
struct Rig {
  ScriptedBus::Shared bus;
  Counters counters, unit_counters;
  GatewayConfig cfg;
  std::unique_ptr<CanGateway> gw;
  WaterjetEmulator units{jets(), 0.5, {}, unit_counters};
  GatewayOutputs out;
  int manual_seen = 0;
  std::vector<std::pair<double, std::array<bool, 2>>> answering;  // what the gateway reported, when
  std::vector<std::pair<double, BusState>> bus_states;             // ditto
  std::size_t delivered = 0;  // frames of bus.sent the units have seen
  int statuses = 0;           // status rounds so far (the k-th at 0.1 k s)
  std::array<double, 2> last_status{{-1.0, -1.0}};  // when each unit last answered
  double last_autonomy = -1.0;                       // when the last autonomy command went in
  explicit Rig(const std::string& framing = "jets") {
    cfg.command_rate = 20.0;
    cfg.watchdog_timeout = 0.5;
    cfg.manual_hold = 0.3;
    cfg.jet_timeout = 0.5;
    cfg.command_frames = framing;
    gw = std::make_unique<CanGateway>(std::make_unique<ScriptedBus>(bus), cfg, jets(), counters, [this] { return bus.now; });
    out.manual = [this](const jet::Command&) { ++manual_seen; };
    out.answering = [this](const std::array<bool, 2>& a) { answering.emplace_back(bus.now, a); };
    out.bus_state = [this](BusState st) { bus_states.emplace_back(bus.now, st); };
  }
  void runUntil(double t) {
    while (bus.now < t) {
      gw->spinOnce(0.01, out);
      for (; delivered < bus.sent.size(); ++delivered) units.onFrame(bus.sent[delivered].second, bus.now);
      if (bus.now >= 0.1 * statuses - 1e-9) {  // the units answer at 10 Hz
        ++statuses;
        for (const auto& f : units.step(bus.now)) {
          bus.incoming.emplace_back(bus.now, f);
          last_status[n2k::decodeId(f.id).source & 1] = bus.now;  // 0x30 port, 0x31 starboard
        }
      }
    }
  }
  // Autonomy commands at 10 Hz until t.
  void drive(double until, double surge, double sway, double yaw) {
    const double start = bus.now;
    for (int k = 0; start + 0.1 * k < until - 1e-9; ++k) {
      runUntil(start + 0.1 * k);
      ASSERT_TRUE(gw->onAutonomy(surge, sway, yaw));
      last_autonomy = bus.now;
    }
    runUntil(until);
  }
  // Per-jet frames sent in [t0, t1), decoded, with their times.
  std::vector<std::pair<double, jet::Setpoint>> sent(double t0, double t1) const {
    std::vector<std::pair<double, jet::Setpoint>> v;
    for (const auto& [t, f] : bus.sent) {
      jet::Setpoint s;
      if (t >= t0 && t < t1 && jet::decodeSetpoint(f, s) == jet::Error::kNone) v.emplace_back(t, s);
    }
    return v;
  }
};

bool neutral(const jet::Setpoint& s) { return s.source == kWatchdog && s.rpm == 0.0 && s.nozzle == 0.0 && s.bucket == 0.0; }
}  // namespace

TEST(CanGatewayOnAScriptedBus, OneFramePerJetToItsAddressAtTheCommandRate) {
  Rig r;
  r.drive(2.0, 0.5, 0.0, 0.1);
  const auto c = r.sent(1.0, 2.0);
  EXPECT_GE(c.size(), 38u);
  EXPECT_LE(c.size(), 42u);
  int per_jet[2] = {0, 0};
  std::uint8_t last[2] = {0, 0};
  for (const auto& [t, s] : c) {
    EXPECT_EQ(s.source, kAutonomy);
    if (per_jet[s.jet] > 0) {
      EXPECT_EQ(s.counter, (last[s.jet] + 1) & 0xF) << "jet " << int(s.jet) << " at " << t;
    }
    last[s.jet] = s.counter;
    ++per_jet[s.jet];
  }
  EXPECT_EQ(per_jet[0], per_jet[1]);
  for (const auto& [t, f] : r.bus.sent) {  // each frame to its own jet's address, none broadcast
    const n2k::IsoId id = n2k::decodeId(f.id);
    EXPECT_EQ(id.pgn, jet::kPgnSetpoint);
    EXPECT_TRUE(id.destination == 0x30 || id.destination == 0x31) << int(id.destination);
    EXPECT_EQ(id.source, 0x20);
  }
  EXPECT_EQ(r.gw->mode(), Mode::kAutonomy);
  EXPECT_EQ(r.unit_counters.get("counter_jumps"), 0u);
  EXPECT_EQ(r.counters.get("counter_jumps"), 0u);
  ASSERT_FALSE(r.answering.empty());
  EXPECT_EQ(r.answering.size(), 1u);  // both answering from the first tick, never changed
  EXPECT_TRUE(r.answering[0].second[0] && r.answering[0].second[1]);
}

TEST(CanGatewayOnAScriptedBus, PerJetFramesRoundTripIntoTheUnitsAndTheModel) {
  Rig r;
  r.drive(3.0, 0.4, -0.3, 0.25);
  // What crossed the bus is the models' allocation of the command, to the wire's resolution ...
  const models::JoystickAllocation direct(jets());
  const models::JetCommands want = direct.allocate({0.4, -0.3, 0.25});
  const JetAllocation wire(jets());
  const auto got = r.sent(2.5, 3.0);
  ASSERT_FALSE(got.empty());
  for (const auto& [t, s] : got) {
    const models::JetCommand m = wire.toModel(s);
    EXPECT_NEAR(m.rpm, want[s.jet].rpm, 0.5);
    EXPECT_NEAR(m.nozzle, want[s.jet].nozzle, jets().nozzle_max / jet::kFullScale);
    EXPECT_NEAR(m.bucket, want[s.jet].bucket, 1.0 / jet::kFullScale);
  }
  // ... and what the units act on, in the units UsvModel::setJetCommands takes.
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(r.units.applied()[i].rpm, want[i].rpm, 0.5);
    EXPECT_NEAR(r.units.applied()[i].nozzle, want[i].nozzle, jets().nozzle_max / jet::kFullScale);
    EXPECT_NEAR(r.units.applied()[i].bucket, want[i].bucket, 1.0 / jet::kFullScale);
    EXPECT_EQ(r.units.appliedSource(i), kAutonomy);
  }
}

TEST(CanGatewayOnAScriptedBus, AllocationThroughTheGatewayReproducesTheCommandWithinTheJetsLimits) {
  const models::JoystickAllocation direct(jets());
  const JetAllocation wire(jets());
  int saturated = 0;
  for (double surge : {-0.6, 0.0, 0.05, 0.5, 1.0})
    for (double sway : {-1.0, 0.0, 0.4})
      for (double yaw : {-0.7, 0.0, 1.0}) {
        Rig r;
        r.drive(0.5, surge, sway, yaw);
        const auto got = r.sent(0.3, 0.5);
        ASSERT_EQ(got.size() % 2, 0u);
        models::JetCommands bus;
        for (const auto& [t, s] : got) bus[s.jet] = wire.toModel(s);
        // The force of the jets on the set-points that crossed the bus is the force the model's own allocation
        // asks for (the thesis' joystick -> jets mapping at the CCPilot): within the wire's resolution.
        const Eigen::Vector3d f = direct.staticForce(bus), w = direct.staticForce(direct.allocate({surge, sway, yaw}));
        const double k = direct.lastScale();
        EXPECT_LT((f - w).norm(), 1e-3 * w.norm() + 0.5) << surge << " " << sway << " " << yaw;
        // Each axis pushes its own way: a pure request gives its axis, with the commanded sign; surge and sway
        // nothing else, yaw no surge (turning on the spot may push the stern sideways: when the differential
        // buckets alone cannot turn the boat the allocation adds the nozzles' moment, docs/models.md). Moments
        // compared as forces at the pivot arm.
        const int axes = (surge != 0.0) + (sway != 0.0) + (yaw != 0.0);
        if (axes == 1) {
          const int a = surge != 0.0 ? 0 : sway != 0.0 ? 1 : 2;
          const Eigen::Vector3d g(f.x(), f.y(), f.z() / jets().l_pivot);
          EXPECT_GT(g[a] * (surge + sway + yaw), 0.0) << surge << " " << sway << " " << yaw << ": " << f.transpose();
          for (int b = 0; b < 3; ++b) {
            if (b == a || (a == 2 && b == 1)) continue;
            EXPECT_LT(std::abs(g[b]), 0.01 * std::abs(g[a])) << surge << " " << sway << " " << yaw << ": " << f.transpose();
          }
        }
        // Beyond the jets' limits the whole request is scaled down (its direction kept) and counted.
        if (k < 1.0) {
          ++saturated;
          EXPECT_GT(r.counters.get("autonomy_saturated"), 0u) << surge << " " << sway << " " << yaw;
          const Eigen::Vector3d scaled = direct.staticForce(direct.allocate({k * surge, k * sway, k * yaw}));
          EXPECT_LT((f - scaled).norm(), 1e-3 * scaled.norm() + 0.5);
        } else {
          EXPECT_EQ(r.counters.get("autonomy_saturated"), 0u) << surge << " " << sway << " " << yaw;
        }
      }
  EXPECT_GT(saturated, 0) << "the grid reaches the jets' limits";
}

TEST(CanGatewayOnAScriptedBus, TheBoatDrivenOverTheBusMovesAsTheBoatDrivenDirectly) {
  // The emulated units' set-points drive the per-jet model (UsvModel::setJetCommands); another model takes the
  // same joystick command directly (its own allocation). After the bus's latency (a command period, a unit step)
  // both boats do the same thing.
  Rig r;
  models::UsvModel over_bus(jets()), direct(jets());
  const models::Environment calm;
  const models::UsvCommand cmd{0.5, 0.2, -0.3};
  double t = 0.0;
  while (t < 40.0) {
    r.drive(t + 0.1, cmd.surge, cmd.sway, cmd.yaw);
    ASSERT_TRUE(over_bus.setJetCommands(r.units.applied()));
    over_bus.step(0.1, calm);
    direct.step(0.1, cmd, calm);
    t += 0.1;
  }
  EXPECT_EQ(over_bus.counters().get("clamped_commands"), 0u);
  const auto &a = over_bus.state(), &b = direct.state();
  EXPECT_GT(b.velocity.x(), 1.0);
  EXPECT_NEAR(a.velocity.x(), b.velocity.x(), 0.01 * b.velocity.norm());
  EXPECT_NEAR(a.velocity.y(), b.velocity.y(), 0.01 * b.velocity.norm());
  EXPECT_NEAR(a.angular_rate.z(), b.angular_rate.z(), 0.02 * std::abs(b.angular_rate.z()) + 1e-4);
  EXPECT_LT((a.position - b.position).norm(), 1.0) << "after 40 s, " << b.position.norm() << " m travelled";
}

TEST(CanGatewayOnAScriptedBus, AJetThatStopsAnsweringIsCountedReportedAndTheOtherJetGoesNeutral) {
  Rig r;
  r.drive(2.0, 0.6, 0.0, 0.2);
  ASSERT_TRUE(r.gw->jetAnswering(1));
  r.units.setSilent(1, true);  // the starboard unit's status frames stop
  const double last = r.last_status[1];
  r.drive(4.0, 0.6, 0.0, 0.2);
  // Within jet_timeout of its last frame the gateway still drives; after it (and a period: the gateway looks at
  // each tick, and takes up to 10 ms to read a frame), both jets neutral.
  const double lost = last + r.cfg.jet_timeout + r.cfg.period() + 0.011;
  for (const auto& [t, s] : r.sent(2.0, 4.0)) {
    if (t < last + r.cfg.jet_timeout - 1e-9) {
      EXPECT_EQ(s.source, kAutonomy) << t;
    }
    if (t > lost) {
      EXPECT_TRUE(neutral(s)) << "jet " << int(s.jet) << " at " << t;
    }
  }
  EXPECT_EQ(r.counters.get("starboard_jet_timeouts"), 1u);
  EXPECT_EQ(r.counters.get("port_jet_timeouts"), 0u);
  EXPECT_FALSE(r.gw->jetAnswering(1));
  EXPECT_TRUE(r.gw->jetAnswering(0));
  EXPECT_NEAR(r.gw->jetSilentFor(1), 4.0 - last, 0.02);
  EXPECT_EQ(r.gw->mode(), Mode::kJetSilent);
  ASSERT_EQ(r.answering.size(), 2u);  // reported: both answering, then starboard not
  EXPECT_FALSE(r.answering[1].second[1]);
  EXPECT_TRUE(r.answering[1].second[0]);
  EXPECT_NEAR(r.answering[1].first, last + r.cfg.jet_timeout, r.cfg.period() + 0.011);
  // The port unit acts on the neutral command: engine idle, nozzle centred, bucket neutral.
  EXPECT_EQ(r.units.applied()[0].rpm, jets().rpm_min);
  EXPECT_EQ(r.units.applied()[0].nozzle, 0.0);
  EXPECT_EQ(r.units.applied()[0].bucket, 0.0);
  EXPECT_EQ(r.units.appliedSource(0), kWatchdog);
  // It answers again: reported, autonomy drives both jets again; the silence was counted once.
  r.units.setSilent(1, false);
  r.drive(5.0, 0.6, 0.0, 0.2);
  EXPECT_TRUE(r.gw->jetAnswering(1));
  EXPECT_EQ(r.gw->mode(), Mode::kAutonomy);
  ASSERT_EQ(r.answering.size(), 3u);
  EXPECT_TRUE(r.answering[2].second[0] && r.answering[2].second[1]);
  for (const auto& [t, s] : r.sent(4.8, 5.0)) EXPECT_EQ(s.source, kAutonomy);
  EXPECT_EQ(r.counters.get("starboard_jet_timeouts"), 1u);
}

TEST(CanGatewayOnAScriptedBus, NoJetEverAnsweringIsReportedAfterOneTimeout) {
  Rig r;
  r.units.setSilent(0, true);
  r.units.setSilent(1, true);
  r.drive(2.0, 0.6, 0.0, 0.0);
  EXPECT_EQ(r.counters.get("port_jet_timeouts"), 1u);
  EXPECT_EQ(r.counters.get("starboard_jet_timeouts"), 1u);
  for (const auto& [t, s] : r.sent(r.cfg.jet_timeout + r.cfg.period() + 0.01, 2.0)) EXPECT_TRUE(neutral(s)) << t;
  ASSERT_FALSE(r.answering.empty());
  EXPECT_FALSE(r.answering.back().second[0] || r.answering.back().second[1]);
}

TEST(CanGatewayOnAScriptedBus, ManualFramesWinOverPerJetFramesAndAutonomyComesBack) {
  Rig r;
  std::uint8_t counter = 0;
  for (int k = 0; k < 30; ++k) {
    const double t = 0.1 * k;
    r.runUntil(t);
    r.gw->onAutonomy(0.4, 0.0, 0.0);
    if (k >= 10 && k < 15) {  // the skipper's joystick on the bus, 1.0 to 1.4 s
      jet::Command m;
      m.source = kJoystick;
      m.surge = -0.2;
      m.counter = counter++ & 0x0F;  // the joystick's rolling counter
      const CanFrame f = jet::encodeCommand(m, true, r.cfg.addresses);
      r.bus.incoming.emplace_back(t, f);
      r.units.onFrame(f, t);  // the units hear the bridge too
    }
    if (k == 14) {
      r.runUntil(t + 0.05);
      for (int i = 0; i < 2; ++i) EXPECT_EQ(r.units.appliedSource(i), kJoystick) << "the units act on the joystick";
    }
  }
  r.runUntil(3.0);
  EXPECT_EQ(r.manual_seen, 5);
  EXPECT_EQ(r.counters.get("counter_jumps"), 0u);
  EXPECT_TRUE(r.sent(1.01, 1.69).empty()) << "autonomy was sent while manual frames were on the bus (last at 1.4 s, hold 0.3 s)";
  EXPECT_FALSE(r.sent(2.0, 3.0).empty()) << "autonomy did not come back after manual_hold";
  for (const auto& [t, s] : r.sent(2.0, 3.0)) EXPECT_EQ(s.source, kAutonomy);
  EXPECT_GT(r.counters.get("autonomy_suppressed"), 0u);
  EXPECT_EQ(r.counters.get("manual_overrides"), 1u);
  EXPECT_EQ(r.units.appliedSource(0), kAutonomy);
}

TEST(CanGatewayOnAScriptedBus, TheWatchdogSendsNeutralPerJetFramesWhenAutonomyGoesQuiet) {
  Rig r;
  r.drive(1.0, 0.8, 0.0, 0.3);
  const double quiet = r.last_autonomy;  // about 0.9 s
  r.runUntil(2.5);
  const auto late = r.sent(1.5, 2.5);
  EXPECT_NEAR(late.size(), 40u, 2u);
  for (const auto& [t, s] : late) EXPECT_TRUE(neutral(s)) << t;
  double first_neutral = 1e9;
  for (const auto& [t, s] : r.sent(quiet, 2.5))
    if (neutral(s)) first_neutral = std::min(first_neutral, t);
  EXPECT_GT(first_neutral - quiet, r.cfg.watchdog_timeout);
  EXPECT_LE(first_neutral - quiet, r.cfg.watchdog_timeout + r.cfg.period() + 1e-9);
  EXPECT_EQ(r.gw->mode(), Mode::kWatchdog);
  EXPECT_EQ(r.counters.get("watchdog_trips"), 1u);
  EXPECT_EQ(r.counters.get("port_jet_timeouts") + r.counters.get("starboard_jet_timeouts"), 0u);
}

TEST(CanGatewayOnAScriptedBus, BadJoystickAxesAreRefusedCountedAndNeverReachTheBus) {
  Rig r;
  r.drive(1.0, 0.3, 0.0, 0.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const auto& bad : {std::array<double, 3>{nan, 0, 0}, {0, INFINITY, 0}, {0, 0, -1.2}, {1.0001, 0, 0}})
    EXPECT_FALSE(r.gw->onAutonomy(bad[0], bad[1], bad[2]));
  EXPECT_EQ(r.counters.get("autonomy_out_of_range"), 4u);
  r.runUntil(1.3);
  const models::JoystickAllocation direct(jets());
  const JetAllocation wire(jets());
  const models::JetCommands good = direct.allocate({0.3, 0.0, 0.0});
  for (const auto& [t, s] : r.sent(1.0, 1.3)) {  // still the last good command
    EXPECT_EQ(s.source, kAutonomy);
    EXPECT_NEAR(wire.toModel(s).rpm, good[s.jet].rpm, 0.5);
    EXPECT_NEAR(wire.toModel(s).bucket, good[s.jet].bucket, 1e-4);
  }
  r.runUntil(2.0);  // and the refused ones did not keep the watchdog away
  EXPECT_EQ(r.gw->mode(), Mode::kWatchdog);
}

TEST(CanGatewayOnAScriptedBus, JoystickFramingDrivesTheUnitsAsThePerJetFramesDo) {
  Rig jets_rig, joystick_rig("joystick");
  jets_rig.drive(2.0, 0.7, -0.4, 0.3);
  joystick_rig.drive(2.0, 0.7, -0.4, 0.3);
  EXPECT_TRUE(joystick_rig.sent(0.0, 2.0).empty());
  int frames = 0;
  for (const auto& [t, f] : joystick_rig.bus.sent) {
    jet::Command c;
    ASSERT_EQ(jet::decodeCommand(f, c), jet::Error::kNone);
    if (t > 1.0) {
      EXPECT_EQ(c.source, kAutonomy);
    }
    ++frames;
  }
  EXPECT_NEAR(frames, 40, 2);
  for (int i = 0; i < 2; ++i) {  // the units allocate the 3-axis frame as the gateway would
    EXPECT_NEAR(joystick_rig.units.applied()[i].rpm, jets_rig.units.applied()[i].rpm, 0.5);
    EXPECT_NEAR(joystick_rig.units.applied()[i].nozzle, jets_rig.units.applied()[i].nozzle, 1.0);
    EXPECT_NEAR(joystick_rig.units.applied()[i].bucket, jets_rig.units.applied()[i].bucket, 1e-4);
  }
}

TEST(CanGatewayOnAScriptedBus, BusOffDropsCommandsInsteadOfQueueingABurst) {
  Rig r;
  r.drive(1.0, 0.3, 0.0, 0.0);
  r.bus.state = BusState::kBusOff;
  r.drive(2.0, 0.3, 0.0, 0.0);
  EXPECT_TRUE(r.sent(1.05, 2.0).empty());
  EXPECT_GT(r.counters.get("commands_not_sent"), 20u);
  EXPECT_EQ(r.gw->state(), BusState::kBusOff);
  EXPECT_GT(r.bus.polls, 0);  // the gateway keeps asking the bus to recover
  r.bus.state = BusState::kErrorActive;  // restarted
  const std::size_t before = r.bus.sent.size();
  r.drive(2.5, 0.3, 0.0, 0.0);
  const std::size_t after = r.bus.sent.size();
  EXPECT_GE(after - before, 16u);
  EXPECT_LE(after - before, 22u) << "commands held during bus-off were sent in a burst";
  // reported (for the safety supervisor's bus_off rule): at the first tick, then each change within a period
  ASSERT_EQ(r.bus_states.size(), 3u);
  EXPECT_EQ(r.bus_states[0].second, BusState::kErrorActive);
  EXPECT_LE(r.bus_states[0].first, r.cfg.period());
  EXPECT_EQ(r.bus_states[1].second, BusState::kBusOff);
  EXPECT_NEAR(r.bus_states[1].first, 1.0, r.cfg.period() + 0.011);
  EXPECT_EQ(r.bus_states[2].second, BusState::kErrorActive);
  EXPECT_NEAR(r.bus_states[2].first, 2.0, r.cfg.period() + 0.011);
}

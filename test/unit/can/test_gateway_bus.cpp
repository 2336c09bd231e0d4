// can::CanGateway on a scripted bus with a simulated clock: the command rate, manual takeover, the watchdog
// and bus-off handling as plain gtests (the same gateway runs on a real vcan0 in test/unit/can/vcan/).
#include <gtest/gtest.h>

#include <memory>

#include "offshore_gnc/can/gateway.h"
#include "scripted_bus.h"

using namespace offshore_gnc;
using namespace offshore_gnc::can;

namespace {
struct Rig {
  ScriptedBus::Shared bus;
  Counters counters;
  GatewayConfig cfg;
  std::unique_ptr<CanGateway> gw;
  GatewayOutputs out;
  int manual_seen = 0;
  Rig() {
    cfg.period = 0.05;
    cfg.watchdog_timeout = 0.5;
    cfg.manual_hold = 0.3;
    gw = std::make_unique<CanGateway>(std::make_unique<ScriptedBus>(bus), cfg, counters, [this] { return bus.now; });
    out.manual = [this](const jet::Command&) { ++manual_seen; };
  }
  void runUntil(double t) {
    while (bus.now < t) gw->spinOnce(0.01, out);
  }
  // Commands sent in [t0, t1), decoded.
  std::vector<jet::Command> sent(double t0, double t1) const {
    std::vector<jet::Command> v;
    for (const auto& [t, f] : bus.sent) {
      jet::Command c;
      if (t >= t0 && t < t1 && jet::decodeCommand(f, c) == jet::Error::kNone) v.push_back(c);
    }
    return v;
  }
};
}  // namespace

TEST(CanGatewayOnAScriptedBus, SendsAtTheCommandRateWithoutDrift) {
  Rig r;
  r.runUntil(0.01);
  for (double t = 0.0; t < 2.0; t += 0.1) {  // autonomy at 10 Hz, the bus at 20 Hz
    r.runUntil(t);
    ASSERT_TRUE(r.gw->onAutonomy(0.5, 0.0, 0.1));
  }
  r.runUntil(2.0);
  const auto c = r.sent(1.0, 2.0);
  EXPECT_GE(c.size(), 19u);
  EXPECT_LE(c.size(), 21u);
  for (const auto& k : c) {
    EXPECT_EQ(k.source, kAutonomy);
    EXPECT_NEAR(k.surge, 0.5, 1e-3);
  }
  EXPECT_EQ(r.gw->mode(), Mode::kAutonomy);
}

TEST(CanGatewayOnAScriptedBus, ManualFramesWinAndAutonomyComesBack) {
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
      r.bus.incoming.emplace_back(t, jet::encodeCommand(m, true, r.cfg.addresses));
    }
  }
  r.runUntil(3.0);
  EXPECT_EQ(r.manual_seen, 5);
  EXPECT_EQ(r.counters.get("counter_jumps"), 0u);
  EXPECT_TRUE(r.sent(1.01, 1.69).empty()) << "autonomy was sent while manual frames were on the bus (last at 1.4 s, hold 0.3 s)";
  EXPECT_FALSE(r.sent(2.0, 3.0).empty()) << "autonomy did not come back after manual_hold";
  EXPECT_GT(r.counters.get("autonomy_suppressed"), 0u);
}

TEST(CanGatewayOnAScriptedBus, TheWatchdogSendsNeutralWhenAutonomyGoesQuiet) {
  Rig r;
  for (double t = 0.0; t < 1.0; t += 0.1) {
    r.runUntil(t);
    r.gw->onAutonomy(0.8, 0.0, 0.3);
  }
  r.runUntil(2.5);  // quiet since 0.9 s
  const auto late = r.sent(1.5, 2.5);
  ASSERT_FALSE(late.empty());
  for (const auto& k : late) {
    EXPECT_EQ(k.source, kWatchdog);
    EXPECT_EQ(k.surge, 0.0);
    EXPECT_EQ(k.yaw, 0.0);
  }
  EXPECT_EQ(r.gw->mode(), Mode::kWatchdog);
  EXPECT_EQ(r.counters.get("watchdog_trips"), 1u);
}

TEST(CanGatewayOnAScriptedBus, BusOffDropsCommandsInsteadOfQueueingABurst) {
  Rig r;
  auto drive = [&](double until) {
    for (double t = r.bus.now; t < until; t += 0.1) {
      r.runUntil(t);
      r.gw->onAutonomy(0.3, 0.0, 0.0);
    }
    r.runUntil(until);
  };
  drive(1.0);
  r.bus.state = BusState::kBusOff;
  drive(2.0);
  EXPECT_TRUE(r.sent(1.05, 2.0).empty());
  EXPECT_GT(r.counters.get("commands_not_sent"), 10u);
  EXPECT_EQ(r.gw->state(), BusState::kBusOff);
  EXPECT_GT(r.bus.polls, 0);  // the gateway keeps asking the bus to recover
  r.bus.state = BusState::kErrorActive;  // restarted
  const std::size_t before = r.bus.sent.size();
  drive(2.5);
  const std::size_t after = r.bus.sent.size();
  EXPECT_GE(after - before, 8u);
  EXPECT_LE(after - before, 11u) << "commands held during bus-off were sent in a burst";
}

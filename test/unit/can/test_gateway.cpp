// Gateway priority and watchdog logic, bus-state interpretation of error frames, and the emulators, with the
// time given explicitly (the same logic runs on vcan0 in test/unit/can/vcan/, see test/suites/can_vcan.sh).
#include <gtest/gtest.h>
#include <linux/can/error.h>

#include <cmath>

#include "offshore_gnc/can/emulator.h"
#include "offshore_gnc/can/gateway.h"
#include "offshore_gnc/common/validate.h"

using namespace offshore_gnc;
using namespace offshore_gnc::can;

namespace {
jet::Command decode(const CanFrame& f) {
  jet::Command c;
  EXPECT_EQ(jet::decodeCommand(f, c), jet::Error::kNone);
  return c;
}
}  // namespace

TEST(GatewayPolicy, AutonomyWatchdogAndManual) {
  Counters counters;
  GatewayConfig cfg;
  cfg.period = 0.05;
  cfg.watchdog_timeout = 0.3;
  cfg.manual_hold = 0.2;
  GatewayPolicy g(cfg, counters);
  // No autonomy yet: neutral from the watchdog.
  auto f = g.tick(0.0);
  ASSERT_TRUE(f);
  EXPECT_EQ(decode(*f).source, kWatchdog);
  EXPECT_EQ(decode(*f).surge, 0.0);
  ASSERT_TRUE(g.onAutonomy(0.6, 0.0, -0.2, 0.01));
  f = g.tick(0.05);
  EXPECT_EQ(decode(*f).source, kAutonomy);
  EXPECT_NEAR(decode(*f).surge, 0.6, 1e-4);
  EXPECT_NEAR(decode(*f).yaw, -0.2, 1e-4);
  // Rolling counter advances per frame.
  EXPECT_EQ(decode(*g.tick(0.10)).counter, (decode(*f).counter + 1) & 0xF);
  // Silence beyond the timeout: neutral, and the trip is counted once.
  f = g.tick(0.35);
  EXPECT_EQ(decode(*f).source, kWatchdog);
  EXPECT_EQ(decode(*f).surge, 0.0);
  g.tick(0.40);
  EXPECT_EQ(counters.get("watchdog_trips"), 1u);
  // Manual seen: nothing sent, autonomy suppressed while it lasts.
  ASSERT_TRUE(g.onAutonomy(0.9, 0.0, 0.0, 0.41));
  jet::Command m;
  m.source = kJoystick;
  g.onManual(m, 0.42);
  EXPECT_FALSE(g.tick(0.45));
  EXPECT_EQ(g.mode(0.45), Mode::kManual);
  ASSERT_TRUE(g.onAutonomy(0.9, 0.0, 0.0, 0.5));
  EXPECT_EQ(counters.get("autonomy_suppressed"), 1u);
  EXPECT_FALSE(g.tick(0.6));
  // Manual released, autonomy still fresh: it comes back.
  ASSERT_TRUE(g.onAutonomy(0.9, 0.0, 0.0, 0.65));
  f = g.tick(0.7);
  ASSERT_TRUE(f);
  EXPECT_EQ(decode(*f).source, kAutonomy);
  EXPECT_EQ(counters.get("manual_overrides"), 1u);
}

TEST(GatewayPolicy, RejectsBadAutonomyAndConfig) {
  Counters counters;
  GatewayPolicy g(GatewayConfig{}, counters);
  EXPECT_FALSE(g.onAutonomy(std::nan(""), 0, 0, 0));
  EXPECT_FALSE(g.onAutonomy(0, 1.5, 0, 0));
  EXPECT_FALSE(g.onAutonomy(0, 0, -INFINITY, 0));
  EXPECT_EQ(counters.get("autonomy_out_of_range"), 3u);
  EXPECT_EQ(decode(*g.tick(0.1)).source, kWatchdog);  // bad input never became a command
  GatewayConfig bad;
  bad.watchdog_timeout = 0.01;  // shorter than the period
  EXPECT_THROW(GatewayPolicy(bad, counters), ConfigError);
  bad = GatewayConfig{};
  bad.addresses.bridge = bad.addresses.gateway;
  EXPECT_THROW(GatewayPolicy(bad, counters), ConfigError);
}

TEST(BusMonitor, ErrorFramesToStates) {
  Counters counters;
  BusMonitor m(counters);
  CanFrame e;
  e.error = true;
  e.len = 8;
  e.id = CAN_ERR_CRTL;
  e.data[1] = CAN_ERR_CRTL_TX_WARNING;
  EXPECT_TRUE(m.onErrorFrame(e));
  EXPECT_EQ(m.state(), BusState::kErrorWarning);
  e.data[1] = CAN_ERR_CRTL_RX_PASSIVE;
  m.onErrorFrame(e);
  EXPECT_EQ(m.state(), BusState::kErrorPassive);
  e.id = CAN_ERR_BUSOFF;
  m.onErrorFrame(e);
  EXPECT_EQ(m.state(), BusState::kBusOff);
  e.id = CAN_ERR_RESTARTED;
  m.onErrorFrame(e);
  EXPECT_EQ(m.state(), BusState::kErrorActive);
  e.id = CAN_ERR_TX_TIMEOUT | CAN_ERR_ACK;
  EXPECT_FALSE(m.onErrorFrame(e));
  EXPECT_EQ(counters.get("bus_off"), 1u);
  EXPECT_EQ(counters.get("restarted"), 1u);
  EXPECT_EQ(counters.get("tx_timeouts"), 1u);
  EXPECT_EQ(counters.get("no_ack"), 1u);
  EXPECT_EQ(counters.get("error_frames"), 5u);
}

TEST(SocketCan, MissingInterfaceIsReportedNotFatal) {
  Counters counters;
  SocketCanOptions o;
  o.iface = "nosuchcan9";
  SocketCan bus(o, counters);
  EXPECT_FALSE(bus.open());
  EXPECT_FALSE(bus.lastError().empty());
  EXPECT_EQ(bus.state(), BusState::kDown);
  EXPECT_TRUE(bus.receive(0.0).empty());
  bus.send(CanFrame{});
  bus.flush();  // kept queued, not lost, not crashing
  EXPECT_EQ(bus.queued(), 1u);
  bus.poll(1.0);
  EXPECT_EQ(bus.state(), BusState::kDown);
  o.iface = std::string(40, 'x');
  SocketCan longname(o, counters);
  EXPECT_FALSE(longname.open());
}

TEST(SocketCan, BoundedQueueDropsOldest) {
  Counters counters;
  SocketCanOptions o;
  o.iface = "nosuchcan9";
  o.tx_queue = 4;
  SocketCan bus(o, counters);
  for (int i = 0; i < 10; ++i) {
    CanFrame f;
    f.id = static_cast<std::uint32_t>(i);
    bus.send(f);
  }
  EXPECT_EQ(bus.queued(), 4u);
  EXPECT_EQ(counters.get("tx_dropped"), 6u);
  CanFrame big;
  big.len = 9;  // classic frame cannot carry 9 bytes
  bus.send(big);
  EXPECT_EQ(counters.get("tx_invalid"), 1u);
}

TEST(WaterjetEmulator, FollowsCommandsManualWinsTimeoutFaults) {
  Counters counters;
  WaterjetModel model;
  WaterjetEmulator emu(model, {}, counters);
  jet::Command c;
  c.surge = 1.0;
  c.yaw = 0.5;
  for (int i = 0; i < 60; ++i) {  // 3 s at 20 Hz
    c.counter = static_cast<std::uint8_t>(i & 0xF);
    emu.onFrame(jet::encodeCommand(c, false), i * 0.05);
    emu.step(i * 0.05);
  }
  EXPECT_NEAR(emu.jets()[0].rpm, model.max_rpm, 0.05 * (model.max_rpm - model.idle_rpm));
  EXPECT_NEAR(emu.jets()[1].nozzle, 0.5, 1e-6);
  EXPECT_EQ(emu.jets()[0].faults, 0);
  // Manual frame wins over later autonomy.
  jet::Command m;
  m.surge = -0.5;
  m.source = kSteeringWheel;
  emu.onFrame(jet::encodeCommand(m, true), 3.0);
  c.counter = 12;
  emu.onFrame(jet::encodeCommand(c, false), 3.05);
  EXPECT_EQ(emu.applied().source, kSteeringWheel);
  // Status frames decode, and silence raises FAULT_COMMS.
  auto st = emu.step(4.0);
  ASSERT_EQ(st.size(), 2u);
  jet::Status s;
  ASSERT_EQ(jet::decodeStatus(st[1], s), jet::Error::kNone);
  EXPECT_EQ(s.jet, 1);
  EXPECT_EQ(s.faults, 8);
  // Broken frames are counted, never applied.
  CanFrame broken = jet::encodeCommand(c, false);
  broken.data[0] ^= 1;
  emu.onFrame(broken, 4.1);
  EXPECT_EQ(counters.get("bad_checksum"), 1u);
}

TEST(GpsCompassEmulator, FramesDecode) {
  GpsCompassEmulator gps(0x40);
  GpsCompassSample s;
  s.lat_deg = 61.45;
  s.lon_deg = 23.72;
  s.heading_rad = 4.0;
  s.cog_rad = 4.1;
  s.sog_mps = 1.2;
  auto frames = gps.frames(s);
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_NEAR(*n2k::decodePositionRapid(frames[0])->lat_deg, 61.45, 1e-7);
  EXPECT_NEAR(*n2k::decodeVesselHeading(frames[1])->heading_rad, 4.0, 1e-4);
  EXPECT_NEAR(*n2k::decodeCogSogRapid(frames[2])->sog_mps, 1.2, 1e-2);
  s.heading_rad = std::nan("");
  EXPECT_FALSE(n2k::decodeVesselHeading(gps.frames(s)[1])->heading_rad);
}

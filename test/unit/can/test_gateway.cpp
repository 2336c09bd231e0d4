// Gateway priority, watchdog and silent-jet logic with both command framings, the wire <-> model units of the
// jets, bus-state interpretation of error frames, and the emulators, with the time given explicitly (the same
// logic runs on vcan0 in test/unit/can/vcan/, see test/suites/can_vcan.sh).
#include <gtest/gtest.h>
#include <linux/can/error.h>

#include <cmath>

#include "offshore_gnc/can/emulator.h"
#include "offshore_gnc/can/gateway.h"
#include "offshore_gnc/common/param_yaml.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/models/params_yaml.h"

using namespace offshore_gnc;
using namespace offshore_gnc::can;

namespace {
const models::UsvParams& jets() {
  static const models::UsvParams p = models::loadUsvParams("config/models/usv.yaml");  // the tests run in the package
  return p;
}
jet::Command decode(const CanFrame& f) {
  jet::Command c;
  EXPECT_EQ(jet::decodeCommand(f, c), jet::Error::kNone);
  return c;
}
// The per-jet frames of one tick, decoded: [0] port, [1] starboard.
std::array<jet::Setpoint, 2> decodeJets(const std::vector<CanFrame>& frames) {
  std::array<jet::Setpoint, 2> out;
  EXPECT_EQ(frames.size(), 2u);
  for (const auto& f : frames) {
    jet::Setpoint s;
    EXPECT_EQ(jet::decodeSetpoint(f, s), jet::Error::kNone);
    out[s.jet] = s;
  }
  return out;
}
bool neutral(const jet::Setpoint& s) { return s.source == kWatchdog && s.rpm == 0.0 && s.nozzle == 0.0 && s.bucket == 0.0; }
jet::Status answer(int jet) {
  jet::Status s;
  s.jet = static_cast<std::uint8_t>(jet);
  return s;
}
}  // namespace

TEST(GatewayPolicy, PerJetFramesWatchdogManualAndSilentJets) {
  Counters counters;
  GatewayConfig cfg;
  cfg.command_rate = 20.0;
  cfg.watchdog_timeout = 0.3;
  cfg.manual_hold = 0.2;
  cfg.jet_timeout = 0.25;
  GatewayPolicy g(cfg, jets(), counters);
  // No autonomy yet: neutral from the watchdog, one frame per jet.
  auto j = decodeJets(g.tick(0.0));
  EXPECT_TRUE(neutral(j[0]) && neutral(j[1]));
  ASSERT_TRUE(g.onAutonomy(0.6, 0.0, -0.2, 0.01));
  for (int i = 0; i < 2; ++i) g.onStatus(answer(i), 0.02);
  j = decodeJets(g.tick(0.05));
  const JetAllocation alloc(jets());
  const auto want = alloc.allocate(0.6, 0.0, -0.2, kAutonomy);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(j[i].source, kAutonomy);
    EXPECT_NEAR(j[i].rpm, want[i].rpm, 0.5);
    EXPECT_NEAR(j[i].nozzle, want[i].nozzle, 1.0 / jet::kFullScale);
    EXPECT_NEAR(j[i].bucket, want[i].bucket, 1.0 / jet::kFullScale);
  }
  EXPECT_GT(j[0].rpm, jets().rpm_min);  // under way: the engines above idle
  // Rolling counter advances per frame of each jet.
  EXPECT_EQ(decodeJets(g.tick(0.10))[1].counter, (j[1].counter + 1) & 0xF);
  // The starboard jet goes quiet (port keeps answering): after jet_timeout both jets neutral, counted once.
  for (int k = 0; k < 10; ++k) {
    const double t = 0.1 + 0.05 * k;
    g.onStatus(answer(0), t);
    ASSERT_TRUE(g.onAutonomy(0.6, 0.0, -0.2, t));
    j = decodeJets(g.tick(t + 0.01));
    const bool quiet = t + 0.01 - 0.02 > cfg.jet_timeout;
    EXPECT_EQ(g.mode(t + 0.01), quiet ? Mode::kJetSilent : Mode::kAutonomy) << t;
    EXPECT_EQ(neutral(j[0]) && neutral(j[1]), quiet) << t;
    EXPECT_EQ(g.answeringAtTick()[1], !quiet) << t;
  }
  EXPECT_TRUE(g.answering(0, 0.6));
  EXPECT_FALSE(g.answering(1, 0.6));
  EXPECT_NEAR(g.silentFor(1, 0.6), 0.58, 1e-9);  // heard last at 0.02 s
  EXPECT_EQ(counters.get("starboard_jet_timeouts"), 1u);
  EXPECT_EQ(counters.get("port_jet_timeouts"), 0u);
  // It answers again: autonomy drives both jets again.
  g.onStatus(answer(1), 0.62);
  j = decodeJets(g.tick(0.65));
  EXPECT_EQ(j[0].source, kAutonomy);
  EXPECT_EQ(g.mode(0.65), Mode::kAutonomy);
  // Silence beyond the watchdog timeout: neutral, and the trip is counted once.
  for (int i = 0; i < 2; ++i) g.onStatus(answer(i), 0.9);
  j = decodeJets(g.tick(0.96));
  EXPECT_TRUE(neutral(j[0]) && neutral(j[1]));
  g.tick(1.0);
  EXPECT_EQ(counters.get("watchdog_trips"), 1u);
  // Manual seen: nothing sent, autonomy suppressed while it lasts, whatever the jets do.
  ASSERT_TRUE(g.onAutonomy(0.9, 0.0, 0.0, 1.01));
  jet::Command m;
  m.source = kJoystick;
  g.onManual(m, 1.02);
  EXPECT_TRUE(g.tick(1.05).empty());
  EXPECT_EQ(g.mode(1.05), Mode::kManual);
  ASSERT_TRUE(g.onAutonomy(0.9, 0.0, 0.0, 1.1));
  EXPECT_EQ(counters.get("autonomy_suppressed"), 1u);
  EXPECT_TRUE(g.tick(1.2).empty());
  // Manual released, autonomy fresh, jets heard: it comes back.
  ASSERT_TRUE(g.onAutonomy(0.9, 0.0, 0.0, 1.25));
  for (int i = 0; i < 2; ++i) g.onStatus(answer(i), 1.25);
  j = decodeJets(g.tick(1.3));
  EXPECT_EQ(j[0].source, kAutonomy);
  EXPECT_EQ(counters.get("manual_overrides"), 1u);
  EXPECT_EQ(counters.get("watchdog_trips"), 1u);
}

TEST(GatewayPolicy, JoystickFramesForUnitsThatAllocateThemselves) {
  Counters counters;
  GatewayConfig cfg;
  cfg.command_frames = "joystick";
  cfg.watchdog_timeout = 0.3;
  cfg.jet_timeout = 0.25;
  GatewayPolicy g(cfg, jets(), counters);
  auto f = g.tick(0.0);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(decode(f[0]).source, kWatchdog);
  ASSERT_TRUE(g.onAutonomy(0.6, 0.1, -0.2, 0.01));
  f = g.tick(0.05);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(decode(f[0]).source, kAutonomy);
  EXPECT_NEAR(decode(f[0]).surge, 0.6, 1e-4);
  EXPECT_NEAR(decode(f[0]).sway, 0.1, 1e-4);
  EXPECT_NEAR(decode(f[0]).yaw, -0.2, 1e-4);
  // A jet that stops answering sends the 3-axis frame neutral too.
  g.onStatus(answer(0), 0.3);
  ASSERT_TRUE(g.onAutonomy(0.6, 0.1, -0.2, 0.3));
  f = g.tick(0.35);
  EXPECT_EQ(g.mode(0.35), Mode::kJetSilent);
  EXPECT_EQ(decode(f[0]).source, kWatchdog);
  EXPECT_EQ(decode(f[0]).surge, 0.0);
  EXPECT_EQ(counters.get("starboard_jet_timeouts"), 1u);
}

TEST(GatewayPolicy, RejectsBadAutonomyAndConfig) {
  Counters counters;
  GatewayPolicy g(GatewayConfig{}, jets(), counters);
  EXPECT_FALSE(g.onAutonomy(std::nan(""), 0, 0, 0));
  EXPECT_FALSE(g.onAutonomy(0, 1.5, 0, 0));
  EXPECT_FALSE(g.onAutonomy(0, 0, -INFINITY, 0));
  EXPECT_FALSE(g.onAutonomy(-1.0001, 0, 0, 0));
  EXPECT_EQ(counters.get("autonomy_out_of_range"), 4u);
  const auto j = decodeJets(g.tick(0.1));  // bad input never became a command
  EXPECT_TRUE(neutral(j[0]) && neutral(j[1]));
  EXPECT_EQ(g.mode(0.1), Mode::kWatchdog);
  auto bad = [](auto change) {
    GatewayConfig c;
    change(c);
    return c;
  };
  EXPECT_THROW(GatewayPolicy(bad([](GatewayConfig& c) { c.watchdog_timeout = 0.01; }), jets(), counters), ConfigError);
  EXPECT_THROW(GatewayPolicy(bad([](GatewayConfig& c) { c.jet_timeout = 0.02; }), jets(), counters), ConfigError);
  EXPECT_THROW(GatewayPolicy(bad([](GatewayConfig& c) { c.command_rate = 0.0; }), jets(), counters), ConfigError);
  EXPECT_THROW(GatewayPolicy(bad([](GatewayConfig& c) { c.command_frames = "both"; }), jets(), counters), ConfigError);
  EXPECT_THROW(GatewayPolicy(bad([](GatewayConfig& c) { c.addresses.bridge = c.addresses.gateway; }), jets(), counters),
               ConfigError);
  EXPECT_THROW(GatewayPolicy(bad([](GatewayConfig& c) { c.addresses.jet_base = 300; }), jets(), counters), ConfigError);
  models::UsvParams broken = jets();
  broken.rpm_max = broken.rpm_min - 1.0;
  EXPECT_THROW(GatewayPolicy(GatewayConfig{}, broken, counters), ConfigError);
}

TEST(GatewayConfig, TheShippedFileThroughTheTables) {
  // config/can/usv.yaml is what can_usv.launch loads into both nodelets; each reads its own table's keys.
  const YAML::Node file = YAML::LoadFile("config/can/usv.yaml");
  GatewayConfig g;
  g.command_rate = g.jet_timeout = 1.0;  // so that the file's values show
  readParamsYaml(file, GatewayConfig::table(), g, "config/can/usv.yaml");
  EXPECT_NO_THROW(g.validate());
  EXPECT_DOUBLE_EQ(g.command_rate, 20.0);
  EXPECT_DOUBLE_EQ(g.jet_timeout, 0.5);
  EXPECT_EQ(g.command_frames, "jets");
  EXPECT_EQ(g.addresses.jet_base, 0x30);
  EmulatorConfig e;
  e.addresses.gateway = 0;
  readParamsYaml(file, EmulatorConfig::table(), e, "config/can/usv.yaml");
  EXPECT_EQ(e.addresses.gateway, 0x20);
  // A bad value names the file and the key.
  YAML::Node bad = YAML::Clone(file);
  bad["command_frames"] = "both";
  try {
    readParamsYaml(bad, GatewayConfig::table(), g, "x.yaml");
    FAIL() << "accepted command_frames: both";
  } catch (const ConfigError& err) {
    EXPECT_NE(std::string(err.what()).find("command_frames"), std::string::npos) << err.what();
  }
}

TEST(JetAllocation, WireAndModelUnits) {
  const JetAllocation a(jets());
  const models::JoystickAllocation direct(jets());
  const models::JetCommands m = direct.allocate({0.3, -0.4, 0.5});
  const auto w = a.allocate(0.3, -0.4, 0.5, kAutonomy);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(w[i].jet, i);
    EXPECT_DOUBLE_EQ(a.toModel(w[i]).rpm, m[i].rpm);
    EXPECT_NEAR(a.toModel(w[i]).nozzle, m[i].nozzle, 1e-9);
    EXPECT_DOUBLE_EQ(a.toModel(w[i]).bucket, m[i].bucket);
  }
  // + on the wire is a nozzle to starboard, which turns the boat to starboard: P < 0 (eq. 3.25's sign).
  jet::Setpoint s;
  s.nozzle = 0.5;
  s.rpm = 10.0;  // below idle: the unit idles
  EXPECT_DOUBLE_EQ(a.toModel(s).nozzle, -0.5 * jets().nozzle_max);
  EXPECT_DOUBLE_EQ(a.toModel(s).rpm, jets().rpm_min);
  s.rpm = 6000.0;
  EXPECT_DOUBLE_EQ(a.toModel(s).rpm, jets().rpm_max);
  EXPECT_GT(a.allocate(0.0, 0.0, 1.0, kAutonomy)[0].nozzle, 0.0) << "yaw to starboard: nozzles to starboard";
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

TEST(WaterjetEmulator, PerJetSetpointsManualWinsTimeoutFaultsSilence) {
  Counters counters;
  WaterjetEmulator emu(jets(), 0.5, {}, counters);
  const JetAllocation alloc(jets());
  auto sp = alloc.allocate(1.0, 0.0, 0.5, kAutonomy);
  std::vector<CanFrame> st;
  for (int i = 0; i < 100; ++i) {  // 5 s at 20 Hz
    for (auto& s : sp) {
      s.counter = static_cast<std::uint8_t>(i & 0xF);
      emu.onFrame(jet::encodeSetpoint(s), i * 0.05);
    }
    st = emu.step(i * 0.05);
  }
  EXPECT_EQ(counters.get("counter_jumps"), 0u);
  // The units act on what each frame asked, and their model's chains settle on it.
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(emu.applied()[i].rpm, sp[i].rpm, 0.5);
    EXPECT_NEAR(emu.applied()[i].nozzle, -sp[i].nozzle * jets().nozzle_max, 1.0);
    EXPECT_EQ(emu.appliedSource(i), kAutonomy);
    EXPECT_NEAR(emu.jets()[i].rpm, sp[i].rpm, 0.02 * sp[i].rpm);
    EXPECT_NEAR(emu.jets()[i].nozzle, sp[i].nozzle, 1e-3);
    EXPECT_NEAR(emu.jets()[i].bucket, sp[i].bucket, 1e-3);
    EXPECT_EQ(emu.jets()[i].faults, 0);
  }
  ASSERT_EQ(st.size(), 2u);
  // A frame for one jet moves that jet only.
  jet::Setpoint port = sp[0];
  port.bucket = -1.0;
  port.counter = 4;
  emu.onFrame(jet::encodeSetpoint(port), 5.0);
  emu.step(5.0);
  EXPECT_EQ(emu.applied()[0].bucket, -1.0);
  EXPECT_NEAR(emu.applied()[1].bucket, sp[1].bucket, 1e-4);
  // A manual frame wins over later autonomy, and the units allocate it as the gateway would.
  jet::Command m;
  m.surge = -0.5;
  m.yaw = 0.2;
  m.source = kSteeringWheel;
  emu.onFrame(jet::encodeCommand(m, true), 5.05);
  port.counter = 5;
  emu.onFrame(jet::encodeSetpoint(port), 5.1);
  emu.step(5.1);
  const auto manual = alloc.allocate(-0.5, 0.0, 0.2, kSteeringWheel);
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(emu.appliedSource(i), kSteeringWheel);
    EXPECT_NEAR(emu.applied()[i].bucket, manual[i].bucket, 1e-4);
  }
  // Silence raises FAULT_COMMS and the units go neutral: idle, nozzles centred, buckets neutral.
  st = emu.step(6.0);
  ASSERT_EQ(st.size(), 2u);
  jet::Status s;
  ASSERT_EQ(jet::decodeStatus(st[1], s), jet::Error::kNone);
  EXPECT_EQ(s.jet, 1);
  EXPECT_EQ(s.faults, 8);
  for (const auto& a : emu.applied()) {
    EXPECT_EQ(a.rpm, jets().rpm_min);
    EXPECT_EQ(a.nozzle, 0.0);
    EXPECT_EQ(a.bucket, 0.0);
  }
  // A silenced unit stops answering; the other goes on.
  emu.setSilent(0, true);
  st = emu.step(6.1);
  ASSERT_EQ(st.size(), 1u);
  ASSERT_EQ(jet::decodeStatus(st[0], s), jet::Error::kNone);
  EXPECT_EQ(s.jet, 1);
  // Broken frames are counted, never applied.
  CanFrame broken = jet::encodeSetpoint(sp[0]);
  broken.data[0] ^= 1;
  emu.onFrame(broken, 6.2);
  EXPECT_EQ(counters.get("bad_checksum"), 1u);
  EXPECT_EQ(emu.applied()[0].rpm, jets().rpm_min);
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

// Driver, gateway and emulator on a real SocketCAN stack: needs vcan0 (classic) up and, for the FD test,
// vcan1 with MTU 72. test/suites/can_vcan.sh creates them, in a throwaway VM when the host kernel has no CAN.
// Runs as root (ip link down/up/del). Timing margins allow for qemu's software emulation.
#include <gtest/gtest.h>
#include <linux/can/error.h>
#include <net/if.h>

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include "offshore_gnc/can/emulator.h"
#include "offshore_gnc/can/gateway.h"

using namespace offshore_gnc;
using namespace offshore_gnc::can;

namespace {

const double kSlack = std::getenv("CAN_TIMING_SLACK") ? std::atof(std::getenv("CAN_TIMING_SLACK")) : 0.05;

SocketCanOptions opts(const std::string& iface = "vcan0") {
  SocketCanOptions o;
  o.iface = iface;
  o.reopen_period = 0.05;
  return o;
}

void sh(const std::string& cmd) { ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd; }

// Collects every frame on the bus with receive times, in a thread.
class Listener {
 public:
  Listener() : bus_(opts(), counters_) {
    EXPECT_TRUE(bus_.open()) << bus_.lastError();
    thread_ = std::thread([this] {
      while (!stop_) {
        bus_.wait(0.005);
        const double t = CanGateway::monotonic();
        for (const auto& f : bus_.receive(t)) {
          std::lock_guard<std::mutex> l(m_);
          frames_.push_back({t, f});
        }
      }
    });
  }
  ~Listener() {
    stop_ = true;
    thread_.join();
  }
  std::vector<std::pair<double, CanFrame>> frames() {
    std::lock_guard<std::mutex> l(m_);
    return frames_;
  }
  // The gateway's per-jet set-point frames from `from` on.
  std::vector<std::pair<double, jet::Setpoint>> setpoints(double from = 0.0) {
    std::vector<std::pair<double, jet::Setpoint>> out;
    for (const auto& tf : frames()) {
      jet::Setpoint s;
      if (tf.first >= from && jet::decodeSetpoint(tf.second, s) == jet::Error::kNone) out.push_back({tf.first, s});
    }
    return out;
  }

 private:
  Counters counters_;
  SocketCan bus_;
  std::mutex m_;
  std::vector<std::pair<double, CanFrame>> frames_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

const models::UsvParams kJets;  // the built-in thesis jets

// A gateway spinning in its own thread, like the nodelet runs it.
class RunningGateway {
 public:
  explicit RunningGateway(GatewayConfig cfg, GatewayOutputs out = {}) : gw(opts(), cfg, kJets, counters), out_(out) {
    thread_ = std::thread([this] {
      while (!stop_) gw.spinOnce(0.01, out_);
    });
  }
  ~RunningGateway() {
    stop_ = true;
    thread_.join();
  }
  Counters counters;
  CanGateway gw;

 private:
  GatewayOutputs out_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

void sleepFor(double s) { std::this_thread::sleep_for(std::chrono::duration<double>(s)); }

// The two waterjet units (the emulator on its own socket) acting on the frames and answering at 10 Hz.
class RunningJets {
 public:
  RunningJets() : bus_(opts(), counters), units_(kJets, 0.5, {}, counters) {
    EXPECT_TRUE(bus_.open()) << bus_.lastError();
    thread_ = std::thread([this] {
      double next = 0.0;
      while (!stop_) {
        bus_.wait(0.005);
        const double t = CanGateway::monotonic();
        for (const auto& f : bus_.receive(t)) units_.onFrame(f, t);
        if (t < next) continue;
        next = t + 0.1;
        for (const auto& f : units_.step(t)) bus_.send(f);
        bus_.flush();
      }
    });
  }
  ~RunningJets() {
    stop_ = true;
    thread_.join();
  }
  Counters counters;

 private:
  SocketCan bus_;
  WaterjetEmulator units_;
  std::mutex m_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// Keeps autonomy commands coming at 50 Hz until stopped.
class Autonomy {
 public:
  explicit Autonomy(CanGateway& gw, double surge = 0.4) {
    thread_ = std::thread([&gw, this, surge] {
      while (!stop_) {
        gw.onAutonomy(surge, 0.0, 0.1);
        sleepFor(0.02);
      }
    });
  }
  ~Autonomy() { stop(); }
  void stop() {
    if (!stop_.exchange(true)) thread_.join();
  }

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace

TEST(Vcan, RawSocketWithCanUtils) {
  Counters counters;
  SocketCanOptions o = opts();
  o.filters = {{0x09F80100, 0x1FFFFF00}};  // PGN 129025 from any source only
  SocketCan bus(o, counters);
  ASSERT_TRUE(bus.open()) << bus.lastError();
  sh("cansend vcan0 18EEFF05#0102030405060708");  // filtered out
  sh("cansend vcan0 09F80102#F8A1A024F073240E");
  sleepFor(0.05);
  auto frames = bus.receive(0.0);
  ASSERT_EQ(frames.size(), 1u);
  EXPECT_NEAR(*n2k::decodePositionRapid(frames[0])->lat_deg, 61.4507, 1e-9);
  // Our frame as candump sees it: resend until candump (slow to start under emulation) has printed it.
  std::FILE* p = ::popen("timeout 20 candump -L -n 1 vcan0,0CFF1000:1FFFFF00", "r");
  ASSERT_NE(p, nullptr);
  std::atomic<bool> done{false};
  std::thread sender([&] {
    jet::Command c;
    c.surge = 0.5;
    while (!done) {
      bus.send(jet::encodeCommand(c, false));
      bus.flush();
      sleepFor(0.1);
    }
  });
  char line[256] = {0};
  const bool got = std::fgets(line, sizeof line, p) != nullptr;
  done = true;
  sender.join();
  ::pclose(p);
  ASSERT_TRUE(got) << "candump printed nothing";
  auto parsed = parseCandump(line);
  ASSERT_TRUE(parsed) << line;
  jet::Command back;
  ASSERT_EQ(jet::decodeCommand(parsed->frame, back), jet::Error::kNone) << line;
  EXPECT_DOUBLE_EQ(back.surge, 0.5);
}

TEST(Vcan, PerJetCommandsAtTheSetRate) {
  Listener bus;
  RunningJets jets;
  GatewayConfig cfg;
  cfg.command_rate = 20.0;
  RunningGateway g(cfg);
  Autonomy a(g.gw);
  sleepFor(0.3);
  const double t0 = CanGateway::monotonic();
  sleepFor(2.0);
  const double t1 = CanGateway::monotonic();
  for (int j = 0; j < 2; ++j) {
    std::vector<std::pair<double, jet::Setpoint>> cmds;
    for (const auto& c : bus.setpoints(t0))
      if (c.second.jet == j) cmds.push_back(c);
    int in_window = 0;
    for (const auto& c : cmds)
      if (c.first < t1) ++in_window;
    EXPECT_NEAR(in_window, 40, 4) << "20 Hz for 2 s to jet " << j;
    for (const auto& c : cmds) EXPECT_EQ(c.second.source, kAutonomy) << "jet " << j;
    for (std::size_t i = 1; i < cmds.size(); ++i) {
      EXPECT_LT(cmds[i].first - cmds[i - 1].first, cfg.period() + kSlack);
      EXPECT_EQ(cmds[i].second.counter, (cmds[i - 1].second.counter + 1) & 0xF);
    }
  }
  EXPECT_TRUE(g.gw.jetAnswering(0) && g.gw.jetAnswering(1));
  EXPECT_EQ(g.counters.get("counter_jumps"), 0u);
  EXPECT_EQ(jets.counters.get("counter_jumps"), 0u);
}

TEST(Vcan, ManualSuppressesAutonomyWithinOnePeriodAndWatchdogSendsNeutral) {
  Listener bus;
  RunningJets jets;
  GatewayConfig cfg;
  cfg.command_rate = 20.0;
  cfg.watchdog_timeout = 0.4;
  cfg.manual_hold = 0.3;
  std::atomic<int> manual_seen{0};
  GatewayOutputs out;
  out.manual = [&](const jet::Command&) { ++manual_seen; };
  RunningGateway g(cfg, out);
  Autonomy a(g.gw);
  Counters bc;
  SocketCan bridge(opts(), bc);
  ASSERT_TRUE(bridge.open());
  sleepFor(0.3);
  // The bridge's joystick takes over for 1 s at 10 Hz.
  jet::Command m;
  m.source = kJoystick;
  m.surge = -0.2;
  const double t_manual = CanGateway::monotonic();
  for (int i = 0; i < 10; ++i) {
    m.counter = static_cast<std::uint8_t>(i);
    bridge.send(jet::encodeCommand(m, true));
    bridge.flush();
    sleepFor(0.1);
  }
  const double t_manual_end = CanGateway::monotonic();
  EXPECT_GE(manual_seen.load(), 9);
  auto during = bus.setpoints(t_manual + cfg.period() + kSlack);
  int autonomy_during = 0;
  for (const auto& c : during)
    if (c.first < t_manual_end) ++autonomy_during;
  EXPECT_EQ(autonomy_during, 0) << "autonomy frames after one period of manual";
  EXPECT_EQ(g.counters.get("manual_overrides"), 1u);
  // Manual released: autonomy back after the hold.
  sleepFor(cfg.manual_hold + 0.2);
  auto back = bus.setpoints(t_manual_end + cfg.manual_hold + cfg.period() + kSlack);
  ASSERT_FALSE(back.empty());
  EXPECT_EQ(back.back().second.source, kAutonomy);
  // Autonomy stops: neutral within timeout + one period.
  a.stop();
  const double t_stop = CanGateway::monotonic();
  sleepFor(cfg.watchdog_timeout + 0.3);
  double first_neutral = -1;
  for (const auto& c : bus.setpoints(t_stop))
    if (c.second.source == kWatchdog) {
      first_neutral = c.first;
      EXPECT_EQ(c.second.rpm, 0.0);
      EXPECT_EQ(c.second.nozzle, 0.0);
      EXPECT_EQ(c.second.bucket, 0.0);
      break;
    }
  ASSERT_GT(first_neutral, 0.0) << "no neutral command";
  EXPECT_LE(first_neutral - t_stop, cfg.watchdog_timeout + cfg.period() + kSlack);
  EXPECT_EQ(g.gw.mode(), Mode::kWatchdog);
  EXPECT_GE(g.counters.get("watchdog_trips"), 1u);
}

TEST(Vcan, BusOffReportedAndRecovered) {
  Listener bus;
  GatewayConfig cfg;
  RunningGateway g(cfg);
  Autonomy a(g.gw);
  Counters ic;
  SocketCan injector(opts(), ic);
  ASSERT_TRUE(injector.open());
  sleepFor(0.2);
  CanFrame e;
  e.error = true;
  e.extended = false;
  e.len = 8;
  e.id = CAN_ERR_BUSOFF;
  injector.send(e);
  injector.flush();
  sleepFor(0.3);
  EXPECT_EQ(g.gw.state(), BusState::kBusOff);
  EXPECT_EQ(g.counters.get("bus_off"), 1u);
  EXPECT_GE(g.counters.get("restart_requests"), 1u);  // libsocketcan asked; vcan refuses it
  const double t_off = CanGateway::monotonic();
  sleepFor(0.2);
  EXPECT_TRUE(bus.setpoints(t_off).empty()) << "nothing is sent while bus-off";
  e.id = CAN_ERR_RESTARTED;
  injector.send(e);
  injector.flush();
  sleepFor(0.3);
  EXPECT_EQ(g.gw.state(), BusState::kErrorActive);
  EXPECT_EQ(g.counters.get("restarted"), 1u);
  EXPECT_FALSE(bus.setpoints(CanGateway::monotonic() - 0.2).empty()) << "commands flow again";
}

TEST(Vcan, BadInputCountedNeverFatal) {
  GatewayConfig cfg;
  RunningGateway g(cfg);
  sleepFor(0.1);
  sh("cansend vcan0 09F11240#055C3D");            // heading with wrong DLC
  sh("cansend vcan0 18EEFF05#0102030405060708");  // unknown id
  sh("cansend vcan0 123#00");                     // standard frame
  sh("cansend vcan0 10FF2030#70170000000000" "00");  // status, bad CRC
  sh("cansend vcan0 0CEF3020#B004C0E0803E05FE");       // per-jet set-point, bad CRC
  sh("cansend vcan0 0CEF3021#B004C0E0803E05FD");       // another gateway's (0x21) set-point: not ours to obey
  jet::Status s;
  s.counter = 1;
  Counters c;
  SocketCan dev(opts(), c);
  ASSERT_TRUE(dev.open());
  dev.send(jet::encodeStatus(s));
  s.counter = 9;  // jump
  dev.send(jet::encodeStatus(s));
  dev.flush();
  sleepFor(0.3);
  EXPECT_EQ(g.counters.get("wrong_dlc"), 1u);
  EXPECT_GE(g.counters.get("unknown_id"), 2u);
  EXPECT_EQ(g.counters.get("bad_checksum"), 2u);
  EXPECT_EQ(g.counters.get("foreign_commands"), 1u);
  EXPECT_EQ(g.counters.get("counter_jumps"), 1u);
}

TEST(Vcan, SurvivesInterfaceDownUpAndRecreate) {
  Listener* bus = nullptr;
  GatewayConfig cfg;
  RunningGateway g(cfg);
  Autonomy a(g.gw);
  sleepFor(0.2);
  sh("ip link set vcan0 down");
  sleepFor(0.3);
  EXPECT_EQ(g.gw.state(), BusState::kDown);
  sh("ip link set vcan0 up");
  sleepFor(0.3);
  {
    Listener l;
    bus = &l;
    sleepFor(0.3);
    EXPECT_EQ(g.gw.state(), BusState::kErrorActive);
    EXPECT_FALSE(bus->setpoints().empty()) << "commands after down/up";
  }
  sh("ip link del vcan0");
  sleepFor(0.2);
  sh("ip link add dev vcan0 type vcan && ip link set vcan0 up");
  sleepFor(0.4);
  {
    Listener l;
    sleepFor(0.3);
    EXPECT_FALSE(l.setpoints().empty()) << "commands after the interface was re-created";
  }
  EXPECT_GE(g.counters.get("interface_down"), 1u);
  EXPECT_GE(g.counters.get("reopened"), 1u);
}

TEST(Vcan, EmulatorAndGatewayEndToEndAndASilentJet) {
  std::mutex m;
  std::vector<jet::Status> statuses;
  std::vector<n2k::PositionRapid> fixes;
  std::vector<std::array<bool, 2>> answering;
  GatewayOutputs out;
  out.status = [&](const jet::Status& s) {
    std::lock_guard<std::mutex> l(m);
    statuses.push_back(s);
  };
  out.position = [&](const n2k::PositionRapid& p, std::uint8_t) {
    std::lock_guard<std::mutex> l(m);
    fixes.push_back(p);
  };
  out.answering = [&](const std::array<bool, 2>& a) {
    std::lock_guard<std::mutex> l(m);
    answering.push_back(a);
  };
  GatewayConfig cfg;
  RunningGateway g(cfg, out);
  Autonomy a(g.gw, 1.0);
  Counters ec;
  SocketCan dev(opts(), ec);
  ASSERT_TRUE(dev.open());
  WaterjetEmulator jets(kJets, 0.5, {}, ec);
  GpsCompassEmulator gps;
  auto run = [&](double seconds) {
    const double t0 = CanGateway::monotonic();
    while (CanGateway::monotonic() - t0 < seconds) {
      dev.wait(0.05);
      const double t = CanGateway::monotonic();
      for (const auto& f : dev.receive(t)) jets.onFrame(f, t);
      for (const auto& f : jets.step(t)) dev.send(f);
      GpsCompassSample s;
      s.lat_deg = 61.45;
      s.lon_deg = 23.72;
      for (const auto& f : gps.frames(s)) dev.send(f);
      dev.flush();
    }
  };
  run(2.0);
  const JetAllocation alloc(kJets);
  const auto want = alloc.allocate(1.0, 0.0, 0.1, kAutonomy);  // what Autonomy asks for
  for (int i = 0; i < 2; ++i) {
    EXPECT_EQ(jets.appliedSource(i), kAutonomy);
    EXPECT_NEAR(jets.applied()[i].rpm, alloc.toModel(want[i]).rpm, 0.5);
    EXPECT_NEAR(jets.applied()[i].bucket, want[i].bucket, 1e-4);
  }
  {
    std::lock_guard<std::mutex> l(m);
    ASSERT_GE(statuses.size(), 10u);
    EXPECT_GT(statuses.back().rpm, 1000.0) << "the jets spun up on the commands sent over vcan0";
    ASSERT_GE(fixes.size(), 5u);
    EXPECT_NEAR(*fixes.back().lat_deg, 61.45, 1e-7);
  }
  EXPECT_EQ(ec.get("bad_checksum"), 0u);
  EXPECT_TRUE(g.gw.jetAnswering(0) && g.gw.jetAnswering(1));
  // The starboard unit stops answering: reported, counted, and the port unit gets the neutral command.
  jets.setSilent(1, true);
  run(cfg.jet_timeout + 0.5 + kSlack);
  EXPECT_FALSE(g.gw.jetAnswering(1));
  EXPECT_TRUE(g.gw.jetAnswering(0));
  EXPECT_EQ(g.gw.mode(), Mode::kJetSilent);
  EXPECT_EQ(g.counters.get("starboard_jet_timeouts"), 1u);
  EXPECT_EQ(jets.appliedSource(0), kWatchdog);
  EXPECT_EQ(jets.applied()[0].rpm, kJets.rpm_min);
  EXPECT_EQ(jets.applied()[0].bucket, 0.0);
  std::lock_guard<std::mutex> l(m);
  ASSERT_GE(answering.size(), 2u);
  EXPECT_TRUE(answering.back()[0]);
  EXPECT_FALSE(answering.back()[1]);
}

TEST(Vcan, CanFdFrameWhenSupported) {
  if (if_nametoindex("vcan1") == 0) GTEST_SKIP() << "no vcan1 (MTU 72) for CAN FD";
  Counters c;
  SocketCanOptions o = opts("vcan1");
  o.fd = true;
  SocketCan a(o, c), b(o, c);
  ASSERT_TRUE(a.open());
  ASSERT_TRUE(b.open());
  ASSERT_TRUE(a.fdEnabled());
  CanFrame f;
  f.fd = true;
  f.id = 0x1F334455;
  f.len = 48;
  for (int i = 0; i < 48; ++i) f.data[i] = static_cast<std::uint8_t>(i);
  a.send(f);
  a.flush();
  sleepFor(0.05);
  auto got = b.receive(0.0);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_TRUE(got[0].fd);
  EXPECT_EQ(got[0].len, 48);
  EXPECT_EQ(got[0].data[47], 47);
}

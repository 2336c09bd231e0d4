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
  std::vector<std::pair<double, jet::Command>> commands(double from = 0.0) {
    std::vector<std::pair<double, jet::Command>> out;
    for (const auto& tf : frames()) {
      jet::Command c;
      bool manual = true;
      if (tf.first >= from && jet::decodeCommand(tf.second, c, &manual) == jet::Error::kNone && !manual)
        out.push_back({tf.first, c});
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

// A gateway spinning in its own thread, like the nodelet runs it.
class RunningGateway {
 public:
  explicit RunningGateway(GatewayConfig cfg, GatewayOutputs out = {}) : gw(opts(), cfg, counters), out_(out) {
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

TEST(Vcan, CommandsAtTheSetRate) {
  Listener bus;
  GatewayConfig cfg;
  cfg.period = 0.05;
  RunningGateway g(cfg);
  Autonomy a(g.gw);
  sleepFor(0.3);
  const double t0 = CanGateway::monotonic();
  sleepFor(2.0);
  const double t1 = CanGateway::monotonic();
  auto cmds = bus.commands(t0);
  int in_window = 0;
  for (const auto& c : cmds)
    if (c.first < t1) ++in_window;
  EXPECT_NEAR(in_window, 40, 4) << "20 Hz for 2 s";
  for (const auto& c : cmds) EXPECT_EQ(c.second.source, kAutonomy);
  for (std::size_t i = 1; i < cmds.size(); ++i) {
    EXPECT_LT(cmds[i].first - cmds[i - 1].first, cfg.period + kSlack);
    EXPECT_EQ(cmds[i].second.counter, (cmds[i - 1].second.counter + 1) & 0xF);
  }
}

TEST(Vcan, ManualSuppressesAutonomyWithinOnePeriodAndWatchdogSendsNeutral) {
  Listener bus;
  GatewayConfig cfg;
  cfg.period = 0.05;
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
  auto during = bus.commands(t_manual + cfg.period + kSlack);
  int autonomy_during = 0;
  for (const auto& c : during)
    if (c.first < t_manual_end) ++autonomy_during;
  EXPECT_EQ(autonomy_during, 0) << "autonomy frames after one period of manual";
  EXPECT_EQ(g.counters.get("manual_overrides"), 1u);
  // Manual released: autonomy back after the hold.
  sleepFor(cfg.manual_hold + 0.2);
  auto back = bus.commands(t_manual_end + cfg.manual_hold + cfg.period + kSlack);
  ASSERT_FALSE(back.empty());
  EXPECT_EQ(back.back().second.source, kAutonomy);
  // Autonomy stops: neutral within timeout + one period.
  a.stop();
  const double t_stop = CanGateway::monotonic();
  sleepFor(cfg.watchdog_timeout + 0.3);
  double first_neutral = -1;
  for (const auto& c : bus.commands(t_stop))
    if (c.second.source == kWatchdog) {
      first_neutral = c.first;
      EXPECT_EQ(c.second.surge, 0.0);
      EXPECT_EQ(c.second.yaw, 0.0);
      break;
    }
  ASSERT_GT(first_neutral, 0.0) << "no neutral command";
  EXPECT_LE(first_neutral - t_stop, cfg.watchdog_timeout + cfg.period + kSlack);
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
  EXPECT_TRUE(bus.commands(t_off).empty()) << "nothing is sent while bus-off";
  e.id = CAN_ERR_RESTARTED;
  injector.send(e);
  injector.flush();
  sleepFor(0.3);
  EXPECT_EQ(g.gw.state(), BusState::kErrorActive);
  EXPECT_EQ(g.counters.get("restarted"), 1u);
  EXPECT_FALSE(bus.commands(CanGateway::monotonic() - 0.2).empty()) << "commands flow again";
}

TEST(Vcan, BadInputCountedNeverFatal) {
  GatewayConfig cfg;
  RunningGateway g(cfg);
  sleepFor(0.1);
  sh("cansend vcan0 09F11240#055C3D");            // heading with wrong DLC
  sh("cansend vcan0 18EEFF05#0102030405060708");  // unknown id
  sh("cansend vcan0 123#00");                     // standard frame
  sh("cansend vcan0 10FF2030#70170000000000" "00");  // status, bad CRC
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
  EXPECT_EQ(g.counters.get("bad_checksum"), 1u);
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
    EXPECT_FALSE(bus->commands().empty()) << "commands after down/up";
  }
  sh("ip link del vcan0");
  sleepFor(0.2);
  sh("ip link add dev vcan0 type vcan && ip link set vcan0 up");
  sleepFor(0.4);
  {
    Listener l;
    sleepFor(0.3);
    EXPECT_FALSE(l.commands().empty()) << "commands after the interface was re-created";
  }
  EXPECT_GE(g.counters.get("interface_down"), 1u);
  EXPECT_GE(g.counters.get("reopened"), 1u);
}

TEST(Vcan, EmulatorAndGatewayEndToEnd) {
  std::mutex m;
  std::vector<jet::Status> statuses;
  std::vector<n2k::PositionRapid> fixes;
  GatewayOutputs out;
  out.status = [&](const jet::Status& s) {
    std::lock_guard<std::mutex> l(m);
    statuses.push_back(s);
  };
  out.position = [&](const n2k::PositionRapid& p, std::uint8_t) {
    std::lock_guard<std::mutex> l(m);
    fixes.push_back(p);
  };
  GatewayConfig cfg;
  RunningGateway g(cfg, out);
  Autonomy a(g.gw, 1.0);
  Counters ec;
  SocketCan dev(opts(), ec);
  ASSERT_TRUE(dev.open());
  WaterjetEmulator jets(WaterjetModel{}, {}, ec);
  GpsCompassEmulator gps;
  const double t0 = CanGateway::monotonic();
  while (CanGateway::monotonic() - t0 < 1.5) {
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
  EXPECT_EQ(jets.applied().source, kAutonomy);
  EXPECT_DOUBLE_EQ(jets.applied().surge, 1.0);
  std::lock_guard<std::mutex> l(m);
  ASSERT_GE(statuses.size(), 10u);
  EXPECT_GT(statuses.back().rpm, 1000.0) << "the jets spun up on the commands sent over vcan0";
  ASSERT_GE(fixes.size(), 5u);
  EXPECT_NEAR(*fixes.back().lat_deg, 61.45, 1e-7);
  EXPECT_EQ(ec.get("bad_checksum"), 0u);
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

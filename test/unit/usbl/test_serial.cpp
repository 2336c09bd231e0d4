// The serial layer on real pseudo-terminals: raw bytes both ways, the device disappearing (pty master closed,
// symlink gone) and coming back under the same path.
#include <gtest/gtest.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <thread>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/usbl/seatrac.h"
#include "offshore_gnc/usbl/serial_port.h"

using namespace offshore_gnc::usbl;

namespace {
struct Pty {
  int master = -1, slave = -1;
  std::string name;
  Pty() {
    EXPECT_EQ(openpty(&master, &slave, nullptr, nullptr, nullptr), 0);
    char buf[256] = {};
    ttyname_r(slave, buf, sizeof buf);
    name = buf;
  }
  ~Pty() { closeAll(); }
  void closeAll() {
    if (slave >= 0) ::close(slave);
    if (master >= 0) ::close(master);
    slave = master = -1;
  }
};
std::string readFor(SerialPort& port, double seconds) {
  std::string out;
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  std::uint8_t buf[256];
  while (std::chrono::steady_clock::now() < end) {
    const std::size_t n = port.read(buf, sizeof buf, 10);
    out.append(reinterpret_cast<char*>(buf), n);
    if (out.find('\n') != std::string::npos) break;
  }
  return out;
}
}  // namespace

TEST(SerialPort, RawBytesBothWays) {
  Pty pty;
  SerialPort port(pty.name, 115200, 0.05);
  ASSERT_TRUE(port.ensureOpen()) << port.lastError();
  const std::string frame = encodeFrame(Message{false, StatusReply{CID_PING_ERROR, 0x34, 2}});
  ASSERT_EQ(::write(pty.master, frame.data(), frame.size()), static_cast<ssize_t>(frame.size()));
  EXPECT_EQ(readFor(port, 2.0), frame);  // CR LF untouched (raw mode)
  const std::string cmd = encodeFrame(Message{true, PingSend{2, MSG_REQU}});
  ASSERT_TRUE(port.write(cmd));
  char buf[64] = {};
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const ssize_t n = ::read(pty.master, buf, sizeof buf);
  EXPECT_EQ(std::string(buf, n > 0 ? n : 0), cmd);
}

TEST(SerialPort, SurvivesTheDeviceDisappearingAndComingBack) {
  const std::string link = "/tmp/usbl_serial_test_" + std::to_string(::getpid());
  auto pty = std::make_unique<Pty>();
  ::unlink(link.c_str());
  ASSERT_EQ(::symlink(pty->name.c_str(), link.c_str()), 0);
  SerialPort port(link, 115200, 0.05);
  ASSERT_TRUE(port.ensureOpen());
  // Unplugged: the other end goes away and the device node disappears.
  ::close(pty->slave);
  pty->slave = -1;
  pty.reset();
  ::unlink(link.c_str());
  readFor(port, 0.5);
  EXPECT_FALSE(port.isOpen());
  EXPECT_GE(port.counters().get("hangups") + port.counters().get("io_errors"), 1u);
  readFor(port, 0.3);  // retries while absent fail and are counted
  EXPECT_GE(port.counters().get("open_failures"), 1u);
  // Plugged back in (a new pty under the same name).
  Pty again;
  ASSERT_EQ(::symlink(again.name.c_str(), link.c_str()), 0);
  const std::string frame = encodeFrame(Message{false, StatusReply{CID_PING_SEND, 0, 2}});
  std::string got;
  for (int i = 0; i < 100 && got.empty(); ++i) {
    if (port.isOpen()) {
      ASSERT_EQ(::write(again.master, frame.data(), frame.size()), static_cast<ssize_t>(frame.size()));
    }
    got = readFor(port, 0.1);
  }
  EXPECT_EQ(got, frame);
  EXPECT_EQ(port.counters().get("opens"), 2u);
  ::unlink(link.c_str());
}

TEST(SerialPort, UnsupportedBaudIsAConfigError) {
  EXPECT_THROW(SerialPort("/dev/null", 12345), offshore_gnc::ConfigError);
}

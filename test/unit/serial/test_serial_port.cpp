// The serial layer on real pseudo-terminals: raw bytes both ways, the device disappearing (pty master closed,
// symlink gone) and coming back under the same path; an emulator's pseudo-terminal seen through a serial port.
#include <gtest/gtest.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <thread>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/serial/pseudo_terminal.h"
#include "offshore_gnc/serial/serial_port.h"

using namespace offshore_gnc::serial;

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
  const std::string frame = std::string("$43340266D5\r\n") + '\0' + "\xff\n";  // a SeaTrac reply, then binary
  ASSERT_EQ(::write(pty.master, frame.data(), frame.size()), static_cast<ssize_t>(frame.size()));
  std::string got = readFor(port, 2.0);
  if (got.size() < frame.size()) got += readFor(port, 0.5);
  EXPECT_EQ(got, frame);  // CR LF and binary bytes untouched (raw mode)
  const std::string cmd = "#40020680B6\r\n";
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
  const std::string frame = "$400002D400\r\n";
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

TEST(PseudoTerminal, AnEmulatorsLineAsADriverSeesIt) {
  const std::string link = "/tmp/serial_pty_test_" + std::to_string(::getpid());
  std::string got;
  {
    PseudoTerminal pty(link);
    SerialPort port(link, 115200, 0.05);
    ASSERT_TRUE(port.ensureOpen()) << port.lastError();
    ASSERT_TRUE(port.write(std::string("@\x00\x0d\x0a", 4)));  // raw: no echo, no CR/LF translation
    std::uint8_t buf[16];
    std::size_t n = 0;
    for (int i = 0; i < 50 && n < 4; ++i) n += pty.read(buf + n, sizeof buf - n, 20);
    EXPECT_EQ(std::string(reinterpret_cast<char*>(buf), n), std::string("@\x00\x0d\x0a", 4));
    ASSERT_TRUE(pty.write("%reply\n"));
    got = readFor(port, 2.0);
  }
  EXPECT_EQ(got, "%reply\n");
  EXPECT_NE(::access(link.c_str(), F_OK), 0);  // the link goes with the pseudo-terminal
}

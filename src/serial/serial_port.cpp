// Serial lines (include/offshore_gnc/serial/serial_port.h).
#include "offshore_gnc/serial/serial_port.h"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <utility>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace serial {

double monotonic() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

namespace {
speed_t baudConstant(int baud) {
  switch (baud) {
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    default: throw ConfigError("parameter 'baud' = " + std::to_string(baud) +
                               " is not one of 9600, 19200, 38400, 57600, 115200, 230400");
  }
}
}  // namespace

SerialPort::SerialPort(std::string path, int baud, double retry_period_s)
    : path_(std::move(path)), baud_(baud), retry_period_s_(retry_period_s) {
  baudConstant(baud_);  // validate now, not at the first open
}

SerialPort::~SerialPort() { close(); }

void SerialPort::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void SerialPort::lost(const std::string& what) {
  last_error_ = what + ": " + std::strerror(errno);
  close();
  next_try_s_ = monotonic() + retry_period_s_;
}

bool SerialPort::ensureOpen() {
  if (fd_ >= 0) return true;
  if (monotonic() < next_try_s_) return false;
  const int fd = ::open(path_.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    counters_.increment("open_failures");
    lost("open " + path_);
    return false;
  }
  termios t{};
  if (tcgetattr(fd, &t) != 0) {
    ::close(fd);
    counters_.increment("open_failures");
    lost("tcgetattr " + path_);
    return false;
  }
  cfmakeraw(&t);  // binary-clean: no echo, no CR/LF translation (the protocol's CR LF must pass untouched)
  t.c_cflag |= CLOCAL | CREAD;
  t.c_cflag &= ~(CSTOPB | PARENB | CRTSCTS);
  cfsetispeed(&t, baudConstant(baud_));
  cfsetospeed(&t, baudConstant(baud_));
  t.c_cc[VMIN] = 0;
  t.c_cc[VTIME] = 0;
  tcsetattr(fd, TCSANOW, &t);
  fd_ = fd;
  counters_.increment("opens");
  return true;
}

std::size_t SerialPort::read(std::uint8_t* buf, std::size_t cap, int timeout_ms) {
  if (!ensureOpen()) {
    usleep(static_cast<useconds_t>(timeout_ms) * 1000);  // behave like a timeout while the device is away
    return 0;
  }
  pollfd p{fd_, POLLIN, 0};
  const int r = ::poll(&p, 1, timeout_ms);
  if (r < 0) {
    if (errno == EINTR) return 0;
    counters_.increment("io_errors");
    lost("poll " + path_);
    return 0;
  }
  if (r == 0) return 0;
  if (p.revents & (POLLERR | POLLNVAL)) {
    counters_.increment("io_errors");
    lost("poll " + path_);
    return 0;
  }
  const ssize_t n = ::read(fd_, buf, cap);
  if (n > 0) return static_cast<std::size_t>(n);
  if (n < 0 && (errno == EAGAIN || errno == EINTR)) return 0;
  // 0 bytes with POLLIN/POLLHUP, or EIO: the other end (USB adapter, pty master) is gone.
  if (n == 0) errno = ENODEV;
  counters_.increment("hangups");
  lost("read " + path_);
  return 0;
}

bool SerialPort::write(const std::string& bytes) {
  if (!ensureOpen()) return false;
  std::size_t done = 0;
  int stalls = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
    } else if (n < 0 && (errno == EAGAIN || errno == EINTR) && ++stalls < 50) {
      pollfd p{fd_, POLLOUT, 0};
      ::poll(&p, 1, 10);
    } else {
      counters_.increment("io_errors");
      lost("write " + path_);
      return false;
    }
  }
  return true;
}

}  // namespace serial
}  // namespace offshore_gnc

#pragma once
// Raw serial line (termios, 8N1, no flow control) that survives the device disappearing and coming back:
// any read/write error or hang-up closes the descriptor, and the next call after `retry_period_s` reopens it.
// ROS-free; works on real UARTs, USB adapters and pseudo-terminals (tests).
#include <cstddef>
#include <cstdint>
#include <string>

#include "offshore_gnc/common/counters.h"

namespace offshore_gnc {
namespace serial {

// The devices' clock: steady seconds, also while a simulated /clock runs (retries, the drivers' timeouts).
double monotonic();

class SerialPort {
 public:
  SerialPort(std::string path, int baud, double retry_period_s = 1.0);
  ~SerialPort();
  SerialPort(const SerialPort&) = delete;
  SerialPort& operator=(const SerialPort&) = delete;

  // Opens when closed and the retry period has passed. True when open afterwards.
  bool ensureOpen();
  bool isOpen() const { return fd_ >= 0; }
  // Waits up to timeout_ms for bytes; returns the count read (0 on timeout or while closed).
  std::size_t read(std::uint8_t* buf, std::size_t cap, int timeout_ms);
  // Writes all bytes or closes the port on error; false when not written.
  bool write(const std::string& bytes);
  void close();
  const std::string& path() const { return path_; }
  const std::string& lastError() const { return last_error_; }
  // opens, open_failures, io_errors, hangups
  const Counters& counters() const { return counters_; }

 private:
  void lost(const std::string& what);
  std::string path_;
  int baud_;
  double retry_period_s_;
  int fd_ = -1;
  double next_try_s_ = 0.0;
  std::string last_error_;
  Counters counters_;
};

}  // namespace serial
}  // namespace offshore_gnc

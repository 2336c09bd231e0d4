#pragma once
// SocketCAN raw-socket driver: named interface, receive filters, non-blocking I/O, error frames turned into
// a bus state, bounded transmit queue, bus-off recovery through libsocketcan, and survival of the interface
// going down / being re-created. ROS-free; all events are counted in a Counters for diagnostics.
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "offshore_gnc/can/frame.h"
#include "offshore_gnc/common/counters.h"

namespace offshore_gnc {
namespace can {

enum class BusState { kDown, kErrorActive, kErrorWarning, kErrorPassive, kBusOff };
const char* toString(BusState s);

// Error-frame interpretation (linux/can/error.h classes), separate from the socket so it is testable anywhere.
class BusMonitor {
 public:
  explicit BusMonitor(Counters& counters) : counters_(counters) {}
  // Returns true when the state changed.
  bool onErrorFrame(const CanFrame& f);
  void set(BusState s) { state_ = s; }
  BusState state() const { return state_; }

 private:
  Counters& counters_;
  BusState state_ = BusState::kErrorActive;
};

struct SocketCanOptions {
  std::string iface = "can0";
  struct Filter {
    std::uint32_t id, mask;  // both 29-bit (extended frames)
  };
  std::vector<Filter> filters;  // empty = everything
  bool fd = false;              // enable CAN FD when the interface's MTU allows it
  std::size_t tx_queue = 32;    // oldest frame dropped beyond this (commands: fresh beats complete)
  bool auto_restart = true;     // try can_do_restart() (libsocketcan) after bus-off
  double restart_delay = 0.1;   // s between bus-off and the restart request
  double reopen_period = 0.5;   // s between attempts while the interface is missing or down
  bool receive_own = false;     // also receive frames this socket sent (tests)
};

class SocketCan {
 public:
  SocketCan(SocketCanOptions options, Counters& counters);
  ~SocketCan();
  SocketCan(const SocketCan&) = delete;
  SocketCan& operator=(const SocketCan&) = delete;

  // Opens and binds; false (with lastError()) when the interface or AF_CAN is missing; poll() retries.
  bool open();
  int fd() const { return fd_; }
  bool fdEnabled() const { return fd_enabled_; }
  // All pending data frames (error frames update state() and are not returned). `now`: monotonic seconds.
  std::vector<CanFrame> receive(double now, std::size_t max = 256);
  // Queues a frame; flush() writes what the kernel accepts.
  void send(const CanFrame& f);
  void flush();
  // Reopen after the interface disappeared, restart after bus-off.
  void poll(double now);
  // Waits up to timeout_s for readable data (or the fd to appear). Returns true when readable.
  bool wait(double timeout_s) const;

  BusState state() const { return monitor_.state(); }
  const std::string& lastError() const { return last_error_; }
  const SocketCanOptions& options() const { return opt_; }
  std::size_t queued() const { return queue_.size(); }

 private:
  void close();
  void goDown(int err);

  SocketCanOptions opt_;
  Counters& counters_;
  BusMonitor monitor_;
  int fd_ = -1;
  unsigned ifindex_ = 0;
  bool fd_enabled_ = false;
  std::deque<CanFrame> queue_;
  std::string last_error_;
  double last_reopen_ = -1e9, busoff_since_ = -1.0, restart_backoff_ = 0.0;
};

}  // namespace can
}  // namespace offshore_gnc

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

// The bus as the gateway and the emulators use it (ros_canopen's DriverInterface): SocketCan on a real or
// virtual interface, or a scripted bus in the tests (test/support/can/scripted_bus.h). Times are the caller's clock.
class BusInterface {
 public:
  virtual ~BusInterface() = default;
  // Opens the bus; false (with lastError()) when it cannot; poll() retries.
  virtual bool open() = 0;
  // All pending data frames (error frames update state() and are not returned).
  virtual std::vector<CanFrame> receive(double now, std::size_t max = 256) = 0;
  // Queues a frame; flush() writes what the bus accepts.
  virtual void send(const CanFrame& f) = 0;
  virtual void flush() = 0;
  // Reopen after the interface disappeared, restart after bus-off.
  virtual void poll(double now) = 0;
  // Waits up to timeout_s for readable data. Returns true when readable.
  virtual bool wait(double timeout_s) = 0;
  virtual BusState state() const = 0;
  virtual std::string lastError() const = 0;
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

class SocketCan : public BusInterface {
 public:
  SocketCan(SocketCanOptions options, Counters& counters);
  ~SocketCan() override;
  SocketCan(const SocketCan&) = delete;
  SocketCan& operator=(const SocketCan&) = delete;

  // Opens and binds; false (with lastError()) when the interface or AF_CAN is missing; poll() retries.
  bool open() override;
  int fd() const { return fd_; }
  bool fdEnabled() const { return fd_enabled_; }
  // All pending data frames (error frames update state() and are not returned). `now`: monotonic seconds.
  std::vector<CanFrame> receive(double now, std::size_t max = 256) override;
  // Queues a frame; flush() writes what the kernel accepts.
  void send(const CanFrame& f) override;
  void flush() override;
  // Reopen after the interface disappeared, restart after bus-off.
  void poll(double now) override;
  // Waits up to timeout_s for readable data (or the fd to appear). Returns true when readable.
  bool wait(double timeout_s) override;

  BusState state() const override { return monitor_.state(); }
  std::string lastError() const override { return last_error_; }
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

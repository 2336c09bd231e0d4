#pragma once
// Relay policies, independent of sockets: rate limiting, replay protection, heartbeats with link quality, and
// the peer's redial backoff. (Reliable delivery is reliable.h.)
#include <cstddef>
#include <cstdint>
#include <deque>

namespace offshore_gnc {
namespace relay {

// Token bucket: rate_hz messages per second, burst of `burst` messages. rate_hz <= 0: unlimited.
class TokenBucket {
 public:
  TokenBucket(double rate_hz = 0.0, double burst = 1.0);
  bool allow(double now_s);

 private:
  double rate_, burst_, tokens_, last_ = -1.0;
};

// Anti-replay window (RFC 4303 style, 64 frames): accepts each counter once, rejects old ones. On a stream
// transport counters arrive in order; the window also serves datagram transports.
class ReplayWindow {
 public:
  bool accept(std::uint64_t counter);
  void reset() { top_ = 0, bits_ = 0; }

 private:
  std::uint64_t top_ = 0, bits_ = 0;
};

// Heartbeat bookkeeping: when the next ping is due, round-trip time of the last pong, loss over the last
// `window` pings.
class LinkMonitor {
 public:
  explicit LinkMonitor(std::size_t window = 20) : window_(window) {}
  bool pingDue(double now) const { return now >= next_ping_; }
  // The id of a ping sent now; the next is due a period later.
  std::uint64_t ping(double now, double period);
  void pingSent(std::uint64_t id);
  // Returns the round-trip time in seconds if the pong matches an outstanding ping.
  bool pongReceived(std::uint64_t id, double rtt_s);
  double rtt() const { return rtt_; }
  double loss() const;
  void reset();
  // A new link: no pings outstanding, the first one due at `now`.
  void restart(double now) {
    reset();
    next_ping_ = now;
  }

 private:
  struct Ping {
    std::uint64_t id;
    bool answered;
  };
  std::size_t window_;
  std::deque<Ping> pings_;
  double rtt_ = 0.0, next_ping_ = 0.0;
  std::uint64_t last_id_ = 0;
};

// Dialling a peer: a failed or lost outbound connection is retried after a wait that doubles from `min` up to
// `max`; a link that comes up starts again from `min`.
class Redial {
 public:
  Redial(double min, double max) : min_(min), max_(max), wait_(min) {}
  bool due(double now) const { return !dialing_ && now >= next_; }
  void dialing() { dialing_ = true; }
  bool inProgress() const { return dialing_; }
  void failed(double now) {
    dialing_ = false;
    next_ = now + wait_;
    wait_ = wait_ * 2 < max_ ? wait_ * 2 : max_;
  }
  void succeeded() {
    dialing_ = false;
    wait_ = min_;
  }
  double untilDue(double now) const { return next_ > now ? next_ - now : 0.0; }

 private:
  double min_, max_, wait_, next_ = 0.0;
  bool dialing_ = false;
};

}  // namespace relay
}  // namespace offshore_gnc

#pragma once
// Relay policies, independent of sockets: rate limiting, the bounded reliable queue (sequence numbers,
// cumulative acks, resend), replay protection and heartbeat-based link quality.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

namespace offshore_gnc {
namespace relay {

using Bytes = std::shared_ptr<const std::vector<std::uint8_t>>;

// Token bucket: rate_hz messages per second, burst of `burst` messages. rate_hz <= 0: unlimited.
class TokenBucket {
 public:
  TokenBucket(double rate_hz = 0.0, double burst = 1.0);
  bool allow(double now_s);

 private:
  double rate_, burst_, tokens_, last_ = -1.0;
};

struct QueuedMessage {
  std::uint64_t seq = 0;
  std::uint16_t topic_id = 0;
  std::uint8_t flags = 0;
  Bytes payload;
};

// Unacknowledged reliable messages of one link. Overflow policy: when max_messages or max_bytes would be
// exceeded, the OLDEST messages are dropped (and counted): a long outage keeps the newest data, memory stays
// bounded. Messages stay queued until the peer's cumulative ack covers them; after a reconnect everything
// unacknowledged is sent again (at-least-once; the receiver drops duplicates by sequence number).
class ReliableQueue {
 public:
  ReliableQueue(std::size_t max_messages, std::size_t max_bytes);
  // Returns the sequence number given; `dropped` receives the messages pushed out by the overflow policy.
  std::uint64_t push(std::uint16_t topic_id, std::uint8_t flags, Bytes payload,
                     std::vector<QueuedMessage>* dropped = nullptr);
  // Cumulative ack: everything with seq <= ack is delivered.
  void ack(std::uint64_t ack);
  // Start sending from the oldest unacknowledged message again (after a reconnect).
  void rewind() { next_ = 0; }
  // Next message not yet sent on the current connection, or nullptr.
  const QueuedMessage* nextToSend();
  std::size_t size() const { return q_.size(); }
  std::size_t bytes() const { return bytes_; }
  std::uint64_t lastSeq() const { return next_seq_ - 1; }

 private:
  std::size_t max_messages_, max_bytes_;
  std::deque<QueuedMessage> q_;
  std::size_t next_ = 0;  // index into q_ of the next message to send
  std::size_t bytes_ = 0;
  std::uint64_t next_seq_ = 1;
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

// Heartbeat bookkeeping: round-trip time of the last pong, loss over the last `window` pings.
class LinkMonitor {
 public:
  explicit LinkMonitor(std::size_t window = 20) : window_(window) {}
  void pingSent(std::uint64_t id);
  // Returns the round-trip time in seconds if the pong matches an outstanding ping.
  bool pongReceived(std::uint64_t id, double rtt_s);
  double rtt() const { return rtt_; }
  double loss() const;
  void reset();

 private:
  struct Ping {
    std::uint64_t id;
    bool answered;
  };
  std::size_t window_;
  std::deque<Ping> pings_;
  double rtt_ = 0.0;
};

}  // namespace relay
}  // namespace offshore_gnc

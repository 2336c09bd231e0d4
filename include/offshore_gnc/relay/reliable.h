#pragma once
// Reliable delivery, both ends of one link, independent of sockets: the sender's bounded queue (sequence
// numbers, cumulative acks, resend after a reconnect) and the receiver's bookkeeping (duplicates dropped by
// sequence number, acks that trail delivery).
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <utility>
#include <vector>

namespace offshore_gnc {
namespace relay {

using Bytes = std::shared_ptr<const std::vector<std::uint8_t>>;

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

// The receiving end of one peer's reliable messages: the peer's session, the last sequence number delivered and
// the acks not yet sent. An ack trails delivery by the ack delay: a message is acknowledged only once it was
// handed on that long ago, so a crash of the receiver before it was written out means a resend, not a loss.
class ReliableReceiver {
 public:
  // The session of the peer at link-up: a new one (the peer restarted) starts its sequence numbers again.
  void startSession(std::uint64_t session);
  std::uint64_t session() const { return session_; }
  std::uint64_t lastSeq() const { return seq_; }
  // A reliable message's sequence number: false for a duplicate (drop it); `skipped` counts the numbers jumped.
  bool accept(std::uint64_t seq, std::uint64_t& skipped);
  // The cumulative ack to send at `now` (0: none yet); send it, then call sent().
  std::uint64_t due(double now, double ack_delay);
  void sent(std::uint64_t ack) { acked_ = ack; }
  std::uint64_t acked() const { return acked_; }
  bool pending() const { return !pending_.empty(); }

 private:
  std::uint64_t session_ = 0, seq_ = 0, acked_ = 0;
  std::deque<std::pair<double, std::uint64_t>> pending_;  // (delivery time, seq) not yet acknowledged
};

}  // namespace relay
}  // namespace offshore_gnc

// Reliable delivery (include/offshore_gnc/relay/reliable.h).
#include "offshore_gnc/relay/reliable.h"

#include <algorithm>

namespace offshore_gnc {
namespace relay {

ReliableQueue::ReliableQueue(std::size_t max_messages, std::size_t max_bytes)
    : max_messages_(std::max<std::size_t>(1, max_messages)), max_bytes_(max_bytes) {}

std::uint64_t ReliableQueue::push(std::uint16_t topic_id, std::uint8_t flags, Bytes payload,
                                  std::vector<QueuedMessage>* dropped) {
  const std::size_t n = payload ? payload->size() : 0;
  while (!q_.empty() && (q_.size() + 1 > max_messages_ || bytes_ + n > max_bytes_)) {
    if (dropped) dropped->push_back(q_.front());
    bytes_ -= q_.front().payload ? q_.front().payload->size() : 0;
    q_.pop_front();
    if (next_ > 0) --next_;
  }
  QueuedMessage m;
  m.seq = next_seq_++;
  m.topic_id = topic_id;
  m.flags = flags;
  m.payload = std::move(payload);
  bytes_ += n;
  q_.push_back(std::move(m));
  return q_.back().seq;
}

void ReliableQueue::ack(std::uint64_t ack) {
  while (!q_.empty() && q_.front().seq <= ack) {
    bytes_ -= q_.front().payload ? q_.front().payload->size() : 0;
    q_.pop_front();
    if (next_ > 0) --next_;
  }
}

const QueuedMessage* ReliableQueue::nextToSend() {
  if (next_ >= q_.size()) return nullptr;
  return &q_[next_++];
}

void ReliableReceiver::startSession(std::uint64_t session) {
  if (session == session_) return;
  session_ = session;
  seq_ = acked_ = 0;
  pending_.clear();
}

bool ReliableReceiver::accept(std::uint64_t seq, std::uint64_t& skipped) {
  skipped = 0;
  if (seq <= seq_) return false;
  if (seq_ && seq > seq_ + 1) skipped = seq - seq_ - 1;
  seq_ = seq;
  return true;
}

std::uint64_t ReliableReceiver::due(double now, double ack_delay) {
  if ((pending_.empty() || pending_.back().second != seq_) && seq_ != acked_) pending_.emplace_back(now, seq_);
  std::uint64_t ack = 0;
  while (!pending_.empty() && pending_.front().first <= now - ack_delay) {
    ack = pending_.front().second;
    pending_.pop_front();
  }
  return ack != acked_ ? ack : 0;
}

}  // namespace relay
}  // namespace offshore_gnc

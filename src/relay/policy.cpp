// Relay policies (include/offshore_gnc/relay/policy.h).
#include "offshore_gnc/relay/policy.h"

#include <algorithm>

namespace offshore_gnc {
namespace relay {

TokenBucket::TokenBucket(double rate_hz, double burst) : rate_(rate_hz), burst_(std::max(1.0, burst)), tokens_(burst_) {}

bool TokenBucket::allow(double now_s) {
  if (rate_ <= 0.0) return true;
  if (last_ >= 0.0) tokens_ = std::min(burst_, tokens_ + (now_s - last_) * rate_);
  last_ = now_s;
  if (tokens_ < 1.0) return false;
  tokens_ -= 1.0;
  return true;
}

bool ReplayWindow::accept(std::uint64_t c) {
  if (c == 0) return false;
  if (c > top_) {
    const std::uint64_t shift = c - top_;
    bits_ = shift >= 64 ? 0 : bits_ << shift;
    bits_ |= 1;
    top_ = c;
    return true;
  }
  const std::uint64_t back = top_ - c;
  if (back >= 64) return false;
  const std::uint64_t bit = std::uint64_t(1) << back;
  if (bits_ & bit) return false;
  bits_ |= bit;
  return true;
}

std::uint64_t LinkMonitor::ping(double now, double period) {
  next_ping_ = now + period;
  pingSent(++last_id_);
  return last_id_;
}

void LinkMonitor::pingSent(std::uint64_t id) {
  pings_.push_back({id, false});
  while (pings_.size() > window_) pings_.pop_front();
}

bool LinkMonitor::pongReceived(std::uint64_t id, double rtt_s) {
  for (auto& p : pings_) {
    if (p.id == id && !p.answered) {
      p.answered = true;
      rtt_ = rtt_s;
      return true;
    }
  }
  return false;
}

double LinkMonitor::loss() const {
  // The newest ping may still be in flight: judge only pings older than it.
  if (pings_.size() < 2) return 0.0;
  std::size_t lost = 0;
  for (std::size_t i = 0; i + 1 < pings_.size(); ++i) lost += pings_[i].answered ? 0 : 1;
  return double(lost) / double(pings_.size() - 1);
}

void LinkMonitor::reset() {
  pings_.clear();
  rtt_ = 0.0;
}

}  // namespace relay
}  // namespace offshore_gnc

// Link statistics (include/offshore_gnc/relay/stats.h).
#include "offshore_gnc/relay/stats.h"

namespace offshore_gnc {
namespace relay {

void TopicTraffic::report(double dt, TopicStatus& s) {
  // what carried the messages so far: udp, tcp, or both (best-effort frames too large for a datagram)
  s.transport = datagrams_ == 0 ? "tcp" : (datagrams_ == messages_ ? "udp" : "udp+tcp");
  s.messages = messages_;
  s.bytes = bytes_;
  s.dropped = dropped_;
  if (dt > 0) {
    s.rate_hz = double(messages_ - last_messages_) / dt;
    s.bandwidth_bps = double(bytes_ - last_bytes_) / dt;
  }
  last_messages_ = messages_;
  last_bytes_ = bytes_;
}

}  // namespace relay
}  // namespace offshore_gnc

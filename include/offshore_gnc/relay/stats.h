#pragma once
// What the relay reports of its links (/relay/link_status): per peer its state, per topic what it carried.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace offshore_gnc {
namespace relay {

struct TopicStatus {
  std::string topic, remote, direction, transport;
  std::uint64_t messages = 0, bytes = 0, dropped = 0;
  double rate_hz = 0.0, bandwidth_bps = 0.0;
};

struct PeerStatus {
  std::string name, address;
  bool up = false;
  double rtt = 0.0, loss = 0.0;
  std::uint32_t reconnects = 0;
  std::uint64_t frames_rejected = 0;
  std::size_t queued = 0;
  std::string refused;  // why the peer's last hello was refused (e.g. another origin); empty once a link is up
  std::vector<TopicStatus> topics;
};

// One topic's traffic to or from one peer.
class TopicTraffic {
 public:
  void carried(std::size_t bytes, bool datagram = false) {
    ++messages_;
    bytes_ += bytes;
    if (datagram) ++datagrams_;
  }
  void dropped() { ++dropped_; }
  // Counts, the transport that carried them, and rates since the last report `dt` seconds ago (0: none).
  void report(double dt, TopicStatus& s);

 private:
  std::uint64_t messages_ = 0, bytes_ = 0, dropped_ = 0, datagrams_ = 0, last_messages_ = 0, last_bytes_ = 0;
};

}  // namespace relay
}  // namespace offshore_gnc

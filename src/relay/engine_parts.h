#pragma once
// The engine's state of one connection and of one peer, shared by engine.cpp (the poll loop), connections.cpp
// (links and the handshake) and receive.cpp (frames in, messages out). Each part's logic is its stage's class.
#include <poll.h>

#include <chrono>
#include <set>
#include <string>
#include <vector>

#include "offshore_gnc/relay/engine.h"
#include "offshore_gnc/relay/handshake.h"
#include "offshore_gnc/relay/tcp_link.h"

namespace offshore_gnc {
namespace relay {

inline double nowS() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

struct Engine::Conn {
  TcpLink link;
  bool outbound = false, hello_received = false, established = false;
  std::string nonce = freshNonce();
  Hello remote;          // the peer's hello: its session and what it holds of ours
  Peer* peer = nullptr;  // known after the hello (outbound: from the start)
  DatagramPath udp;
  std::set<std::size_t> tcp_first_sent;  // topics whose first message went by TCP (behind the announce)
  Conn(int fd, bool connecting, double now, const Authenticator& psk)
      : link(fd, connecting, now, kMaxHelloPayload, psk) {}  // small frames until the peer's hello authenticates
};

struct Engine::Peer {
  PeerConfig cfg;
  Conn* conn = nullptr;  // the established connection
  ReliableQueue queue;        // our reliable messages to it
  ReliableReceiver received;  // its reliable messages to us
  Redial redial;
  LinkMonitor monitor;
  bool ever_up = false;
  std::uint32_t reconnects = 0;
  std::uint64_t rejected = 0;
  std::string refused;  // PeerStatus::refused
  std::uint64_t latched_session = 0;  // the peer session that has our latched messages
  RemoteTopics incoming;
  TokenBucket log_limit{1.0, 5.0};  // refusals this peer causes are logged at most about once a second
  std::vector<TokenBucket> limits;  // per topic index
  std::vector<TopicTraffic> out_traffic, in_traffic;  // per topic index
  double last_status = 0.0;
  Peer(const PeerConfig& c, const RelayConfig& rc)
      : cfg(c),
        queue(std::size_t(rc.queue_messages), std::size_t(rc.queue_bytes)),
        redial(rc.backoff_min, rc.backoff_max) {
    for (const auto& t : rc.topics) limits.emplace_back(t.rate_hz, std::max(1.0, t.rate_hz * 0.5));
    out_traffic.resize(rc.topics.size());
    in_traffic.resize(rc.topics.size());
  }
  bool dials() const { return !cfg.host.empty(); }
};

// One poll round: the wake-up event, the listening socket, every connection, the UDP socket (last: a datagram and
// the TCP announce of its topic from the same round are handled announce first).
struct Engine::PollSet {
  std::vector<pollfd> fds;
  std::vector<Conn*> conns;  // per fds entry; nullptr for the engine's own sockets
  void add(int fd, short events, Conn* c = nullptr) {
    fds.push_back({fd, events, 0});
    conns.push_back(c);
  }
};

struct Engine::Delivery {
  enum Kind { Announce_, Message } kind;
  Peer* peer;
  std::uint16_t remote_id;
  long index;
  Announce announce;
  std::vector<std::uint8_t> data;
  bool datagram = false;  // arrived over UDP (for the link status' transport)
};

}  // namespace relay
}  // namespace offshore_gnc

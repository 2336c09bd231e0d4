#pragma once
// The relay engine: TCP links to the peer relays (plain POSIX sockets + poll on one I/O thread), handshake
// with fresh nonces, per-connection HMAC keys and replay protection, announces with type + md5sum,
// reliable queue with acks and resend, rate limits, compression, heartbeats and reconnection with backoff.
// ROS-free: the nodelet feeds serialized messages in and publishes what the callbacks hand out.
#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/relay/policy.h"
#include "offshore_gnc/relay/wire.h"

namespace offshore_gnc {
namespace relay {

struct TopicConfig {
  std::string topic;      // local name
  std::string type;       // ROS type, e.g. offshore_gnc/Target (checked at both ends)
  std::string direction;  // "out" (local -> peers) or "in" (peers -> local)
  std::string remote;     // out: name on the far side (default: topic)
  std::vector<std::string> peers;  // out: destinations, in: accepted sources (empty = all peers)
  bool reliable = true;
  double rate_hz = 0.0;  // 0 = unlimited
  bool latched = false;
  bool compress = false;
};

struct PeerConfig {
  std::string name;
  std::string host;  // empty: the peer dials us
  int port = 0;
};

struct RelayConfig {
  std::string name;
  std::string listen_host = "127.0.0.1";
  int listen_port = 0;  // 0 = do not listen (-1 in tests: any free port)
  bool auth = true;     // HMAC-SHA256 on every frame; off only by explicit configuration
  // Best-effort topics go in UDP datagrams (same frames, same session keys, own replay window; loss counted,
  // never resent) when the encoded frame fits max_datagram_bytes; larger ones and latched repeats use TCP.
  bool udp = true;
  std::size_t max_datagram_bytes = 60000;
  std::string key;      // pre-shared key (required when auth)
  // Simulation: any key of >= 16 bytes, the shipped config/relay/sim.key too. Off (hardware), the key must be a
  // deployment key (relay/key.h: >= 32 random bytes, not the published simulation key).
  bool sim = false;
  double heartbeat_period = 0.2, link_timeout = 1.0, backoff_min = 0.1, backoff_max = 2.0;
  double ack_delay = 0.5;  // acks trail delivery to ROS by this long (crash window covered by resends)
  // The site's origin, announced in the hello: a peer whose origin lies farther than origin_tolerance [m] is
  // refused, both named (two vehicles on different origins would misplace every position they exchange). Unset
  // here or at the peer: not checked.
  std::optional<geo::LatLonAlt> origin;
  double origin_tolerance = 1.0;
  std::size_t queue_messages = 1000, queue_bytes = 64u << 20, max_frame_bytes = 32u << 20;
  std::vector<PeerConfig> peers;
  std::vector<TopicConfig> topics;
};

// Fills defaults and throws ConfigError naming the offending entry.
void validate(RelayConfig& c);

struct TypeInfo {
  std::string type, md5, definition;
};

struct Announce {
  std::string topic;  // the name on this side
  TypeInfo info;
  bool latched = false, reliable = true;
};

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

// What the engine holds in memory, for tests of its limits (docs/relay.md, "Security model").
struct MemoryUse {
  std::size_t connections = 0;  // open TCP connections, authenticated or not
  std::size_t input_bytes = 0;  // frame decoders' buffers (capacity)
  std::size_t output_bytes = 0; // unsent output (capacity)
  std::size_t remote_topics = 0;  // announced topics remembered, all peers
  std::size_t queued_bytes = 0;   // reliable queues
};

struct Callbacks {
  // An announced topic from `peer` matched in-topic `index`: return "" to accept, or the refusal reason.
  std::function<std::string(std::size_t index, const std::string& peer, const Announce&)> on_announce;
  // A message for in-topic `index` (serialized ROS message).
  std::function<void(std::size_t index, const std::string& peer, const std::vector<std::uint8_t>& data)> on_message;
  // Something a user must see (the ROS side throttles): level 1 = warn, 2 = error.
  std::function<void(int level, const std::string& text)> on_log;
};

class Engine {
 public:
  Engine(RelayConfig cfg, Callbacks cb, Counters& counters);
  ~Engine();
  Engine(const Engine&) = delete;
  Engine& operator=(const Engine&) = delete;
  // Starts the I/O thread; with run_thread false the caller drives the engine with pollOnce (tests, fuzzing).
  void start(bool run_thread = true);
  void stop();
  // One round of the I/O loop: dial, heartbeats, poll (at most max_wait_s), read, deliver, ack.
  void pollOnce(double max_wait_s);
  // Takes a connected stream socket (e.g. one end of a socketpair) as if a peer had dialled in.
  void adopt(int fd);
  MemoryUse memoryUse();
  // A local message on out-topic `index`; the type is checked against the configuration.
  void publish(std::size_t index, const TypeInfo& info, Bytes data);
  std::vector<PeerStatus> status();
  int listenPort() const { return listen_port_; }
  const RelayConfig& config() const { return cfg_; }

 private:
  struct Conn;
  struct Peer;
  struct Delivery;
  void run();
  void step(double max_wait_s);
  void acceptOne();
  void addInbound(int fd);
  bool congested(const Conn& c) const;
  void dial(Peer& p, double now);
  void closeConn(Conn& c, const std::string& why);
  void onReadable(Conn& c, double now, std::vector<Delivery>& out);
  void handleFrame(Conn& c, Frame& f, double now, std::vector<Delivery>& out);
  void establish(Conn& c, double now);
  void sendFrame(Conn& c, FrameHeader h, const std::uint8_t* p, std::size_t n);
  bool sendDatagram(Conn& c, FrameHeader h, const std::uint8_t* p, std::size_t n);
  void onDatagrams(std::vector<Delivery>& out);
  void handleData(Peer& p, Frame& f, std::vector<Delivery>& out);
  void sendHello(Conn& c);
  // Why a peer announcing `theirs` as its origin must be refused; empty when it agrees (or either has none).
  std::string siteMismatch(const std::optional<geo::LatLonAlt>& theirs) const;
  void sendAnnounce(Conn& c, std::size_t index);
  void pump(Peer& p);
  void sendAcks(double now);
  void flush(Conn& c);
  void log(int level, const std::string& s);
  bool goesTo(const TopicConfig& t, const std::string& peer) const;

  RelayConfig cfg_;
  Callbacks cb_;
  Counters& counters_;
  Authenticator psk_;
  std::uint64_t session_;
  int listen_fd_ = -1, listen_port_ = 0, wake_fd_ = -1, udp_fd_ = -1, udp_port_ = 0;
  std::mutex mutex_;
  std::vector<std::unique_ptr<Peer>> peers_;
  std::vector<std::unique_ptr<Conn>> conns_;
  std::vector<TypeInfo> out_types_;             // per topic index: type seen locally
  std::vector<Bytes> latched_;                  // per topic index: last message (latched topics)
  std::vector<std::uint8_t> latched_flags_;
  std::atomic<bool> running_{false};
  std::thread thread_;
};

}  // namespace relay
}  // namespace offshore_gnc

#pragma once
// The relay engine: a small poll loop on one I/O thread around the relay's stages, each in its own file:
// config.h (what to carry), tcp_link.h and udp_link.h (the transports), handshake.h (hello, session keys, the site
// check), routing.h (announces, which topic goes where), reliable.h (queue, acks, resend), policy.h (rate limits,
// replay windows, heartbeats, redial backoff), stats.h (link status). ROS-free: the nodelet feeds serialized
// messages in and publishes what the callbacks hand out.
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/relay/config.h"
#include "offshore_gnc/relay/policy.h"
#include "offshore_gnc/relay/reliable.h"
#include "offshore_gnc/relay/routing.h"
#include "offshore_gnc/relay/stats.h"
#include "offshore_gnc/relay/udp_link.h"
#include "offshore_gnc/relay/wire.h"

namespace offshore_gnc {
namespace relay {

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
  struct PollSet;
  // the poll loop (engine.cpp)
  void run();
  void step(double max_wait_s);
  void heartbeats(double now);
  double pollSet(double now, PollSet& set);
  void dispatch(const PollSet& set, double now, std::vector<Delivery>& out);
  void sendBestEffort(Peer& p, std::size_t index, std::uint8_t flags, const Bytes& wire);
  void pump(Peer& p);
  void sendAcks(double now);
  // links and the handshake (connections.cpp)
  void dial(Peer& p, double now);
  void acceptOne();
  void addInbound(int fd);
  void closeConn(Conn& c, const std::string& why);
  void flush(Conn& c);
  void sendHello(Conn& c);
  void onHello(Conn& c, const Frame& f);
  void establish(Conn& c, double now);
  void sendAnnounce(Conn& c, std::size_t index);
  // frames in, messages out (receive.cpp)
  void onReadable(Conn& c, double now, std::vector<Delivery>& out);
  void handleFrame(Conn& c, Frame& f, double now, std::vector<Delivery>& out);
  void onAnnounce(Conn& c, const Frame& f, double now, std::vector<Delivery>& out);
  void handleData(Peer& p, Frame& f, std::vector<Delivery>& out);
  void onDatagrams(std::vector<Delivery>& out);
  void refuse(Conn& c, std::uint16_t topic_id, const std::string& why);
  void deliver(std::vector<Delivery>& deliveries);
  void log(int level, const std::string& s);

  RelayConfig cfg_;
  Callbacks cb_;
  Counters& counters_;
  Authenticator psk_;
  std::uint64_t session_;
  int listen_fd_ = -1, listen_port_ = 0, wake_fd_ = -1;
  UdpSocket udp_;
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

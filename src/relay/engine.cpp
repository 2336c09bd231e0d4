#include "offshore_gnc/relay/engine.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <set>
#include <sstream>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/relay/key.h"

namespace offshore_gnc {
namespace relay {

namespace {
constexpr std::size_t kOutBufferLimit = 8u << 20;  // pump reliable frames only while below this
constexpr std::size_t kNonceSize = 16;
// Limits against a flooding peer (docs/relay.md, "Security model"): frames before an authenticated hello are
// at most a hello's size, announced message definitions are at most 256 KiB, a peer has at most 1024 topics.
constexpr std::size_t kMaxHelloPayload = 512;
constexpr std::size_t kMaxDefinitionBytes = 256u << 10;
constexpr std::size_t kMaxRemoteTopics = 1024;

double nowS() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string randomBytes(std::size_t n) {
  static thread_local std::random_device rd;
  std::string s(n, '\0');
  for (auto& ch : s) ch = static_cast<char>(rd() & 0xff);
  return s;
}

void setNonBlocking(int fd) {
  fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
  int one = 1;
  setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof(one));  // small messages: no Nagle delay
  int buf = 4 << 20;  // large messages (point clouds): fewer poll rounds per frame
  setsockopt(fd, SOL_SOCKET, SO_SNDBUF, &buf, sizeof(buf));
  setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &buf, sizeof(buf));
}

ConfigError configError(const std::string& what) { return ConfigError("relay config: " + what); }
}  // namespace

void validate(RelayConfig& c) {
  if (c.name.empty()) throw configError("'name' must be set (this relay's name, e.g. usv)");
  if (c.auth && c.key.size() < 16)
    throw configError("'auth' is on but the pre-shared key is missing or shorter than 16 bytes "
                      "(set key_file, or auth: none to disable authentication explicitly)");
  if (c.auth && !c.sim) {
    const std::string why = deploymentKeyProblem(c.key);
    if (!why.empty())
      throw configError("refusing to start on hardware (sim: false): the pre-shared key " + why + ". " + kMakeKeyHint);
  }
  requireRange("listen_port", c.listen_port, -1, 65535);
  requireRange("heartbeat_period", c.heartbeat_period, 0.01, 10.0);
  requireRange("link_timeout", c.link_timeout, 2 * c.heartbeat_period, 60.0);
  requireRange("ack_delay", c.ack_delay, 0.0, 10.0);
  requireRange("backoff_min", c.backoff_min, 0.01, 10.0);
  requireRange("backoff_max", c.backoff_max, c.backoff_min, 60.0);
  requireRange("queue/max_messages", double(c.queue_messages), 1, 1e6);
  requireRange("queue/max_bytes", double(c.queue_bytes), 1024, 4e9);
  requireRange("max_frame_bytes", double(c.max_frame_bytes), 1024, 1u << 30);
  requireRange("max_datagram_bytes", double(c.max_datagram_bytes), 512, 65000);
  requireRange("origin_tolerance", c.origin_tolerance, 0.0, 1e4);
  if (c.origin) geo::checkLatLonAlt(*c.origin);
  std::set<std::string> names;
  for (const auto& p : c.peers) {
    if (p.name.empty() || p.name == c.name) throw configError("peer name '" + p.name + "' is empty or our own");
    if (!names.insert(p.name).second) throw configError("peer '" + p.name + "' listed twice");
    if (!p.host.empty()) requireRange("peers/" + p.name + "/port", p.port, 1, 65535);
  }
  if (c.topics.size() > 65535) throw configError("too many topics");
  std::set<std::string> in_names, out_names;
  for (auto& t : c.topics) {
    const std::string where = "topic '" + t.topic + "'";
    if (t.topic.empty() || t.topic[0] != '/') throw configError(where + ": 'topic' must be an absolute name");
    if (t.type.find('/') == std::string::npos) throw configError(where + ": 'type' must be package/Message");
    if (t.direction != "out" && t.direction != "in") throw configError(where + ": 'direction' must be out or in");
    if (t.remote.empty()) t.remote = t.topic;
    if (t.remote[0] != '/') throw configError(where + ": 'remote' must be an absolute name");
    requireRange(where + " rate_hz", t.rate_hz, 0.0, 1e6);
    for (const auto& p : t.peers)
      if (!names.count(p)) throw configError(where + ": peer '" + p + "' is not in 'peers'");
    if (t.direction == "in" && !in_names.insert(t.topic).second)
      throw configError(where + ": listed twice as 'in' (list the accepted peers in one entry)");
    if (t.direction == "out") out_names.insert(t.topic);
  }
  for (const auto& n : in_names)
    if (out_names.count(n)) throw configError("topic '" + n + "': both 'in' and 'out' (it would loop)");
}

struct Engine::Conn {
  int fd = -1;
  bool outbound = false, connecting = false, hello_received = false, established = false, closed = false;
  double opened = 0.0, last_rx = 0.0;
  FrameDecoder decoder;
  std::vector<std::uint8_t> out;
  std::size_t out_pos = 0;
  Authenticator tx_auth, rx_auth;
  std::uint64_t tx_counter = 0;
  ReplayWindow replay;
  // UDP side of the link: the peer's datagram address (its TCP address, the port from its hello), our own
  // frame counter and the replay window of what arrives (datagrams may be lost or reordered).
  sockaddr_in udp_to{};
  bool udp = false;
  std::uint64_t udp_tx_counter = 0, udp_rx_max = 0;
  ReplayWindow udp_replay;
  std::set<std::size_t> tcp_first_sent;  // topics whose first message went by TCP (behind the announce)
  std::string nonce = randomBytes(kNonceSize), remote_nonce;
  Peer* peer = nullptr;  // known after the hello
  std::uint64_t hello_ack_session = 0, hello_ack_seq = 0, remote_session = 0;
  Conn() : decoder(kMaxHelloPayload) {}  // until the peer's hello is authenticated
};

struct Engine::Peer {
  PeerConfig cfg;
  Conn* conn = nullptr;  // established connection
  ReliableQueue queue;
  double next_dial = 0.0, backoff;
  bool dialing = false, ever_up = false;
  LinkMonitor monitor;
  std::uint64_t ping_id = 0;
  double next_ping = 0.0;
  std::uint32_t reconnects = 0;
  std::uint64_t rejected = 0;
  std::string refused;  // PeerStatus::refused
  // receive side: the peer's session and the last reliable sequence delivered from it
  std::uint64_t rx_session = 0, rx_seq = 0, acked_seq = 0;
  std::deque<std::pair<double, std::uint64_t>> pending_acks;  // (delivery time, seq) not yet acknowledged
  std::uint64_t latched_session = 0;  // the peer session that has our latched messages
  struct Incoming {
    long index = -1;           // in-topic index once the callback accepted the announce, else -1
    std::uint64_t digest = 0;  // of the announce (an identical repeat changes nothing)
  };
  std::map<std::uint16_t, Incoming> incoming;  // remote topic id -> what it maps to
  TokenBucket log_limit{1.0, 5.0};  // refusals this peer causes are logged at most about once a second
  std::vector<TokenBucket> limits;  // per topic index
  struct Stat {
    std::uint64_t messages = 0, bytes = 0, dropped = 0, last_messages = 0, last_bytes = 0, datagrams = 0;
    bool used = false;
  };
  std::vector<Stat> out_stats, in_stats;  // per topic index
  double last_status = 0.0;
  Peer(const PeerConfig& c, const RelayConfig& rc)
      : cfg(c), queue(rc.queue_messages, rc.queue_bytes), backoff(rc.backoff_min) {}
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

Engine::Engine(RelayConfig cfg, Callbacks cb, Counters& counters)
    : cfg_(std::move(cfg)), cb_(std::move(cb)), counters_(counters) {
  validate(cfg_);
  if (cfg_.auth) psk_ = Authenticator(cfg_.key);
  std::mt19937_64 rng(std::random_device{}());
  session_ = rng() | 1;
  out_types_.resize(cfg_.topics.size());
  latched_.resize(cfg_.topics.size());
  latched_flags_.resize(cfg_.topics.size());
  for (const auto& pc : cfg_.peers) {
    auto p = std::make_unique<Peer>(pc, cfg_);
    for (const auto& t : cfg_.topics) p->limits.emplace_back(t.rate_hz, std::max(1.0, t.rate_hz * 0.5));
    p->out_stats.resize(cfg_.topics.size());
    p->in_stats.resize(cfg_.topics.size());
    peers_.push_back(std::move(p));
  }
}

Engine::~Engine() { stop(); }

void Engine::start(bool run_thread) {
  if (cfg_.listen_port != 0) {
    listen_fd_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    int one = 1;
    setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(cfg_.listen_port > 0 ? cfg_.listen_port : 0);
    if (inet_pton(AF_INET, cfg_.listen_host.c_str(), &a.sin_addr) != 1)
      throw configError("listen host '" + cfg_.listen_host + "' is not an IPv4 address");
    if (bind(listen_fd_, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0 || listen(listen_fd_, 16) != 0) {
      const std::string err = std::strerror(errno);
      close(listen_fd_);
      listen_fd_ = -1;
      throw std::runtime_error("relay: cannot listen on " + cfg_.listen_host + ":" +
                               std::to_string(cfg_.listen_port) + ": " + err);
    }
    socklen_t len = sizeof(a);
    getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&a), &len);
    listen_port_ = ntohs(a.sin_port);
    setNonBlocking(listen_fd_);
  }
  if (cfg_.udp) {
    // Bound to the TCP listening address and port when listening (peers know it), else any free port; the
    // hello tells the peer which.
    udp_fd_ = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(listen_fd_ >= 0 ? listen_port_ : 0);
    if (listen_fd_ < 0 || inet_pton(AF_INET, cfg_.listen_host.c_str(), &a.sin_addr) != 1) a.sin_addr.s_addr = INADDR_ANY;
    if (udp_fd_ < 0 || bind(udp_fd_, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0) {
      log(2, std::string("relay ") + cfg_.name + ": no UDP socket (" + std::strerror(errno) +
                 "): best-effort topics use TCP");
      if (udp_fd_ >= 0) close(udp_fd_);
      udp_fd_ = -1;
    } else {
      socklen_t len = sizeof(a);
      getsockname(udp_fd_, reinterpret_cast<sockaddr*>(&a), &len);
      udp_port_ = ntohs(a.sin_port);
      int buf = 4 << 20;  // room for bursts of large best-effort messages
      setsockopt(udp_fd_, SOL_SOCKET, SO_RCVBUF, &buf, sizeof(buf));
      setsockopt(udp_fd_, SOL_SOCKET, SO_SNDBUF, &buf, sizeof(buf));
      setNonBlocking(udp_fd_);
    }
  }
  wake_fd_ = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  running_ = true;
  if (run_thread) thread_ = std::thread([this] { run(); });
}

void Engine::pollOnce(double max_wait_s) {
  if (running_ && !thread_.joinable()) step(max_wait_s);
}

void Engine::adopt(int fd) {
  std::lock_guard<std::mutex> lock(mutex_);
  addInbound(fd);
}

MemoryUse Engine::memoryUse() {
  std::lock_guard<std::mutex> lock(mutex_);
  MemoryUse m;
  for (const auto& c : conns_) {
    if (c->closed) continue;
    ++m.connections;
    m.input_bytes += c->decoder.capacity();
    m.output_bytes += c->out.capacity();
  }
  for (const auto& p : peers_) {
    m.remote_topics += p->incoming.size();
    m.queued_bytes += p->queue.bytes();
  }
  return m;
}

bool Engine::congested(const Conn& c) const { return c.out.size() - c.out_pos >= kOutBufferLimit; }

void Engine::stop() {
  if (!running_.exchange(false)) return;
  std::uint64_t one = 1;
  if (write(wake_fd_, &one, sizeof(one)) < 0) {
  }
  if (thread_.joinable()) thread_.join();
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto& c : conns_) {
    flush(*c);  // last acks out before we go
    if (c->fd >= 0) close(c->fd);
  }
  conns_.clear();
  for (auto& p : peers_) p->conn = nullptr;
  if (listen_fd_ >= 0) close(listen_fd_);
  if (wake_fd_ >= 0) close(wake_fd_);
  if (udp_fd_ >= 0) close(udp_fd_);
  listen_fd_ = wake_fd_ = udp_fd_ = -1;
}

void Engine::log(int level, const std::string& s) {
  if (cb_.on_log) cb_.on_log(level, s);
}

bool Engine::goesTo(const TopicConfig& t, const std::string& peer) const {
  return t.peers.empty() || std::find(t.peers.begin(), t.peers.end(), peer) != t.peers.end();
}

void Engine::publish(std::size_t index, const TypeInfo& info, Bytes data) {
  if (index >= cfg_.topics.size() || !data || cfg_.topics[index].direction != "out") return;
  const TopicConfig& t = cfg_.topics[index];
  if (info.type != t.type) {
    counters_.increment("refused_type_mismatch");
    log(2, "topic " + t.topic + ": local type " + info.type + " differs from the configured " + t.type +
               "; not relayed");
    return;
  }
  const double now = nowS();
  std::uint8_t flags = (t.reliable ? kReliable : 0) | (t.latched ? kLatched : 0);
  Bytes wire = data;
  if (t.compress) {
    wire = std::make_shared<const std::vector<std::uint8_t>>(compress(data->data(), data->size()));
    flags |= kCompressed;
  }
  std::lock_guard<std::mutex> lock(mutex_);
  const bool type_changed = out_types_[index].md5 != info.md5;
  if (type_changed) out_types_[index] = info;
  if (t.latched) {
    latched_[index] = wire;
    latched_flags_[index] = flags;
  }
  for (auto& pp : peers_) {
    Peer& p = *pp;
    if (!goesTo(t, p.cfg.name)) continue;
    auto& st = p.out_stats[index];
    st.used = true;
    if (!p.limits[index].allow(now)) {
      ++st.dropped;
      counters_.increment("rate_limited");
      continue;
    }
    if (p.conn && type_changed) sendAnnounce(*p.conn, index);
    if (t.reliable) {
      std::vector<QueuedMessage> dropped;
      p.queue.push(static_cast<std::uint16_t>(index), flags, wire, &dropped);
      for (const auto& d : dropped) {
        ++p.out_stats[d.topic_id].dropped;
        counters_.increment("queue_overflow");
      }
      pump(p);
    } else if (p.conn && p.conn->established && p.conn->udp && p.conn->tcp_first_sent.count(index) &&
               wire->size() + kHeaderSize + kTagSize <= cfg_.max_datagram_bytes) {
      // (the first message of a topic on a link goes by TCP, in order behind its announce: a datagram could
      // overtake the announce and be dropped as an unknown topic, and the first message is never lost)
      FrameHeader h;
      h.type = FrameType::Data;
      h.flags = flags;
      h.topic_id = static_cast<std::uint16_t>(index);
      if (sendDatagram(*p.conn, h, wire->data(), wire->size())) {
        ++st.messages;
        ++st.datagrams;
        st.bytes += wire->size();
      } else {
        ++st.dropped;  // socket buffer full: best effort
        counters_.increment("best_effort_dropped");
      }
    } else if (p.conn && p.conn->out.size() - p.conn->out_pos < kOutBufferLimit) {
      FrameHeader h;
      h.type = FrameType::Data;
      h.flags = flags;
      h.topic_id = static_cast<std::uint16_t>(index);
      sendFrame(*p.conn, h, wire->data(), wire->size());
      if (p.conn->established) p.conn->tcp_first_sent.insert(index);
      ++st.messages;
      st.bytes += wire->size();
    } else {
      ++st.dropped;  // best effort: link down or congested
      counters_.increment("best_effort_dropped");
    }
    if (p.conn) {
      flush(*p.conn);
      if (p.conn && p.conn->out_pos < p.conn->out.size()) {  // the I/O thread must poll for POLLOUT
        std::uint64_t one = 1;
        if (write(wake_fd_, &one, sizeof(one)) < 0) counters_.increment("wake_failed");
      }
    }
  }
}

void Engine::pump(Peer& p) {
  if (!p.conn) return;
  Conn& c = *p.conn;
  while (c.out.size() - c.out_pos < kOutBufferLimit) {
    const QueuedMessage* m = p.queue.nextToSend();
    if (!m) break;
    FrameHeader h;
    h.type = FrameType::Data;
    h.flags = m->flags;
    h.topic_id = m->topic_id;
    h.seq = m->seq;
    sendFrame(c, h, m->payload->data(), m->payload->size());
    auto& st = p.out_stats[m->topic_id];
    ++st.messages;
    st.bytes += m->payload->size();
  }
}

void Engine::sendFrame(Conn& c, FrameHeader h, const std::uint8_t* p, std::size_t n) {
  if (c.closed) return;
  h.counter = ++c.tx_counter;
  encodeFrame(h, p, n, c.tx_auth, c.out);
}

bool Engine::sendDatagram(Conn& c, FrameHeader h, const std::uint8_t* p, std::size_t n) {
  static thread_local std::vector<std::uint8_t> buf;
  buf.clear();
  h.counter = ++c.udp_tx_counter;
  encodeFrame(h, p, n, c.tx_auth, buf);
  const ssize_t r = sendto(udp_fd_, buf.data(), buf.size(), MSG_DONTWAIT, reinterpret_cast<const sockaddr*>(&c.udp_to),
                           sizeof(c.udp_to));
  return r == static_cast<ssize_t>(buf.size());
}

void Engine::onDatagrams(std::vector<Delivery>& out) {
  static thread_local std::vector<std::uint8_t> buf(65536);
  for (int budget = 0; budget < 1024; ++budget) {
    sockaddr_in from{};
    socklen_t len = sizeof(from);
    const ssize_t r = recvfrom(udp_fd_, buf.data(), buf.size(), MSG_DONTWAIT, reinterpret_cast<sockaddr*>(&from), &len);
    if (r < 0) break;
    // Only from the UDP address of an established link, authenticated with that link's session key.
    Conn* c = nullptr;
    for (auto& cc : conns_)
      if (!cc->closed && cc->established && cc->udp && cc->udp_to.sin_port == from.sin_port &&
          cc->udp_to.sin_addr.s_addr == from.sin_addr.s_addr)
        c = cc.get();
    if (!c) {
      counters_.increment("udp_unknown_source");
      continue;
    }
    FrameDecoder d(cfg_.max_datagram_bytes);
    d.setAuthenticator(c->rx_auth);
    d.feed(buf.data(), std::size_t(r));
    Frame f;
    const DecodeStatus s = d.next(f);
    if (s != DecodeStatus::Ok || d.buffered() != 0 || f.header.type != FrameType::Data ||
        (f.header.flags & kReliable)) {
      counters_.increment(s == DecodeStatus::BadAuth ? "frames_bad_auth" : "udp_malformed");
      ++c->peer->rejected;
      continue;
    }
    if (!c->udp_replay.accept(f.header.counter)) {
      counters_.increment("frames_replayed");
      ++c->peer->rejected;
      continue;
    }
    // Loss: counters skipped over (a reordered datagram that arrives later is still within the window).
    if (f.header.counter > c->udp_rx_max + 1 && c->udp_rx_max > 0)
      counters_.increment("udp_lost", f.header.counter - c->udp_rx_max - 1);
    c->udp_rx_max = std::max(c->udp_rx_max, f.header.counter);
    counters_.increment("udp_datagrams");
    const std::size_t before = out.size();
    handleData(*c->peer, f, out);
    if (out.size() > before) out.back().datagram = true;
  }
}

void Engine::flush(Conn& c) {
  while (!c.closed && !c.connecting && c.out_pos < c.out.size()) {
    const ssize_t r = send(c.fd, c.out.data() + c.out_pos, c.out.size() - c.out_pos, MSG_NOSIGNAL);
    if (r > 0) {
      c.out_pos += static_cast<std::size_t>(r);
    } else {
      if (r < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) break;
      closeConn(c, std::string("send failed: ") + std::strerror(errno));
      return;
    }
  }
  if (c.out_pos == c.out.size()) {
    c.out.clear();
    c.out_pos = 0;
  } else if (c.out_pos > (1u << 20) && c.out_pos * 2 > c.out.size()) {
    // a peer that never quite catches up: drop what was sent, or the buffer grows for ever
    c.out.erase(c.out.begin(), c.out.begin() + static_cast<std::ptrdiff_t>(c.out_pos));
    c.out_pos = 0;
  }
}

std::string Engine::siteMismatch(const std::optional<geo::LatLonAlt>& theirs) const {
  if (!theirs || !cfg_.origin) return "";
  const geo::LatLonAlt& ours = *cfg_.origin;
  const bool finite = std::isfinite(theirs->lat_deg) && std::isfinite(theirs->lon_deg) && std::isfinite(theirs->alt_m);
  const double apart = finite ? std::hypot(geo::surfaceDistance(ours, *theirs), theirs->alt_m - ours.alt_m) : NAN;
  if (finite && apart <= cfg_.origin_tolerance) return "";
  char b[400];
  std::snprintf(b, sizeof b,
                "its origin (%.7f, %.7f, %.1f m) is %.1f m from %s's (%.7f, %.7f, %.1f m), over the %.1f m tolerance: "
                "both vehicles must run on one site origin (the same site:= file or origin:=LAT,LON[,ALT])",
                theirs->lat_deg, theirs->lon_deg, theirs->alt_m, apart, cfg_.name.c_str(), ours.lat_deg, ours.lon_deg,
                ours.alt_m, cfg_.origin_tolerance);
  return b;
}

void Engine::sendHello(Conn& c) {
  Writer w;
  w.u16(kWireVersion);
  w.str(cfg_.name);
  w.u64(session_);
  w.bytes(reinterpret_cast<const std::uint8_t*>(c.nonce.data()), kNonceSize);
  // What we hold from this peer (only known for outbound connections, where the peer is known in advance).
  std::uint64_t ack_session = 0, ack_seq = 0;
  if (c.peer) ack_session = c.peer->rx_session, ack_seq = c.peer->rx_seq;
  w.u64(ack_session);
  w.u64(ack_seq);
  w.u16(static_cast<std::uint16_t>(udp_fd_ >= 0 ? udp_port_ : 0));  // 0: no UDP here
  w.u8(cfg_.origin ? 1 : 0);
  if (cfg_.origin) {
    w.f64(cfg_.origin->lat_deg);
    w.f64(cfg_.origin->lon_deg);
    w.f64(cfg_.origin->alt_m);
  }
  FrameHeader h;
  h.type = FrameType::Hello;
  c.tx_auth = psk_;  // the hello is authenticated with the PSK itself
  sendFrame(c, h, w.b.data(), w.b.size());
}

void Engine::sendAnnounce(Conn& c, std::size_t index) {
  const TopicConfig& t = cfg_.topics[index];
  const TypeInfo& ti = out_types_[index];
  if (ti.md5.empty()) return;  // type not known until the first local message
  Writer w;
  w.str(t.remote);
  w.str(ti.type);
  w.str(ti.md5);
  w.str(ti.definition);
  w.u8(t.latched);
  w.u8(t.reliable);
  FrameHeader h;
  h.type = FrameType::Announce;
  h.topic_id = static_cast<std::uint16_t>(index);
  sendFrame(c, h, w.b.data(), w.b.size());
}

void Engine::closeConn(Conn& c, const std::string& why) {
  if (c.closed) return;
  c.closed = true;
  if (c.fd >= 0) close(c.fd);
  c.fd = -1;
  if (c.peer) {
    Peer& p = *c.peer;
    if (p.conn == &c) {
      p.conn = nullptr;
      log(1, "link to " + p.cfg.name + " down: " + why);
    }
    if (c.outbound) {
      p.dialing = false;
      p.next_dial = nowS() + p.backoff;
      p.backoff = std::min(cfg_.backoff_max, p.backoff * 2);
    }
  }
}

void Engine::dial(Peer& p, double now) {
  p.dialing = true;
  auto c = std::make_unique<Conn>();
  c->fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  c->outbound = true;
  c->peer = &p;
  c->opened = c->last_rx = now;
  setNonBlocking(c->fd);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(p.cfg.port));
  inet_pton(AF_INET, p.cfg.host.c_str(), &a.sin_addr);
  const int r = connect(c->fd, reinterpret_cast<sockaddr*>(&a), sizeof(a));
  c->decoder.setAuthenticator(psk_);
  if (r != 0 && errno != EINPROGRESS) {
    Conn& ref = *c;
    conns_.push_back(std::move(c));
    closeConn(ref, "connect failed");
    return;
  }
  c->connecting = (r != 0);
  sendHello(*c);
  conns_.push_back(std::move(c));
}

void Engine::acceptOne() {
  const int fd = accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
  if (fd >= 0) addInbound(fd);
}

void Engine::addInbound(int fd) {
  // Connection flood (half-open or never authenticated): memory stays bounded. The oldest connection without a
  // link gives way, so that a flood delays a real peer's reconnect instead of locking it out until it ends.
  std::size_t open = 0;
  Conn* oldest = nullptr;
  for (auto& c : conns_) {
    if (c->closed) continue;
    ++open;
    if (!c->established && !c->outbound && (!oldest || c->opened < oldest->opened)) oldest = c.get();
  }
  if (open >= 4 * peers_.size() + 8) {
    if (!oldest) {
      close(fd);
      counters_.increment("connections_refused");
      return;
    }
    counters_.increment("connections_evicted");
    closeConn(*oldest, "evicted by a newer connection (too many without a link)");
  }
  setNonBlocking(fd);
  auto c = std::make_unique<Conn>();
  c->fd = fd;
  c->opened = c->last_rx = nowS();
  c->decoder.setAuthenticator(psk_);
  sendHello(*c);
  flush(*c);
  conns_.push_back(std::move(c));
}

void Engine::establish(Conn& c, double now) {
  Peer& p = *c.peer;
  if (p.conn && p.conn != &c) closeConn(*p.conn, "replaced by a new connection");
  c.established = true;
  p.conn = &c;
  p.refused.clear();
  if (p.ever_up) ++p.reconnects;
  p.ever_up = true;
  p.backoff = cfg_.backoff_min;
  p.dialing = false;
  p.monitor.reset();
  p.next_ping = now;
  if (c.remote_session != p.rx_session) {  // the peer restarted: its sequence numbers start again
    p.rx_session = c.remote_session;
    p.rx_seq = p.acked_seq = 0;
    p.pending_acks.clear();
  }
  // A new peer process has none of our latched messages, even those it acknowledged before it restarted.
  const bool peer_restarted = p.latched_session != 0 && c.remote_session != p.latched_session;
  p.latched_session = c.remote_session;
  p.incoming.clear();
  if (c.hello_ack_session == session_) p.queue.ack(c.hello_ack_seq);
  p.queue.rewind();
  log(0, "link to " + p.cfg.name + " up");
  for (std::size_t i = 0; i < cfg_.topics.size(); ++i) {
    if (cfg_.topics[i].direction != "out" || !goesTo(cfg_.topics[i], p.cfg.name)) continue;
    sendAnnounce(c, i);
    // Latched topics: the last message again for the far side (best effort: after every reconnect;
    // reliable: after the peer restarted, as the queue no longer holds what it acknowledged).
    if (latched_[i] && (!cfg_.topics[i].reliable || peer_restarted)) {
      FrameHeader h;
      h.type = FrameType::Data;
      h.flags = latched_flags_[i] & ~kReliable;
      h.topic_id = static_cast<std::uint16_t>(i);
      sendFrame(c, h, latched_[i]->data(), latched_[i]->size());
    }
  }
  pump(p);
}

void Engine::handleFrame(Conn& c, Frame& f, double now, std::vector<Delivery>& out) {
  const FrameHeader& h = f.header;
  if (!c.hello_received) {
    if (h.type != FrameType::Hello) {
      counters_.increment("frames_malformed");
      closeConn(c, "first frame is not a hello");
      return;
    }
    Reader r(f.payload.data(), f.payload.size());
    std::uint16_t version = 0;
    std::string name;
    std::uint8_t nonce[kNonceSize];
    r.u16(version);
    r.str(name, 256);
    r.u64(c.remote_session);
    r.bytes(nonce, kNonceSize);
    r.u64(c.hello_ack_session);
    r.u64(c.hello_ack_seq);
    std::uint16_t udp_port = 0;
    r.u16(udp_port);
    std::uint8_t has_origin = 0;
    std::optional<geo::LatLonAlt> origin;
    if (r.u8(has_origin) && has_origin) {
      origin.emplace();
      r.f64(origin->lat_deg);
      r.f64(origin->lon_deg);
      r.f64(origin->alt_m);
    }
    if (!r.ok() || version != kWireVersion) {
      counters_.increment("frames_malformed");
      closeConn(c, "bad hello");
      return;
    }
    Peer* peer = nullptr;
    for (auto& p : peers_)
      if (p->cfg.name == name) peer = p.get();
    if (!peer || (c.peer && c.peer != peer)) {
      counters_.increment("peer_unknown");
      log(2, "refused a connection from '" + name + "': not a configured peer of " + cfg_.name);
      closeConn(c, "unknown peer");
      return;
    }
    const std::string site = siteMismatch(origin);
    if (!site.empty()) {
      counters_.increment("origin_mismatch");
      peer->refused = "refused " + name + ": " + site;
      if (peer->log_limit.allow(nowS())) log(2, peer->refused);
      closeConn(c, "origin mismatch");
      return;
    }
    c.peer = peer;
    c.hello_received = true;
    c.remote_nonce.assign(reinterpret_cast<const char*>(nonce), kNonceSize);
    // Per-direction session keys from both fresh nonces.
    c.tx_auth = psk_.derive("ogr1" + c.nonce + c.remote_nonce);
    c.rx_auth = psk_.derive("ogr1" + c.remote_nonce + c.nonce);
    c.decoder.setAuthenticator(c.rx_auth);
    c.decoder.setMaxPayload(cfg_.max_frame_bytes);
    socklen_t alen = sizeof(c.udp_to);
    if (udp_port && udp_fd_ >= 0 && getpeername(c.fd, reinterpret_cast<sockaddr*>(&c.udp_to), &alen) == 0 &&
        c.udp_to.sin_family == AF_INET) {
      c.udp_to.sin_port = htons(udp_port);
      c.udp = true;
    }
    // Prove liveness with the session key; the link counts as up on the first session frame received.
    Writer w;
    w.u64(0);
    w.u64(0);
    FrameHeader ph;
    ph.type = FrameType::Ping;
    sendFrame(c, ph, w.b.data(), w.b.size());
    return;
  }
  if (!c.replay.accept(h.counter)) {
    counters_.increment("frames_replayed");
    if (c.peer) ++c.peer->rejected;
    closeConn(c, "replayed frame");
    return;
  }
  if (!c.established) establish(c, now);
  Peer& p = *c.peer;
  switch (h.type) {
    case FrameType::Hello:
      counters_.increment("frames_malformed");
      closeConn(c, "second hello");
      return;
    case FrameType::Ping: {
      if (congested(c)) {  // a peer that sends but does not read gets no more replies queued
        counters_.increment("replies_dropped");
        return;
      }
      FrameHeader ph;
      ph.type = FrameType::Pong;  // the ping's id and time: a large ping does not make a large reply
      sendFrame(c, ph, f.payload.data(), std::min<std::size_t>(f.payload.size(), 16));
      return;
    }
    case FrameType::Pong: {
      Reader r(f.payload.data(), f.payload.size());
      std::uint64_t id = 0, t_ns = 0;
      if (r.u64(id) && r.u64(t_ns) && id)
        p.monitor.pongReceived(id, now - double(t_ns) * 1e-9);
      return;
    }
    case FrameType::Ack: {
      p.queue.ack(h.seq);
      pump(p);
      return;
    }
    case FrameType::Refuse: {
      Reader r(f.payload.data(), f.payload.size());
      std::string why;
      r.str(why, 4096);
      counters_.increment("refused_by_peer");
      if (p.log_limit.allow(now))
        log(2, "peer " + p.cfg.name + " refused topic " +
                 (h.topic_id < cfg_.topics.size() ? cfg_.topics[h.topic_id].topic : std::string("?")) + ": " + why);
      return;
    }
    case FrameType::Announce: {
      Reader r(f.payload.data(), f.payload.size());
      Announce a;
      std::uint8_t latched = 0, reliable = 0;
      r.str(a.topic, 1024);
      r.str(a.info.type, 1024);
      r.str(a.info.md5, 64);
      r.str(a.info.definition, kMaxDefinitionBytes);
      r.u8(latched);
      r.u8(reliable);
      if (!r.ok()) {
        counters_.increment("frames_malformed");
        ++p.rejected;
        return;
      }
      a.latched = latched;
      a.reliable = reliable;
      // What the announce says, hashed: an identical repeat (a peer replaying its own announces) changes nothing.
      std::uint64_t digest = 1469598103934665603ull;  // FNV-1a
      for (const std::string* part : {&a.topic, &a.info.type, &a.info.md5, &a.info.definition})
        for (unsigned char ch : *part + '\0') digest = (digest ^ ch) * 1099511628211ull;
      digest = (digest ^ (latched ? 2u : 0u) ^ (reliable ? 1u : 0u)) * 1099511628211ull;
      auto known = p.incoming.find(h.topic_id);
      if (known != p.incoming.end() && known->second.digest == digest) {
        counters_.increment("announces_repeated");
        return;
      }
      if (known == p.incoming.end() && p.incoming.size() >= kMaxRemoteTopics) {
        counters_.increment("announces_over_limit");
        ++p.rejected;
        if (p.log_limit.allow(now))
          log(2, "peer " + p.cfg.name + " announced more than " + std::to_string(kMaxRemoteTopics) + " topics; ignored");
        return;
      }
      long index = -1;
      for (std::size_t i = 0; i < cfg_.topics.size(); ++i) {
        const auto& t = cfg_.topics[i];
        if (t.direction == "in" && t.topic == a.topic && goesTo(t, p.cfg.name)) index = long(i);
      }
      if (index < 0) {
        counters_.increment("refused_not_configured");
        const std::string why = "topic " + a.topic + " from " + p.cfg.name + " is not configured as 'in' on " + cfg_.name;
        if (p.log_limit.allow(now)) log(2, why);
        if (congested(c)) {
          counters_.increment("replies_dropped");
        } else {
          Writer w;
          w.str(why);
          FrameHeader rh;
          rh.type = FrameType::Refuse;
          rh.topic_id = h.topic_id;
          sendFrame(c, rh, w.b.data(), w.b.size());
        }
      }
      p.incoming[h.topic_id] = {-1, digest};  // accepted only once the callback agrees
      if (index >= 0) out.push_back({Delivery::Announce_, &p, h.topic_id, index, a, {}});
      return;
    }
    case FrameType::Data:
      handleData(p, f, out);
      return;
  }
}

void Engine::handleData(Peer& p, Frame& f, std::vector<Delivery>& out) {
  const FrameHeader& h = f.header;
  auto it = p.incoming.find(h.topic_id);
  if (it == p.incoming.end()) {
    counters_.increment("unknown_topic");
    ++p.rejected;
    return;
  }
  if (h.flags & kReliable) {
    if (h.seq <= p.rx_seq) {
      counters_.increment("duplicates_dropped");
      return;
    }
    if (p.rx_seq && h.seq > p.rx_seq + 1) counters_.increment("sequence_gaps", h.seq - p.rx_seq - 1);
    p.rx_seq = h.seq;  // acked after delivery (below, in run)
  }
  // index resolved later (the announce may be decided in this same batch)
  Delivery d{Delivery::Message, &p, h.topic_id, -1, {}, {}};
  if (h.flags & kCompressed) {
    if (!decompress(f.payload.data(), f.payload.size(), cfg_.max_frame_bytes, d.data)) {
      counters_.increment("frames_malformed");
      ++p.rejected;
      return;
    }
  } else {
    d.data = std::move(f.payload);
  }
  out.push_back(std::move(d));
}

void Engine::onReadable(Conn& c, double now, std::vector<Delivery>& out) {
  static thread_local std::vector<std::uint8_t> buf(1 << 20);
  std::size_t budget = 16u << 20;  // per poll round: one busy peer cannot starve the others
  while (!c.closed && budget > 0) {
    const std::size_t room = std::min(c.decoder.room(), buf.size());
    if (room == 0) break;
    const ssize_t r = recv(c.fd, buf.data(), room, 0);
    if (r == 0) {
      closeConn(c, "closed by peer");
      return;
    }
    if (r < 0) {
      if (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) break;
      closeConn(c, std::string("recv failed: ") + std::strerror(errno));
      return;
    }
    budget -= std::min<std::size_t>(budget, std::size_t(r));
    c.last_rx = now;
    c.decoder.feed(buf.data(), std::size_t(r));
    Frame f;
    for (;;) {
      const DecodeStatus s = c.decoder.next(f);
      if (s == DecodeStatus::NeedMore) break;
      if (s != DecodeStatus::Ok) {
        counters_.increment(s == DecodeStatus::BadAuth ? "frames_bad_auth"
                            : s == DecodeStatus::Oversized ? "frames_oversized"
                                                           : "frames_malformed");
        if (c.peer) ++c.peer->rejected;
        log(2, std::string("relay ") + cfg_.name + ": dropped a connection" +
                   (c.peer ? " from " + c.peer->cfg.name : std::string()) + ": " + toString(s));
        closeConn(c, toString(s));
        return;
      }
      handleFrame(c, f, now, out);
      if (c.closed) return;
    }
  }
}

void Engine::run() {
  while (running_) step(cfg_.heartbeat_period);
}

void Engine::step(double max_wait_s) {
  std::vector<pollfd> fds;
  std::vector<Conn*> polled;
  std::vector<Delivery> deliveries;
  double timeout = cfg_.heartbeat_period;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const double now = nowS();
    // dial, heartbeat, timeouts
    for (auto& pp : peers_) {
      Peer& p = *pp;
      if (!p.cfg.host.empty() && !p.conn && !p.dialing && now >= p.next_dial) dial(p, now);
      if (p.conn && now >= p.next_ping && !congested(*p.conn)) {  // (a peer that does not read gets no more)
        Writer w;
        w.u64(++p.ping_id);
        w.u64(static_cast<std::uint64_t>(now * 1e9));
        FrameHeader h;
        h.type = FrameType::Ping;
        sendFrame(*p.conn, h, w.b.data(), w.b.size());
        p.monitor.pingSent(p.ping_id);
        p.next_ping = now + cfg_.heartbeat_period;
        flush(*p.conn);
      }
    }
    for (auto& c : conns_) {
      if (c->closed) continue;
      const double limit = c->established ? cfg_.link_timeout : 2 * cfg_.link_timeout;
      if (now - c->last_rx > limit) closeConn(*c, c->established ? "heartbeat timeout" : "handshake timeout");
    }
    conns_.erase(std::remove_if(conns_.begin(), conns_.end(), [](const auto& c) { return c->closed; }),
                 conns_.end());
    fds.push_back({wake_fd_, POLLIN, 0});
    polled.push_back(nullptr);
    if (listen_fd_ >= 0) {
      fds.push_back({listen_fd_, POLLIN, 0});
      polled.push_back(nullptr);
    }
    for (auto& c : conns_) {
      short ev = c->connecting ? POLLOUT : POLLIN;
      if (c->out_pos < c->out.size()) ev |= POLLOUT;
      fds.push_back({c->fd, ev, 0});
      polled.push_back(c.get());
    }
    // last: a datagram and the TCP announce of its topic from the same poll round are handled announce first
    if (udp_fd_ >= 0) {
      fds.push_back({udp_fd_, POLLIN, 0});
      polled.push_back(nullptr);
    }
    for (auto& p : peers_) {
      if (!p->pending_acks.empty()) timeout = std::min(timeout, std::max(0.0, cfg_.ack_delay / 2));
      if (!p->cfg.host.empty() && !p->conn && !p->dialing) timeout = std::min(timeout, std::max(0.0, p->next_dial - now));
    }
  }
  poll(fds.data(), fds.size(), max_wait_s <= 0 ? 0 : static_cast<int>(std::min(timeout, max_wait_s) * 1000) + 1);
  if (!running_) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const double now = nowS();
    std::size_t i = 0;
    if (fds[i].revents & POLLIN) {
      std::uint64_t v;
      if (read(wake_fd_, &v, sizeof(v)) < 0) {
      }
    }
    ++i;
    if (listen_fd_ >= 0) {
      if (fds[i].revents & POLLIN) acceptOne();
      ++i;
    }
    const std::size_t n_conn_fds = fds.size() - (udp_fd_ >= 0 ? 1 : 0);
    for (; i < n_conn_fds; ++i) {
      Conn& c = *polled[i];
      if (c.closed || !fds[i].revents) continue;
      if (c.connecting) {
        int err = 0;
        socklen_t len = sizeof(err);
        getsockopt(c.fd, SOL_SOCKET, SO_ERROR, &err, &len);
        if (err) {
          closeConn(c, std::strerror(err));
          continue;
        }
        c.connecting = false;
      }
      if (fds[i].revents & (POLLIN | POLLHUP | POLLERR)) onReadable(c, now, deliveries);
      if (!c.closed) flush(c);
    }
    if (udp_fd_ >= 0 && (fds.back().revents & POLLIN)) onDatagrams(deliveries);
  }
  if (deliveries.empty()) {
    sendAcks(nowS());
    return;
  }
  // Callbacks run without the lock: the ROS side may take time (advertising, waiting for subscribers).
  std::vector<std::pair<Delivery*, std::string>> decisions;
  for (auto& d : deliveries) {
    if (d.kind == Delivery::Announce_) {
      std::string why = cb_.on_announce ? cb_.on_announce(std::size_t(d.index), d.peer->cfg.name, d.announce) : "";
      decisions.emplace_back(&d, why);
      std::lock_guard<std::mutex> lock(mutex_);
      auto it = d.peer->incoming.find(d.remote_id);
      if (it != d.peer->incoming.end()) it->second.index = why.empty() ? d.index : -1;
      if (!why.empty()) {
        counters_.increment("refused_type_mismatch");
        if (d.peer->log_limit.allow(nowS())) log(2, why);
        if (d.peer->conn && congested(*d.peer->conn)) {
          counters_.increment("replies_dropped");
        } else if (d.peer->conn) {
          Writer w;
          w.str(why);
          FrameHeader rh;
          rh.type = FrameType::Refuse;
          rh.topic_id = d.remote_id;
          sendFrame(*d.peer->conn, rh, w.b.data(), w.b.size());
        }
      }
      continue;
    }
    long index = -1;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      auto it = d.peer->incoming.find(d.remote_id);
      if (it != d.peer->incoming.end()) index = it->second.index;
      if (index >= 0) {
        auto& st = d.peer->in_stats[std::size_t(index)];
        st.used = true;
        if (!d.peer->limits[std::size_t(index)].allow(nowS())) {
          ++st.dropped;
          counters_.increment("rate_limited");
          continue;
        }
        ++st.messages;
        if (d.datagram) ++st.datagrams;
        st.bytes += d.data.size();
      } else {
        counters_.increment("refused_messages_dropped");
        continue;
      }
    }
    if (cb_.on_message) cb_.on_message(std::size_t(index), d.peer->cfg.name, d.data);
  }
  sendAcks(nowS());
}

void Engine::sendAcks(double now) {
  // Acks trail delivery by ack_delay: a message is acknowledged only once it has been handed to ROS that long
  // ago, so a crash of this relay (or of its process) before ROS wrote it out means a resend, not a loss.
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto& p : peers_) {
    if (p->pending_acks.empty() || p->pending_acks.back().second != p->rx_seq)
      if (p->rx_seq != p->acked_seq) p->pending_acks.emplace_back(now, p->rx_seq);
    std::uint64_t ack = 0;
    while (!p->pending_acks.empty() && p->pending_acks.front().first <= now - cfg_.ack_delay) {
      ack = p->pending_acks.front().second;
      p->pending_acks.pop_front();
    }
    if (ack && p->conn && ack != p->acked_seq && !congested(*p->conn)) {
      FrameHeader h;
      h.type = FrameType::Ack;
      h.seq = ack;
      sendFrame(*p->conn, h, nullptr, 0);
      p->acked_seq = ack;
      flush(*p->conn);
    }
  }
}

std::vector<PeerStatus> Engine::status() {
  std::lock_guard<std::mutex> lock(mutex_);
  const double now = nowS();
  std::vector<PeerStatus> out;
  for (auto& pp : peers_) {
    Peer& p = *pp;
    PeerStatus s;
    s.name = p.cfg.name;
    s.address = p.cfg.host.empty() ? std::string("(dials in)") : p.cfg.host + ":" + std::to_string(p.cfg.port);
    s.up = p.conn && now - p.conn->last_rx < cfg_.link_timeout;
    s.rtt = p.monitor.rtt();
    s.loss = p.monitor.loss();
    s.reconnects = p.reconnects;
    s.frames_rejected = p.rejected;
    s.queued = p.queue.size();
    s.refused = p.refused;
    const double dt = p.last_status > 0 ? now - p.last_status : 0.0;
    p.last_status = now;
    for (std::size_t i = 0; i < cfg_.topics.size(); ++i) {
      const auto& t = cfg_.topics[i];
      if (!goesTo(t, p.cfg.name)) continue;
      auto& st = t.direction == "out" ? p.out_stats[i] : p.in_stats[i];
      TopicStatus ts;
      ts.topic = t.topic;
      ts.remote = t.direction == "out" ? t.remote : t.topic;
      ts.direction = t.direction;
      // what carried the messages so far: udp, tcp, or both (best-effort frames too large for a datagram)
      ts.transport = st.datagrams == 0 ? "tcp" : (st.datagrams == st.messages ? "udp" : "udp+tcp");
      ts.messages = st.messages;
      ts.bytes = st.bytes;
      ts.dropped = st.dropped;
      if (dt > 0) {
        ts.rate_hz = double(st.messages - st.last_messages) / dt;
        ts.bandwidth_bps = double(st.bytes - st.last_bytes) / dt;
      }
      st.last_messages = st.messages;
      st.last_bytes = st.bytes;
      s.topics.push_back(ts);
    }
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace relay
}  // namespace offshore_gnc

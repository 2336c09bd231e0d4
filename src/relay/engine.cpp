// The relay engine's poll loop (include/offshore_gnc/relay/engine.h): start and stop, one round of dialling,
// heartbeats, timeouts, poll, reading and delivery; local messages out; the link status. Links and the handshake
// are connections.cpp, frames in receive.cpp.
#include "offshore_gnc/relay/engine.h"

#include <sys/eventfd.h>
#include <unistd.h>

#include <algorithm>
#include <random>

#include "engine_parts.h"

namespace offshore_gnc {
namespace relay {

Engine::Engine(RelayConfig cfg, Callbacks cb, Counters& counters)
    : cfg_(std::move(cfg)), cb_(std::move(cb)), counters_(counters) {
  validate(cfg_);
  if (cfg_.authenticated()) psk_ = Authenticator(cfg_.key);
  std::mt19937_64 rng(std::random_device{}());
  session_ = rng() | 1;
  out_types_.resize(cfg_.topics.size());
  latched_.resize(cfg_.topics.size());
  latched_flags_.resize(cfg_.topics.size());
  for (const auto& pc : cfg_.peers) peers_.push_back(std::make_unique<Peer>(pc, cfg_));
}

Engine::~Engine() { stop(); }

void Engine::start(bool run_thread) {
  if (cfg_.listen_port != 0) listen_fd_ = listenTcp(cfg_.listen_host, cfg_.listen_port, listen_port_);
  if (cfg_.udp) {
    const std::string err = udp_.open(cfg_.listen_host, listen_port_, listen_fd_ >= 0);
    if (!err.empty()) log(2, "relay " + cfg_.name + ": no UDP socket (" + err + "): best-effort topics use TCP");
  }
  wake_fd_ = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  running_ = true;
  if (run_thread) thread_ = std::thread([this] { run(); });
}

void Engine::stop() {
  if (!running_.exchange(false)) return;
  std::uint64_t one = 1;
  if (write(wake_fd_, &one, sizeof(one)) < 0) {
  }
  if (thread_.joinable()) thread_.join();
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto& c : conns_) {
    flush(*c);  // last acks out before we go
    c->link.close();
  }
  conns_.clear();
  for (auto& p : peers_) p->conn = nullptr;
  if (listen_fd_ >= 0) close(listen_fd_);
  if (wake_fd_ >= 0) close(wake_fd_);
  udp_.close();
  listen_fd_ = wake_fd_ = -1;
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
    if (c->link.closed()) continue;
    ++m.connections;
    m.input_bytes += c->link.inputCapacity();
    m.output_bytes += c->link.outputCapacity();
  }
  for (const auto& p : peers_) {
    m.remote_topics += p->incoming.size();
    m.queued_bytes += p->queue.bytes();
  }
  return m;
}

void Engine::log(int level, const std::string& s) {
  if (cb_.on_log) cb_.on_log(level, s);
}

void Engine::run() {
  while (running_) step(cfg_.heartbeat_period);
}

void Engine::step(double max_wait_s) {
  PollSet set;
  std::vector<Delivery> deliveries;
  double timeout = cfg_.heartbeat_period;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const double now = nowS();
    heartbeats(now);
    timeout = std::min(timeout, pollSet(now, set));
  }
  poll(set.fds.data(), set.fds.size(), max_wait_s <= 0 ? 0 : static_cast<int>(std::min(timeout, max_wait_s) * 1000) + 1);
  if (!running_) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    dispatch(set, nowS(), deliveries);
  }
  deliver(deliveries);
  sendAcks(nowS());
}

// Dialling, heartbeats and timeouts, before the poll.
void Engine::heartbeats(double now) {
  for (auto& pp : peers_) {
    Peer& p = *pp;
    if (p.dials() && !p.conn && p.redial.due(now)) dial(p, now);
    if (p.conn && p.monitor.pingDue(now) && !p.conn->link.congested()) {  // (a peer that does not read gets no more)
      Writer w;
      w.u64(p.monitor.ping(now, cfg_.heartbeat_period));
      w.u64(static_cast<std::uint64_t>(now * 1e9));
      FrameHeader h;
      h.type = FrameType::Ping;
      p.conn->link.send(h, w.b.data(), w.b.size());
      flush(*p.conn);
    }
  }
  for (auto& c : conns_) {
    if (c->link.closed()) continue;
    const double limit = c->established ? cfg_.link_timeout : 2 * cfg_.link_timeout;
    if (now - c->link.lastReceived() > limit) closeConn(*c, c->established ? "heartbeat timeout" : "handshake timeout");
  }
  conns_.erase(std::remove_if(conns_.begin(), conns_.end(), [](const auto& c) { return c->link.closed(); }),
               conns_.end());
}

// What to poll, and how long at most: until the next ack or redial is due.
double Engine::pollSet(double now, PollSet& set) {
  set.add(wake_fd_, POLLIN);
  if (listen_fd_ >= 0) set.add(listen_fd_, POLLIN);
  for (auto& c : conns_) {
    short ev = c->link.connecting() ? POLLOUT : POLLIN;
    if (c->link.pendingOutput()) ev |= POLLOUT;
    set.add(c->link.fd(), ev, c.get());
  }
  if (udp_.isOpen()) set.add(udp_.fd(), POLLIN);
  double timeout = cfg_.heartbeat_period;
  for (auto& p : peers_) {
    if (p->received.pending()) timeout = std::min(timeout, std::max(0.0, cfg_.ack_delay / 2));
    if (p->dials() && !p->conn && !p->redial.inProgress()) timeout = std::min(timeout, p->redial.untilDue(now));
  }
  return timeout;
}

// What the poll found: a wake-up, a new connection, connections readable or writable, datagrams.
void Engine::dispatch(const PollSet& set, double now, std::vector<Delivery>& out) {
  for (std::size_t i = 0; i < set.fds.size(); ++i) {
    const pollfd& pf = set.fds[i];
    if (!pf.revents) continue;
    Conn* c = set.conns[i];
    if (!c) {
      if (pf.fd == wake_fd_) {
        std::uint64_t v;
        if (read(wake_fd_, &v, sizeof(v)) < 0) {
        }
      } else if (pf.fd == listen_fd_) {
        if (pf.revents & POLLIN) acceptOne();
      } else if (pf.fd == udp_.fd() && (pf.revents & POLLIN)) {
        onDatagrams(out);
      }
      continue;
    }
    if (c->link.closed()) continue;
    if (c->link.connecting()) {
      const std::string err = c->link.finishConnect();
      if (!err.empty()) {
        closeConn(*c, err);
        continue;
      }
    }
    if (pf.revents & (POLLIN | POLLHUP | POLLERR)) onReadable(*c, now, out);
    if (!c->link.closed()) flush(*c);
  }
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
    if (!p.limits[index].allow(now)) {
      p.out_traffic[index].dropped();
      counters_.increment("rate_limited");
      continue;
    }
    if (p.conn && type_changed) sendAnnounce(*p.conn, index);
    if (t.reliable) {
      std::vector<QueuedMessage> dropped;
      p.queue.push(static_cast<std::uint16_t>(index), flags, wire, &dropped);
      for (const auto& d : dropped) {
        p.out_traffic[d.topic_id].dropped();
        counters_.increment("queue_overflow");
      }
      pump(p);
    } else {
      sendBestEffort(p, index, flags, wire);
    }
    if (p.conn) {
      flush(*p.conn);
      if (p.conn && p.conn->link.pendingOutput()) {  // the I/O thread must poll for POLLOUT
        std::uint64_t one = 1;
        if (write(wake_fd_, &one, sizeof(one)) < 0) counters_.increment("wake_failed");
      }
    }
  }
}

// A best-effort message: a datagram when the link has UDP and it fits, else a TCP frame unless the link is down
// or congested (then it is dropped and counted).
void Engine::sendBestEffort(Peer& p, std::size_t index, std::uint8_t flags, const Bytes& wire) {
  FrameHeader h;
  h.type = FrameType::Data;
  h.flags = flags;
  h.topic_id = static_cast<std::uint16_t>(index);
  TopicTraffic& traffic = p.out_traffic[index];
  Conn* c = p.conn;
  // (the first message of a topic on a link goes by TCP, in order behind its announce: a datagram could overtake
  // the announce and be dropped as an unknown topic, and the first message is never lost)
  if (c && c->established && c->udp.enabled && c->tcp_first_sent.count(index) &&
      wire->size() + kHeaderSize + kTagSize <= std::size_t(cfg_.max_datagram_bytes)) {
    if (c->udp.send(udp_, h, wire->data(), wire->size(), c->link.sendKey())) {
      traffic.carried(wire->size(), true);
    } else {
      traffic.dropped();  // socket buffer full: best effort
      counters_.increment("best_effort_dropped");
    }
  } else if (c && !c->link.congested()) {
    c->link.send(h, wire->data(), wire->size());
    if (c->established) c->tcp_first_sent.insert(index);
    traffic.carried(wire->size());
  } else {
    traffic.dropped();
    counters_.increment("best_effort_dropped");
  }
}

// Reliable messages not yet sent on the current link, while its output is not congested.
void Engine::pump(Peer& p) {
  if (!p.conn) return;
  TcpLink& link = p.conn->link;
  while (!link.congested()) {
    const QueuedMessage* m = p.queue.nextToSend();
    if (!m) break;
    FrameHeader h;
    h.type = FrameType::Data;
    h.flags = m->flags;
    h.topic_id = m->topic_id;
    h.seq = m->seq;
    link.send(h, m->payload->data(), m->payload->size());
    p.out_traffic[m->topic_id].carried(m->payload->size());
  }
}

void Engine::sendAcks(double now) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto& p : peers_) {
    const std::uint64_t ack = p->received.due(now, cfg_.ack_delay);
    if (ack && p->conn && !p->conn->link.congested()) {
      FrameHeader h;
      h.type = FrameType::Ack;
      h.seq = ack;
      p->conn->link.send(h, nullptr, 0);
      p->received.sent(ack);
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
    s.address = p.dials() ? p.cfg.host + ":" + std::to_string(p.cfg.port) : std::string("(dials in)");
    s.up = p.conn && now - p.conn->link.lastReceived() < cfg_.link_timeout;
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
      TopicStatus ts;
      ts.topic = t.topic;
      ts.remote = t.direction == "out" ? t.remote : t.topic;
      ts.direction = t.direction;
      (t.direction == "out" ? p.out_traffic[i] : p.in_traffic[i]).report(dt, ts);
      s.topics.push_back(ts);
    }
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace relay
}  // namespace offshore_gnc

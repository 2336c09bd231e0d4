// The relay engine's links (include/offshore_gnc/relay/engine.h): dialling and accepting TCP connections, the
// handshake that turns one into a peer's link, and closing them (the peer redials after its backoff).
#include <sys/socket.h>
#include <unistd.h>

#include "engine_parts.h"

namespace offshore_gnc {
namespace relay {

void Engine::dial(Peer& p, double now) {
  p.redial.dialing();
  bool in_progress = false;
  const int fd = TcpLink::dial(p.cfg.host, p.cfg.port, in_progress);
  if (fd < 0) {
    p.redial.failed(nowS());
    return;
  }
  auto c = std::make_unique<Conn>(fd, in_progress, now, psk_);
  c->outbound = true;
  c->peer = &p;
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
    if (c->link.closed()) continue;
    ++open;
    if (!c->established && !c->outbound && (!oldest || c->link.opened() < oldest->link.opened())) oldest = c.get();
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
  auto c = std::make_unique<Conn>(fd, false, nowS(), psk_);
  sendHello(*c);
  flush(*c);
  conns_.push_back(std::move(c));
}

void Engine::closeConn(Conn& c, const std::string& why) {
  if (c.link.closed()) return;
  c.link.close();
  if (!c.peer) return;
  Peer& p = *c.peer;
  if (p.conn == &c) {
    p.conn = nullptr;
    log(1, "link to " + p.cfg.name + " down: " + why);
  }
  if (c.outbound) p.redial.failed(nowS());
}

void Engine::flush(Conn& c) {
  const std::string err = c.link.flush();
  if (!err.empty()) closeConn(c, err);
}

void Engine::sendHello(Conn& c) {
  Hello h;
  h.name = cfg_.name;
  h.session = session_;
  h.nonce = c.nonce;
  // What we hold from this peer (only known for outbound connections, where the peer is known in advance).
  if (c.peer) h.ack_session = c.peer->received.session(), h.ack_seq = c.peer->received.lastSeq();
  h.udp_port = static_cast<std::uint16_t>(udp_.isOpen() ? udp_.port() : 0);
  h.origin = cfg_.origin;
  c.link.setSendKey(psk_);  // the hello is authenticated with the PSK itself
  const auto payload = encodeHello(h);
  FrameHeader fh;
  fh.type = FrameType::Hello;
  c.link.send(fh, payload.data(), payload.size());
}

// The first frame of a connection: the peer's hello, under the pre-shared key. A configured peer on our site gets
// the session keys and a ping (the link counts as up on the first session frame received).
void Engine::onHello(Conn& c, const Frame& f) {
  if (f.header.type != FrameType::Hello) {
    counters_.increment("frames_malformed");
    closeConn(c, "first frame is not a hello");
    return;
  }
  Hello hello;
  if (!decodeHello(f.payload, hello)) {
    counters_.increment("frames_malformed");
    closeConn(c, "bad hello");
    return;
  }
  Peer* peer = nullptr;
  for (auto& p : peers_)
    if (p->cfg.name == hello.name) peer = p.get();
  if (!peer || (c.peer && c.peer != peer)) {
    counters_.increment("peer_unknown");
    log(2, "refused a connection from '" + hello.name + "': not a configured peer of " + cfg_.name);
    closeConn(c, "unknown peer");
    return;
  }
  const std::string site = siteMismatch(cfg_.origin, hello.origin, cfg_.origin_tolerance, cfg_.name);
  if (!site.empty()) {
    counters_.increment("origin_mismatch");
    peer->refused = "refused " + hello.name + ": " + site;
    if (peer->log_limit.allow(nowS())) log(2, peer->refused);
    closeConn(c, "origin mismatch");
    return;
  }
  c.peer = peer;
  c.hello_received = true;
  c.remote = hello;
  const SessionKeys keys = sessionKeys(psk_, c.nonce, hello.nonce);
  c.link.setKeys(keys.tx, keys.rx, std::size_t(cfg_.max_frame_bytes));
  if (udp_.isOpen()) c.udp.connect(c.link.fd(), hello.udp_port);
  Writer w;
  w.u64(0);
  w.u64(0);
  FrameHeader ph;
  ph.type = FrameType::Ping;
  c.link.send(ph, w.b.data(), w.b.size());
}

// The first session frame from the peer: the connection becomes its link (replacing an older one), what it
// acknowledged in its hello leaves the queue, the rest is sent again behind our announces.
void Engine::establish(Conn& c, double now) {
  Peer& p = *c.peer;
  if (p.conn && p.conn != &c) closeConn(*p.conn, "replaced by a new connection");
  c.established = true;
  p.conn = &c;
  p.refused.clear();
  if (p.ever_up) ++p.reconnects;
  p.ever_up = true;
  p.redial.succeeded();
  p.monitor.restart(now);
  p.received.startSession(c.remote.session);  // the peer restarted: its sequence numbers start again
  // A new peer process has none of our latched messages, even those it acknowledged before it restarted.
  const bool peer_restarted = p.latched_session != 0 && c.remote.session != p.latched_session;
  p.latched_session = c.remote.session;
  p.incoming.clear();
  if (c.remote.ack_session == session_) p.queue.ack(c.remote.ack_seq);
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
      c.link.send(h, latched_[i]->data(), latched_[i]->size());
    }
  }
  pump(p);
}

void Engine::sendAnnounce(Conn& c, std::size_t index) {
  const TypeInfo& info = out_types_[index];
  if (info.md5.empty()) return;  // type not known until the first local message
  const auto payload = encodeAnnounce(cfg_.topics[index], info);
  FrameHeader h;
  h.type = FrameType::Announce;
  h.topic_id = static_cast<std::uint16_t>(index);
  c.link.send(h, payload.data(), payload.size());
}

}  // namespace relay
}  // namespace offshore_gnc

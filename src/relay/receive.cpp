// The relay engine's receiving side (include/offshore_gnc/relay/engine.h): frames from a link's TCP stream and
// from datagrams, checked and turned into deliveries, which the callbacks then get without the engine's lock.
#include <algorithm>

#include "engine_parts.h"

namespace offshore_gnc {
namespace relay {

void Engine::onReadable(Conn& c, double now, std::vector<Delivery>& out) {
  DecodeStatus bad = DecodeStatus::Ok;
  const std::string why = c.link.receive(
      now,
      [&](Frame& f) {
        handleFrame(c, f, now, out);
        return !c.link.closed();
      },
      bad);
  if (why.empty() || c.link.closed()) return;
  if (bad != DecodeStatus::Ok) {
    counters_.increment(bad == DecodeStatus::BadAuth     ? "frames_bad_auth"
                        : bad == DecodeStatus::Oversized ? "frames_oversized"
                                                         : "frames_malformed");
    if (c.peer) ++c.peer->rejected;
    log(2, "relay " + cfg_.name + ": dropped a connection" + (c.peer ? " from " + c.peer->cfg.name : std::string()) +
               ": " + why);
  }
  closeConn(c, why);
}

void Engine::handleFrame(Conn& c, Frame& f, double now, std::vector<Delivery>& out) {
  const FrameHeader& h = f.header;
  if (!c.hello_received) return onHello(c, f);
  if (!c.link.fresh(h.counter)) {
    counters_.increment("frames_replayed");
    ++c.peer->rejected;
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
      if (c.link.congested()) {  // a peer that sends but does not read gets no more replies queued
        counters_.increment("replies_dropped");
        return;
      }
      FrameHeader ph;
      ph.type = FrameType::Pong;  // the ping's id and time: a large ping does not make a large reply
      c.link.send(ph, f.payload.data(), std::min<std::size_t>(f.payload.size(), 16));
      return;
    }
    case FrameType::Pong: {
      Reader r(f.payload.data(), f.payload.size());
      std::uint64_t id = 0, t_ns = 0;
      if (r.u64(id) && r.u64(t_ns) && id) p.monitor.pongReceived(id, now - double(t_ns) * 1e-9);
      return;
    }
    case FrameType::Ack:
      p.queue.ack(h.seq);
      pump(p);
      return;
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
    case FrameType::Announce:
      onAnnounce(c, f, now, out);
      return;
    case FrameType::Data:
      handleData(p, f, out);
      return;
  }
}

// A peer's topic: accepted (for the callback to decide) when it matches a configured in-topic, refused back
// otherwise; repeats change nothing, a peer's topics are bounded.
void Engine::onAnnounce(Conn& c, const Frame& f, double now, std::vector<Delivery>& out) {
  Peer& p = *c.peer;
  const std::uint16_t id = f.header.topic_id;
  Announce a;
  if (!decodeAnnounce(f.payload, a)) {
    counters_.increment("frames_malformed");
    ++p.rejected;
    return;
  }
  const std::uint64_t digest = announceDigest(a);
  switch (p.incoming.check(id, digest)) {
    case RemoteTopics::Verdict::Repeat:
      counters_.increment("announces_repeated");
      return;
    case RemoteTopics::Verdict::OverLimit:
      counters_.increment("announces_over_limit");
      ++p.rejected;
      if (p.log_limit.allow(now))
        log(2, "peer " + p.cfg.name + " announced more than " + std::to_string(kMaxRemoteTopics) + " topics; ignored");
      return;
    case RemoteTopics::Verdict::New:
      break;
  }
  const long index = inTopicFor(cfg_.topics, a.topic, p.cfg.name);
  if (index < 0) {
    counters_.increment("refused_not_configured");
    const std::string why = "topic " + a.topic + " from " + p.cfg.name + " is not configured as 'in' on " + cfg_.name;
    if (p.log_limit.allow(now)) log(2, why);
    refuse(c, id, why);
  }
  p.incoming.remember(id, digest);  // accepted only once the callback agrees
  if (index >= 0) out.push_back({Delivery::Announce_, &p, id, index, a, {}});
}

void Engine::refuse(Conn& c, std::uint16_t topic_id, const std::string& why) {
  if (c.link.congested()) {
    counters_.increment("replies_dropped");
    return;
  }
  Writer w;
  w.str(why);
  FrameHeader h;
  h.type = FrameType::Refuse;
  h.topic_id = topic_id;
  c.link.send(h, w.b.data(), w.b.size());
}

void Engine::handleData(Peer& p, Frame& f, std::vector<Delivery>& out) {
  const FrameHeader& h = f.header;
  if (!p.incoming.known(h.topic_id)) {
    counters_.increment("unknown_topic");
    ++p.rejected;
    return;
  }
  if (h.flags & kReliable) {
    std::uint64_t skipped = 0;
    if (!p.received.accept(h.seq, skipped)) {  // acked after delivery (sendAcks)
      counters_.increment("duplicates_dropped");
      return;
    }
    if (skipped) counters_.increment("sequence_gaps", skipped);
  }
  // index resolved later (the announce may be decided in this same batch)
  Delivery d{Delivery::Message, &p, h.topic_id, -1, {}, {}};
  if (h.flags & kCompressed) {
    if (!decompress(f.payload.data(), f.payload.size(), std::size_t(cfg_.max_frame_bytes), d.data)) {
      counters_.increment("frames_malformed");
      ++p.rejected;
      return;
    }
  } else {
    d.data = std::move(f.payload);
  }
  out.push_back(std::move(d));
}

void Engine::onDatagrams(std::vector<Delivery>& out) {
  static thread_local std::vector<std::uint8_t> buf(65536);
  for (int budget = 0; budget < 1024; ++budget) {
    sockaddr_in from{};
    std::size_t n = 0;
    if (!udp_.receive(buf, n, from)) break;
    // Only from the UDP address of an established link, authenticated with that link's session key.
    Conn* c = nullptr;
    for (auto& cc : conns_)
      if (!cc->link.closed() && cc->established && cc->udp.from(from)) c = cc.get();
    if (!c) {
      counters_.increment("udp_unknown_source");
      continue;
    }
    FrameDecoder d(std::size_t(cfg_.max_datagram_bytes));
    d.setAuthenticator(c->link.receiveKey());
    d.feed(buf.data(), n);
    Frame f;
    const DecodeStatus s = d.next(f);
    if (s != DecodeStatus::Ok || d.buffered() != 0 || f.header.type != FrameType::Data ||
        (f.header.flags & kReliable)) {
      counters_.increment(s == DecodeStatus::BadAuth ? "frames_bad_auth" : "udp_malformed");
      ++c->peer->rejected;
      continue;
    }
    std::uint64_t lost = 0;
    if (!c->udp.accept(f.header.counter, lost)) {
      counters_.increment("frames_replayed");
      ++c->peer->rejected;
      continue;
    }
    if (lost) counters_.increment("udp_lost", lost);
    counters_.increment("udp_datagrams");
    const std::size_t before = out.size();
    handleData(*c->peer, f, out);
    if (out.size() > before) out.back().datagram = true;
  }
}

// Callbacks run without the lock: the ROS side may take time (advertising, waiting for subscribers).
void Engine::deliver(std::vector<Delivery>& deliveries) {
  for (auto& d : deliveries) {
    if (d.kind == Delivery::Announce_) {
      const std::string why =
          cb_.on_announce ? cb_.on_announce(std::size_t(d.index), d.peer->cfg.name, d.announce) : "";
      std::lock_guard<std::mutex> lock(mutex_);
      d.peer->incoming.decide(d.remote_id, why.empty() ? d.index : -1);
      if (!why.empty()) {
        counters_.increment("refused_type_mismatch");
        if (d.peer->log_limit.allow(nowS())) log(2, why);
        if (d.peer->conn) refuse(*d.peer->conn, d.remote_id, why);
      }
      continue;
    }
    long index = -1;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      index = d.peer->incoming.indexOf(d.remote_id);
      if (index < 0) {
        counters_.increment("refused_messages_dropped");
        continue;
      }
      TopicTraffic& traffic = d.peer->in_traffic[std::size_t(index)];
      if (!d.peer->limits[std::size_t(index)].allow(nowS())) {
        traffic.dropped();
        counters_.increment("rate_limited");
        continue;
      }
      traffic.carried(d.data.size(), d.datagram);
    }
    if (cb_.on_message) cb_.on_message(std::size_t(index), d.peer->cfg.name, d.data);
  }
}

}  // namespace relay
}  // namespace offshore_gnc

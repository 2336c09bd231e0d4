// The relay under hostile input (relay/fuzz_check.h): a scripted peer with its own protocol code, and the two
// fuzz entry points. The peer's encoding follows docs/relay.md, not the engine's code paths.
#include "relay/fuzz_check.h"

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <set>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/relay/engine.h"

namespace offshore_gnc {
namespace relay {

namespace {
constexpr std::size_t kNonce = 16;
const char* const kWrongKey = "a-key-the-engine-does-not-have-0123456789";

std::string bytesOf(const std::vector<std::uint8_t>& v) { return std::string(v.begin(), v.end()); }
}  // namespace

// ------------------------------------------------------------------------------------------ ScriptedPeer
ScriptedPeer::ScriptedPeer(int fd, std::string psk, std::function<void()> pump)
    : fd_(fd), psk_(std::move(psk)), pump_(std::move(pump)), in_(2u << 20) {
  // A fixed nonce per object is enough: the engine's is fresh, so session keys differ per connection.
  static std::uint64_t n = 0;
  ++n;
  nonce_.assign(kNonce, '\0');
  for (std::size_t i = 0; i < kNonce; ++i) nonce_[i] = static_cast<char>((n >> (8 * (i % 8))) ^ (i * 37));
  in_.setAuthenticator(Authenticator(psk_));
}

ScriptedPeer::~ScriptedPeer() {
  if (fd_ >= 0) close(fd_);
}

std::vector<std::uint8_t> ScriptedPeer::helloPayload(std::uint16_t version, const std::string& name,
                                                     std::uint64_t session, const std::string& nonce,
                                                     std::uint64_t ack_session, std::uint64_t ack_seq,
                                                     std::uint16_t udp_port) {
  Writer w;
  w.u16(version);
  w.str(name);
  w.u64(session);
  std::string n = nonce;
  n.resize(kNonce, '\0');
  w.bytes(reinterpret_cast<const std::uint8_t*>(n.data()), kNonce);
  w.u64(ack_session);
  w.u64(ack_seq);
  w.u16(udp_port);
  w.u8(0);  // no site origin: not checked
  return w.b;
}

std::vector<std::uint8_t> ScriptedPeer::announcePayload(const std::string& topic, const std::string& type,
                                                        const std::string& md5, const std::string& definition,
                                                        bool latched, bool reliable) {
  Writer w;
  w.str(topic);
  w.str(type);
  w.str(md5);
  w.str(definition);
  w.u8(latched);
  w.u8(reliable);
  return w.b;
}

std::vector<std::uint8_t> ScriptedPeer::encode(FrameHeader h, const std::vector<std::uint8_t>& payload,
                                               const Authenticator& auth) {
  std::vector<std::uint8_t> out;
  encodeFrame(h, payload.data(), payload.size(), auth, out);
  return out;
}

std::vector<std::uint8_t> ScriptedPeer::encodeWith(FrameHeader h, const std::vector<std::uint8_t>& payload,
                                                   Key key) const {
  switch (key) {
    case Key::Session: return encode(h, payload, session_ ? tx_ : Authenticator(psk_));
    case Key::Psk: return encode(h, payload, Authenticator(psk_));
    case Key::Wrong: return encode(h, payload, Authenticator(kWrongKey));
    case Key::None: return encode(h, payload, Authenticator());
  }
  return {};
}

std::vector<std::uint8_t> ScriptedPeer::hello(const std::vector<std::uint8_t>& payload, Key key) {
  FrameHeader h;
  h.type = FrameType::Hello;
  h.counter = 1;
  const auto bytes = encodeWith(h, payload, key == Key::Session ? Key::Psk : key);
  if ((key == Key::Psk || key == Key::Session) && !session_) {
    receive();  // what the engine sent before this hello is still under the old keys
    if (haveEngineHello()) {
      // Per-direction session keys as docs/relay.md specifies: HMAC(PSK, "ogr1" || sender nonce || receiver nonce).
      const Authenticator psk(psk_);
      tx_ = psk.derive("ogr1" + nonce_ + engine_nonce_);
      rx_ = psk.derive("ogr1" + engine_nonce_ + nonce_);
      in_.setAuthenticator(rx_);
      session_ = true;
    } else {
      verify_ = false;
    }
  }
  raw(bytes);
  return bytes;
}

std::vector<std::uint8_t> ScriptedPeer::frame(FrameHeader h, const std::vector<std::uint8_t>& payload, Key key,
                                              bool literal_counter) {
  if (h.counter == 0 && !literal_counter) h.counter = ++counter_;
  counter_ = std::max(counter_, h.counter);
  const auto bytes = encodeWith(h, payload, key);
  raw(bytes);
  return bytes;
}

bool ScriptedPeer::raw(const std::uint8_t* p, std::size_t n) {
  std::size_t off = 0;
  while (off < n && !eof_) {
    const ssize_t r = send(fd_, p + off, n - off, MSG_DONTWAIT | MSG_NOSIGNAL);
    if (r > 0) {
      off += static_cast<std::size_t>(r);
      continue;
    }
    if (r < 0 && (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR)) {
      if (pump_) {
        pump_();
        receive();  // the engine may be waiting to write to us
      } else {
        pollfd pf{fd_, POLLOUT, 0};
        ::poll(&pf, 1, 100);
        receive();
      }
      continue;
    }
    eof_ = true;  // EPIPE / ECONNRESET: the engine closed the connection
  }
  return !eof_;
}

std::string ScriptedPeer::receive(double wait_s) {
  std::uint8_t buf[65536];
  bool waited = false;
  while (!eof_) {
    if (wait_s > 0 && !waited) {
      pollfd pf{fd_, POLLIN, 0};
      ::poll(&pf, 1, static_cast<int>(wait_s * 1000));
      waited = true;
    }
    const ssize_t r = recv(fd_, buf, sizeof buf, MSG_DONTWAIT);
    if (r == 0 || (r < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR)) {
      eof_ = true;
      break;
    }
    if (r < 0) break;
    bytes_in_ += static_cast<std::size_t>(r);
    if (!verify_) continue;
    in_.feed(buf, static_cast<std::size_t>(r));
    Frame f;
    for (;;) {
      if (haveEngineHello() && !session_) {
        // Frames after the engine's hello but before ours answer a hello someone else sent first (a replayed
        // one): they are keyed with that sender's nonce, which we cannot check.
        if (in_.buffered()) verify_ = false;
        break;
      }
      const DecodeStatus s = in_.next(f);
      if (s == DecodeStatus::NeedMore) break;
      if (s != DecodeStatus::Ok) return std::string("the engine sent a frame that does not decode: ") + toString(s);
      ++counts_[static_cast<std::size_t>(f.header.type)];
      if (engine_nonce_.empty()) {
        Reader rd(f.payload.data(), f.payload.size());
        std::uint16_t version = 0;
        std::string name;
        std::uint64_t session = 0;
        std::uint8_t nonce[kNonce];
        if (f.header.type != FrameType::Hello || !rd.u16(version) || !rd.str(name, 256) || !rd.u64(session) ||
            !rd.bytes(nonce, kNonce) || version != kWireVersion)
          return "the engine's first frame is not a hello";
        engine_nonce_.assign(reinterpret_cast<const char*>(nonce), kNonce);
      } else if (f.header.type == FrameType::Hello) {
        return "the engine sent a second hello";
      }
    }
  }
  return "";
}

void abortOnViolation(const char* what, const std::string& violation) {
  if (violation.empty()) return;
  std::fprintf(stderr, "relay %s invariant violated: %s\n", what, violation.c_str());
  std::abort();
}

// ------------------------------------------------------------------------------------------ wire fuzzing
std::string fuzzWireOnce(const std::uint8_t* data, std::size_t n) {
  const Authenticator auth("fuzz-key-0123456789abcdef");
  for (const bool with_auth : {false, true}) {
    FrameDecoder whole(4096), bytewise(4096);
    if (with_auth) {
      whole.setAuthenticator(auth);
      bytewise.setAuthenticator(auth);
    }
    whole.feed(data, n);
    std::vector<std::pair<DecodeStatus, Frame>> a, b;
    for (;;) {
      Frame f;
      const DecodeStatus s = whole.next(f);
      if (s == DecodeStatus::NeedMore) break;
      a.emplace_back(s, f);
      if (s != DecodeStatus::Ok) break;
    }
    bool stopped = false;
    for (std::size_t i = 0; i < n && !stopped; ++i) {
      bytewise.feed(data + i, 1);
      for (;;) {
        Frame f;
        const DecodeStatus s = bytewise.next(f);
        if (s == DecodeStatus::NeedMore) break;
        b.emplace_back(s, f);
        if (s != DecodeStatus::Ok) {
          stopped = true;
          break;
        }
      }
    }
    if (a.size() != b.size()) return "chunking changed the number of frames";
    std::size_t at = 0;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (a[i].first != b[i].first) return "chunking changed a decode status";
      if (a[i].first != DecodeStatus::Ok) break;
      const Frame& f = a[i].second;
      if (f.payload != b[i].second.payload || f.header.counter != b[i].second.header.counter)
        return "chunking changed a frame";
      if (f.payload.size() > 4096) return "a frame above the payload limit was accepted";
      // Re-encoded, a frame is the bytes it came from (the reserved header word aside: ignored on receipt).
      std::vector<std::uint8_t> again;
      encodeFrame(f.header, f.payload.data(), f.payload.size(), with_auth ? auth : Authenticator(), again);
      if (at + again.size() > n) return "a frame longer than the input";
      for (std::size_t k = 0; k < again.size(); ++k)
        if ((k < 28 || k >= 32) && again[k] != data[at + k] && !(with_auth && k >= kHeaderSize + f.payload.size()))
          return "decode/encode round trip differs";
      at += again.size();
      // The control payload readers on whatever arrived, within their limits.
      Reader r(f.payload.data(), f.payload.size());
      std::string s1, s2;
      std::uint64_t u = 0;
      if (r.str(s1, 1024) && s1.size() > 1024) return "a string above its limit was read";
      r.u64(u);
      if (r.str(s2, 16) && s2.size() > 16) return "a string above its limit was read";
      std::vector<std::uint8_t> out;
      if (decompress(f.payload.data(), f.payload.size(), 1 << 16, out)) {
        if (out.size() > (1u << 16)) return "decompression above its limit";
        const auto back = compress(out.data(), out.size());
        std::vector<std::uint8_t> again2;
        if (!decompress(back.data(), back.size(), 1 << 16, again2) || again2 != out) return "zlib round trip differs";
      }
    }
  }
  return "";
}

// ------------------------------------------------------------------------------------------ session fuzzing
namespace {

// The fuzz input as a stream of small numbers (zeros after the end).
class Script {
 public:
  Script(const std::uint8_t* p, std::size_t n) : p_(p), n_(n) {}
  bool done() const { return i_ >= n_; }
  std::uint8_t u8() { return i_ < n_ ? p_[i_++] : 0; }
  std::uint64_t le(int bytes) {  // little-endian, read in order
    std::uint64_t v = 0;
    for (int k = 0; k < bytes; ++k) v |= std::uint64_t(u8()) << (8 * k);
    return v;
  }
  std::uint16_t u16() { return static_cast<std::uint16_t>(le(2)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(le(4)); }
  std::uint64_t u64() { return le(8); }
  std::vector<std::uint8_t> bytes(std::size_t k) {
    k = std::min(k, n_ - std::min(n_, i_));
    std::vector<std::uint8_t> v(p_ + i_, p_ + i_ + k);
    i_ += k;
    return v;
  }
  std::string text(std::size_t k) { return bytesOf(bytes(k)); }

 private:
  const std::uint8_t* p_;
  std::size_t n_, i_ = 0;
};

const char* const kSessionKey = "session-fuzz-key-0123456789abcdefghij";

RelayConfig sessionConfig() {
  RelayConfig c;
  c.name = "usv";
  c.key = kSessionKey;
  c.sim = true;
  c.udp = false;
  c.heartbeat_period = 10.0;  // heartbeats and timeouts stay out of the (millisecond) script
  c.link_timeout = 60.0;
  c.ack_delay = 0.0;
  c.queue_messages = 8;  // small: the overflow path is reachable
  c.queue_bytes = 4096;
  c.max_frame_bytes = 1u << 20;
  c.peers = {{"auv", "", 0}, {"ground", "", 0}};
  c.topics = {{"/target", "offshore_gnc/Target", "in", "", {}, true, 0.0, true, false},
              {"/fix", "offshore_gnc/UsblFix", "in", "", {"auv"}, false, 0.0, false, false},
              {"/usv_gps", "sensor_msgs/NavSatFix", "out", "", {}, false, 0.0, false, false},
              {"/usv_status", "std_msgs/String", "out", "", {"auv"}, true, 0.0, true, true}};
  return c;
}

struct Connection {
  std::unique_ptr<ScriptedPeer> peer;
  bool sent_any = false, ok = false;  // ok: a valid hello went first and nothing broke the stream since
  std::set<std::uint64_t> used;         // counters used after the hello
};

}  // namespace

std::string fuzzSessionOnce(const std::uint8_t* data, std::size_t n) {
  Script in(data, n);
  static const bool trace = std::getenv("RELAY_FUZZ_TRACE") != nullptr;  // one line per step on stderr
  const RelayConfig cfg = sessionConfig();
  std::string violation;
  auto violate = [&violation](const std::string& what) {
    if (violation.empty()) violation = what;
  };
  // What the engine may hand out during the current step: content -> times (one authentic frame per step).
  std::map<std::vector<std::uint8_t>, int> allowed;
  bool step_authentic = false;
  Callbacks cb;
  cb.on_announce = [&](std::size_t i, const std::string& peer, const Announce& a) -> std::string {
    if (!step_authentic) violate("an announce reached the callback from a frame the peer was not entitled to send");
    if (i >= cfg.topics.size() || cfg.topics[i].direction != "in" || cfg.topics[i].topic != a.topic)
      violate("an announce was matched to the wrong topic");
    if (!cfg.topics[i].peers.empty() && peer != cfg.topics[i].peers[0]) violate("an announce from a peer not listed");
    return a.info.type == cfg.topics[i].type ? "" : "type mismatch";
  };
  cb.on_message = [&](std::size_t i, const std::string&, const std::vector<std::uint8_t>& d) {
    if (i >= cfg.topics.size() || cfg.topics[i].direction != "in") violate("a message for a topic that is not 'in'");
    auto it = allowed.find(d);
    if (it == allowed.end() || it->second <= 0)
      violate("a message was delivered that the peer did not send authentically in this step (replay, wrong key, "
              "duplicate or forgery)");
    else
      --it->second;
  };
  Counters counters;
  Engine engine(cfg, cb, counters);
  engine.start(false);
  auto pump = [&engine] { engine.pollOnce(0); };

  std::vector<Connection> conns;
  std::size_t cur = 0;
  std::vector<std::vector<std::uint8_t>> sent;  // every frame sent, for replays
  auto connect = [&]() {
    int sv[2];
    if (socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0) return;
    engine.adopt(sv[0]);
    Connection c;
    c.peer = std::make_unique<ScriptedPeer>(sv[1], kSessionKey, pump);
    conns.push_back(std::move(c));
    cur = conns.size() - 1;
    engine.pollOnce(0);
    const std::string p = conns[cur].peer->receive();
    if (!p.empty()) violate(p);
  };
  connect();
  std::uint64_t tag = 0;  // makes each authentic message distinct
  for (int ops = 0; !in.done() && ops < 48 && violation.empty() && !conns.empty(); ++ops) {
    Connection& c = conns[cur];
    ScriptedPeer& peer = *c.peer;
    allowed.clear();
    step_authentic = false;
    const std::uint8_t op = in.u8();
    // How a frame of this step is keyed and counted, and whether the engine must then accept it.
    auto keyed = [&](FrameHeader& h, ScriptedPeer::Key& key) {
      const std::uint8_t k = in.u8();
      key = static_cast<ScriptedPeer::Key>(k & 3);
      switch ((k >> 2) & 3) {
        case 1: h.counter = peer.lastCounter(); break;  // reuse the last one
        case 2: h.counter = peer.lastCounter() - std::min<std::uint64_t>(peer.lastCounter(), in.u8()); break;
        case 3: h.counter = peer.lastCounter() + 1 + in.u32(); break;
        default: h.counter = peer.lastCounter() + 1; break;
      }
      c.sent_any = true;
      const bool fresh = h.counter != 0 && !c.used.count(h.counter);
      const bool authentic = c.ok && key == ScriptedPeer::Key::Session && fresh;
      if (c.ok && h.counter != 0) c.used.insert(h.counter);
      if (!authentic) c.ok = false;  // the engine closes the connection (or at least delivers nothing more)
      return authentic;
    };
    switch (op % 12) {
      case 0: {  // raw garbage
        const auto b = in.bytes(in.u8());
        if (!b.empty()) c.ok = false;
        peer.raw(b);
        c.sent_any |= !b.empty();
        break;
      }
      case 1: {  // hello: valid or broken in one of several ways
        // bytes: f [name_len name] [version u16] session ack_flag [ack_session u64] ack_seq udp_port(u16) [cut]
        const std::uint8_t f = in.u8();
        const std::string name = (f & 4) ? in.text(in.u8() % 24) : ((f & 8) ? "ground" : "auv");
        const std::uint16_t version = (f & 2) ? in.u16() : kWireVersion;
        const std::uint64_t session = 1 + (in.u8() & 3);
        const std::uint64_t ack_session = (in.u8() & 1) ? 0 : in.u64();
        const std::uint64_t ack_seq = in.u8();
        const std::uint16_t udp_port = in.u16();
        auto payload = ScriptedPeer::helloPayload(version, name, session, peer.nonce(), ack_session, ack_seq, udp_port);
        if (f & 16) payload.resize(payload.size() - std::min<std::size_t>(payload.size(), 1 + in.u8() % 40));
        const auto key = (f & 1) ? ScriptedPeer::Key::Wrong : ScriptedPeer::Key::Psk;
        const bool valid = !c.sent_any && key == ScriptedPeer::Key::Psk && version == kWireVersion &&
                           (name == "auv" || name == "ground") && !(f & 16);
        c.ok = valid;
        c.sent_any = true;
        sent.push_back(peer.hello(payload, key));
        break;
      }
      case 2: {  // announce
        FrameHeader h;
        h.type = FrameType::Announce;
        h.topic_id = in.u8() % 8;
        ScriptedPeer::Key key;
        step_authentic = keyed(h, key);
        const std::uint8_t f = in.u8();
        static const char* topics[] = {"/target", "/fix", "/usv_gps"};
        static const char* types[] = {"offshore_gnc/Target", "offshore_gnc/UsblFix", "std_msgs/String"};
        const std::string topic = (f & 3) == 3 ? in.text(in.u8() % 32) : topics[f & 3];
        const std::string type = ((f >> 2) & 3) == 3 ? in.text(in.u8() % 32) : types[(f >> 2) & 3];
        const std::string md5 = (f & 16) ? in.text(in.u8() % 40) : "0123456789abcdef0123456789abcdef";
        std::string def = in.text(in.u8());
        if (f & 32) def.resize(300u << 10, 'x');  // above the definition limit: malformed, not kept
        sent.push_back(peer.frame(h, ScriptedPeer::announcePayload(topic, type, md5, def, f & 64, f & 128), key, true));
        break;
      }
      case 3: {  // data: plain, compressed, garbage-compressed, reliable or not
        FrameHeader h;
        h.type = FrameType::Data;
        h.topic_id = in.u8() % 8;
        const std::uint8_t f = in.u8();
        h.flags = f & 7;
        h.seq = (f & 8) ? in.u64() : (f & 16 ? 0 : 1 + (in.u8() & 15));
        ScriptedPeer::Key key;
        const bool authentic = keyed(h, key);
        std::vector<std::uint8_t> msg(8);
        ++tag;
        for (int i = 0; i < 8; ++i) msg[i] = static_cast<std::uint8_t>(tag >> (8 * i));
        const auto body = in.bytes(in.u8());
        msg.insert(msg.end(), body.begin(), body.end());
        std::vector<std::uint8_t> payload = msg;
        if ((h.flags & kCompressed) && !(f & 32)) {
          payload = compress(msg.data(), msg.size());
        } else if (h.flags & kCompressed) {
          payload = body;  // garbage under the compressed flag: what it decompresses to, if anything, is allowed
          msg.clear();
          if (!decompress(payload.data(), payload.size(), cfg.max_frame_bytes, msg)) msg.clear();
        }
        if (authentic) {
          ++allowed[msg];
          step_authentic = true;
        }
        sent.push_back(peer.frame(h, payload, key, true));
        break;
      }
      case 4: {  // control frames, and frame types that do not exist
        FrameHeader h;
        const std::uint8_t t = in.u8();
        static const FrameType kinds[] = {FrameType::Ping, FrameType::Pong, FrameType::Ack, FrameType::Refuse,
                                          FrameType::Hello};
        h.type = (t & 8) ? static_cast<FrameType>(t >> 4) : kinds[t % 5];
        h.seq = in.u64();
        ScriptedPeer::Key key;
        const bool valid_type = static_cast<std::uint8_t>(h.type) >= 1 && static_cast<std::uint8_t>(h.type) <= 7;
        const bool authentic = keyed(h, key);
        const auto payload = in.bytes(in.u8() % 64);
        if (!valid_type || h.type == FrameType::Hello) c.ok = false;
        if (authentic && h.type == FrameType::Announce) step_authentic = true;  // may even parse
        if (authentic && h.type == FrameType::Data) {
          ++allowed[payload];
          step_authentic = true;
        }
        sent.push_back(peer.frame(h, payload, key, true));
        break;
      }
      case 5: {  // replay a frame sent earlier, on this connection or another
        if (!sent.empty()) {
          const auto& b = sent[in.u16() % sent.size()];
          peer.raw(b);
          c.ok = false;
          c.sent_any = true;
        }
        break;
      }
      case 6: {  // a frame cut short: the stream is desynchronised from here on
        FrameHeader h;
        h.type = FrameType::Data;
        h.counter = peer.lastCounter() + 1;
        const auto b = peer.encodeWith(h, in.bytes(in.u8()), ScriptedPeer::Key::Session);
        const std::size_t cut = in.u8() % b.size();
        peer.raw(b.data(), cut);
        if (cut) c.ok = false;
        c.sent_any |= cut > 0;
        break;
      }
      case 7: {  // a huge (or just wrong) length field, then a little of what it promises
        std::vector<std::uint8_t> b(kHeaderSize, 0);
        const std::uint32_t magic = kMagic, low = in.u32();
        const std::uint32_t len = low | ((in.u8() & 1) ? 0x80000000u : 0u);
        for (int i = 0; i < 4; ++i) b[i] = static_cast<std::uint8_t>(magic >> (8 * i));
        b[4] = static_cast<std::uint8_t>(FrameType::Data);
        for (int i = 0; i < 4; ++i) b[24 + i] = static_cast<std::uint8_t>(len >> (8 * i));
        const auto tail = in.bytes(in.u8());
        b.insert(b.end(), tail.begin(), tail.end());
        peer.raw(b);
        c.ok = false;
        c.sent_any = true;
        break;
      }
      case 8: {  // a new connection; the old one stays open or is closed
        if (conns.size() < 6) {
          if (in.u8() & 1) conns[cur].peer.reset(new ScriptedPeer(-1, kSessionKey));
          connect();
        }
        break;
      }
      case 9: {  // carry on with another open connection
        cur = in.u8() % conns.size();
        break;
      }
      case 10: {  // the local side publishes (to every peer that is up), with the right type or not
        const std::size_t i = in.u8() % cfg.topics.size();
        const std::uint8_t f = in.u8();
        const TypeInfo ti{(f & 1) ? std::string("std_msgs/Bool") : cfg.topics[i].type,
                          (f & 2) ? "ffffffffffffffffffffffffffffffff" : "0123456789abcdef0123456789abcdef", "x"};
        engine.publish(i, ti, std::make_shared<const std::vector<std::uint8_t>>(in.bytes(in.u8())));
        break;
      }
      default: {  // wait for the engine (nothing sent)
        break;
      }
    }
    if (trace)
      std::fprintf(stderr, "op %d (%d) on connection %zu: ok %d authentic %d\n", ops, op % 12, cur, conns[cur].ok,
                   step_authentic);
    for (int k = 0; k < 2; ++k) engine.pollOnce(0);
    for (auto& cc : conns) {
      if (cc.peer->fd() < 0) continue;
      const std::string p = cc.peer->receive();
      if (!p.empty()) violate(p);
    }
    const MemoryUse m = engine.memoryUse();
    if (m.connections > 4 * cfg.peers.size() + 8) violate("more connections than the limit");
    if (m.output_bytes > 2 * ((8u << 20) + cfg.max_frame_bytes)) violate("output buffers above their limit");
    if (m.queued_bytes > cfg.queue_bytes + cfg.max_frame_bytes) violate("reliable queue above its limit");
  }
  engine.stop();
  return violation;
}

}  // namespace relay
}  // namespace offshore_gnc

// Tritech SeaNet packet codec (see include/offshore_gnc/micron/seanet.h for the layout).
#include "offshore_gnc/micron/seanet.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "offshore_gnc/common/angles.h"

namespace offshore_gnc {
namespace micron {

namespace {

// Little-endian body writer / reader over whole packets (offsets are the protocol's byte numbers).
struct Writer {
  std::string s;
  void u8(std::uint8_t v) { s.push_back(static_cast<char>(v)); }
  void u16(std::uint16_t v) { u8(v & 0xFF); u8(v >> 8); }
  void u32(std::uint32_t v) { u16(v & 0xFFFF); u16(v >> 16); }
  void bytes(const std::uint8_t* b, std::size_t n) { s.append(reinterpret_cast<const char*>(b), n); }
};
struct Reader {
  const std::uint8_t* p;
  std::uint8_t u8(std::size_t at) const { return p[at]; }
  std::uint16_t u16(std::size_t at) const { return static_cast<std::uint16_t>(p[at] | (p[at + 1] << 8)); }
  std::uint32_t u32(std::size_t at) const { return u16(at) | (static_cast<std::uint32_t>(u16(at + 2)) << 16); }
};

constexpr std::size_t kHeadCommandBody = 52, kV3bBlock = 16, kHeadDataFixed = 31;

void writeBody(const Body& b, Writer& w) {
  if (auto a = std::get_if<Alive>(&b)) {
    w.u8(a->spare); w.u32(a->head_time_ms); w.u16(a->motor_position); w.u8(a->head_inf);
  } else if (auto v = std::get_if<VersionData>(&b)) {
    w.u8(v->software_version); w.u8(v->info_bits); w.u16(v->uid); w.u32(v->program_length); w.u16(v->checksum);
    w.u8(v->extra);
  } else if (auto c = std::get_if<HeadCommand>(&b)) {
    w.u8(c->v3b); w.u16(c->hd_ctrl); w.u8(c->head_type);
    w.bytes(c->txn_ch1, 4); w.bytes(c->txn_ch2, 4); w.bytes(c->rxn_ch1, 4); w.bytes(c->rxn_ch2, 4);
    w.u16(c->tx_pulse_len); w.u16(c->range_scale); w.u16(c->left_limit); w.u16(c->right_limit);
    w.u8(c->ad_span); w.u8(c->ad_low); w.u8(c->igain_ch1); w.u8(c->igain_ch2);
    w.u16(c->slope_ch1); w.u16(c->slope_ch2); w.u8(c->mo_time); w.u8(c->step_angle);
    w.u16(c->ad_interval); w.u16(c->nbins); w.u16(c->max_ad_buf); w.u16(c->lockout); w.u16(c->minor_axis);
    w.u8(c->major_axis); w.u8(c->ctl2); w.u16(c->scan_z);
    if (c->v3b == 0x1D) {
      std::vector<std::uint8_t> blk = c->v3b_block;
      blk.resize(kV3bBlock, 0);
      w.bytes(blk.data(), blk.size());
    }
  } else if (auto sd = std::get_if<SendData>(&b)) {
    w.u32(sd->time_ms);
  } else if (auto h = std::get_if<HeadData>(&b)) {
    w.u16(static_cast<std::uint16_t>(kHeadDataFixed + h->data.size()));
    w.u8(h->device_type); w.u8(h->head_status); w.u8(h->sweep_code); w.u16(h->hd_ctrl); w.u16(h->range_scale);
    w.bytes(h->txn, 4); w.u8(h->gain); w.u16(h->slope); w.u8(h->ad_span); w.u8(h->ad_low);
    w.u16(h->heading_offset); w.u16(h->ad_interval); w.u16(h->left_limit); w.u16(h->right_limit);
    w.u8(h->step_angle); w.u16(h->bearing); w.u16(static_cast<std::uint16_t>(h->data.size()));
    w.bytes(h->data.data(), h->data.size());
  } else if (auto o = std::get_if<Other>(&b)) {
    w.bytes(o->body.data(), o->body.size());
  }
}

int hexDigit(std::uint8_t c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

}  // namespace

const char* typeName(std::uint8_t t) {
  switch (t) {
    case mtVersionData: return "mtVersionData";
    case mtHeadData: return "mtHeadData";
    case mtAlive: return "mtAlive";
    case mtBBUserData: return "mtBBUserData";
    case mtReBoot: return "mtReBoot";
    case mtHeadCommand: return "mtHeadCommand";
    case mtSendVersion: return "mtSendVersion";
    case mtSendBBUser: return "mtSendBBUser";
    case mtSendData: return "mtSendData";
    case mtFpgaVersionData: return "mtFpgaVersionData";
    default: return "unknown";
  }
}

std::uint8_t Message::type() const {
  struct V {
    std::uint8_t operator()(const Alive&) const { return mtAlive; }
    std::uint8_t operator()(const VersionData&) const { return mtVersionData; }
    std::uint8_t operator()(const HeadCommand&) const { return mtHeadCommand; }
    std::uint8_t operator()(const SendData&) const { return mtSendData; }
    std::uint8_t operator()(const HeadData&) const { return mtHeadData; }
    std::uint8_t operator()(const Command& c) const { return c.type; }
    std::uint8_t operator()(const Other& o) const { return o.type; }
  };
  return std::visit(V{}, body);
}

const ParamTable<FourBitFormat>& FourBitFormat::table() {
  using P = FourBitFormat;
  static const ParamTable<P> t = ParamTable<P>()
      .choice("four_bit_order", &P::order, {"high_first", "low_first"},
              "4-bit data (adc8on off): which nibble of a byte is the nearer bin")
      .integer("four_bit_scale", &P::scale, 16, 17, "4-bit data: each level times this (17: level 15 is 255)");
  return t;
}

std::vector<std::uint8_t> HeadData::bins(const FourBitFormat& f) const {
  if (hd_ctrl & kAdc8On) return data;
  const bool high_first = f.order != "low_first";
  std::vector<std::uint8_t> out;
  out.reserve(2 * data.size());
  for (std::uint8_t b : data) {
    const int hi = b >> 4, lo = b & 0x0F;
    out.push_back(static_cast<std::uint8_t>((high_first ? hi : lo) * f.scale));
    out.push_back(static_cast<std::uint8_t>((high_first ? lo : hi) * f.scale));
  }
  return out;
}

Message fromPc(Body b) {
  Message m;
  m.tx = kPcNode;
  m.rx = kSonarNode;
  m.node = kSonarNode;
  m.body = std::move(b);
  return m;
}

Message fromSonar(Body b) {
  Message m;
  m.tx = kSonarNode;
  m.rx = kPcNode;
  m.node = kSonarNode;
  m.body = std::move(b);
  return m;
}

std::string encode(const Message& m) {
  Writer body;
  writeBody(m.body, body);
  const std::size_t total = kHeaderBytes + body.s.size() + 1;
  const std::size_t len = total - 6;
  char hex[5];
  std::snprintf(hex, sizeof hex, "%04X", static_cast<unsigned>(len & 0xFFFF));
  Writer w;
  w.u8('@');
  w.s.append(hex, 4);
  w.u16(static_cast<std::uint16_t>(len));
  w.u8(m.tx);
  w.u8(m.rx);
  const std::uint8_t type = m.type();
  // The byte count covers type .. last body byte; mtHeadData sends 0 (no multi-packet mode).
  w.u8(type == mtHeadData ? 0 : static_cast<std::uint8_t>(std::min<std::size_t>(255, total - 11)));
  w.u8(type);
  w.u8(m.sequence);
  w.u8(m.node);
  w.s += body.s;
  w.u8(0x0A);
  return w.s;
}

std::optional<Message> decodePacket(const std::uint8_t* p, std::size_t n, std::string& reason) {
  if (n < kHeaderBytes + 1 || p[0] != '@' || p[n - 1] != 0x0A) {
    reason = "bad_framing";
    return std::nullopt;
  }
  const Reader r{p};
  Message m;
  m.tx = p[7];
  m.rx = p[8];
  const std::uint8_t type = p[10];
  m.sequence = p[11];
  m.node = p[12];
  const std::size_t body = n - kHeaderBytes - 1;  // bytes 13 .. n-2
  auto need = [&](bool ok, const char* why) {
    if (!ok) reason = why;
    return ok;
  };
  switch (type) {
    case mtAlive: {
      if (!need(body == 8, "bad_alive_length")) return std::nullopt;
      m.body = Alive{r.u8(13), r.u32(14), r.u16(18), r.u8(20)};
      return m;
    }
    case mtVersionData: {
      if (!need(body == 11, "bad_version_length")) return std::nullopt;
      m.body = VersionData{r.u8(13), r.u8(14), r.u16(15), r.u32(17), r.u16(21), r.u8(23)};
      return m;
    }
    case mtSendData: {
      if (!need(body == 4, "bad_send_data_length")) return std::nullopt;
      m.body = SendData{r.u32(13)};
      return m;
    }
    case mtReBoot:
    case mtSendVersion:
    case mtSendBBUser: {
      if (!need(body == 0, "bad_command_length")) return std::nullopt;
      m.body = Command{type};
      return m;
    }
    case mtHeadCommand: {
      if (body != kHeadCommandBody && body != kHeadCommandBody + kV3bBlock) break;  // e.g. the 1-byte reverse
      HeadCommand c;
      c.v3b = r.u8(13);
      if (!need((c.v3b == 0x1D) == (body == kHeadCommandBody + kV3bBlock), "bad_head_command_v3b")) return std::nullopt;
      c.hd_ctrl = r.u16(14);
      c.head_type = r.u8(16);
      for (int i = 0; i < 4; ++i) {
        c.txn_ch1[i] = p[17 + i];
        c.txn_ch2[i] = p[21 + i];
        c.rxn_ch1[i] = p[25 + i];
        c.rxn_ch2[i] = p[29 + i];
      }
      c.tx_pulse_len = r.u16(33);
      c.range_scale = r.u16(35);
      c.left_limit = r.u16(37);
      c.right_limit = r.u16(39);
      c.ad_span = r.u8(41);
      c.ad_low = r.u8(42);
      c.igain_ch1 = r.u8(43);
      c.igain_ch2 = r.u8(44);
      c.slope_ch1 = r.u16(45);
      c.slope_ch2 = r.u16(47);
      c.mo_time = r.u8(49);
      c.step_angle = r.u8(50);
      c.ad_interval = r.u16(51);
      c.nbins = r.u16(53);
      c.max_ad_buf = r.u16(55);
      c.lockout = r.u16(57);
      c.minor_axis = r.u16(59);
      c.major_axis = r.u8(61);
      c.ctl2 = r.u8(62);
      c.scan_z = r.u16(63);
      if (c.v3b == 0x1D) c.v3b_block.assign(p + 65, p + 65 + kV3bBlock);
      m.body = std::move(c);
      return m;
    }
    case mtHeadData: {
      if (!need(body >= kHeadDataFixed, "head_data_too_short")) return std::nullopt;
      HeadData h;
      h.byte_count = r.u16(13);
      const std::size_t dbytes = r.u16(42);
      if (!need(dbytes == body - kHeadDataFixed, "head_data_dbytes_mismatch")) return std::nullopt;
      if (!need(h.byte_count == body, "head_data_count_mismatch")) return std::nullopt;
      h.device_type = r.u8(15);
      h.head_status = r.u8(16);
      h.sweep_code = r.u8(17);
      h.hd_ctrl = r.u16(18);
      h.range_scale = r.u16(20);
      for (int i = 0; i < 4; ++i) h.txn[i] = p[22 + i];
      h.gain = r.u8(26);
      h.slope = r.u16(27);
      h.ad_span = r.u8(29);
      h.ad_low = r.u8(30);
      h.heading_offset = r.u16(31);
      h.ad_interval = r.u16(33);
      h.left_limit = r.u16(35);
      h.right_limit = r.u16(37);
      h.step_angle = r.u8(39);
      h.bearing = r.u16(40);
      if (!need(h.bearing < kAngleUnitsPerTurn, "head_data_bad_bearing")) return std::nullopt;
      h.data.assign(p + 44, p + 44 + dbytes);
      m.body = std::move(h);
      return m;
    }
    default:
      break;
  }
  m.body = Other{type, std::vector<std::uint8_t>(p + kHeaderBytes, p + n - 1)};
  return m;
}

void StreamDecoder::reject(const std::string& reason, std::size_t bytes, std::vector<Event>& out) {
  counters_.increment(reason);
  Event e;
  e.reason = reason;
  e.raw.assign(buf_.begin(), buf_.begin() + static_cast<long>(std::min(bytes, buf_.size())));
  out.push_back(std::move(e));
  // Drop only the '@': a real packet may start inside the rejected candidate.
  buf_.erase(buf_.begin());
}

void StreamDecoder::feed(const std::uint8_t* data, std::size_t n, std::vector<Event>& out) {
  buf_.insert(buf_.end(), data, data + n);
  for (;;) {
    // Resynchronise on '@'.
    std::size_t skip = 0;
    while (skip < buf_.size() && buf_[skip] != '@') ++skip;
    if (skip) {
      counters_.increment("garbage_bytes", skip);
      buf_.erase(buf_.begin(), buf_.begin() + static_cast<long>(skip));
    }
    if (buf_.size() < 7) return;
    int hex = 0;
    bool hex_ok = true;
    for (int i = 1; i <= 4; ++i) {
      const int d = hexDigit(buf_[i]);
      if (d < 0) hex_ok = false;
      hex = hex * 16 + std::max(d, 0);
    }
    if (!hex_ok) {
      reject("bad_hex_length", 7, out);
      continue;
    }
    const std::size_t len = buf_[5] | (buf_[6] << 8);
    if (len != static_cast<std::size_t>(hex)) {
      reject("length_mismatch", 7, out);
      continue;
    }
    const std::size_t total = len + 6;
    if (total < kHeaderBytes + 1) {
      reject("too_short", 7, out);
      continue;
    }
    if (total > kMaxPacket) {
      reject("too_long", 7, out);
      continue;
    }
    if (buf_.size() < total) return;
    if (buf_[total - 1] != 0x0A) {
      reject("bad_terminator", total, out);
      continue;
    }
    std::string reason;
    auto m = decodePacket(buf_.data(), total, reason);
    if (!m) {
      reject(reason, total, out);
      continue;
    }
    counters_.increment("packets");
    if (!(m->sequence & 0x80)) counters_.increment("multipacket");
    Event e;
    e.message = std::move(m);
    e.raw.assign(buf_.begin(), buf_.begin() + static_cast<long>(total));
    out.push_back(std::move(e));
    buf_.erase(buf_.begin(), buf_.begin() + static_cast<long>(total));
  }
}

double unitsToRad(int units) { return units * (2.0 * kPi / kAngleUnitsPerTurn); }

int radToUnits(double rad) {
  const long u = std::lround(rad * kAngleUnitsPerTurn / (2.0 * kPi));
  return static_cast<int>(((u % kAngleUnitsPerTurn) + kAngleUnitsPerTurn) % kAngleUnitsPerTurn);
}

}  // namespace micron
}  // namespace offshore_gnc

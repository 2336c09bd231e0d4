#include "offshore_gnc/usbl/seatrac.h"

#include <type_traits>

#include "offshore_gnc/common/angles.h"

namespace offshore_gnc {
namespace usbl {

namespace {

const char kHex[] = "0123456789ABCDEF";

int hexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;
}

// Little-endian field reader that refuses to run past the end (each read says whether it fitted).
struct Reader {
  const std::uint8_t* d;
  std::size_t n;
  std::size_t& pos;
  template <typename T>
  bool get(T& v) {
    if (pos > n || n - pos < sizeof(T)) return false;
    std::uint64_t u = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) u |= static_cast<std::uint64_t>(d[pos + i]) << (8 * i);
    v = static_cast<T>(u);
    pos += sizeof(T);
    return true;
  }
};

template <typename T>
void put(std::vector<std::uint8_t>& out, T v) {
  auto u = static_cast<std::uint64_t>(static_cast<std::make_unsigned_t<T>>(v));
  for (std::size_t i = 0; i < sizeof(T); ++i) out.push_back(static_cast<std::uint8_t>(u >> (8 * i)));
}

bool fail(std::string* reason, const char* r) {
  if (reason) *reason = r;
  return false;
}

}  // namespace

const char* cidName(std::uint8_t cid) {
  switch (cid) {
    case CID_SYS_INFO: return "SYS_INFO";
    case CID_STATUS: return "STATUS";
    case CID_SETTINGS_GET: return "SETTINGS_GET";
    case CID_XCVR_USBL: return "XCVR_USBL";
    case CID_XCVR_FIX: return "XCVR_FIX";
    case CID_PING_SEND: return "PING_SEND";
    case CID_PING_REQ: return "PING_REQ";
    case CID_PING_RESP: return "PING_RESP";
    case CID_PING_ERROR: return "PING_ERROR";
    case CID_DAT_SEND: return "DAT_SEND";
    case CID_DAT_RECEIVE: return "DAT_RECEIVE";
    case CID_DAT_ERROR: return "DAT_ERROR";
    default: return "";
  }
}

std::uint16_t crc16(const std::uint8_t* data, std::size_t n) {
  std::uint16_t crc = 0;
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= data[i];
    for (int b = 0; b < 8; ++b) crc = (crc & 1) ? static_cast<std::uint16_t>((crc >> 1) ^ 0xA001) : crc >> 1;
  }
  return crc;
}

double AcoFix::azimuthRad() const { return deg2rad(azimuth * 0.1); }
double AcoFix::elevationRad() const { return deg2rad(elevation * 0.1); }

bool AcoFix::operator==(const AcoFix& o) const {
  // Compare only the fields the flags make present: absent ones are not on the wire.
  bool same = dest_id == o.dest_id && src_id == o.src_id && flags == o.flags && msg_type == o.msg_type &&
              yaw == o.yaw && pitch == o.pitch && roll == o.roll && depth_local == o.depth_local && vos == o.vos &&
              rssi == o.rssi;
  if (has(RANGE)) same = same && range_count == o.range_count && range_time == o.range_time && range_dist == o.range_dist;
  if (has(USBL))
    same = same && usbl_rssi == o.usbl_rssi && azimuth == o.azimuth && elevation == o.elevation && fit_error == o.fit_error;
  if (has(POSITION)) same = same && east == o.east && north == o.north && depth == o.depth;
  return same;
}

void appendFix(std::vector<std::uint8_t>& out, const AcoFix& f) {
  put(out, f.dest_id);
  put(out, f.src_id);
  put(out, f.flags);
  put(out, f.msg_type);
  put(out, f.yaw);
  put(out, f.pitch);
  put(out, f.roll);
  put(out, f.depth_local);
  put(out, f.vos);
  put(out, f.rssi);
  if (f.has(AcoFix::RANGE)) {
    put(out, f.range_count);
    put(out, f.range_time);
    put(out, f.range_dist);
  }
  if (f.has(AcoFix::USBL)) {
    put(out, static_cast<std::uint8_t>(f.usbl_rssi.size()));
    for (auto r : f.usbl_rssi) put(out, r);
    put(out, f.azimuth);
    put(out, f.elevation);
    put(out, f.fit_error);
  }
  if (f.has(AcoFix::POSITION)) {
    put(out, f.east);
    put(out, f.north);
    put(out, f.depth);
  }
}

bool parseFix(const std::uint8_t* data, std::size_t n, std::size_t& pos, AcoFix& f, std::string* reason) {
  Reader r{data, n, pos};
  if (!(r.get(f.dest_id) && r.get(f.src_id) && r.get(f.flags) && r.get(f.msg_type) && r.get(f.yaw) &&
        r.get(f.pitch) && r.get(f.roll) && r.get(f.depth_local) && r.get(f.vos) && r.get(f.rssi)))
    return fail(reason, "truncated");
  if (f.has(AcoFix::RANGE) && !(r.get(f.range_count) && r.get(f.range_time) && r.get(f.range_dist)))
    return fail(reason, "truncated");
  if (f.has(AcoFix::USBL)) {
    std::uint8_t channels = 0;
    if (!r.get(channels)) return fail(reason, "truncated");
    if (channels > kMaxUsblChannels) return fail(reason, "too_many_channels");
    f.usbl_rssi.assign(channels, 0);
    for (auto& v : f.usbl_rssi)
      if (!r.get(v)) return fail(reason, "truncated");
    if (!(r.get(f.azimuth) && r.get(f.elevation) && r.get(f.fit_error))) return fail(reason, "truncated");
  }
  if (f.has(AcoFix::POSITION) && !(r.get(f.east) && r.get(f.north) && r.get(f.depth))) return fail(reason, "truncated");
  return true;
}

std::optional<Message> decodePayload(bool command, const std::uint8_t* d, std::size_t n, std::string* reason) {
  if (n < 1) {
    fail(reason, "truncated");
    return std::nullopt;
  }
  const std::uint8_t cid = d[0];
  if (cidName(cid)[0] == '\0') {
    fail(reason, "unknown_cid");
    return std::nullopt;
  }
  std::size_t pos = 1;
  Reader r{d, n, pos};
  Message m;
  m.command = command;
  bool ok = true;
  auto status = [&]() {
    StatusReply s;
    s.cid = cid;
    ok = r.get(s.status) && r.get(s.beacon_id);
    m.body = s;
  };
  if (command && cid == CID_PING_SEND) {
    PingSend p;
    ok = r.get(p.dest_id) && r.get(p.msg_type);
    m.body = p;
  } else if (command && cid == CID_DAT_SEND) {
    DatSend s;
    std::uint8_t len = 0;
    ok = r.get(s.dest_id) && r.get(s.msg_type) && r.get(len) && len <= kMaxDataPacket && n - pos >= len;
    if (ok) {
      s.data.assign(d + pos, d + pos + len);
      pos += len;
    } else if (len > kMaxDataPacket) {
      fail(reason, "bad_length");
      return std::nullopt;
    }
    m.body = s;
  } else if (!command && (cid == CID_PING_SEND || cid == CID_DAT_SEND || cid == CID_PING_ERROR || cid == CID_DAT_ERROR)) {
    status();
  } else if (!command && (cid == CID_PING_RESP || cid == CID_XCVR_FIX)) {
    FixMessage fm;
    fm.cid = cid;
    if (!parseFix(d, n, pos, fm.fix, reason)) return std::nullopt;
    m.body = fm;
  } else if (!command && cid == CID_DAT_RECEIVE) {
    DatReceive dr;
    if (!parseFix(d, n, pos, dr.fix, reason)) return std::nullopt;
    std::uint8_t ack = 0, len = 0;
    ok = r.get(ack) && r.get(len) && len <= kMaxDataPacket && n - pos >= len;
    if (ok && ack > 1) {
      fail(reason, "bad_value");
      return std::nullopt;
    }
    if (ok) {
      dr.ack = ack != 0;
      dr.data.assign(d + pos, d + pos + len);
      pos += len;
    }
    m.body = dr;
  } else {
    m.body = Opaque{cid, std::vector<std::uint8_t>(d + 1, d + n)};
    pos = n;
  }
  if (!ok) {
    fail(reason, "truncated");
    return std::nullopt;
  }
  // Every field is positional: a message that does not consume its bytes exactly is misread, not padded.
  if (pos != n) {
    fail(reason, "trailing_bytes");
    return std::nullopt;
  }
  return m;
}

std::vector<std::uint8_t> encodePayload(const Message& m) {
  std::vector<std::uint8_t> out;
  std::visit(
      [&out](const auto& b) {
        using T = std::decay_t<decltype(b)>;
        if constexpr (std::is_same_v<T, PingSend>) {
          out = {CID_PING_SEND, b.dest_id, b.msg_type};
        } else if constexpr (std::is_same_v<T, StatusReply>) {
          out = {b.cid, b.status, b.beacon_id};
        } else if constexpr (std::is_same_v<T, FixMessage>) {
          out = {b.cid};
          appendFix(out, b.fix);
        } else if constexpr (std::is_same_v<T, DatSend>) {
          out = {CID_DAT_SEND, b.dest_id, b.msg_type, static_cast<std::uint8_t>(b.data.size())};
          out.insert(out.end(), b.data.begin(), b.data.end());
        } else if constexpr (std::is_same_v<T, DatReceive>) {
          out = {CID_DAT_RECEIVE};
          appendFix(out, b.fix);
          out.push_back(b.ack ? 1 : 0);
          out.push_back(static_cast<std::uint8_t>(b.data.size()));
          out.insert(out.end(), b.data.begin(), b.data.end());
        } else {
          out = {b.cid};
          out.insert(out.end(), b.payload.begin(), b.payload.end());
        }
      },
      m.body);
  return out;
}

std::string encodeFrameRaw(bool command, const std::vector<std::uint8_t>& payload) {
  std::string s(1, command ? '#' : '$');
  auto hex = [&s](std::uint8_t b) {
    s += kHex[b >> 4];
    s += kHex[b & 15];
  };
  for (auto b : payload) hex(b);
  const std::uint16_t crc = crc16(payload.data(), payload.size());
  hex(static_cast<std::uint8_t>(crc & 0xFF));
  hex(static_cast<std::uint8_t>(crc >> 8));
  s += "\r\n";
  return s;
}

std::string encodeFrame(const Message& m) { return encodeFrameRaw(m.command, encodePayload(m)); }

void StreamDecoder::feed(const std::uint8_t* data, std::size_t n, std::vector<Event>& out) {
  for (std::size_t i = 0; i < n; ++i) {
    const char c = static_cast<char>(data[i]);
    if (c == '#' || c == '$') {
      // A sync character always starts a new frame: an unterminated one before it is lost.
      if (in_frame_) {
        counters_.increment("unterminated");
        out.push_back({std::nullopt, "unterminated", line_});
      }
      line_.assign(1, c);
      in_frame_ = true;
      overflow_ = false;
    } else if (!in_frame_) {
      if (c != '\r' && c != '\n') counters_.increment("garbage_bytes");
    } else if (c == '\r' || c == '\n') {
      finishLine(out);
    } else if (line_.size() >= max_line_) {
      overflow_ = true;  // keep consuming until the end of the line, then report once
    } else {
      line_ += c;
    }
  }
}

void StreamDecoder::finishLine(std::vector<Event>& out) {
  in_frame_ = false;
  auto reject = [&](const char* r) {
    counters_.increment(r);
    out.push_back({std::nullopt, r, line_});
  };
  if (overflow_) return reject("line_too_long");
  const std::size_t hex_len = line_.size() - 1;
  if (hex_len % 2 != 0) return reject("odd_hex_length");
  std::vector<std::uint8_t> bin;
  bin.reserve(hex_len / 2);
  for (std::size_t i = 1; i + 1 < line_.size(); i += 2) {
    const int hi = hexValue(line_[i]), lo = hexValue(line_[i + 1]);
    if (hi < 0 || lo < 0) return reject("non_hex");
    bin.push_back(static_cast<std::uint8_t>(hi << 4 | lo));
  }
  if (bin.size() < 3) return reject("truncated");
  const std::size_t n = bin.size() - 2;
  const std::uint16_t crc = static_cast<std::uint16_t>(bin[n] | bin[n + 1] << 8);
  if (crc != crc16(bin.data(), n)) return reject("bad_crc");
  std::string reason;
  auto m = decodePayload(line_[0] == '#', bin.data(), n, &reason);
  if (!m) return reject(reason.c_str());
  counters_.increment("frames_ok");
  out.push_back({std::move(m), "", line_});
}

}  // namespace usbl
}  // namespace offshore_gnc

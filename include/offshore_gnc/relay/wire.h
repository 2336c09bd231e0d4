#pragma once
// Relay wire format (docs/relay.md): length-prefixed frames with a fixed 32-byte little-endian header and an
// optional HMAC-SHA256 tag. ROS-free; the same frames could go over an acoustic modem later (the transport
// only has to carry opaque frames).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace offshore_gnc {
namespace relay {

// The hello's protocol version; peers of another version are refused. 2: the hello carries the UDP port;
// 3: and the site's origin (a flag, then latitude, longitude, altitude as f64).
constexpr std::uint16_t kWireVersion = 3;

constexpr std::uint32_t kMagic = 0x3152474F;  // "OGR1"
constexpr std::size_t kHeaderSize = 32;
constexpr std::size_t kTagSize = 32;  // HMAC-SHA256

enum class FrameType : std::uint8_t { Hello = 1, Announce = 2, Data = 3, Ack = 4, Ping = 5, Pong = 6, Refuse = 7 };
enum FrameFlags : std::uint8_t { kCompressed = 1, kReliable = 2, kLatched = 4 };

struct FrameHeader {
  FrameType type = FrameType::Ping;
  std::uint8_t flags = 0;
  std::uint16_t topic_id = 0;
  std::uint64_t seq = 0;      // reliable data sequence number (0 = not reliable)
  std::uint64_t counter = 0;  // per-connection frame counter, strictly increasing (replay protection)
};

struct Frame {
  FrameHeader header;
  std::vector<std::uint8_t> payload;
};

// HMAC-SHA256 with a pre-shared key (OpenSSL). An empty key means "no authentication".
class Authenticator {
 public:
  Authenticator() = default;
  explicit Authenticator(std::string key) : key_(std::move(key)) {}
  bool enabled() const { return !key_.empty(); }
  void tag(const std::uint8_t* data, std::size_t n, std::uint8_t out[kTagSize]) const;
  bool verify(const std::uint8_t* data, std::size_t n, const std::uint8_t* tag) const;
  // Per-connection key derived from the PSK and both sides' fresh nonces: replayed frames of an
  // earlier connection fail authentication.
  Authenticator derive(const std::string& context) const;
  std::size_t tagSize() const { return enabled() ? kTagSize : 0; }

 private:
  std::string key_;
};

// Appends one encoded frame (header + payload + tag) to out.
void encodeFrame(const FrameHeader& h, const std::uint8_t* payload, std::size_t n, const Authenticator& auth,
                 std::vector<std::uint8_t>& out);

enum class DecodeStatus { NeedMore, Ok, BadMagic, Oversized, BadAuth, BadType };
const char* toString(DecodeStatus s);

// Incremental decoder for a byte stream. Memory is bounded by max_payload + header + tag.
class FrameDecoder {
 public:
  explicit FrameDecoder(std::size_t max_payload) : max_payload_(max_payload) {}
  void setAuthenticator(const Authenticator& a) { auth_ = a; }
  // Larger frames than this are Oversized (e.g. small until the peer has authenticated its hello).
  void setMaxPayload(std::size_t max_payload) { max_payload_ = max_payload; }
  // Appends received bytes. Callers read at most room() bytes at a time.
  void feed(const std::uint8_t* data, std::size_t n);
  std::size_t room() const;
  // Next complete frame. After an error status the stream is desynchronised: close the connection.
  DecodeStatus next(Frame& f);
  std::size_t buffered() const { return buf_.size() - pos_; }
  std::size_t capacity() const { return buf_.capacity(); }  // memory held

 private:
  std::size_t max_payload_;
  Authenticator auth_;
  std::vector<std::uint8_t> buf_;
  std::size_t pos_ = 0;
};

// Little-endian payload builder / reader for the control frames.
class Writer {
 public:
  void u8(std::uint8_t v) { b.push_back(v); }
  void u16(std::uint16_t v);
  void u32(std::uint32_t v);
  void u64(std::uint64_t v);
  void f64(double v);              // IEEE 754 bits as u64
  void str(const std::string& s);  // u32 length + bytes
  void bytes(const std::uint8_t* p, std::size_t n) { b.insert(b.end(), p, p + n); }
  std::vector<std::uint8_t> b;
};

class Reader {
 public:
  Reader(const std::uint8_t* p, std::size_t n) : p_(p), n_(n) {}
  // Each returns false (and leaves ok() false) when the payload is too short.
  bool u8(std::uint8_t& v);
  bool u16(std::uint16_t& v);
  bool u32(std::uint32_t& v);
  bool u64(std::uint64_t& v);
  bool f64(double& v);
  bool str(std::string& s, std::size_t max_len = 1 << 20);
  bool bytes(std::uint8_t* out, std::size_t n);
  bool ok() const { return ok_; }

 private:
  const std::uint8_t* p_;
  std::size_t n_, i_ = 0;
  bool ok_ = true;
};

// zlib; decompress refuses output larger than max_out (decompression bombs).
std::vector<std::uint8_t> compress(const std::uint8_t* p, std::size_t n, int level = 1);
bool decompress(const std::uint8_t* p, std::size_t n, std::size_t max_out, std::vector<std::uint8_t>& out);

}  // namespace relay
}  // namespace offshore_gnc

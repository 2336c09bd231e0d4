#include "offshore_gnc/relay/wire.h"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <zlib.h>

#include <cstring>
#include <stdexcept>

namespace offshore_gnc {
namespace relay {

namespace {
void put16(std::uint8_t* p, std::uint16_t v) {
  p[0] = v & 0xff;
  p[1] = v >> 8;
}
void put32(std::uint8_t* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = (v >> (8 * i)) & 0xff;
}
void put64(std::uint8_t* p, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) p[i] = (v >> (8 * i)) & 0xff;
}
std::uint16_t get16(const std::uint8_t* p) { return std::uint16_t(p[0] | (p[1] << 8)); }
std::uint32_t get32(const std::uint8_t* p) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}
std::uint64_t get64(const std::uint8_t* p) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | p[i];
  return v;
}
}  // namespace

void Authenticator::tag(const std::uint8_t* data, std::size_t n, std::uint8_t out[kTagSize]) const {
  unsigned int len = kTagSize;
  if (!HMAC(EVP_sha256(), key_.data(), static_cast<int>(key_.size()), data, n, out, &len))
    throw std::runtime_error("HMAC-SHA256 failed");
}

bool Authenticator::verify(const std::uint8_t* data, std::size_t n, const std::uint8_t* tag) const {
  std::uint8_t expect[kTagSize];
  this->tag(data, n, expect);
  return CRYPTO_memcmp(expect, tag, kTagSize) == 0;  // constant time
}

Authenticator Authenticator::derive(const std::string& context) const {
  if (!enabled()) return {};
  std::uint8_t k[kTagSize];
  tag(reinterpret_cast<const std::uint8_t*>(context.data()), context.size(), k);
  return Authenticator(std::string(reinterpret_cast<const char*>(k), kTagSize));
}

void encodeFrame(const FrameHeader& h, const std::uint8_t* payload, std::size_t n, const Authenticator& auth,
                 std::vector<std::uint8_t>& out) {
  const std::size_t start = out.size();
  out.resize(start + kHeaderSize + n + auth.tagSize());
  std::uint8_t* p = out.data() + start;
  put32(p, kMagic);
  p[4] = static_cast<std::uint8_t>(h.type);
  p[5] = h.flags;
  put16(p + 6, h.topic_id);
  put64(p + 8, h.seq);
  put64(p + 16, h.counter);
  put32(p + 24, static_cast<std::uint32_t>(n));
  put32(p + 28, 0);
  if (n) std::memcpy(p + kHeaderSize, payload, n);
  if (auth.enabled()) auth.tag(p, kHeaderSize + n, p + kHeaderSize + n);
}

const char* toString(DecodeStatus s) {
  switch (s) {
    case DecodeStatus::NeedMore: return "need more";
    case DecodeStatus::Ok: return "ok";
    case DecodeStatus::BadMagic: return "bad magic (not a relay frame)";
    case DecodeStatus::Oversized: return "oversized frame";
    case DecodeStatus::BadAuth: return "failed authentication";
    case DecodeStatus::BadType: return "unknown frame type";
  }
  return "?";
}

std::size_t FrameDecoder::room() const {
  const std::size_t cap = kHeaderSize + max_payload_ + kTagSize;
  const std::size_t have = buf_.size() - pos_;
  return have >= cap ? 0 : cap - have;
}

void FrameDecoder::feed(const std::uint8_t* data, std::size_t n) {
  if (pos_ > 0 && pos_ == buf_.size()) {
    buf_.clear();
    pos_ = 0;
  } else if (pos_ > (1 << 16) && pos_ * 2 > buf_.size()) {  // compact now and then, not per frame
    buf_.erase(buf_.begin(), buf_.begin() + static_cast<std::ptrdiff_t>(pos_));
    pos_ = 0;
  }
  buf_.insert(buf_.end(), data, data + n);
}

DecodeStatus FrameDecoder::next(Frame& f) {
  const std::size_t have = buf_.size() - pos_;
  if (have < kHeaderSize) return DecodeStatus::NeedMore;
  const std::uint8_t* p = buf_.data() + pos_;
  if (get32(p) != kMagic) return DecodeStatus::BadMagic;
  const std::uint32_t n = get32(p + 24);
  if (n > max_payload_) return DecodeStatus::Oversized;
  const std::size_t total = kHeaderSize + n + auth_.tagSize();
  if (have < total) return DecodeStatus::NeedMore;
  if (auth_.enabled() && !auth_.verify(p, kHeaderSize + n, p + kHeaderSize + n)) return DecodeStatus::BadAuth;
  const std::uint8_t t = p[4];
  if (t < static_cast<std::uint8_t>(FrameType::Hello) || t > static_cast<std::uint8_t>(FrameType::Refuse))
    return DecodeStatus::BadType;
  f.header.type = static_cast<FrameType>(t);
  f.header.flags = p[5];
  f.header.topic_id = get16(p + 6);
  f.header.seq = get64(p + 8);
  f.header.counter = get64(p + 16);
  f.payload.assign(p + kHeaderSize, p + kHeaderSize + n);
  pos_ += total;
  return DecodeStatus::Ok;
}

void Writer::u16(std::uint16_t v) {
  b.resize(b.size() + 2);
  put16(&b[b.size() - 2], v);
}
void Writer::u32(std::uint32_t v) {
  b.resize(b.size() + 4);
  put32(&b[b.size() - 4], v);
}
void Writer::u64(std::uint64_t v) {
  b.resize(b.size() + 8);
  put64(&b[b.size() - 8], v);
}
void Writer::f64(double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  u64(bits);
}
void Writer::str(const std::string& s) {
  u32(static_cast<std::uint32_t>(s.size()));
  b.insert(b.end(), s.begin(), s.end());
}

bool Reader::bytes(std::uint8_t* out, std::size_t n) {
  if (!ok_ || n_ - i_ < n) return ok_ = false;
  std::memcpy(out, p_ + i_, n);
  i_ += n;
  return true;
}
bool Reader::u8(std::uint8_t& v) { return bytes(&v, 1); }
bool Reader::u16(std::uint16_t& v) {
  std::uint8_t t[2];
  if (!bytes(t, 2)) return false;
  v = get16(t);
  return true;
}
bool Reader::u32(std::uint32_t& v) {
  std::uint8_t t[4];
  if (!bytes(t, 4)) return false;
  v = get32(t);
  return true;
}
bool Reader::u64(std::uint64_t& v) {
  std::uint8_t t[8];
  if (!bytes(t, 8)) return false;
  v = get64(t);
  return true;
}
bool Reader::f64(double& v) {
  std::uint64_t bits = 0;
  if (!u64(bits)) return false;
  std::memcpy(&v, &bits, sizeof v);
  return true;
}
bool Reader::str(std::string& s, std::size_t max_len) {
  std::uint32_t n = 0;
  if (!u32(n)) return false;
  if (n > max_len || n_ - i_ < n) return ok_ = false;
  s.assign(reinterpret_cast<const char*>(p_ + i_), n);
  i_ += n;
  return true;
}

// Compressed payload: u32 original size, then the zlib stream.
std::vector<std::uint8_t> compress(const std::uint8_t* p, std::size_t n, int level) {
  uLongf out_len = compressBound(n);
  std::vector<std::uint8_t> out(4 + out_len);
  put32(out.data(), static_cast<std::uint32_t>(n));
  if (compress2(out.data() + 4, &out_len, p, n, level) != Z_OK) throw std::runtime_error("zlib compress failed");
  out.resize(4 + out_len);
  return out;
}

bool decompress(const std::uint8_t* p, std::size_t n, std::size_t max_out, std::vector<std::uint8_t>& out) {
  if (n < 4) return false;
  const std::uint32_t size = get32(p);
  if (size > max_out) return false;
  out.resize(size);
  uLongf out_len = size;
  if (uncompress(out.data(), &out_len, p + 4, n - 4) != Z_OK || out_len != size) return false;
  return true;
}

}  // namespace relay
}  // namespace offshore_gnc

// The session handshake (include/offshore_gnc/relay/handshake.h).
#include "offshore_gnc/relay/handshake.h"

#include <cmath>
#include <cstdio>
#include <random>

namespace offshore_gnc {
namespace relay {

std::vector<std::uint8_t> encodeHello(const Hello& h) {
  Writer w;
  w.u16(h.version);
  w.str(h.name);
  w.u64(h.session);
  std::string nonce = h.nonce;
  nonce.resize(kNonceSize, '\0');
  w.bytes(reinterpret_cast<const std::uint8_t*>(nonce.data()), kNonceSize);
  w.u64(h.ack_session);
  w.u64(h.ack_seq);
  w.u16(h.udp_port);
  w.u8(h.origin ? 1 : 0);
  if (h.origin) {
    w.f64(h.origin->lat_deg);
    w.f64(h.origin->lon_deg);
    w.f64(h.origin->alt_m);
  }
  return w.b;
}

bool decodeHello(const std::vector<std::uint8_t>& payload, Hello& h) {
  Reader r(payload.data(), payload.size());
  std::uint8_t nonce[kNonceSize];
  r.u16(h.version);
  r.str(h.name, 256);
  r.u64(h.session);
  r.bytes(nonce, kNonceSize);
  r.u64(h.ack_session);
  r.u64(h.ack_seq);
  r.u16(h.udp_port);
  std::uint8_t has_origin = 0;
  h.origin.reset();
  if (r.u8(has_origin) && has_origin) {
    h.origin.emplace();
    r.f64(h.origin->lat_deg);
    r.f64(h.origin->lon_deg);
    r.f64(h.origin->alt_m);
  }
  if (!r.ok() || h.version != kWireVersion) return false;
  h.nonce.assign(reinterpret_cast<const char*>(nonce), kNonceSize);
  return true;
}

std::string freshNonce() {
  static thread_local std::random_device rd;
  std::string s(kNonceSize, '\0');
  for (auto& ch : s) ch = static_cast<char>(rd() & 0xff);
  return s;
}

SessionKeys sessionKeys(const Authenticator& psk, const std::string& our_nonce, const std::string& their_nonce) {
  return {psk.derive("ogr1" + our_nonce + their_nonce), psk.derive("ogr1" + their_nonce + our_nonce)};
}

std::string siteMismatch(const std::optional<geo::LatLonAlt>& ours, const std::optional<geo::LatLonAlt>& theirs,
                         double tolerance, const std::string& our_name) {
  if (!theirs || !ours) return "";
  const bool finite = std::isfinite(theirs->lat_deg) && std::isfinite(theirs->lon_deg) && std::isfinite(theirs->alt_m);
  const double apart = finite ? std::hypot(geo::surfaceDistance(*ours, *theirs), theirs->alt_m - ours->alt_m) : NAN;
  if (finite && apart <= tolerance) return "";
  char b[400];
  std::snprintf(b, sizeof b,
                "its origin (%.7f, %.7f, %.1f m) is %.1f m from %s's (%.7f, %.7f, %.1f m), over the %.1f m tolerance: "
                "both vehicles must run on one site origin (the same site:= file or origin:=LAT,LON[,ALT])",
                theirs->lat_deg, theirs->lon_deg, theirs->alt_m, apart, our_name.c_str(), ours->lat_deg, ours->lon_deg,
                ours->alt_m, tolerance);
  return b;
}

}  // namespace relay
}  // namespace offshore_gnc

#pragma once
// The session handshake (docs/relay.md, "Wire format"): each side sends a hello under the pre-shared key with a
// fresh nonce; both then derive per-direction session keys from the two nonces, so that frames of an earlier
// connection fail authentication. The hello also carries what the far side must know at link-up: the sender's
// session (a new one: it restarted), what it holds of ours (the reliable sequence it acknowledges), its UDP port
// and its site origin (two vehicles on different origins refuse each other).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/relay/wire.h"

namespace offshore_gnc {
namespace relay {

constexpr std::size_t kNonceSize = 16;
// Frames before an authenticated hello are at most a hello's size (a flood of large frames costs no memory).
constexpr std::size_t kMaxHelloPayload = 512;

struct Hello {
  std::uint16_t version = kWireVersion;
  std::string name;
  std::uint64_t session = 0;
  std::string nonce;  // kNonceSize bytes
  std::uint64_t ack_session = 0, ack_seq = 0;  // the sender holds our messages up to ack_seq of ack_session
  std::uint16_t udp_port = 0;                   // 0: no UDP at the sender
  std::optional<geo::LatLonAlt> origin;
};

std::vector<std::uint8_t> encodeHello(const Hello& h);
// False when the payload is truncated or of another protocol version.
bool decodeHello(const std::vector<std::uint8_t>& payload, Hello& h);

// kNonceSize fresh random bytes.
std::string freshNonce();

struct SessionKeys {
  Authenticator tx, rx;
};
// The per-direction keys of a connection from the pre-shared key and both sides' nonces.
SessionKeys sessionKeys(const Authenticator& psk, const std::string& our_nonce, const std::string& their_nonce);

// Why a peer announcing `theirs` as its origin must be refused by relay `our_name` on `ours`; empty when they
// lie within `tolerance` metres (or either has none).
std::string siteMismatch(const std::optional<geo::LatLonAlt>& ours, const std::optional<geo::LatLonAlt>& theirs,
                         double tolerance, const std::string& our_name);

}  // namespace relay
}  // namespace offshore_gnc

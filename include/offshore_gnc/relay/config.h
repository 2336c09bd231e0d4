#pragma once
// The relay's configuration: this relay, its peers and the topics it carries (docs/relay.md, "Configuration").
// ROS-free; the ROS side fills it from the node's private parameters (src/relay/ros_relay.h) through the tables
// below: the defaults are the structs' own values, the ranges the tables', docs/parameters.md lists both.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/geo/geo.h"

namespace offshore_gnc {
namespace relay {

struct TopicConfig {
  std::string topic;      // local name
  std::string type;       // ROS type, e.g. offshore_gnc/Target (checked at both ends)
  std::string direction;  // "out" (local -> peers) or "in" (peers -> local)
  std::string remote;     // out: name on the far side (default: topic)
  std::vector<std::string> peers;  // out: destinations, in: accepted sources (empty = all peers)
  bool reliable = true;
  double rate_hz = 0.0;  // 0 = unlimited
  bool latched = false;
  bool compress = false;
  // An entry of `topics` (its `peers` list is read beside the table).
  static const ParamTable<TopicConfig>& table();
};

struct PeerConfig {
  std::string name;
  std::string host;  // empty: the peer dials us
  int port = 0;
};

// An entry of `peers` as configured: the peer's name and the host:port to dial (none: the peer dials us).
struct PeerEntry {
  std::string name, address;
  static const ParamTable<PeerEntry>& table();
  // Throws ConfigError naming `where` when the address is not host:port.
  PeerConfig toConfig(const std::string& where) const;
};

struct RelayConfig {
  std::string name;
  std::string listen_host = "127.0.0.1";
  int listen_port = 0;  // 0 = do not listen (-1 in tests: any free port)
  // HMAC-SHA256 on every frame; "none" only by explicit configuration
  std::string auth = "hmac-sha256";
  bool authenticated() const { return auth != "none"; }
  // Best-effort topics go in UDP datagrams (same frames, same session keys, own replay window; loss counted,
  // never resent) when the encoded frame fits max_datagram_bytes; larger ones and latched repeats use TCP.
  bool udp = true;
  int max_datagram_bytes = 60000;
  std::string key;       // pre-shared key (required when authenticated)
  std::string key_file;  // the key's file, read by the ROS side when `key` is empty (relay/key.h)
  // Simulation: any key of >= 16 bytes, the shipped config/relay/sim.key too. Off (hardware), the key must be a
  // deployment key (relay/key.h: >= 32 random bytes, not the published simulation key).
  bool sim = false;
  double heartbeat_period = 0.2, link_timeout = 1.0, backoff_min = 0.1, backoff_max = 2.0;
  double ack_delay = 0.5;  // acks trail delivery to ROS by this long (crash window covered by resends)
  // The site's origin, announced in the hello: a peer whose origin lies farther than origin_tolerance [m] is
  // refused, both named (two vehicles on different origins would misplace every position they exchange). Unset
  // here or at the peer: not checked.
  std::optional<geo::LatLonAlt> origin;
  double origin_tolerance = 1.0;
  int queue_messages = 1000;
  double queue_bytes = 64u << 20;
  int max_frame_bytes = 32u << 20;
  double status_period = 1.0;  // [s] /relay/link_status and diagnostics (ROS side)
  std::vector<PeerConfig> peers;
  std::vector<TopicConfig> topics;
  // The scalar parameters (the site origin is /site/origin, peers and topics are lists of the tables above).
  static const ParamTable<RelayConfig>& table();
};

// Checks against the tables and across fields, fills defaults (a topic's remote name); throws ConfigError naming
// the offending entry.
void validate(RelayConfig& c);

}  // namespace relay
}  // namespace offshore_gnc

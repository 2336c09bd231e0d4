// Checks of the relay's configuration (include/offshore_gnc/relay/config.h).
#include "offshore_gnc/relay/config.h"

#include <set>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/relay/key.h"

namespace offshore_gnc {
namespace relay {

namespace {
ConfigError configError(const std::string& what) { return ConfigError("relay config: " + what); }

}  // namespace

PeerConfig PeerEntry::toConfig(const std::string& where) const {
  PeerConfig p{name, "", 0};
  if (address.empty()) return p;
  const auto colon = address.rfind(':');
  if (colon == std::string::npos) throw configError(where + "/address must be host:port");
  p.host = address.substr(0, colon);
  try {
    p.port = std::stoi(address.substr(colon + 1));
  } catch (const std::exception&) {
    throw configError(where + "/address '" + address + "' has no valid port");
  }
  return p;
}

const ParamTable<RelayConfig>& RelayConfig::table() {
  using C = RelayConfig;
  static const ParamTable<C> t = ParamTable<C>()
      .string("name", &C::name, "this relay's name (usv, auv): required, the peers know it by this")
      .string("listen_host", &C::listen_host, "IPv4 address to listen on (TCP, and UDP on the same port)")
      .integer("listen_port", &C::listen_port, -1, 65535, "0: do not listen (the peers are dialled); -1: any free port")
      .choice("auth", &C::auth, {"hmac-sha256", "none"}, "HMAC-SHA256 on every frame; none only explicitly")
      .string("key_file", &C::key_file, "the pre-shared key's file (first line; docs/relay.md, \"Keys\")")
      .string("key", &C::key, "the pre-shared key itself, instead of key_file")
      .flag("sim", &C::sim, "simulation: any key of >= 16 bytes; false (hardware): a deployment key only")
      .number("heartbeat_period", &C::heartbeat_period, 0.01, 10.0, "s", "pings (round-trip time, loss)")
      .number("link_timeout", &C::link_timeout, 0.02, 60.0, "s",
              "a link with no frame for this long is closed and redialled (at least 2 heartbeat periods)")
      .number("ack_delay", &C::ack_delay, 0.0, 10.0, "s",
              "acks trail delivery by this long (a crash before the message is written out means a resend)")
      .number("backoff_min", &C::backoff_min, 0.01, 10.0, "s", "first redial wait, doubling after each failure")
      .number("backoff_max", &C::backoff_max, 0.01, 60.0, "s", "longest redial wait (at least backoff_min)")
      .integer("queue/max_messages", &C::queue_messages, 1, 1000000, "reliable messages queued per peer (oldest dropped)")
      .number("queue/max_bytes", &C::queue_bytes, 1024, 4e9, "bytes", "reliable bytes queued per peer (oldest dropped)")
      .integer("max_frame_bytes", &C::max_frame_bytes, 1024, 1 << 30, "largest frame accepted from a peer [bytes]")
      .flag("udp", &C::udp, "best-effort topics in UDP datagrams when they fit")
      .integer("max_datagram_bytes", &C::max_datagram_bytes, 512, 65000, "largest frame sent as a datagram [bytes]")
      .number("origin_tolerance", &C::origin_tolerance, 0.0, 1e4, "m",
              "a peer whose site origin lies farther is refused (/site/origin)")
      .number("status_period", &C::status_period, 0.05, 60.0, "s", "/relay/link_status and diagnostics");
  return t;
}

const ParamTable<PeerEntry>& PeerEntry::table() {
  using P = PeerEntry;
  static const ParamTable<P> t = ParamTable<P>()
      .string("name", &P::name, "the peer relay's name: required")
      .string("address", &P::address, "host:port to dial; empty: the peer dials us");
  return t;
}

const ParamTable<TopicConfig>& TopicConfig::table() {
  using T = TopicConfig;
  static const ParamTable<T> t = ParamTable<T>()
      .string("topic", &T::topic, "local name (absolute): required")
      .string("type", &T::type, "ROS type, package/Message, checked at both ends: required")
      .string("direction", &T::direction, "out (local -> peers) or in (peers -> local): required")
      .string("remote", &T::remote, "out: the name on the far side (empty: topic)")
      .flag("reliable", &T::reliable, "queued, acknowledged, resent (false: best effort, UDP when it fits)")
      .number("rate_hz", &T::rate_hz, 0.0, 1e6, "Hz", "at most this rate, per peer (0: unlimited)")
      .flag("latched", &T::latched, "the last message again for a peer that (re)connects")
      .flag("compress", &T::compress, "zlib");
  return t;
}

void validate(RelayConfig& c) {
  if (c.name.empty()) throw configError("'name' must be set (this relay's name, e.g. usv)");
  RelayConfig::table().validate(c);
  if (c.authenticated() && c.key.size() < 16)
    throw configError("'auth' is on but the pre-shared key is missing or shorter than 16 bytes "
                      "(set key_file, or auth: none to disable authentication explicitly)");
  if (c.authenticated() && !c.sim) {
    const std::string why = deploymentKeyProblem(c.key);
    if (!why.empty())
      throw configError("refusing to start on hardware (sim: false): the pre-shared key " + why + ". " + kMakeKeyHint);
  }
  // across fields (each field's own range: the table)
  requireRange("link_timeout", c.link_timeout, 2 * c.heartbeat_period, 60.0);
  requireRange("backoff_max", c.backoff_max, c.backoff_min, 60.0);
  if (c.origin) geo::checkLatLonAlt(*c.origin);
  std::set<std::string> names;
  for (const auto& p : c.peers) {
    if (p.name.empty() || p.name == c.name) throw configError("peer name '" + p.name + "' is empty or our own");
    if (!names.insert(p.name).second) throw configError("peer '" + p.name + "' listed twice");
    if (!p.host.empty()) requireRange("peers/" + p.name + "/port", p.port, 1, 65535);
  }
  if (c.topics.size() > 65535) throw configError("too many topics");
  std::set<std::string> in_names, out_names;
  for (auto& t : c.topics) {
    const std::string where = "topic '" + t.topic + "'";
    if (t.topic.empty() || t.topic[0] != '/') throw configError(where + ": 'topic' must be an absolute name");
    if (t.type.find('/') == std::string::npos) throw configError(where + ": 'type' must be package/Message");
    if (t.direction != "out" && t.direction != "in") throw configError(where + ": 'direction' must be out or in");
    if (t.remote.empty()) t.remote = t.topic;
    if (t.remote[0] != '/') throw configError(where + ": 'remote' must be an absolute name");
    TopicConfig::table().validate(t, where + " ");
    for (const auto& p : t.peers)
      if (!names.count(p)) throw configError(where + ": peer '" + p + "' is not in 'peers'");
    if (t.direction == "in" && !in_names.insert(t.topic).second)
      throw configError(where + ": listed twice as 'in' (list the accepted peers in one entry)");
    if (t.direction == "out") out_names.insert(t.topic);
  }
  for (const auto& n : in_names)
    if (out_names.count(n)) throw configError("topic '" + n + "': both 'in' and 'out' (it would loop)");
}

}  // namespace relay
}  // namespace offshore_gnc

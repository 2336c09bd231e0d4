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

void validate(RelayConfig& c) {
  if (c.name.empty()) throw configError("'name' must be set (this relay's name, e.g. usv)");
  if (c.auth && c.key.size() < 16)
    throw configError("'auth' is on but the pre-shared key is missing or shorter than 16 bytes "
                      "(set key_file, or auth: none to disable authentication explicitly)");
  if (c.auth && !c.sim) {
    const std::string why = deploymentKeyProblem(c.key);
    if (!why.empty())
      throw configError("refusing to start on hardware (sim: false): the pre-shared key " + why + ". " + kMakeKeyHint);
  }
  requireRange("listen_port", c.listen_port, -1, 65535);
  requireRange("heartbeat_period", c.heartbeat_period, 0.01, 10.0);
  requireRange("link_timeout", c.link_timeout, 2 * c.heartbeat_period, 60.0);
  requireRange("ack_delay", c.ack_delay, 0.0, 10.0);
  requireRange("backoff_min", c.backoff_min, 0.01, 10.0);
  requireRange("backoff_max", c.backoff_max, c.backoff_min, 60.0);
  requireRange("queue/max_messages", double(c.queue_messages), 1, 1e6);
  requireRange("queue/max_bytes", double(c.queue_bytes), 1024, 4e9);
  requireRange("max_frame_bytes", double(c.max_frame_bytes), 1024, 1u << 30);
  requireRange("max_datagram_bytes", double(c.max_datagram_bytes), 512, 65000);
  requireRange("origin_tolerance", c.origin_tolerance, 0.0, 1e4);
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
    requireRange(where + " rate_hz", t.rate_hz, 0.0, 1e6);
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

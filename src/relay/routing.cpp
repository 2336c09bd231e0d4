// Announces and topic routing (include/offshore_gnc/relay/routing.h).
#include "offshore_gnc/relay/routing.h"

#include <algorithm>

#include "offshore_gnc/relay/wire.h"

namespace offshore_gnc {
namespace relay {

std::vector<std::uint8_t> encodeAnnounce(const TopicConfig& t, const TypeInfo& info) {
  Writer w;
  w.str(t.remote);
  w.str(info.type);
  w.str(info.md5);
  w.str(info.definition);
  w.u8(t.latched);
  w.u8(t.reliable);
  return w.b;
}

bool decodeAnnounce(const std::vector<std::uint8_t>& payload, Announce& a) {
  Reader r(payload.data(), payload.size());
  std::uint8_t latched = 0, reliable = 0;
  r.str(a.topic, 1024);
  r.str(a.info.type, 1024);
  r.str(a.info.md5, 64);
  r.str(a.info.definition, kMaxDefinitionBytes);
  r.u8(latched);
  r.u8(reliable);
  a.latched = latched;
  a.reliable = reliable;
  return r.ok();
}

std::uint64_t announceDigest(const Announce& a) {
  std::uint64_t digest = 1469598103934665603ull;  // FNV-1a
  for (const std::string* part : {&a.topic, &a.info.type, &a.info.md5, &a.info.definition})
    for (unsigned char ch : *part + '\0') digest = (digest ^ ch) * 1099511628211ull;
  return (digest ^ (a.latched ? 2u : 0u) ^ (a.reliable ? 1u : 0u)) * 1099511628211ull;
}

bool goesTo(const TopicConfig& t, const std::string& peer) {
  return t.peers.empty() || std::find(t.peers.begin(), t.peers.end(), peer) != t.peers.end();
}

long inTopicFor(const std::vector<TopicConfig>& topics, const std::string& topic, const std::string& peer) {
  long index = -1;
  for (std::size_t i = 0; i < topics.size(); ++i) {
    const auto& t = topics[i];
    if (t.direction == "in" && t.topic == topic && goesTo(t, peer)) index = long(i);
  }
  return index;
}

RemoteTopics::Verdict RemoteTopics::check(std::uint16_t id, std::uint64_t digest) const {
  auto known = topics_.find(id);
  if (known != topics_.end() && known->second.digest == digest) return Verdict::Repeat;
  if (known == topics_.end() && topics_.size() >= kMaxRemoteTopics) return Verdict::OverLimit;
  return Verdict::New;
}

void RemoteTopics::decide(std::uint16_t id, long index) {
  auto it = topics_.find(id);
  if (it != topics_.end()) it->second.index = index;
}

long RemoteTopics::indexOf(std::uint16_t id) const {
  auto it = topics_.find(id);
  return it == topics_.end() ? -1 : it->second.index;
}

}  // namespace relay
}  // namespace offshore_gnc

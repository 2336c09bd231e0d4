#pragma once
// Which topic goes where: a topic's announce (type, md5sum, definition) before its first message, an out-topic's
// destinations, the in-topic a peer's announced topic maps to, and what each peer has announced.
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "offshore_gnc/relay/config.h"

namespace offshore_gnc {
namespace relay {

// Limits against a flooding peer (docs/relay.md, "Security model"): announced message definitions are at most
// 256 KiB, a peer has at most 1024 topics.
constexpr std::size_t kMaxDefinitionBytes = 256u << 10;
constexpr std::size_t kMaxRemoteTopics = 1024;

struct TypeInfo {
  std::string type, md5, definition;
};

struct Announce {
  std::string topic;  // the name on this side
  TypeInfo info;
  bool latched = false, reliable = true;
};

// An out-topic's announce as its peers see it (its remote name).
std::vector<std::uint8_t> encodeAnnounce(const TopicConfig& t, const TypeInfo& info);
// False when the payload is truncated or a field is over its limit.
bool decodeAnnounce(const std::vector<std::uint8_t>& payload, Announce& a);
// What an announce says, hashed: an identical repeat (a peer replaying its own announces) changes nothing.
std::uint64_t announceDigest(const Announce& a);

// Whether topic `t` goes to (out) or is accepted from (in) `peer`.
bool goesTo(const TopicConfig& t, const std::string& peer);
// The in-topic that `topic` from `peer` is delivered to, or -1 when none is configured.
long inTopicFor(const std::vector<TopicConfig>& topics, const std::string& topic, const std::string& peer);

// The topics one peer has announced on the current link: its topic id -> our in-topic, once accepted.
class RemoteTopics {
 public:
  enum class Verdict { New, Repeat, OverLimit };
  Verdict check(std::uint16_t id, std::uint64_t digest) const;
  // Remembered undecided (nothing is delivered) until accept().
  void remember(std::uint16_t id, std::uint64_t digest) { topics_[id] = {-1, digest}; }
  // The callback's decision: `index` >= 0 delivers to that in-topic, -1 refuses.
  void decide(std::uint16_t id, long index);
  bool known(std::uint16_t id) const { return topics_.count(id) != 0; }
  long indexOf(std::uint16_t id) const;  // -1: unknown or refused
  std::size_t size() const { return topics_.size(); }
  void clear() { topics_.clear(); }

 private:
  struct Entry {
    long index = -1;
    std::uint64_t digest = 0;
  };
  std::map<std::uint16_t, Entry> topics_;
};

}  // namespace relay
}  // namespace offshore_gnc

#pragma once
// The relay's pre-shared key: the key file, the rules a key must meet on hardware, and the fingerprint that
// shows two relays hold the same key without revealing it. ROS-free (OpenSSL).
#include <cstddef>
#include <string>

namespace offshore_gnc {
namespace relay {

constexpr std::size_t kMinKeyBytes = 32;  // random bytes a deployment key must carry

// How a user makes a deployment key (ends every refusal).
extern const char* const kMakeKeyHint;

// The key in a key file: its first line, surrounding whitespace removed. Throws ConfigError naming the file
// when it cannot be read or holds no key.
std::string readKeyFile(const std::string& path);

// Why `key` must not authenticate a relay on hardware, or "" when it may: a deployment key is hex or base64
// text of at least kMinKeyBytes random bytes (as `openssl rand -base64 32` writes) and is not the simulation
// key published in config/relay/sim.key.
std::string deploymentKeyProblem(const std::string& key);

// "sha256:" + the first 16 hex digits of SHA-256 over the key text (what scripts/relay-key prints).
std::string keyFingerprint(const std::string& key);

}  // namespace relay
}  // namespace offshore_gnc

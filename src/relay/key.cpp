// Deployment-key rules (docs/relay.md, "Keys"). Decoding and hashing are OpenSSL's.
#include "offshore_gnc/relay/key.h"

#include <openssl/crypto.h>
#include <openssl/evp.h>

#include <cctype>
#include <fstream>
#include <set>
#include <vector>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace relay {

namespace {
// SHA-256 of config/relay/sim.key's key (a unit test checks that they still match).
const char* const kSimulationKeySha256 = "adb0a199192893f9aaab4853ea10552e1128d3022829146af80b8c456ecf9c5a";

std::string sha256Hex(const std::string& s) {
  unsigned char d[EVP_MAX_MD_SIZE];
  unsigned int n = 0;
  if (!EVP_Digest(s.data(), s.size(), d, &n, EVP_sha256(), nullptr)) return "";
  static const char* hex = "0123456789abcdef";
  std::string out;
  for (unsigned int i = 0; i < n; ++i) {
    out += hex[d[i] >> 4];
    out += hex[d[i] & 15];
  }
  return out;
}

// Decoded key material: hex (an even number of hex digits) or base64 (OpenSSL's decoder); false for other text.
bool decode(const std::string& key, std::vector<unsigned char>& out) {
  bool all_hex = !key.empty() && key.size() % 2 == 0;
  for (char ch : key) all_hex = all_hex && std::isxdigit(static_cast<unsigned char>(ch));
  if (all_hex) {
    out.clear();
    for (std::size_t i = 0; i < key.size(); i += 2) out.push_back(static_cast<unsigned char>(std::stoi(key.substr(i, 2), nullptr, 16)));
    return true;
  }
  if (key.empty() || key.size() % 4 != 0) return false;
  out.assign(key.size() / 4 * 3, 0);
  const int n = EVP_DecodeBlock(out.data(), reinterpret_cast<const unsigned char*>(key.data()), static_cast<int>(key.size()));
  if (n < 0) return false;
  std::size_t pad = 0;
  for (std::size_t i = key.size(); i > 0 && key[i - 1] == '='; --i) ++pad;
  if (pad > 2) return false;
  out.resize(static_cast<std::size_t>(n) - pad);  // EVP_DecodeBlock counts the padding as zero bytes
  return true;
}
}  // namespace

const char* const kMakeKeyHint =
    "Make a deployment key with `scripts/relay-key FILE` (or `rosrun offshore_gnc relay-key FILE`: 32 random bytes "
    "from OpenSSL, readable only by you), copy the same file to every vehicle and start with key_file:=FILE; in "
    "simulation set sim:=true";

std::string readKeyFile(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw ConfigError("relay config: cannot read key_file '" + path + "'");
  std::string line;
  std::getline(f, line);
  const auto b = line.find_first_not_of(" \t\r\n");
  const auto e = line.find_last_not_of(" \t\r\n");
  if (b == std::string::npos) throw ConfigError("relay config: key_file '" + path + "' holds no key (first line empty)");
  return line.substr(b, e - b + 1);
}

std::string deploymentKeyProblem(const std::string& key) {
  if (CRYPTO_memcmp(sha256Hex(key).data(), kSimulationKeySha256, 64) == 0)
    return "is the simulation key published in this repository (config/relay/sim.key)";
  std::vector<unsigned char> bytes;
  if (!decode(key, bytes)) return "is not hex or base64 text of random bytes";
  if (bytes.size() < kMinKeyBytes)
    return "carries " + std::to_string(bytes.size()) + " bytes, fewer than the " + std::to_string(kMinKeyBytes) +
           " random bytes a deployment key needs";
  // 32 random bytes hold about 30 different values; fewer than 16 is a pattern, not randomness (p < 1e-9).
  if (std::set<unsigned char>(bytes.begin(), bytes.end()).size() < 16) return "is a repetitive pattern, not random bytes";
  return "";
}

std::string keyFingerprint(const std::string& key) { return "sha256:" + sha256Hex(key).substr(0, 16); }

}  // namespace relay
}  // namespace offshore_gnc

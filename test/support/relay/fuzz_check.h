#pragma once
// What a hostile network peer can do to the relay, checked on arbitrary input: shared by the libFuzzer targets
// (src/relay/*_fuzz.cpp, `scripts/fuzz relay_wire|relay_session`) and the gtests that run the same entry points
// over random input and floods in the normal suite.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "offshore_gnc/relay/wire.h"

namespace offshore_gnc {
namespace relay {

// A peer relay played by a test over a connected stream socket. It speaks the wire format of docs/relay.md with
// its own code (not the engine's), so that it can also break the protocol on purpose, and it checks that every
// frame the engine sends authenticates (its hello under the pre-shared key, then under the session key).
class ScriptedPeer {
 public:
  enum class Key { Session, Psk, Wrong, None };
  // `pump` lets a synchronously driven engine read while a send would block (Engine::pollOnce).
  ScriptedPeer(int fd, std::string psk, std::function<void()> pump = {});
  ~ScriptedPeer();
  ScriptedPeer(const ScriptedPeer&) = delete;
  ScriptedPeer& operator=(const ScriptedPeer&) = delete;

  static std::vector<std::uint8_t> helloPayload(std::uint16_t version, const std::string& name, std::uint64_t session,
                                                const std::string& nonce, std::uint64_t ack_session = 0,
                                                std::uint64_t ack_seq = 0, std::uint16_t udp_port = 0);
  static std::vector<std::uint8_t> announcePayload(const std::string& topic, const std::string& type,
                                                   const std::string& md5, const std::string& definition,
                                                   bool latched, bool reliable);
  // Our hello with our nonce. Sent under the pre-shared key, it makes Key::Session mean the keys both nonces
  // give (the engine's hello must have been received first: receive()).
  std::vector<std::uint8_t> hello(const std::vector<std::uint8_t>& payload, Key key = Key::Psk);
  // Encodes and sends one frame; counter 0 takes the next unused one unless literal_counter. Returns the bytes.
  std::vector<std::uint8_t> frame(FrameHeader h, const std::vector<std::uint8_t>& payload, Key key = Key::Session,
                                  bool literal_counter = false);
  static std::vector<std::uint8_t> encode(FrameHeader h, const std::vector<std::uint8_t>& payload,
                                          const Authenticator& auth);
  std::vector<std::uint8_t> encodeWith(FrameHeader h, const std::vector<std::uint8_t>& payload, Key key) const;
  // Sends bytes as they are (false when the engine has closed the connection).
  bool raw(const std::uint8_t* p, std::size_t n);
  bool raw(const std::vector<std::uint8_t>& b) { return raw(b.data(), b.size()); }
  // Reads what the engine sent (without blocking; `wait_s` > 0 waits that long for the first bytes). Returns an
  // error text when a frame does not decode or authenticate, "" otherwise.
  std::string receive(double wait_s = 0.0);

  bool haveEngineHello() const { return !engine_nonce_.empty(); }
  bool sessionKeys() const { return session_; }
  bool closedByEngine() const { return eof_; }
  const std::string& nonce() const { return nonce_; }
  std::uint64_t lastCounter() const { return counter_; }
  std::size_t framesReceived(FrameType t) const { return counts_[static_cast<std::size_t>(t)]; }
  std::size_t bytesReceived() const { return bytes_in_; }
  int fd() const { return fd_; }

 private:
  int fd_;
  std::string psk_, nonce_, engine_nonce_;
  std::function<void()> pump_;
  Authenticator tx_, rx_;
  bool session_ = false, eof_ = false, verify_ = true;
  std::uint64_t counter_ = 0;
  FrameDecoder in_;
  std::size_t counts_[8] = {};
  std::size_t bytes_in_ = 0;
};

// Frame decoding on arbitrary bytes: chunking never changes the result, every decoded frame re-encodes to the
// same bytes, the payload readers and zlib stay within their limits. Returns "" or the invariant broken.
std::string fuzzWireOnce(const std::uint8_t* data, std::size_t n);

// A relay engine (driven synchronously) and a scripted peer on a socketpair; `data` is the peer's script: hellos
// (valid, wrong key, wrong version, unknown name, truncated), announces, data (reliable, compressed, garbage),
// control frames, raw garbage, truncated frames, huge length fields, replays within and across connections,
// reused counters, reconnects and local publishes. Checked after every step: nothing the peer was not entitled
// to is delivered (no frame under a wrong key, no replay, nothing before an authenticated hello, each message at
// most once), announces reach the callback only for configured in-topics, everything the engine sends
// authenticates, memory stays within the engine's limits. Returns "" or the invariant broken.
std::string fuzzSessionOnce(const std::uint8_t* data, std::size_t n);

// For the libFuzzer entry points: prints the broken invariant and aborts (the fuzzer records the input).
void abortOnViolation(const char* what, const std::string& violation);

}  // namespace relay
}  // namespace offshore_gnc

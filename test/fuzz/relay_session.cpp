// libFuzzer target: a hostile peer against a real relay engine over a socketpair (handshake, announces, data,
// replays, wrong keys, truncated frames, huge lengths, reconnects; relay/fuzz_check.h, fuzzSessionOnce).
// Built and run by `scripts/fuzz relay_session SECONDS`.
#include "relay/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  offshore_gnc::relay::abortOnViolation("session", offshore_gnc::relay::fuzzSessionOnce(data, size));
  return 0;
}

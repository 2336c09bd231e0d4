// libFuzzer target: a hostile peer against a real relay engine over a socketpair (handshake, announces, data,
// replays, wrong keys, truncated frames, huge lengths, reconnects; relay/fuzz_check.h, fuzzSessionOnce).
// Built and run by `scripts/fuzz relay_session SECONDS`.
#include <cstdio>
#include <cstdlib>

#include "offshore_gnc/relay/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string v = offshore_gnc::relay::fuzzSessionOnce(data, size);
  if (!v.empty()) {
    std::fprintf(stderr, "relay session invariant violated: %s\n", v.c_str());
    std::abort();
  }
  return 0;
}

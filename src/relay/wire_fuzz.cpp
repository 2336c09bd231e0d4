// libFuzzer target: arbitrary bytes through the relay's frame decoder (with and without HMAC), the payload
// readers and zlib (relay/fuzz_check.h, fuzzWireOnce). Built and run by `scripts/fuzz relay_wire SECONDS`.
#include <cstdio>
#include <cstdlib>

#include "offshore_gnc/relay/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string v = offshore_gnc::relay::fuzzWireOnce(data, size);
  if (!v.empty()) {
    std::fprintf(stderr, "relay wire invariant violated: %s\n", v.c_str());
    std::abort();
  }
  return 0;
}

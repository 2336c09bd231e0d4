// libFuzzer target: arbitrary bytes through the relay's frame decoder (with and without HMAC), the payload
// readers and zlib (relay/fuzz_check.h, fuzzWireOnce). Built and run by `scripts/fuzz relay_wire SECONDS`.
#include "relay/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  offshore_gnc::relay::abortOnViolation("wire", offshore_gnc::relay::fuzzWireOnce(data, size));
  return 0;
}

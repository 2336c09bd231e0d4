// libFuzzer target for the SeaNet codec and the Micron driver; built and run by scripts/fuzz micron (clang,
// ASan + UBSan).
#include <cstddef>
#include <cstdint>

#include "micron_sim/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  offshore_gnc::micron_sim::fuzzCodecOnce(data, size);
  return 0;
}

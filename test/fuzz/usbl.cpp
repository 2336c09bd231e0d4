// libFuzzer target for the SeaTrac codec; built and run by `scripts/fuzz usbl` (clang, ASan + UBSan).
#include <cstddef>
#include <cstdint>

#include "usbl/fuzz_check.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  offshore_gnc::usbl::fuzzCodecOnce(data, size);
  return 0;
}

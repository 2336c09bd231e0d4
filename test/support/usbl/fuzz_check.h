#pragma once
// The codec's invariants, checked on arbitrary input: shared by the libFuzzer target (`scripts/fuzz usbl`) and
// the gtest that runs the same entry point over random and mutated streams in the normal suite.
#include <cstddef>
#include <cstdint>

namespace offshore_gnc {
namespace usbl {

// Feeds `data` to a StreamDecoder in two chunk layouts and to decodePayload directly. Aborts (so that the
// fuzzer records a crash) when: chunking changes the result, a decoded message does not re-encode to the
// same frame, or a decoded fix carries more than 4 USBL channels. Returns the number of frames decoded.
std::size_t fuzzCodecOnce(const std::uint8_t* data, std::size_t n);

}  // namespace usbl
}  // namespace offshore_gnc

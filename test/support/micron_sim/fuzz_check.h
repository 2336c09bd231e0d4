#pragma once
// The SeaNet codec's and the driver's invariants on arbitrary input: shared by the libFuzzer target
// (scripts/fuzz micron) and the gtest that runs the same entry point over random and mutated streams.
#include <cstddef>
#include <cstdint>

namespace offshore_gnc {
namespace micron_sim {

// Feeds `data` to a StreamDecoder in two chunk layouts, to a driver Session and to a HeadEmulator. Aborts (so
// that the fuzzer records a crash) when: chunking changes the result, a decoded packet does not survive
// encode -> decode -> encode unchanged, or a beam leaves [0, 2pi) / has no bins. Returns the packets decoded.
std::size_t fuzzCodecOnce(const std::uint8_t* data, std::size_t n);

}  // namespace micron_sim
}  // namespace offshore_gnc

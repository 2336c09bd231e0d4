// The fuzz target's invariants (test/support/micron_sim/fuzz_check.h) over random and mutated SeaNet streams in the
// normal suite: the codec, the driver session and the head emulator on the same bytes.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "micron_sim/fuzz_check.h"
#include "offshore_gnc/micron/seanet.h"
#include "offshore_gnc/micron/session.h"

using namespace offshore_gnc;
using namespace offshore_gnc::micron;
using offshore_gnc::micron_sim::fuzzCodecOnce;

TEST(SeaNetFuzz, RandomAndMutatedStreamsKeepTheInvariants) {
  std::mt19937 rng(7);
  std::string seed = encode(fromSonar(Alive{0, 1, 3200, 0x8A}));
  HeadData h;
  h.hd_ctrl = kAdc8On;
  h.data.assign(50, 100);
  seed += encode(fromSonar(h)) + encode(fromPc(SonarSettings{}.headCommand())) + encode(fromSonar(VersionData{}));
  for (int i = 0; i < 300; ++i) {
    std::string s = seed;
    const int edits = 1 + static_cast<int>(rng() % 8);
    for (int k = 0; k < edits; ++k) s[rng() % s.size()] = static_cast<char>(rng() % 256);
    fuzzCodecOnce(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
    std::string r(rng() % 300, '\0');
    for (auto& c : r) c = static_cast<char>(rng() % 4 == 0 ? '@' : rng() % 256);
    fuzzCodecOnce(reinterpret_cast<const std::uint8_t*>(r.data()), r.size());
  }
  EXPECT_GE(fuzzCodecOnce(reinterpret_cast<const std::uint8_t*>(seed.data()), seed.size()), 4u);
}

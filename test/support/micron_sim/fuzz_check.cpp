// Invariants of the SeaNet codec and the Micron driver on arbitrary bytes (test/support/micron_sim/fuzz_check.h).
#include "micron_sim/fuzz_check.h"

#include <cmath>
#include <cstdlib>
#include <vector>

#include "offshore_gnc/micron_sim/emulator.h"
#include "offshore_gnc/micron/seanet.h"
#include "offshore_gnc/micron/session.h"

namespace offshore_gnc {
namespace micron_sim {

using namespace micron;

namespace {
std::vector<std::string> decodeAll(const std::uint8_t* data, std::size_t n, std::size_t chunk) {
  StreamDecoder d;
  std::vector<StreamDecoder::Event> ev;
  for (std::size_t i = 0; i < n; i += chunk) d.feed(data + i, std::min(chunk, n - i), ev);
  std::vector<std::string> out;
  for (const auto& e : ev) out.push_back(e.message ? encode(*e.message) : "!" + e.reason);
  return out;
}
}  // namespace

std::size_t fuzzCodecOnce(const std::uint8_t* data, std::size_t n) {
  const auto whole = decodeAll(data, n, n ? n : 1);
  if (whole != decodeAll(data, n, 7)) std::abort();  // chunking must not matter
  std::size_t packets = 0;
  for (const auto& s : whole) {
    if (s[0] == '!') continue;
    ++packets;
    std::string reason;
    auto again = decodePacket(reinterpret_cast<const std::uint8_t*>(s.data()), s.size(), reason);
    if (!again || encode(*again) != s) std::abort();  // encode -> decode -> encode is stable
  }
  // The driver and the emulator take the same bytes without crashing; beams stay well-formed.
  Session session{SonarSettings{}};
  std::vector<Beam> beams;
  double t = 0.0;
  for (std::size_t i = 0; i < n; i += 64) {
    session.poll(t);
    session.feed(data + i, std::min<std::size_t>(64, n - i), t, beams);
    t += 0.3;
  }
  for (const auto& b : beams)
    if (!(b.bearing >= 0.0 && b.bearing < 2.0 * kPi) || b.intensities.empty() || !std::isfinite(b.range_resolution))
      std::abort();
  HeadEmulator emu(EmulatorConfig{}, sim::World{});
  emu.setVehicle(VehicleState{});
  t = 0.0;
  for (std::size_t i = 0; i < n; i += 64) {
    emu.receive(data + i, std::min<std::size_t>(64, n - i), t);
    emu.poll(t);
    t += 0.2;
  }
  return packets;
}

}  // namespace micron_sim
}  // namespace offshore_gnc

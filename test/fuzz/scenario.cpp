// libFuzzer target: arbitrary text through the scenario loader (parseScenario, map images resolved against
// config/scenarios/). A scenario is accepted with finite values or refused with a ConfigError; any other
// exception or a crash is a finding. Built and run by `scripts/fuzz scenario SECONDS`.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/sim/scenario.h"

using namespace offshore_gnc;

namespace {
[[noreturn]] void violated(const std::string& what) {
  std::fprintf(stderr, "scenario loader invariant violated: %s\n", what.c_str());
  std::abort();
}
bool finite(const Eigen::Vector2d& v) { return v.allFinite() && v.cwiseAbs().maxCoeff() <= 1e5; }
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::string base = std::getenv("FUZZ_SCENARIO_DIR") ? std::getenv("FUZZ_SCENARIO_DIR") : ".";
  sim::Scenario s;
  try {
    s = sim::parseScenario(std::string(reinterpret_cast<const char*>(data), size), base, "fuzz");
  } catch (const ConfigError&) {
    return 0;  // refused with a message naming the key: what a user should get
  } catch (const std::exception& e) {
    violated(std::string("an exception other than ConfigError escaped: ") + e.what());
  }
  if (!std::isfinite(s.origin.lat_deg) || !std::isfinite(s.origin.lon_deg) || !std::isfinite(s.usv.yaw) ||
      !finite({s.usv.north, s.usv.east}) || !finite({s.auv.north, s.auv.east}) || !std::isfinite(s.auv.depth))
    violated("an accepted scenario has a non-finite or out-of-area start");
  for (const auto& b : s.world.buoys)
    if (!finite(b.centre) || !(b.radius > 0)) violated("an accepted buoy is not finite");
  for (const auto& v : s.world.vessels) {
    if (!finite(v.centre) || !(v.length > 0) || !(v.width > 0) || !std::isfinite(v.yaw)) violated("vessel");
    const sim::VesselMotion& m = v.motion;
    if (!(m.speed >= 0 && m.speed <= 30) || !std::isfinite(m.course) ||
        (m.kind == sim::VesselMotion::Kind::kTrack && m.track.size() < 2))
      violated("an accepted vessel under way has a negative or non-finite speed or course, or a track of < 2 points");
    for (const auto& p : m.track)
      if (!finite(p)) violated("an accepted vessel's track has a point that is not finite");
  }
  for (const auto& w : s.world.walls)
    if (!finite(w.a) || !finite(w.b) || (w.b - w.a).norm() < 0.1) violated("an accepted wall is degenerate");
  for (const auto& t : s.world.targets)
    if (!t.position.allFinite() || t.position.z() < t.radius) violated("an accepted target is not under water");
  if (!s.map.empty() && s.map.data.size() != std::size_t(s.map.width) * std::size_t(s.map.height))
    violated("the occupancy grid's size does not match its dimensions");
  return 0;
}

// The mission's shared parts: phase names, holdPath (the AUV's and the USV's parts: mission_internal.h).
#include "offshore_gnc/mission/mission.h"

#include <cmath>

namespace offshore_gnc {
namespace mission {

namespace {
template <class Phase, std::size_t N>
std::optional<Phase> phaseFromString(const std::string& s, const Phase (&all)[N]) {
  for (Phase p : all)
    if (s == toString(p)) return p;
  return std::nullopt;
}
}  // namespace

const char* toString(AuvPhase p) {
  switch (p) {
    case AuvPhase::Idle: return "IDLE";
    case AuvPhase::Coverage: return "COVERAGE";
    case AuvPhase::TargetFound: return "TARGET_FOUND";
    case AuvPhase::NoTarget: return "NO_TARGET";
    case AuvPhase::Ascent: return "ASCENT";
    case AuvPhase::Surfaced: return "SURFACED";
    case AuvPhase::Recovered: return "RECOVERED";
  }
  return "?";
}

const char* toString(UsvPhase p) {
  switch (p) {
    case UsvPhase::StationKeeping: return "STATION_KEEPING";
    case UsvPhase::Transit: return "TRANSIT";
    case UsvPhase::Arrived: return "ARRIVED";
    case UsvPhase::Recovery: return "RECOVERY";
    case UsvPhase::Recovered: return "RECOVERED";
    case UsvPhase::Manual: return "MANUAL";
    case UsvPhase::PeerLost: return "PEER_LOST";
  }
  return "?";
}

std::optional<AuvPhase> auvPhaseFromString(const std::string& s) {
  static const AuvPhase all[] = {AuvPhase::Idle,    AuvPhase::Coverage, AuvPhase::TargetFound, AuvPhase::NoTarget,
                                 AuvPhase::Ascent, AuvPhase::Surfaced, AuvPhase::Recovered};
  return phaseFromString(s, all);
}

std::optional<UsvPhase> usvPhaseFromString(const std::string& s) {
  static const UsvPhase all[] = {UsvPhase::StationKeeping, UsvPhase::Transit, UsvPhase::Arrived, UsvPhase::Recovery,
                                 UsvPhase::Recovered,      UsvPhase::Manual,  UsvPhase::PeerLost};
  return phaseFromString(s, all);
}

std::vector<Eigen::Vector2d> holdPath(const Eigen::Vector2d& p, double heading, double lead_in) {
  if (!p.allFinite() || !std::isfinite(heading) || !(lead_in > 0.0)) return {};
  return {p - lead_in * Eigen::Vector2d(std::cos(heading), std::sin(heading)), p};
}

}  // namespace mission
}  // namespace offshore_gnc

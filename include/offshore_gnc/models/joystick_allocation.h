#pragma once
// The 3-axis joystick of the twin-waterjet USV onto its two jets, as the CCPilot display computer does it at the
// intermediate level (thesis 4.3.1): the CAN gateway runs it on the vessel, the USV model in simulation.
// - Surge asks for the thesis' force (Publication IV Table 2: |surge| -> rpm, the sign and bucket_band -> the
//   buckets); yaw for the moment the thesis' nozzles give (joystick -> nozzle lookup, eq. 3.25's sign) at the rpm.
//   The engines run at the rpm of max(|surge|, |sway|, yaw_rpm_share |yaw|) and the buckets are trimmed to keep
//   the surge force. Under way (|surge| >= bucket_band) with sway 0 the jets get what the thesis' model gave its
//   lumped jet (at the raised rpm), so Table 4.1's gains keep their meaning.
// - Sway (the third axis): both nozzles turned for a side force at the stern, the buckets moved differentially so
//   that its turning moment is cancelled (the differential-bucket scheme). Sway is linear in force: sway = +-1
//   is the largest side force the buckets can balance at the surge axis' full rpm (sideForceFull()), and the
//   engines run at the least rpm that gives the share asked for (dynamic positioning trims with small ones).
// - At low speed (the buckets near neutral) the yaw's moment comes first from the differential buckets, then the
//   nozzles, so that turning on the spot does not push the stern sideways; between, the two blend.
// - Saturation (a nozzle at its stop): the three axes are scaled down together until the jets can do it, so the
//   direction of the request is kept.
#include <Eigen/Core>

#include "offshore_gnc/models/usv.h"
#include "offshore_gnc/models/waterjets.h"

namespace offshore_gnc {
namespace models {

class JoystickAllocation {
 public:
  explicit JoystickAllocation(const UsvParams& p);  // validates p (ConfigError)
  // Per-jet set-points for a normalised joystick command (-1..1 per axis; outside clamped; NaN -> neutral).
  JetCommands allocate(const UsvCommand& c) const;
  // What the jets push at rest once their chains have settled on `c` (body X, Y, N).
  Eigen::Vector3d staticForce(const JetCommands& c) const;
  // The scale (0..1] allocate() applied to the last command (1: no saturation).
  double lastScale() const { return last_scale_; }
  // The side force of full sway (joystick sway +-1) at rest [N]; sway asks for a share of it in proportion.
  double sideForceFull() const { return side_full_; }
  // The joystick surge whose jets push `force` [N] ahead (< 0: astern) at rest, sway and yaw neutral: the
  // inverse of the surge axis (Table 2's rpm and the buckets), far from linear (dynamic positioning asks forces).
  double surgeFor(double force) const;

 private:
  bool tryAllocate(const UsvCommand& c, JetCommands& out) const;

  UsvParams p_;
  Lookup1D joy_rpm_, joy_nozzle_;
  JetForces forces_;
  double rpm_full_ = 0.0, side_full_ = 0.0;
  mutable double last_scale_ = 1.0;
};

}  // namespace models
}  // namespace offshore_gnc

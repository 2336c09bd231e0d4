#pragma once
// The USV's two waterjets one by one (UsvParams::propulsion = twin). Each jet sits at the stern (x = -l_pivot,
// y = -/+ jet_y for port / starboard) with its own engine rpm chain (eq. 3.24), nozzle (delay + first-order lag,
// eq. 3.25) and reversing bucket (continuous from full astern -1 through neutral 0 to full ahead +1, moving at
// most bucket_rate per second: an assumption, docs/models.md). Gross thrust per jet from Table 3.1 with the
// affinity law (eq. 3.11) and the nozzle efficiency (eq. 3.12). The nozzle turns the whole jet before the bucket,
// so its side force T sin(alpha) stays with the bucket neutral; the bucket only splits the flow ahead and astern:
// the longitudinal force is T cos(alpha) g(bucket), g = bucket ahead and reverse_efficiency x bucket astern.
// This is what lets a twin-jet boat hold station: buckets in unison give surge, nozzles in unison a side force
// at the stern, buckets moved differentially a turning moment (the differential-bucket patents, docs/models.md).
#include <array>

#include <Eigen/Core>

#include "offshore_gnc/models/blocks.h"

namespace offshore_gnc {
namespace models {

struct UsvParams;
Lookup2D makeThrustTable(const UsvParams& p);  // usv.h

// One jet's set-points: engine rpm, nozzle position P (-nozzle_max..nozzle_max, < 0 turns the boat to starboard,
// the sign of eq. 3.25's output) and bucket (-1 full astern .. +1 full ahead).
struct JetCommand {
  double rpm = 0.0, nozzle = 0.0, bucket = 0.0;
};
using JetCommands = std::array<JetCommand, 2>;  // 0 port, 1 starboard

struct JetState {
  double rpm = 0.0;     // engine speed [rev/min]
  double nozzle = 0.0;  // P_nozzle, -10000..10000 (< 0 turns to starboard)
  double bucket = 0.0;  // -1 full astern .. +1 full ahead
  double thrust = 0.0;  // this jet's longitudinal force after nozzle efficiency and bucket [N]
};

// The static force law of the jets, shared by the model and the joystick allocation (joystick_allocation.h).
class JetForces {
 public:
  explicit JetForces(const UsvParams& p);
  double grossThrust(double ur, double rpm, double nozzle) const;  // T: Table 3.1 x affinity x eq. 3.12 [N]
  double bucketGain(double bucket) const;                          // g(bucket)
  double angle(double nozzle) const;                               // alpha [rad]
  // Body force (X, Y, N) of the jets in `s` at relative surge speed ur.
  Eigen::Vector3d force(const std::array<JetState, 2>& s, double ur) const;
  double jetY(int i) const;  // lateral position of jet i (FRD, port < 0)

 private:
  double l_pivot_, jet_y_, reverse_efficiency_, nozzle_max_, nozzle_max_angle_, eff_a_, eff_b_;
  Lookup2D thrust_;
};

class TwinWaterjets {
 public:
  explicit TwinWaterjets(const UsvParams& p);
  void reset();  // idle rpm, nozzles centred, buckets neutral
  void setCommands(const JetCommands& c);  // clamped to the jets' ranges (callers reject NaN)
  void step(double t0, double dt);         // the chains advance over dt with the commands held
  Eigen::Vector3d force(double ur) const { return forces_.force(state_, ur); }
  const std::array<JetState, 2>& state() const { return state_; }
  const JetCommands& commands() const { return cmd_; }
  void updateThrust(double ur);  // JetState::thrust for the reports

 private:
  double rpm_min_, rpm_max_, nozzle_max_, bucket_rate_;
  JetForces forces_;
  JetCommands cmd_;
  std::array<JetState, 2> state_;
  std::array<TransferFunction, 2> rpm_tf_, nozzle_lag_;
  std::array<TransportDelay, 2> nozzle_delay_;
};

}  // namespace models
}  // namespace offshore_gnc

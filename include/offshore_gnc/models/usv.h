#pragma once
// Twin-waterjet USV model (thesis 3.2, Publications III and IV), ROS-free.
//
// Full model (UsvModelType::Dynamic3Dof): 3-DOF rigid body M nu' + D(nu_r) nu_r = tau + tau_wind (eq. 3.3-3.10,
// Tables 3.3, 3.4), integrated with RK4, driven by the waterjets:
// - UsvPropulsion::Twin (default): each jet on its own (models/waterjets.h: rpm chain, nozzle, reversing bucket,
//   side force), the joystick mapped onto both by the CCPilot's allocation (models/joystick_allocation.h), or
//   per-jet set-points (setJetCommands, as the jets' CAN frames carry them);
// - UsvPropulsion::Lumped (the thesis' eq. 3.13): joystick -> 1-D lookups -> engine rpm transfer function
//   (eq. 3.24) and nozzle delay + first-order lag (eq. 3.25) -> thrust per jet from a 2-D lookup (surge speed x
//   rpm, Table 3.1 + affinity law eq. 3.11) -> nozzle efficiency (eq. 3.12) -> tau = [2F, 0, -l_pivot sin(alpha)
//   2F]: no sway force and, with the bucket neutral, no moment.
// Simple model (UsvModelType::Nomoto): the same rpm and nozzle chains, then the identified surge transfer
// function u/rpm (eq. 3.23, 0.8 s delay) and Nomoto's r/P_nozzle (eq. 3.2), Table 3.2.
// Sign conventions: body x forward, y starboard, z down; yaw clockwise from north. Joystick yaw +1 turns to
// starboard (r > 0); as in eq. 3.25 the nozzle position is the negated lookup value, so P_nozzle < 0 turns to
// starboard (Nomoto K_p < 0 in Table 3.2) and tau_r = -l_pivot sin(alpha) F E.
#include <array>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/models/blocks.h"
#include "offshore_gnc/models/environment.h"
#include "offshore_gnc/models/state.h"
#include "offshore_gnc/models/waterjets.h"

namespace offshore_gnc {
namespace models {

enum class UsvModelType { Dynamic3Dof, Nomoto };
enum class UsvPropulsion { Twin, Lumped };

struct UsvParams {
  UsvModelType type = UsvModelType::Dynamic3Dof;
  UsvPropulsion propulsion = UsvPropulsion::Twin;  // the Nomoto model always uses the lumped chains
  // Table 3.3
  double mass = 3500.0, m_pt = 1100.0, m_hull = 2400.0, length = 8.0, l_pivot = 2.40, l_pt = 2.16;
  double kappa = 0.70, c_g = 0.30, i_cor = 0.6, x_g = 0.0425;
  // Table 3.4 (magnitudes are used: damping must dissipate, added mass adds; see docs/models.md)
  double X_u = -10.586, X_udot = -3277.0, X_uu = 315.45;
  double N_r = 3907.9, N_rdot = -36.555, N_rr = 3459.6;
  // Sway is not identified in the thesis ("-" in Table 3.4): assumed values (docs/models.md).
  double Y_v = -100.0, Y_vdot = -1750.0, Y_vv = -3000.0, Y_r = 0.0, Y_rdot = 0.0;
  // Waterjets: Table 3.1 at the reference rpm, affinity law over [rpm_min, rpm_max] (eq. 3.11).
  std::vector<double> table_speed_kt{2.0, 4.0, 6.0};
  std::vector<double> table_thrust_kn{2.0, 1.85, 1.7};
  double rpm_ref = 1800.0, rpm_min = 600.0, rpm_max = 2400.0;
  // 1-D lookups (Publication IV Table 2): joystick counts -> rpm and -> nozzle position. A normalised
  // joystick of 1 is joy_u_full / joy_r_full counts. (0, rpm_min) is our idle point.
  std::vector<double> joy_u{0, 400, 500, 600, 700, 800, 900, 1000};
  std::vector<double> joy_u_rpm{600, 690, 920, 1110, 1300, 1480, 1650, 1820};
  std::vector<double> joy_r{0, 50, 150, 200, 250, 300, 400};
  std::vector<double> joy_r_nozzle{0, 1175, 3500, 4665, 5830, 7000, 9325};
  double joy_u_full = 1000.0, joy_r_full = 400.0;
  // Reversing bucket (assumed): bucket = clamp(surge / bucket_band, -1, 1); astern thrust is
  // reverse_efficiency x ahead thrust. Zero surge = bucket neutral = no net thrust at idle.
  double bucket_band = 0.1, reverse_efficiency = 0.45;
  // Twin jets (assumed for the 8 m hull, docs/models.md): jets +-jet_y from the centreline at x = -l_pivot; a
  // bucket moves at most bucket_rate per second (full ahead to full astern, 2 units, in 2 s).
  double jet_y = 0.45, bucket_rate = 1.0;
  // The joystick allocation runs the engines at least at the rpm of yaw_rpm_share x |yaw| on the surge axis (the
  // nozzles' moment grows with the thrust; the buckets keep the surge force): steering at any speed.
  double yaw_rpm_share = 0.8;
  // Engine rpm transfer function (eq. 3.24) and nozzle chain (eq. 3.25)
  std::vector<double> rpm_num{0.317, 2.793, 1.828}, rpm_den{1.0, 3.499, 1.828};
  double nozzle_delay = 0.25, nozzle_time_constant = 0.1;
  double nozzle_max = 10000.0, nozzle_max_angle = 0.436332313;  // P = 10000 <-> 25 deg
  double nozzle_eff_a = 1.0, nozzle_eff_b = -9.163e-5;            // eq. 3.12 (applied to |P|)
  // Table 3.2 (Nomoto model)
  double surge_kp = 2.930e-3, surge_tz = 0.17563, surge_tp1 = 4.08900, surge_tp2 = 0.17299, surge_td = 0.8;
  double yaw_kp = -3.177e-5, yaw_tz = 0.09835, yaw_tp1 = 1.81108, yaw_tp2 = 0.00144;
  // Wind (assumed hull/superstructure): projected areas [m^2] and coefficients
  double wind_area_front = 4.0, wind_area_side = 10.0, wind_cx = 0.6, wind_cy = 0.8, wind_cn = 0.08;
  double max_step = 0.02;  // largest RK4 sub-step [s]

  double inertiaZ() const;  // I_z from eq. 3.5-3.7 (11,284.61 kg m^2 with Table 3.3)
  void validate() const;    // throws ConfigError naming the bad value
};

// Normalised joystick, same meaning as offshore_gnc/JoystickCommand: surge -1 astern..+1 ahead, sway
// (no effect: the waterjets give no sway force, tau = [tau_u, 0, tau_r]), yaw -1 port..+1 starboard.
struct UsvCommand {
  double surge = 0.0, sway = 0.0, yaw = 0.0;
};


// The 2-D thrust table of one jet (Table 3.1 over surge speed, linearly extrapolated, x the affinity law eq. 3.11).
Lookup2D makeThrustTable(const UsvParams& p);

class JoystickAllocation;

class UsvModel {
 public:
  explicit UsvModel(const UsvParams& p);  // validates (ConfigError)
  ~UsvModel();
  // Low-frequency state (wave motion removed), jets at idle with bucket and nozzle neutral, and the command
  // reset to neutral. Velocities are kept (initial speed allowed) and the engine chain is at equilibrium.
  void reset(const VehicleState& s);
  // Overwrites the low-frequency position, yaw and (3-DOF model) velocities, keeping time, command and the
  // waterjet chain: restarts a run from a measured state in mid-log (model identification). The Nomoto model's
  // velocities are its transfer functions' outputs and are kept. Non-finite: counted ("rejected_states").
  void setState(const VehicleState& s);
  // Accepts a command for the next steps. NaN/inf: rejected, counted ("rejected_commands"), previous kept.
  // Outside [-1, 1]: clamped and counted ("clamped_commands").
  bool setCommand(const UsvCommand& c);
  // Per-jet set-points (twin propulsion; the jets' own CAN frames). NaN: rejected and counted; outside the
  // ranges: clamped and counted. With lumped propulsion: rejected ("unsupported_jet_commands").
  bool setJetCommands(const JetCommands& c);
  // Advance dt (> 0, finite; otherwise counted as "rejected_steps" and nothing happens).
  void step(double dt, const Environment& env);
  bool step(double dt, const UsvCommand& c, const Environment& env) {
    const bool ok = setCommand(c);
    step(dt, env);
    return ok;
  }
  // Reported state: low-frequency motion + wave-frequency motion (what the sensors see).
  const VehicleState& state() const { return out_; }
  const VehicleState& lowFrequencyState() const { return lf_; }
  JetState jet(int i) const;  // 0 port, 1 starboard
  const Eigen::Vector3d& tau() const { return tau_; }          // propulsion [X N, Y N, N Nm] last step
  const Eigen::Vector3d& tauWind() const { return tau_wind_; }
  const Eigen::Vector2d& waveDrift() const { return drift_; }  // mean wave drift force, NED [N], last step
  // What the waves act on: the thesis' 8 m hull (Table 3.3's length); beam 2.5 m and draft 0.5 m are our estimates
  // for an 8 m waterjet workboat (not given in the thesis).
  static Hull hull(const UsvParams& p) { return Hull{p.length, 2.5, 0.5}; }
  const UsvCommand& command() const { return cmd_; }
  const Counters& counters() const { return counters_; }
  const UsvParams& params() const { return p_; }

  // Exposed pieces of the waterjet chain (tests, tools, the control engineer's feed-forward).
  double jetThrust(double surge_speed, double rpm) const;  // one jet, nozzle neutral, bucket up [N]
  double rpmSetpoint(double surge) const;                  // f(Joy_u) [rpm]
  double nozzleSetpoint(double yaw) const;                 // f(Joy_r) before eq. 3.25's minus sign
  double bucket(double surge) const;
  double nozzleEfficiency(double nozzle) const;

 private:
  void updateOutput(const Environment& env);
  UsvParams p_;
  Eigen::Matrix3d m_inv_;
  Lookup1D joy_rpm_, joy_nozzle_;
  Lookup2D thrust_;
  TransferFunction rpm_tf_, nozzle_lag_, surge_tf_, yaw_tf_;
  TransportDelay nozzle_delay_, surge_delay_;
  std::unique_ptr<JoystickAllocation> allocation_;  // twin propulsion only
  std::unique_ptr<TwinWaterjets> twin_;
  UsvCommand cmd_;
  VehicleState lf_, out_;
  std::array<JetState, 2> jets_;
  Eigen::Vector3d tau_ = Eigen::Vector3d::Zero(), tau_wind_ = Eigen::Vector3d::Zero();
  Eigen::Vector2d drift_ = Eigen::Vector2d::Zero();
  Counters counters_;
};

}  // namespace models
}  // namespace offshore_gnc

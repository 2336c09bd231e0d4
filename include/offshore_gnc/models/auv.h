#pragma once
// 4-DOF AUV model (surge, sway, heave, yaw; thesis 3.3, eq. 3.14-3.22, Tables 3.3 and 3.4), ROS-free:
// M nu' + D(nu_r) nu_r + g = tau, tau = T f (eq. 3.16), f from per-thruster 1-D lookup curves
// (normalised command -> N, asymmetric forward/reverse, saturated like the BlueRobotics T200 chart).
// Roll and pitch are held at zero. Body x forward, y starboard, z down; NED world.
#include <string>
#include <vector>

#include <Eigen/Core>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/models/blocks.h"
#include "offshore_gnc/models/environment.h"
#include "offshore_gnc/models/state.h"

namespace offshore_gnc {
namespace models {

enum class AuvType { Girona500, AColor };

struct Thruster {
  std::string name;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();        // from the centre of mass, body [m]
  Eigen::Vector3d direction = Eigen::Vector3d::UnitX();      // unit force per positive command, body
  // Curve: normalised command (-1..1, e.g. (PWM - 1500 us) / 400 us) -> thrust [N], increasing.
  std::vector<double> curve_command{-1.0, -0.75, -0.5, -0.25, -0.1, 0.1, 0.25, 0.5, 0.75, 1.0};
  std::vector<double> curve_thrust{-40.2, -29.0, -14.7, -3.9, 0.0, 0.0, 5.0, 18.6, 35.3, 51.5};
};

struct AuvParams {
  AuvType type = AuvType::Girona500;
  // Table 3.3 (Girona500)
  double mass = 180.0, volume = 0.1837, I_z = 40.70;
  double gravity = 9.81;
  // Table 3.4 (Girona500). Magnitudes are used (damping dissipates, added mass adds; docs/models.md).
  double X_u = 21.750, X_udot = -250.184, X_uu = 216.423;
  double Y_v = 6.192, Y_vdot = -580.969, Y_vv = 485.538;
  double Z_w = 92.657, Z_wdot = -471.215, Z_ww = 189.788;
  double N_r = 15.560, N_rdot = -44.297, N_rr = 69.364;
  // Thrusters in the order of eq. 3.18 (Girona500: T1 port surge, T2 starboard surge, T3/T4 heave, T5 sway).
  std::vector<Thruster> thrusters;
  double max_step = 0.02;  // largest RK4 sub-step [s]

  static AuvParams girona500();  // thesis numbers, eq. 3.18 geometry (l_y1 = l_y2 = 0.2432 m)
  static AuvParams aColor();     // 6 x T200 (4 vectored horizontal + 2 vertical); assumed masses, see docs
  void validate() const;         // throws ConfigError naming the bad value
  // Thruster configuration matrix T (4 x n; rows surge X, sway Y, heave Z, yaw N; column i = wrench of
  // 1 N on thruster i): [d_x, d_y, d_z, p_x d_y - p_y d_x]. Reproduces eq. 3.18 for girona500().
  Eigen::MatrixXd tcm() const;
  Eigen::VectorXd maxThrust() const;      // per thruster, max(|forward|, |reverse|) [N]
  double weight() const { return mass * gravity; }                // W (eq. 3.21)
  double buoyancy(double water_density) const { return water_density * gravity * volume; }  // B
};

// A flight controller's mixer (ArduSub's, as the aColor's Pixhawk runs it): normalised axis commands (surge, sway,
// heave, yaw; -1..1) to per-thruster commands, each thruster's factor per axis its column of the thruster
// configuration matrix normalised per axis; the sum clamped to -1..1. The simulator drives the aColor through it,
// and its control predicts its own speed through it.
Eigen::VectorXd mixAxes(const Eigen::MatrixXd& tcm, const Eigen::Vector4d& axes);

class AuvModel {
 public:
  explicit AuvModel(const AuvParams& p);  // validates (ConfigError)
  void reset(const VehicleState& s);      // low-frequency state; commands to zero
  int thrusters() const { return static_cast<int>(p_.thrusters.size()); }
  // Normalised per-thruster commands -1..1. Wrong size or NaN/inf: rejected and counted
  // ("rejected_commands"), previous kept. Outside [-1, 1]: clamped and counted ("clamped_commands").
  bool setCommand(const Eigen::VectorXd& thruster_commands);
  void step(double dt, const Environment& env);  // dt > 0 finite, else "rejected_steps"
  bool step(double dt, const Eigen::VectorXd& thruster_commands, const Environment& env) {
    const bool ok = setCommand(thruster_commands);
    step(dt, env);
    return ok;
  }
  double thrust(int i, double command) const;  // curve of thruster i [N] (command clamped to -1..1)
  // One step of the surge and sway equations through still water, decoupled, under a body force (X, Y) [N] from
  // the velocity v (surge, sway) [m/s]: (m - added mass) dv/dt = force - (|lin| + |quad| |v|) v, semi-implicit
  // (stable at any step: the aColor's surge time constant near full speed, 0.09 s, is shorter than a control
  // step). What a vehicle without a DVL predicts of its own speed from the commands it sends.
  Eigen::Vector2d waterVelocityStep(const Eigen::Vector2d& v, const Eigen::Vector2d& force, double dt) const;
  // Inverse curve: the command giving `thrust_n` on thruster i (just outside the dead band for small thrust,
  // clamped to -1..1 beyond saturation; 0 for 0 or non-finite). For allocation set-points and RC channels.
  double commandFor(int i, double thrust_n) const;
  const Eigen::MatrixXd& tcm() const { return tcm_; }
  const VehicleState& state() const { return out_; }  // low-frequency + wave motion
  const VehicleState& lowFrequencyState() const { return lf_; }
  const Eigen::VectorXd& command() const { return cmd_; }
  const Eigen::VectorXd& thrusterForces() const { return f_; }  // [N], last step
  Eigen::Vector4d tau() const { return tcm_ * f_; }              // [X, Y, Z, N]
  const Counters& counters() const { return counters_; }
  const AuvParams& params() const { return p_; }
  // What the waves act on, from the makers' data sheets: Girona500 1.5 x 1.0 x 1.0 m (IQUA Robotics), the aColor
  // BlueROV2 Heavy-class 0.46 x 0.58 x 0.25 m (Blue Robotics); draft: half its height, as it floats.
  static Hull hull(const AuvParams& p) {
    return p.type == AuvType::Girona500 ? Hull{1.5, 1.0, 0.5} : Hull{0.46, 0.58, 0.125};
  }
  const Eigen::Vector2d& waveDrift() const { return drift_; }  // NED [N], last step

 private:
  AuvParams p_;
  Eigen::MatrixXd tcm_;
  Eigen::Vector4d m_, d_lin_, d_quad_;
  std::vector<Lookup1D> curves_;
  Eigen::VectorXd cmd_, f_;
  Eigen::Vector2d drift_ = Eigen::Vector2d::Zero();
  VehicleState lf_, out_;
  Counters counters_;
};

}  // namespace models
}  // namespace offshore_gnc

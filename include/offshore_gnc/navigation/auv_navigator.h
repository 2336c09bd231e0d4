#pragma once
// AUV state estimation: a linear Kalman filter in local NED (x north, y east, z down) on position, NED velocity
// over ground and the horizontal water current, constant-velocity model. The absolute position comes from SeaTrac
// USBL fixes computed on the USV (placed by its GPS and heading) and relayed to the AUV, so they arrive 0.5-2 s
// after they were taken: the filter keeps the last history_s seconds of inputs with the state after each, rolls
// back to the fix's stamp, applies it and replays what came later. Velocity from the DVL (Girona500) or, without
// one (aColor), from its commands (the speed through the water they give): the current (a slowly
// varying state the fixes reveal) makes it the velocity over ground. Depth from the pressure sensor; yaw from the
// AHRS, less a heading bias the filter estimates (a magnetic compass is off by a degree or more: the DVL's or the
// commands' velocity then points that far off, and the fixes show the drift it causes). ROS-free; a nodelet wraps it.
#include <Eigen/Dense>

#include <array>
#include <deque>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/models/state.h"

namespace offshore_gnc {
namespace navigation {

struct AuvNavigatorConfig {
  double history_s = 10.0;            // inputs kept for delayed fixes (waits for the relayed USV pose) [s]
  double fix_timeout = 10.0;          // no accepted fix for longer: kFixLost [s]
  double heading_timeout = 1.0;       // no heading for longer: kNoHeading, DVL and commands unusable [s]
  double dvl_timeout = 1.0;           // no DVL sample for longer: the commanded-speed model takes over [s]
  double gate_chi2 = 16.27;           // Mahalanobis gate on fixes (chi-square, 3 dof, 99.9 %)
  int max_rejects_in_row = 5;         // after this many gated fixes in a row the next gated one re-initialises,
                                      // when they agree with each other (an outlier streak does not)
  int confirm_fixes = 2;              // a start is confirmed when this many fixes agree with it; before that the
                                      // second gated fix in a row re-initialises, if the two agree (a first fix
                                      // that was an outlier)
  double accel_psd_h = 0.05;          // white-acceleration spectral density, north and east [m^2/s^3]
  double accel_psd_v = 0.01;          // the same, down [m^2/s^3]
  double position_psd = 0.01;         // horizontal position random walk: unmodelled DVL/heading errors [m^2/s]
  double dvl_sigma = 0.03;            // DVL velocity noise, each axis [m/s]
  double depth_sigma = 0.05;          // depth sensor noise [m]
  double cmd_sigma = 0.3;             // commanded-speed model error, each horizontal axis, per command [m/s]
  double current_sigma = 0.3;         // the water current: its standard deviation (first-order Markov) [m/s]
  double current_tau = 3600.0;        // and its correlation time [s]
  double init_velocity_sigma = 1.0;   // velocity uncertainty at (re-)initialisation [m/s]
  double heading_bias_sigma = 0.035;  // the AHRS heading's bias: standard deviation (first-order Markov) [rad]
  double heading_bias_tau = 1800.0;   // and its correlation time [s]
  // Coming up within surface_depth, the wind sets the exposed hull: the drift learnt at depth no longer holds, and
  // the current's variance grows by surface_drift_sigma^2 once (an aColor's estimate stood still while the wind
  // drifted it 0.45 m/s, and the gate then refused the true fixes 14 m off). surface_drift_sigma 0: off.
  double surface_depth = kAuvSurfaceDepth;  // [m]
  double surface_drift_sigma = 0.5;         // [m/s]
  static const ParamTable<AuvNavigatorConfig>& table();
};

enum class NavStatus {
  kNoFix,      // never initialised: the estimate means nothing
  kOk,
  kFixLost,    // no fix accepted for fix_timeout: dead reckoning, the covariance grows
  kNoHeading,  // no heading for heading_timeout: velocity inputs cannot be rotated into NED
};

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;
// position (3), velocity over ground (3), horizontal current (2), AHRS heading bias (1)
constexpr int kNavStates = 9;
constexpr int kPos = 0, kVel = 3, kCur = 6, kBias = 8;
using NavVector = Eigen::Matrix<double, kNavStates, 1>;
using NavMatrix = Eigen::Matrix<double, kNavStates, kNavStates>;

struct AuvNavEstimate {
  double t = 0.0;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // NED [m]
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // NED [m/s]
  double yaw = 0.0, yaw_rate = 0.0;                    // the AHRS's less its estimated bias [rad], [rad/s]
  double heading_bias = 0.0, heading_bias_sigma = 0.0; // the AHRS heading's estimated bias, its sigma [rad]
  Matrix6d covariance = Matrix6d::Identity();          // of [position; velocity]
  Eigen::Vector2d current = Eigen::Vector2d::Zero();   // water current, north and east [m/s]
  Eigen::Matrix2d current_covariance = Eigen::Matrix2d::Identity();
  NavStatus status = NavStatus::kNoFix;
};

class AuvNavigator {
 public:
  explicit AuvNavigator(const AuvNavigatorConfig& cfg = AuvNavigatorConfig{});  // throws ConfigError

  // Every input returns false when refused (counted). Inputs may come out of order within history_s; one older
  // than that is refused (a fix, "fix_too_old") or taken as the clock going back (any other: "time_reset").
  // USBL fix taken at t_taken (NED position, its covariance). True when it went into the state.
  bool usblFix(double t_taken, const Eigen::Vector3d& ned, const Eigen::Matrix3d& cov);
  bool depth(double t, double z);                               // z down [m]
  bool heading(double t, double yaw, double yaw_rate);          // NED yaw [rad], rate [rad/s]
  bool dvl(double t, const Eigen::Vector3d& v_body);            // velocity over ground, body FRD [m/s]
  // Velocity through the water that the thrusters' commands give, body surge and sway [m/s] (no DVL: the aColor's
  // control predicts it from the channels it sends, following or holding; AcolorController::waterVelocity). Not
  // guidance's desired surge: a dynamic-positioning hold's thrust is no speed demand (its desired surge of 0 read
  // as "still in the water" made every fix's motion current; the aColor holding at the surface chased it 130 m).
  bool commandedVelocity(double t, double surge, double sway);
  // A GPS fix at the surface (the Girona500's), north and east [m] with its sigma per axis: a position fix like a
  // USBL one, horizontal only (the depth sensor gives the depth; the fix's is taken as unknown).
  bool gpsFix(double t, const Eigen::Vector2d& ne, double sigma);
  bool predict(double t);                                       // propagate the filter to t
  // The estimate at t (extrapolated from the latest state, or from the history for an earlier t); const.
  AuvNavEstimate estimate(double t) const;

  // "fix_accepted", "fix_rejected_gate", "fix_too_old", "bad_input", "reinit", "reinit_refused_scattered" (a
  // streak of gated fixes that did not agree with each other), "reinit_unconfirmed" (of the re-initialisations,
  // those of a start not yet confirmed), "time_reset", "velocity_without_heading". Each input is counted once, when it arrives, not again when replayed.
  const Counters& counters() const { return counters_; }
  const AuvNavigatorConfig& config() const { return cfg_; }

 private:
  struct Filter {
    double t = -1e300;  // time of x and P
    bool initialised = false;
    NavVector x = NavVector::Zero();
    NavMatrix P = NavMatrix::Identity();
    double yaw = 0.0, yaw_rate = 0.0;
    double heading_t = -1e300, dvl_t = -1e300, fix_t = -1e300;
    int rejects_in_row = 0;
    int agreeing = 0;  // fixes accepted since the latest (re-)initialisation, that one included
    bool at_surface = false;  // within surface_depth (its drift re-learnt once on arrival)
    // The innovations of the latest gated fixes in a row (ring by rejects_in_row) and their variance: a
    // re-initialisation needs them to agree, i.e. the estimate is off, not the fixes scattered.
    std::array<Eigen::Vector4d, 8> streak{};
  };
  enum class Kind { kFix, kDepth, kHeading, kDvl, kCommand, kPredict };
  struct Input {
    Kind kind;
    double t;
    Eigen::Vector3d v = Eigen::Vector3d::Zero();  // fix position, DVL velocity
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();  // fix covariance
    double a = 0.0, b = 0.0;                      // depth, yaw / yaw rate, surge / sway
  };
  struct Entry {
    Input in;
    Filter after;
  };

  bool submit(const Input& in);
  bool apply(Filter& f, const Input& in, bool first);
  bool applyFix(Filter& f, const Input& in, bool first);
  void propagate(Filter& f, double t) const;
  bool streakAgrees(const Filter& f, int n) const;
  template <int M>
  void update(Filter& f, const Eigen::Matrix<double, M, kNavStates>& H, const Eigen::Matrix<double, M, 1>& innovation,
              const Eigen::Matrix<double, M, M>& R) const;
  bool headingAt(const Filter& f, double t, double& yaw) const;
  void count(bool first, const char* name) {
    if (first) counters_.increment(name);
  }
  bool refuse(bool first, const char* name) {  // count and return false
    count(first, name);
    return false;
  }

  AuvNavigatorConfig cfg_;
  Filter state_;  // after the newest entry (== history_.back().after, or base_ when the history is empty)
  Filter base_;   // before the oldest entry
  std::deque<Entry> history_;
  double latest_t_ = -1e300;  // newest input stamp seen
  Counters counters_;
};

}  // namespace navigation
}  // namespace offshore_gnc

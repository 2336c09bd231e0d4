// model_manoeuvre: command CSVs for the standard identification runs, in the format model_run and sim_log take
// (USV: t,surge,sway,yaw normalised joystick; AUV: t,c1..cn normalised thruster commands).
//   model_manoeuvre --vehicle usv|girona500|acolor --params FILE.yaml [--plan ITEM[,ITEM...]] [--duration S]
//                   [--period S] [--seed N] [--output FILE.csv|-]
// ITEM is NAME or NAME@SURGE (the cruise surge command of that item, default 0.6):
//   steps     surge steps from rest (0.3, 0.8, 0.5, 1.0, 0.6; 25 s each)
//   zigzag10  10/10 zig-zag: nozzle (USV) at +-10 deg, switched when the heading has changed +-10 deg; 6 switches
//   zigzag20  20/20 zig-zag (the AUV's "rudder" is a yaw moment of 40 % / 80 % of its maximum)
//   turn      turning circle: full yaw for 400 deg to starboard, then to port
//   prbs      pseudo-random binary sequences on surge (+-0.2 about the cruise, 0.5 s clock) and yaw (+-0.4, 2 s), 120 s
//   sway, heave  (AUV) steps of the sway / heave force
//   standard  USV: steps,zigzag10@0.4,prbs,zigzag20@1,turn@0.3,zigzag20@0.6,turn@1 (several speeds); AUV: steps,zigzag10,turn,sway,heave,prbs
// --duration repeats the plan until that many seconds (cut there). Heading switches are timed on the model of
// --params in calm water: on another boat the angles differ a little, which still excites the same dynamics.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/QR>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/models/cli.h"
#include "offshore_gnc/models/auv.h"
#include "offshore_gnc/models/params_yaml.h"
#include "offshore_gnc/models/usv.h"

using namespace offshore_gnc;
using namespace offshore_gnc::models;

namespace {

int usage(const std::string& msg) {
  std::cerr << "model_manoeuvre: " << msg << "\n"
            << "usage: model_manoeuvre --vehicle usv|girona500|acolor --params FILE.yaml [--plan ITEM[,ITEM...]]\n"
               "                       [--duration S] [--period S] [--seed N] [--output FILE.csv|-]\n"
               "  ITEM = steps | zigzag10 | zigzag20 | turn | prbs | sway | heave | standard, optionally @SURGE\n";
  return 2;
}

// Maximal-length 9-bit LFSR (x^9 + x^5 + 1): the classic PRBS of identification experiments.
class Prbs {
 public:
  explicit Prbs(unsigned seed) : s_((seed % 511u) + 1u) {}
  bool next() {
    const unsigned bit = ((s_ >> 8) ^ (s_ >> 4)) & 1u;
    s_ = ((s_ << 1) | bit) & 0x1ffu;
    return bit != 0;
  }

 private:
  unsigned s_;
};

// A vehicle driven by generalised commands (surge, sway, heave, yaw in -1..1), simulated in calm water so that
// the heading-based switches of the zig-zag and the turn can be timed.
class Driver {
 public:
  virtual ~Driver() = default;
  virtual void command(double surge, double sway, double heave, double yaw, double rudder_deg) = 0;
  virtual void advance(double dt) = 0;
  virtual double yaw() const = 0;
  virtual std::string header() const = 0;
  virtual std::string row() const = 0;  // the current command, CSV
};

class UsvDriver : public Driver {
 public:
  explicit UsvDriver(const UsvParams& p) : m_(p), p_(p) { m_.reset(VehicleState()); }
  // rudder_deg != 0: the yaw command that puts the nozzle at that angle (inverse of the Table 2 lookup).
  void command(double surge, double, double, double yaw, double rudder_deg) override {
    if (rudder_deg != 0.0) yaw = std::copysign(yawForNozzleAngle(std::abs(rudder_deg)), rudder_deg);
    c_ = {std::clamp(surge, -1.0, 1.0), 0.0, std::clamp(yaw, -1.0, 1.0)};
    m_.setCommand(c_);
  }
  void advance(double dt) override { m_.step(dt, env_); }
  double yaw() const override { return m_.state().yaw; }
  std::string header() const override { return "t,surge,sway,yaw"; }
  std::string row() const override {
    char b[96];
    std::snprintf(b, sizeof b, "%.4f,%.4f,%.4f", c_.surge, c_.sway, c_.yaw);
    return b;
  }

 private:
  double yawForNozzleAngle(double deg) const {
    const double target = p_.nozzle_max * deg2rad(deg) / p_.nozzle_max_angle;
    for (double y = 0.0; y <= 1.0; y += 1e-4)
      if (m_.nozzleSetpoint(y) >= target) return y;
    return 1.0;
  }
  UsvModel m_;
  UsvParams p_;
  Environment env_;
  UsvCommand c_;
};

class AuvDriver : public Driver {
 public:
  explicit AuvDriver(const AuvParams& p) : m_(p), p_(p), pinv_(m_.tcm().completeOrthogonalDecomposition().pseudoInverse()) {
    VehicleState s;
    s.position.z() = 3.0;  // identification runs are done submerged
    m_.reset(s);
    const Eigen::VectorXd fmax = p_.maxThrust();
    for (int a = 0; a < 4; ++a) {  // largest force along each axis alone within every thruster's limit
      const Eigen::VectorXd f = pinv_.col(a);
      double s = 1e300;
      for (int i = 0; i < f.size(); ++i)
        if (std::abs(f(i)) > 1e-12) s = std::min(s, fmax(i) / std::abs(f(i)));
      axis_max_(a) = s < 1e300 ? s : 0.0;
    }
    trim_ = p_.buoyancy(1000.0) - p_.weight();  // heave force that holds depth (eq. 3.21, 3.22)
    cmd_ = Eigen::VectorXd::Zero(m_.thrusters());
  }
  void command(double surge, double sway, double heave, double yaw, double rudder_deg) override {
    if (rudder_deg != 0.0) yaw = std::clamp(rudder_deg / 25.0, -1.0, 1.0);
    const Eigen::Vector4d tau(surge * axis_max_(0), sway * axis_max_(1), trim_ + heave * axis_max_(2),
                              yaw * axis_max_(3));
    Eigen::VectorXd f = pinv_ * tau;
    const Eigen::VectorXd fmax = p_.maxThrust();
    double over = 1.0;
    for (int i = 0; i < f.size(); ++i) over = std::max(over, std::abs(f(i)) / fmax(i));
    f /= over;
    for (int i = 0; i < f.size(); ++i) cmd_(i) = m_.commandFor(i, f(i));
    m_.setCommand(cmd_);
  }
  void advance(double dt) override { m_.step(dt, env_); }
  double yaw() const override { return m_.state().yaw; }
  std::string header() const override {
    std::string h = "t";
    for (int i = 0; i < m_.thrusters(); ++i) h += ",c" + std::to_string(i + 1);
    return h;
  }
  std::string row() const override {
    std::string r;
    char b[32];
    for (int i = 0; i < cmd_.size(); ++i) {
      std::snprintf(b, sizeof b, "%s%.4f", i ? "," : "", cmd_(i));
      r += b;
    }
    return r;
  }

 private:
  AuvModel m_;
  AuvParams p_;
  Eigen::MatrixXd pinv_;
  Eigen::Vector4d axis_max_ = Eigen::Vector4d::Zero();
  double trim_ = 0.0;
  Environment env_;
  Eigen::VectorXd cmd_;
};

class Plan {
 public:
  Plan(Driver& d, double period, double duration, std::ostream& out, unsigned seed)
      : d_(d), period_(period), duration_(duration), out_(out), prbs_(seed) {
    out_ << d_.header() << "\n";
  }
  bool full() const { return duration_ > 0 && t_ >= duration_ - 1e-9; }

  // Holds the command for `seconds`, one row per period; stops early when `until` says so. False when full.
  template <class Until>
  bool hold(double seconds, Until until) {
    for (double e = 0; e < seconds - 1e-9; e += period_) {
      if (full()) return false;
      out_ << fmt(t_) << "," << d_.row() << "\n";
      d_.advance(period_);
      t_ += period_;
      if (until()) break;
    }
    return !full();
  }
  bool hold(double seconds) {
    return hold(seconds, [] { return false; });
  }
  void set(double surge, double yaw, double rudder = 0, double sway = 0, double heave = 0) {
    d_.command(surge, sway, heave, yaw, rudder);
  }

  bool run(const std::string& name, double surge, bool auv) {
    if (name == "steps") {
      for (double s : {0.0, 0.3, 0.8, 0.5, 1.0, 0.6}) {
        set(s, 0);
        if (!hold(s == 0.0 ? 5.0 : 25.0)) return false;
      }
      return true;
    }
    if (name == "zigzag10" || name == "zigzag20") {
      const double a = name == "zigzag10" ? 10.0 : 20.0;
      set(surge, 0);
      if (!hold(20.0)) return false;  // approach: steady on course
      const double course = d_.yaw();
      double side = 1.0;
      for (int k = 0; k < 6; ++k) {
        set(surge, 0, side * a);
        const double s = side;
        if (!hold(120.0, [&] { return s * rad2deg(wrapAngle(d_.yaw() - course)) >= a; })) return false;
        side = -side;
      }
      set(surge, 0);
      return hold(15.0);
    }
    if (name == "turn") {
      for (double side : {1.0, -1.0}) {
        set(surge, 0);
        if (!hold(15.0)) return false;
        set(surge, side);
        double turned = 0, last = d_.yaw();
        if (!hold(300.0, [&] {
              turned += std::abs(wrapAngle(d_.yaw() - last));
              last = d_.yaw();
              return rad2deg(turned) >= 400.0;
            }))
          return false;
      }
      set(surge, 0);
      return hold(15.0);
    }
    if (name == "prbs") {  // surge clocked at 0.5 s (the engine's 1-4 rad/s), yaw at 2 s (the hull's)
      double yaw = 0.4;
      for (int k = 0; k < 240; ++k) {
        if (k % 4 == 0) yaw = prbs_.next() ? 0.4 : -0.4;
        set(std::clamp(surge + (prbs_.next() ? 0.2 : -0.2), 0.1, 1.0), yaw);
        if (!hold(0.5)) return false;
      }
      return true;
    }
    if (auv && (name == "sway" || name == "heave")) {
      for (double l : {0.5, -0.5, 0.8, 0.0, -0.8, 0.3, 0.0}) {
        if (name == "sway") set(0, 0, 0, l, 0);
        else set(0, 0, 0, 0, l);
        if (!hold(15.0)) return false;
      }
      return true;
    }
    throw ConfigError("unknown manoeuvre '" + name + "'" + (auv ? "" : " for the usv"));
  }

 private:
  static std::string fmt(double t) {
    char b[32];
    std::snprintf(b, sizeof b, "%.2f", t);
    return b;
  }
  Driver& d_;
  double period_, duration_, t_ = 0;
  std::ostream& out_;
  Prbs prbs_;
};

}  // namespace

int main(int argc, char** argv) {
  std::string vehicle, params, plan = "standard", output = "-";
  double period = 0.1, duration = 0;
  unsigned seed = 1;
  double seed_n = 1;
  const std::string err = CliOptions()
                              .text("--vehicle", &vehicle)
                              .text("--params", &params)
                              .text("--plan", &plan)
                              .text("--output", &output)
                              .number("--period", &period, 0.01, 10)
                              .number("--duration", &duration, 0, 1e6)
                              .number("--seed", &seed_n, 0, 1e9)
                              .parse(argc, argv);
  if (err == "help") return usage(err), 0;
  if (!err.empty()) return usage(err);
  seed = static_cast<unsigned>(seed_n);
  if (params.empty()) return usage("--params is required");
  try {
    std::unique_ptr<Driver> d;
    const bool auv = vehicle != "usv";
    if (vehicle == "usv") d = std::make_unique<UsvDriver>(loadUsvParams(params));
    else if (vehicle == "girona500" || vehicle == "acolor") d = std::make_unique<AuvDriver>(loadAuvParams(params));
    else return usage("--vehicle must be usv, girona500 or acolor");
    std::vector<std::string> items;
    std::stringstream ss(plan);
    for (std::string it; std::getline(ss, it, ',');) {
      if (it == "standard") {
        const char* usv_std[] = {"steps", "zigzag10@0.4", "prbs", "zigzag20@1", "turn@0.3", "zigzag20@0.6", "turn@1"};
        const char* auv_std[] = {"steps", "zigzag10", "turn", "sway", "heave", "prbs"};
        if (auv) items.insert(items.end(), std::begin(auv_std), std::end(auv_std));
        else items.insert(items.end(), std::begin(usv_std), std::end(usv_std));
      } else {
        items.push_back(it);
      }
    }
    std::ofstream f;
    if (output != "-") {
      f.open(output);
      if (!f) throw ConfigError(output + ": cannot open the file for writing");
    }
    std::ostream& out = output == "-" ? std::cout : f;
    Plan p(*d, period, duration, out, seed);
    do {
      for (const auto& it : items) {
        const auto at = it.find('@');
        const double surge = at == std::string::npos ? 0.6 : requireRange("surge of " + it, std::stod(it.substr(at + 1)), -1, 1);
        if (!p.run(it.substr(0, at), surge, auv)) break;
      }
    } while (duration > 0 && !p.full());
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "model_manoeuvre: " << e.what() << "\n";
    return 1;
  }
}

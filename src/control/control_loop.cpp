#include "offshore_gnc/control/control_loop.h"

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace control {

const ParamTable<ControlLoopParams>& ControlLoopParams::table() {
  using P = ControlLoopParams;
  static const ParamTable<P> t = ParamTable<P>()
      .choice("vehicle", &P::vehicle, {"usv", "girona500", "acolor"}, "vehicle whose controller runs")
      .number("rate", &P::rate, 0.1, 200.0, "Hz", "control steps per second")
      .number("input_timeout", &P::input_timeout, 0.01, 60.0, "s",
              "older guidance reference or navigation: neutral command");
  return t;
}

const std::vector<ReconfigureGroup>& ControlLoopParams::reconfigurable() {
  static const std::vector<ReconfigureGroup> g = [] {
    ReconfigureGroup pid{"pid", {}};
    // the USV's surge, every vehicle's yaw, the Girona500's position, the aColor's heave
    for (const char* axis : {"surge", "yaw", "north", "east", "down", "heave"})
      for (const char* gain : {"kp", "ki", "kd"}) pid.params.push_back(std::string(axis) + "/" + gain);
    return std::vector<ReconfigureGroup>{pid, {"usv", {"filter/tf", "filter/xi"}}};
  }();
  return g;
}

void ControlLoopParams::validate() const {
  table().validate(*this);
  if (vehicle == "usv") usv.validate();
  else if (vehicle == "girona500") girona500.validate();
  else acolor.validate();
}

ControlLoop::ControlLoop(const ControlLoopParams& p) : p_(p) {
  p_.usv.dt = p_.girona500.dt = p_.acolor.dt = 1.0 / p_.rate;
  p_.validate();
  if (p_.vehicle == "usv") usv_ = std::make_unique<UsvController>(p_.usv);
  else if (p_.vehicle == "girona500") g500_ = std::make_unique<Girona500Controller>(p_.girona500);
  else acolor_ = std::make_unique<AcolorController>(p_.acolor);
}

void ControlLoop::setParams(const ControlLoopParams& p) {
  if (p.vehicle != p_.vehicle) throw ConfigError("parameter 'vehicle' cannot change at run time");
  ControlLoopParams q = p;
  q.usv.dt = q.girona500.dt = q.acolor.dt = 1.0 / q.rate;
  q.validate();
  if (usv_) usv_->setParams(q.usv);
  if (g500_) g500_->setParams(q.girona500);
  if (acolor_) acolor_->setParams(q.acolor);
  p_ = q;
}

void ControlLoop::onReference(const MotionReference& r, double t) {
  ref_ = r;
  ref_t_ = t;
  have_ref_ = true;
}

void ControlLoop::onState(const VehicleState& s, double t) {
  state_ = s;
  state_t_ = t;
  have_state_ = true;
}

void ControlLoop::onFixLost(bool lost) {
  if (acolor_) acolor_->setFixLost(lost);
}

const char* safetyOverrideName(SafetyOverride o) {
  switch (o) {
    case SafetyOverride::kNone: return "none";
    case SafetyOverride::kHold: return "hold";
    case SafetyOverride::kNeutral: return "neutral";
    case SafetyOverride::kSurface: return "surface";
  }
  return "?";
}

SafetyOverride safetyOverrideOf(SupervisorAction action, bool manual) {
  using A = SupervisorAction;
  if (manual) return SafetyOverride::kNone;
  switch (action) {
    case A::kHold: return SafetyOverride::kHold;
    case A::kNeutral: return SafetyOverride::kNeutral;
    case A::kSurface:
    case A::kAbort: return SafetyOverride::kSurface;
    default: return SafetyOverride::kNone;
  }
}

void ControlLoop::setSafety(SafetyOverride o, const std::string& reason) {
  if (o != safety_) have_hold_ = false;  // a new override holds where the vehicle then is
  safety_ = o;
  safety_reason_ = reason;
}

const Counters& ControlLoop::controllerCounters() const {
  return usv_ ? usv_->counters() : g500_ ? g500_->counters() : acolor_->counters();
}

ActuatorCommand ControlLoop::update(double t) {
  MotionReference r;  // idle = neutral
  ActuatorCommand out;
  if (!have_ref_ || !have_state_) {
    why_ = "waiting for guidance status and odometry";
  } else if (t - ref_t_ > p_.input_timeout || t - state_t_ > p_.input_timeout) {
    counters_.increment("stale_input");
    why_ = "guidance status or odometry stale";
  } else if (!ref_.valid()) {
    counters_.increment("bad_reference");
    why_ = "bad guidance reference";
  } else {
    r = ref_;
    why_.clear();
    out.active = true;
  }
  if (safety_ != SafetyOverride::kNone) {
    const bool neutral = safety_ == SafetyOverride::kNeutral || (safety_ == SafetyOverride::kSurface && usv_) ||
                         !have_state_ || !isFinite(state_);
    if (neutral) {
      r = MotionReference();
      out.active = false;
    } else {
      if (!have_hold_) {  // where the vehicle is when the override begins (or when it first has a state)
        hold_ = MotionReference();
        hold_.mode = ReferenceMode::kHold;
        hold_.point = state_.position;
        hold_.heading = hold_.path_angle = state_.yaw;
        hold_.depth = safety_ == SafetyOverride::kSurface ? 0.0 : state_.position.z();
        have_hold_ = true;
      }
      r = hold_;
      out.active = true;
    }
    why_ = std::string("safety ") + safetyOverrideName(safety_) + ": " + safety_reason_;
  }
  if (usv_) out.joystick = usv_->update(state_, r);
  else if (g500_) {
    out.thrusters = g500_->update(state_, r);
    out.water_velocity = g500_->waterVelocity();
  } else {
    out.rc = acolor_->update(state_, r);
    out.water_velocity = acolor_->waterVelocity();
  }
  return out;
}

}  // namespace control
}  // namespace offshore_gnc

#pragma once
// The control of one vehicle as it runs on board: the guidance reference and the navigation state in (each with
// the time it came), the actuator command out at the control rate. Stale or missing input, or a reference that
// is not finite, gives the neutral command and says why; the vehicle's controller is one of the three of
// vehicle_control.h. The Control nodelet and the ROS-free loops both run exactly this. ROS-free.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/common/reconfigure_form.h"
#include "offshore_gnc/control/vehicle_control.h"
#include "offshore_gnc/models/reference.h"
#include "offshore_gnc/models/state.h"

namespace offshore_gnc {
namespace control {

struct ControlLoopParams {
  std::string vehicle = "usv";  // usv | girona500 | acolor
  double rate = 10.0;           // control steps per second [Hz]
  double input_timeout = 1.0;   // older guidance reference or navigation -> neutral [s]
  UsvControlParams usv;
  Girona500ControlParams girona500;
  AcolorControlParams acolor;
  // vehicle, rate, input_timeout; the active vehicle's own table is read at the same level.
  static const ParamTable<ControlLoopParams>& table();
  // What the Control nodelet's dynamic_reconfigure form shows: entries of the vehicles' tables (cfg/Control.cfg
  // is generated from this and them; a field's default is the first of usv, girona500, acolor that has it).
  static const std::vector<ReconfigureGroup>& reconfigurable();
  void validate() const;
};

// The command for the vehicle's actuators: the USV's joystick, the Girona500's thruster set-points or the
// aColor's RC channels (only the one of `vehicle` is set).
struct ActuatorCommand {
  JoystickOut joystick;
  Girona500Out thrusters;
  std::vector<std::uint16_t> rc;
  // The AUVs: the velocity through the water (body surge, sway) [m/s] the command gives (AcolorController::
  // waterVelocity), the navigation's speed without a DVL
  Eigen::Vector2d water_velocity = Eigen::Vector2d::Zero();
  bool active = false;  // false: the neutral command (why() says why)
};

// What the vehicle's safety supervisor asks of control (the supervisor's action, by safetyOverrideOf; warn asks
// nothing): hold the position (and depth) where the override began, neutral actuators, or surface (the AUV holds
// its horizontal position at depth 0; the USV goes neutral). It wins over guidance until cleared.
enum class SafetyOverride : std::uint8_t { kNone, kHold, kNeutral, kSurface };
const char* safetyOverrideName(SafetyOverride o);

// The safety supervisor's action as control reads it: the values of safety::Action and SafetyState.msg's ACTION_*
// (control does not depend on safety; each caller converts and asserts the values match where it does).
enum class SupervisorAction : std::uint8_t { kNone, kWarn, kHold, kNeutral, kSurface, kAbort };
// The supervisor's decision -> the override, for the Control nodelet and the ROS-free stacks alike: manual control
// wins (none), warn asks nothing, abort surfaces like surface; an unknown action asks nothing.
SafetyOverride safetyOverrideOf(SupervisorAction action, bool manual);

class ControlLoop {
 public:
  explicit ControlLoop(const ControlLoopParams& p);
  const ControlLoopParams& params() const { return p_; }
  void setParams(const ControlLoopParams& p);  // the same vehicle; validates

  void onReference(const MotionReference& r, double t);
  void onState(const VehicleState& s, double t);
  // The navigation's fix status (no position fix accepted lately): the aColor's hold drifts while lost
  // (AcolorController::setFixLost); the Girona500 dead-reckons on its DVL and the USV on its GPS, unaffected.
  void onFixLost(bool lost);
  ActuatorCommand update(double t);
  void setSafety(SafetyOverride o, const std::string& reason);
  SafetyOverride safety() const { return safety_; }

  const std::string& why() const { return why_; }  // empty while controlling
  const Counters& counters() const { return counters_; }            // stale_input, bad_reference
  const Counters& controllerCounters() const;                        // nan_state, bad_reference
  const UsvController* usvController() const { return usv_.get(); }  // null on the AUVs

 private:
  ControlLoopParams p_;
  std::unique_ptr<UsvController> usv_;
  std::unique_ptr<Girona500Controller> g500_;
  std::unique_ptr<AcolorController> acolor_;
  MotionReference ref_;
  VehicleState state_;
  double ref_t_ = 0.0, state_t_ = 0.0;
  bool have_ref_ = false, have_state_ = false;
  SafetyOverride safety_ = SafetyOverride::kNone;
  std::string safety_reason_;
  bool have_hold_ = false;  // the hold point of the current override
  MotionReference hold_;
  std::string why_ = "waiting for guidance status and odometry";
  Counters counters_;
};

}  // namespace control
}  // namespace offshore_gnc

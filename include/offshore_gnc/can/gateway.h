#pragma once
// The intermediate level of the USV (thesis 4.3.1, Publication III Fig. 11), formerly the CCPilot display
// computer: the 3-axis autonomy command is allocated onto the two jets (JetAllocation) and each jet gets its
// set-points in its own frame at a fixed rate; manual joystick / steering wheel frames seen on the bus win and
// silence autonomy; a watchdog sends the neutral command when autonomy goes quiet; a jet whose status frames
// stop is reported and both jets get the neutral command. GatewayPolicy is the pure logic (time given by the
// caller); CanGateway runs it on a bus.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "offshore_gnc/can/jet_allocation.h"
#include "offshore_gnc/can/nmea2000.h"
#include "offshore_gnc/can/socket_can.h"
#include "offshore_gnc/can/waterjet_protocol.h"
#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"

namespace offshore_gnc {
namespace can {

struct GatewayConfig {
  double command_rate = 20.0;      // Hz, command frames
  double watchdog_timeout = 0.5;   // s without autonomy commands before neutral is sent
  double manual_hold = 0.3;        // s a manual frame keeps autonomy silenced
  double jet_timeout = 0.5;        // s without a valid status frame from a jet: it is not answering
  std::string command_frames = "jets";  // "jets": per-jet set-points; "joystick": the 3-axis frame (docs/can-protocol.md)
  jet::Addresses addresses;
  double period() const { return 1.0 / command_rate; }
  static const ParamTable<GatewayConfig>& table();
  void validate() const;           // the table's ranges and the cross-field rules; throws ConfigError naming one
};

// The CanGateway nodelet's own parameters beside GatewayConfig's: its bus, the jets' model and its frames.
struct GatewayNodeParams {
  SocketCanOptions bus;
  std::string model_params;  // the jets the allocation drives (config/models/); empty: the built-in ones
  std::string gps_frame = "usv/gps", world_frame = "map";
  static const ParamTable<GatewayNodeParams>& table();
};

// kJetSilent: autonomy is fresh but a jet stopped answering, so both jets get the neutral command.
enum class Mode { kAutonomy, kManual, kWatchdog, kJetSilent };
const char* toString(Mode m);
const char* jetName(int jet);  // "port", "starboard"

class GatewayPolicy {
 public:
  // `jets`: the waterjets' model parameters the allocation works with (config/models/usv.yaml).
  GatewayPolicy(GatewayConfig config, const models::UsvParams& jets, Counters& counters);
  // Autonomy command from the controller; false (counted) when non-finite or outside [-1, 1].
  bool onAutonomy(double surge, double sway, double yaw, double now);
  // A manual frame decoded from the bus.
  void onManual(const jet::Command& c, double now);
  // A valid status frame from a jet: it answers.
  void onStatus(const jet::Status& s, double now);
  // Frames to send now: one per jet (command_frames "jets") or one 3-axis frame; none while manual is active.
  // Call every period(); it also notes the jets that stopped answering (counted once per silence).
  std::vector<CanFrame> tick(double now);
  Mode mode(double now) const;
  // A valid status frame from `jet` within jet_timeout (the start counts as one: a jet has one timeout to speak).
  bool answering(int jet, double now) const;
  double silentFor(int jet, double now) const;  // s since its last valid status frame (or the start)
  // Both jets as of the last tick().
  const std::array<bool, 2>& answeringAtTick() const { return answering_; }
  const GatewayConfig& config() const { return cfg_; }
  const jet::Command& lastManual() const { return manual_; }

 private:
  GatewayConfig cfg_;
  Counters& counters_;
  JetAllocation allocation_;
  bool per_jet_;
  jet::Command autonomy_, manual_;
  std::array<jet::Setpoint, 2> autonomy_jets_;
  double autonomy_at_ = -1e9, manual_at_ = -1e9;
  std::array<double, 2> heard_at_{{-1e9, -1e9}};
  std::array<bool, 2> answering_{{true, true}};
  Mode last_mode_ = Mode::kWatchdog;
  bool first_tick_ = true;
  std::uint8_t counter_ = 0;
};

// Everything decoded from the bus that the ROS side publishes. Called from spinOnce() under the gateway's
// lock: publish and return, never call back into the CanGateway.
struct GatewayOutputs {
  std::function<void(const n2k::PositionRapid&, std::uint8_t source)> position;
  std::function<void(const n2k::VesselHeading&, std::uint8_t source)> heading;
  std::function<void(const n2k::CogSogRapid&, std::uint8_t source)> cog_sog;
  std::function<void(const jet::Status&)> status;
  std::function<void(const jet::Command&)> manual;
  // Both jets' answering state (port, starboard): after the first tick and on every change.
  std::function<void(const std::array<bool, 2>&)> answering;
  // The bus state: after the first tick and on every change (the safety supervisor's bus_off rule).
  std::function<void(BusState)> bus_state;
};

class CanGateway {
 public:
  using Clock = std::function<double()>;
  CanGateway(SocketCanOptions bus, GatewayConfig config, const models::UsvParams& jets, Counters& counters);
  // On any bus and clock (tests: a scripted bus and a simulated clock).
  CanGateway(std::unique_ptr<BusInterface> bus, GatewayConfig config, const models::UsvParams& jets,
             Counters& counters, Clock clock);
  // One iteration: waits up to max_wait_s for frames, handles them, sends the periodic command when due.
  void spinOnce(double max_wait_s, const GatewayOutputs& out);
  // Thread-safe: the ROS callbacks call these while another thread spins.
  bool onAutonomy(double surge, double sway, double yaw);
  Mode mode() const;
  BusState state() const;
  bool jetAnswering(int jet) const;
  double jetSilentFor(int jet) const;
  static double monotonic();  // seconds

 private:
  void handle(const CanFrame& f, double t, const GatewayOutputs& out);

  Counters& counters_;
  std::unique_ptr<BusInterface> bus_;
  Clock now_;
  GatewayPolicy policy_;
  jet::CounterCheck counters_check_;
  std::optional<std::array<bool, 2>> reported_answering_;
  std::optional<BusState> reported_state_;
  double next_tick_ = 0.0;
  mutable std::mutex mutex_;  // policy_ and bus_ state between the spinning thread and callers
};

}  // namespace can
}  // namespace offshore_gnc

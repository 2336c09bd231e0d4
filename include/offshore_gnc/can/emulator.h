#pragma once
// Emulated bus devices for simulation and tests: the two waterjet control units (acting on the gateway's
// per-jet set-points or a 3-axis frame, answering with status frames) and the GPS-compass (NMEA 2000 PGNs
// 129025/127250/129026). Pure logic: the caller feeds frames and time and puts the returned frames on a bus.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "offshore_gnc/can/frame.h"
#include "offshore_gnc/can/jet_allocation.h"
#include "offshore_gnc/can/waterjet_protocol.h"
#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/models/waterjets.h"

namespace offshore_gnc {
namespace can {

// The two units on the models' per-jet model (models/waterjets.h: rpm chain, nozzle, reversing bucket and its
// rate, from `jets`): what they report is what the simulated boat's jets do on the same set-points.
class WaterjetEmulator {
 public:
  WaterjetEmulator(const models::UsvParams& jets, double command_timeout, jet::Addresses addresses,
                   Counters& counters);
  // Per-jet set-points or 3-axis frames (the units allocate those as the gateway would); manual frames from
  // the bridge win over both, as in the real units.
  void onFrame(const CanFrame& f, double now);
  // Advances the jets and returns the status frame of each unit that answers.
  std::vector<CanFrame> step(double now);
  // The set-points each unit acts on as of the last step (neutral once its command stream is lost): what the
  // simulated boat takes (models::UsvModel::setJetCommands).
  const models::JetCommands& applied() const { return applied_; }
  std::uint8_t appliedSource(int jet) const { return source_[jet & 1]; }
  const std::array<jet::Status, 2>& jets() const { return status_; }
  // A unit that stops answering (its status frames stop) while it still acts on commands: fault injection.
  void setSilent(int jet, bool silent) { silent_[jet & 1] = silent; }

 private:
  void command(int jet, const jet::Setpoint& s, double now);

  double command_timeout_;
  jet::Addresses a_;
  Counters& counters_;
  JetAllocation allocation_;
  models::TwinWaterjets model_;
  jet::CounterCheck check_;
  std::array<jet::Setpoint, 2> commanded_;
  models::JetCommands applied_;
  std::array<std::uint8_t, 2> source_{};
  std::array<double, 2> command_at_{{-1e9, -1e9}};
  double manual_at_ = -1e9, last_step_ = -1.0;
  std::array<jet::Status, 2> status_{};
  std::array<bool, 2> silent_{};
  std::uint8_t counter_ = 0;
};

// The CanEmulator nodelet's parameters (the jets' model comes from `model_params`, a config/models/ file).
struct EmulatorConfig {
  double rate = 10.0;              // Hz, status and GPS-compass frames
  double command_timeout = 0.5;    // s without commands: the unit goes neutral and raises FAULT_COMMS
  int gps_address = 0x40;
  jet::Addresses addresses;
  std::string interface = "vcan0";
  std::string model_params;  // the jets' model (config/models/), as the simulator's; empty: the built-in one
  static const ParamTable<EmulatorConfig>& table();
};

struct GpsCompassSample {
  double lat_deg = 0.0, lon_deg = 0.0;
  double heading_rad = 0.0;   // NED, clockwise from north
  double cog_rad = 0.0, sog_mps = 0.0;
};

class GpsCompassEmulator {
 public:
  explicit GpsCompassEmulator(std::uint8_t source = 0x40) : source_(source) {}
  std::vector<CanFrame> frames(const GpsCompassSample& s);

 private:
  std::uint8_t source_;
  std::uint8_t sid_ = 0;
};

}  // namespace can
}  // namespace offshore_gnc

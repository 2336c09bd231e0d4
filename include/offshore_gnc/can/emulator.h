#pragma once
// Emulated bus devices for simulation and tests: the two waterjet control units (answering our command
// protocol with status frames) and the GPS-compass (NMEA 2000 PGNs 129025/127250/129026). Pure logic: the
// caller feeds frames and time and puts the returned frames on a bus.
#include <array>
#include <cstdint>
#include <vector>

#include "offshore_gnc/can/frame.h"
#include "offshore_gnc/can/waterjet_protocol.h"
#include "offshore_gnc/common/counters.h"

namespace offshore_gnc {
namespace can {

struct WaterjetModel {
  double idle_rpm = 700.0;
  double max_rpm = 2300.0;
  double rpm_time_constant = 0.8;     // s, first-order engine response
  double nozzle_rate = 1.5;           // full-scale units per second (hydraulic actuator rate limit)
  double command_timeout = 0.5;       // s without commands -> FAULT_COMMS and neutral
};

class WaterjetEmulator {
 public:
  WaterjetEmulator(WaterjetModel model, jet::Addresses addresses, Counters& counters);
  // Commands from the gateway or the bridge; manual frames win, as in the real units.
  void onFrame(const CanFrame& f, double now);
  // Advances the jets and returns one status frame per jet.
  std::vector<CanFrame> step(double now);
  // The command the units act on (what the vessel would feel): surge, sway, yaw and its source.
  const jet::Command& applied() const { return applied_; }
  const std::array<jet::Status, 2>& jets() const { return jets_; }

 private:
  WaterjetModel m_;
  jet::Addresses a_;
  Counters& counters_;
  jet::CounterCheck check_;
  jet::Command applied_;
  double command_at_ = -1e9, manual_at_ = -1e9, last_step_ = -1.0;
  std::array<jet::Status, 2> jets_{};
  std::uint8_t counter_ = 0;
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

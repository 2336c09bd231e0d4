#pragma once
// The sonar side of the SeaNet protocol, for tests and simulation without the head: answers mtReBoot,
// mtSendVersion, mtHeadCommand and mtSendData like a Micron (re-centring after power-up or reboot, mtAlive every
// second with HeadInf, one mtHeadData per mtSendData after the ping time) and draws each beam with the
// simulator's sonar model (sim::Sonar) from the vehicle's state and the scenario's world, configured from the
// head command it received (range from ADInterval x bins, step, sector). ROS-free; time from the caller.
#include <cstdint>
#include <memory>
#include <string>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/micron/seanet.h"
#include "offshore_gnc/micron/session.h"
#include "offshore_gnc/models/state.h"
#include "offshore_gnc/sim/sensors.h"
#include "offshore_gnc/sim/world.h"

namespace offshore_gnc {
namespace micron_sim {

struct EmulatorConfig {
  micron::HeadGeometry geometry;   // must match the driver's (same head, same mounting)
  double sound_speed = 1500.0;     // [m/s] of the emulated water
  double recentre_time = 1.0;      // [s] after power-up / mtReBoot before the head is centred
  double alive_period = 1.0;       // [s]
  double ping_period = 0.05;       // [s] from mtSendData to mtHeadData (two-way travel + motor step)
  sim::SonarConfig model;          // noise, beam widths, mount: range/bins/step/sector come from the command
  int seed = 1;
  // The MicronEmulator nodelet's parameters: `port` (the pseudo-terminal's path) and `scenario` (the world the
  // head sees) beside these.
  std::string port = "/tmp/micron_sim", scenario;
  static const ParamTable<EmulatorConfig>& table();
};

class HeadEmulator {
 public:
  HeadEmulator(const EmulatorConfig& cfg, const sim::World& world);
  // Bytes from the PC; returns the bytes to send back at once (may be empty).
  std::string receive(const std::uint8_t* data, std::size_t n, double now);
  // Periodic output (mtAlive, head data whose ping time has come). Call every few ms.
  std::string poll(double now);
  // The vehicle's true state (NED), for the beams drawn from now on.
  void setVehicle(const VehicleState& s) { vehicle_ = s; have_vehicle_ = true; }
  bool configured() const { return model_ != nullptr; }
  const micron::StreamDecoder& decoder() const { return decoder_; }
  // requests, beams, reboots, bad_head_commands, no_vehicle_state, unsupported, ...
  const Counters& counters() const { return counters_; }

 private:
  std::string handle(const micron::Message& m, double now);
  std::uint8_t headInf(double now) const;
  EmulatorConfig cfg_;
  sim::World world_;
  micron::StreamDecoder decoder_;
  std::vector<micron::StreamDecoder::Event> events_;
  double powered_at_ = 0.0, next_alive_ = 0.0, configured_at_ = -1.0;
  bool started_ = false, ping_pending_ = false;
  double ping_due_ = 0.0;
  micron::HeadCommand command_;
  std::unique_ptr<sim::Sonar> model_;
  sim::SonarBeamReading beam_;
  VehicleState vehicle_;
  bool have_vehicle_ = false;
  Counters counters_;
};

}  // namespace micron_sim
}  // namespace offshore_gnc

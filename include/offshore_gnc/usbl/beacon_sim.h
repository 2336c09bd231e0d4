#pragma once
// A SeaTrac X150 (on the USV) + X110 (on the AUV) pair, simulated at the protocol level: it answers PING_SEND
// with the acknowledgement, then PING_RESP after the two-way acoustic delay (range / sound speed), or
// PING_ERROR XCVR_RESP_TIMEOUT after the response timeout on a dropout or out of range; DAT_SEND likewise
// (REQ types are answered with DAT_RECEIVE carrying the remote's queued packet). Range and angle noise are
// Gaussian and seeded. The replies are real frames, so the real decoder reads them. ROS-free.
#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <random>
#include <string>
#include <vector>

#include "offshore_gnc/common/faults.h"
#include "offshore_gnc/usbl/positioning.h"
#include "offshore_gnc/usbl/seatrac.h"

namespace offshore_gnc {
namespace usbl {

struct BeaconSimConfig {
  std::uint8_t local_id = 1;    // the transceiver's own beacon id
  std::uint8_t remote_id = 2;   // the only remote beacon in the water
  Mounting mount;
  double sound_speed = 1500.0;  // [m/s]
  double range_sigma = 0.05;    // [m]
  double angle_sigma = 0.0087;  // [rad] azimuth and elevation noise (about 0.5 deg)
  double dropout_probability = 0.05;
  double max_range = 1000.0;    // [m], beyond it every ping times out
  double timeout = 1.0;         // [s] response timeout before PING_ERROR
  double fit_error = 0.3;       // nominal USBL fit error
  double rssi_db = -60.0;
  unsigned seed = 1;
  FaultPlan faults;  // "usbl": the remote beacon does not reply (every ping times out) while active
  void validate() const;  // throws ConfigError naming the field
};

class BeaconSimulator {
 public:
  explicit BeaconSimulator(const BeaconSimConfig& cfg);
  // One decoded command at time t: returns the immediate reply frames (acknowledgement or error) and schedules
  // the acoustic reply. Replies to '$' frames and unknown commands are ignored (as the beacon does).
  std::string handle(const Message& cmd, double t);
  // Frames due by t, computed from the poses at t (the moment the reply reaches the transceiver).
  std::string poll(double t, const Pose& usv, const Eigen::Vector3d& remote_ned);
  // Noisy fix of the remote beacon as the transceiver would report it.
  AcoFix makeFix(const Pose& usv, const Eigen::Vector3d& remote_ned, std::uint8_t msg_type);
  // Range used to time a reply scheduled now (set from the latest poses by the caller).
  void setCurrentRange(double r) { current_range_ = r; }
  // Packet the remote beacon returns to DAT_SEND requests.
  void setRemoteQueue(const std::vector<std::uint8_t>& data) { remote_queue_ = data; }
  const Counters& counters() const { return counters_; }

 private:
  struct Pending {
    double due;
    std::uint8_t cid;       // PING_SEND or DAT_SEND
    std::uint8_t dest;
    std::uint8_t msg_type;
    bool timeout;
  };
  BeaconSimConfig cfg_;
  std::mt19937 rng_;
  std::deque<Pending> pending_;
  double current_range_ = 0.0;
  std::vector<std::uint8_t> remote_queue_;
  Counters counters_;
};

// Range from the transceiver (on the USV) to the remote beacon.
double transceiverRange(const Mounting& mount, const Pose& usv, const Eigen::Vector3d& remote_ned);

}  // namespace usbl
}  // namespace offshore_gnc

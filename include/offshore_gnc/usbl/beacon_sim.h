#pragma once
// A SeaTrac X150 (on the USV) + X110 (on the AUV) pair, simulated at the protocol level: it answers PING_SEND
// with the acknowledgement, then PING_RESP after the two-way acoustic delay (range / sound speed), or
// PING_ERROR XCVR_RESP_TIMEOUT after the response timeout on a dropout or out of range; DAT_SEND likewise
// (REQ types are answered with DAT_RECEIVE carrying the remote's queued packet). The replies are real frames, so
// the real decoder reads them. ROS-free, seeded. What a real pair in a shallow lake shows (docs/usbl.md, "The
// simulated pair"): range and angle noise that grows as the signal weakens with range and blurs as the USV turns,
// a fit error that follows both, a range scaled by the transceiver's velocity-of-sound error, replies that come
// by a reflected path now and then (longer range, another direction, a poor fit: the outliers), and dropouts
// that come alone or in bursts.
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
  double fit_error = 0.3;       // USBL fit error of a direct arrival at short range, the USV steady
  double rssi_db = -60.0;
  double sound_speed_error = 7.0;   // [m/s] the transceiver's velocity of sound minus the water's (range scale)
  double snr_range = 300.0;         // [m] the angle noise grows as sqrt(1 + (range / this)^2): spreading loss
  double motion_time = 0.05;        // [s] the USV's rotation over this long blurs the angles (reception, AHRS lag)
  double fit_error_scatter = 0.3;   // the reported fit error's lognormal spread about what the conditions give
  double multipath_probability = 0.04;    // a reply that came by a reflected path (surface, bottom, hull)
  double multipath_extra_range = 3.0;     // [m] its extra path length, mean (exponential)
  double multipath_angle = 0.17;          // [rad] its direction error, azimuth and elevation each, 1-sigma
  double multipath_fit_error = 2.0;       // its fit error, median
  double burst_probability = 0.01;  // per ping: a burst of dropouts starts (shadowing, the jets' bubbles)
  double burst_pings = 6.0;         // mean pings a burst lasts (geometric)
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
  // pings, responses, timeouts, multipath (replies by a reflected path), bursts, busy, ...
  const Counters& counters() const { return counters_; }

 private:
  void trackUsvRotation(double t, const Eigen::Quaterniond& q);  // the USV's rotation rate from successive poses

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
  int burst_left_ = 0;         // pings of the current dropout burst still to drop
  double usv_rate_ = 0.0;      // [rad/s]
  double rate_t_ = -1.0;       // the pose the rate is measured from
  Eigen::Quaterniond rate_q_ = Eigen::Quaterniond::Identity();
  Counters counters_;
};

// Range from the transceiver (on the USV) to the remote beacon.
double transceiverRange(const Mounting& mount, const Pose& usv, const Eigen::Vector3d& remote_ned);

}  // namespace usbl
}  // namespace offshore_gnc

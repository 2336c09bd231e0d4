#pragma once
// The AUV's navigation as auv.launch (navigation:=usbl) runs it, without ROS: the SeaTrac pair at the protocol
// level (the transceiver session's frames go as bytes through the real codec to the beacon simulator, whose
// replies come back as bytes, as over the simulation's pseudo-terminal), each reply placed by the USV's relayed GPS
// and heading at its time with the quality gates (usbl::Positioner, the Usbl nodelet's core), and the accepted
// fixes fused with depth, the AHRS and the DVL or the commands' velocity (navigation::AuvNavigator, the AuvNavigation
// nodelet's core), the estimate given at that nodelet's rate. Configured from the same files (config/usbl/usbl.yaml,
// config/navigation/auv_<model>.yaml), as config/vehicles/auv.yaml lists them.
#include <Eigen/Core>

#include <cmath>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "offshore_gnc/closed_loop/manifest.h"
#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/faults.h"
#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/models/state.h"
#include "offshore_gnc/navigation/auv_navigation_params.h"
#include "offshore_gnc/navigation/auv_navigator.h"
#include "offshore_gnc/sim/radio.h"
#include "offshore_gnc/usbl/beacon_sim.h"
#include "offshore_gnc/usbl/positioning.h"
#include "offshore_gnc/usbl/session.h"

namespace offshore_gnc {
namespace closed_loop {

struct UsblNavigationConfig {
  usbl::SessionParams session;       // config/usbl/usbl.yaml (the Usbl nodelet's)
  usbl::QualityLimits limits;
  usbl::Mounting mount;              // from the point /usv_gps reports
  usbl::BeaconSimConfig beacon;      // the simulated pair (the UsblSim nodelet's); its mounting is set from mount
  navigation::AuvNavigatorConfig filter;   // config/navigation/auv_<model>.yaml
  navigation::AuvNavigationParams params;
};
// The usbl, usbl_sim and navigation components of config/vehicles/auv.yaml (the manifest under config_dir).
UsblNavigationConfig loadUsblNavigation(const std::string& config_dir, const std::string& model);
UsblNavigationConfig loadUsblNavigation(const VehicleManifest& auv, const std::string& model);

// One accepted or rejected fix, for the report's figures (what /auv/usbl/fix records).
struct UsblFixRecord {
  double t = 0.0;                  // when the beacon was where the fix says
  std::uint8_t quality = 0;        // usbl::Quality
  Eigen::Vector3d ned = Eigen::Vector3d::Constant(std::nan(""));
  bool fused = false;              // the filter took it (not gated)
  // a gate's quality name, or "fused" / "gated" by the filter
  const char* verdict() const { return quality != usbl::Q_OK ? usbl::qualityName(quality) : (fused ? "fused" : "gated"); }
};

class UsblNavigation {
 public:
  // `site`: the local frame the relayed GPS fixes are converted in; `gps_antenna`: where on the USV (body FRD) the
  // GPS reports, which the transceiver's mounting is relative to; `faults`: the AUV's plan ("usbl" silences the
  // beacon).
  UsblNavigation(const UsblNavigationConfig& cfg, const geo::LocalNed& site, const Eigen::Vector3d& gps_antenna,
                 unsigned seed, const FaultPlan& faults);

  // The USV's GPS fix and heading as the relay delivers them on the AUV's side, with their stamps.
  void usvGps(double stamp, const geo::LatLonAlt& fix);
  void usvHeading(double stamp, double yaw);
  // The AUV's own sensors.
  void depth(double t, double pressure_pa);
  void ahrs(double t, double roll, double pitch, double yaw, const Eigen::Vector3d& rate_frd);
  void dvl(double t, const Eigen::Vector3d& v_body);
  void commandedVelocity(double t, const Eigen::Vector2d& surge_sway) {  // /auv/commanded_velocity
    nav_.commandedVelocity(t, surge_sway.x(), surge_sway.y());
  }
  // The AUV's own GPS fix at the surface (/auv/gps/fix), placed in the site's frame, straight into the filter;
  // true when it went in (not gated).
  bool gpsFix(double t, const geo::LatLonAlt& fix, double sigma) {
    return nav_.gpsFix(t, site_.toNed(fix).head<2>(), sigma);
  }
  // One simulation step at t: the transceiver's serial traffic (the acoustic replies from both vehicles' true
  // poses), fixes placed once the relayed USV pose has reached their time, into the filter.
  void step(double t, const VehicleState& usv_truth, const VehicleState& auv_truth);
  // /auv/odom at t (the nodelet's timer): nothing before the first fix or without a heading.
  std::optional<VehicleState> estimate(double t) const;
  navigation::NavStatus status(double t) const { return nav_.estimate(t).status; }

  const std::vector<UsblFixRecord>& fixes() const { return fixes_; }
  // Fixes accepted this step (the supervisor's usbl source): their stamps.
  const std::vector<double>& acceptedNow() const { return accepted_now_; }
  const Counters& positionerCounters() const { return positioner_.counters(); }
  const Counters& filterCounters() const { return nav_.counters(); }
  const Counters& sessionCounters() const { return session_.counters(); }
  const Counters& beaconCounters() const { return beacon_.counters(); }  // the simulated pair's (multipath, ...)
  const navigation::AuvNavigationParams& params() const { return cfg_.params; }

 private:
  void exchange(double t, const usbl::Pose& usv, const Eigen::Vector3d& auv_ned);
  void place(double t);

  UsblNavigationConfig cfg_;
  geo::LocalNed site_;
  usbl::BeaconSimulator beacon_;
  usbl::Mounting beacon_mount_;  // the transceiver from the hull's reference point (the truth's)
  usbl::TransceiverSession session_;
  usbl::StreamDecoder to_beacon_, to_transceiver_;  // the serial line, each direction
  usbl::Positioner positioner_;
  navigation::AuvNavigator nav_;
  std::deque<std::pair<usbl::AcoFix, double>> pending_;  // replies waiting for the USV's pose at their time
  std::vector<UsblFixRecord> fixes_;
  std::vector<double> accepted_now_;
  double roll_ = 0.0, pitch_ = 0.0;
  Eigen::Vector2d rate_pq_ = Eigen::Vector2d::Zero();
};

// The radio between the two masters, as the relay meets it (sim::RadioChannel: the main job's simulated radio,
// from the same parameters): each message arrives after its time on the channel, the latency and a jitter;
// best-effort ones (the relay's datagrams) are lost in runs, reliable ones (its queue over TCP) come late
// instead. While the link is down (the `link` fault) nothing arrives; best-effort messages are lost, reliable
// ones wait for it.
template <class T>
class RadioLink {
 public:
  RadioLink(const sim::RadioParams& p, std::uint64_t seed) : channel_(p, seed) {}
  void setUp(bool up) { up_ = up; }
  bool up() const { return up_; }
  // `bytes`: the message's size as the relay frames it.
  void send(double t, const T& m, std::size_t bytes, bool reliable) {
    const std::optional<double> due = reliable || up_ ? channel_.schedule(t, bytes, reliable) : std::nullopt;
    if (!due) {
      ++lost_;
      return;
    }
    queue_.emplace(*due, m);
  }
  // Messages due by t, in the order they arrive.
  std::vector<T> receive(double t) {
    std::vector<T> out;
    while (up_ && !queue_.empty() && queue_.begin()->first <= t) {
      out.push_back(std::move(queue_.begin()->second));
      queue_.erase(queue_.begin());
    }
    return out;
  }
  std::size_t lost() const { return lost_; }
  const sim::RadioChannel& channel() const { return channel_; }

 private:
  sim::RadioChannel channel_;
  bool up_ = true;
  std::multimap<double, T> queue_;  // by arrival time (datagrams may overtake each other by their jitter)
  std::size_t lost_ = 0;
};

}  // namespace closed_loop
}  // namespace offshore_gnc

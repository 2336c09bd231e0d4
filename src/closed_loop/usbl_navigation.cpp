#include "offshore_gnc/closed_loop/usbl_navigation.h"

#include <Eigen/Geometry>

#include "offshore_gnc/common/param_yaml.h"
#include "offshore_gnc/usbl/config.h"

namespace offshore_gnc {
namespace closed_loop {

UsblNavigationConfig loadUsblNavigation(const std::string& dir, const std::string& model) {
  return loadUsblNavigation(VehicleManifest::load(dir, "auv"), model);
}

UsblNavigationConfig loadUsblNavigation(const VehicleManifest& m, const std::string& model) {
  UsblNavigationConfig c;
  for (const auto& s : m.sources("usbl", model)) {  // the Usbl nodelet's
    readParamsYaml(s.yaml, usbl::SessionParams::table(), c.session, s.name);
    readParamsYaml(s.yaml, usbl::qualityLimitsTable(), c.limits, s.name);
    readParamsYaml(s.yaml, usbl::mountingTable(), c.mount, s.name);
  }
  usbl::BeaconSimNodeParams node;
  for (const auto& s : m.sources("usbl_sim", model)) {  // its simulator's
    readParamsYaml(s.yaml, usbl::beaconSimTable(), c.beacon, s.name);
    readParamsYaml(s.yaml, usbl::BeaconSimNodeParams::table(), node, s.name);
  }
  c.beacon.remote_id = static_cast<std::uint8_t>(c.session.remote_id);
  c.beacon.seed = static_cast<unsigned>(node.seed);  // the UsblSim nodelet's `seed` (its launch arg's default)
  for (const auto& s : m.sources("navigation", model)) {  // the AuvNavigation nodelet's
    readParamsYaml(s.yaml, navigation::AuvNavigatorConfig::table(), c.filter, s.name);
    readParamsYaml(s.yaml, navigation::AuvNavigationParams::table(), c.params, s.name);
  }
  return c;
}

namespace {
usbl::Pose poseOf(const VehicleState& s) {
  usbl::Pose p;
  p.ned = s.position;
  p.q = Eigen::AngleAxisd(s.yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(s.pitch, Eigen::Vector3d::UnitY()) *
        Eigen::AngleAxisd(s.roll, Eigen::Vector3d::UnitX());
  return p;
}

usbl::BeaconSimConfig beaconConfig(usbl::BeaconSimConfig b, const usbl::Mounting& m, const Eigen::Vector3d& antenna,
                                   unsigned seed, const FaultPlan& faults) {
  // The mounting is from the GPS point, the truth is the hull's reference point (as the UsblSim nodelet adds it).
  b.mount = m;
  b.mount.offset += antenna;
  b.seed = seed;
  b.faults = faults;
  return b;
}
}  // namespace

UsblNavigation::UsblNavigation(const UsblNavigationConfig& cfg, const geo::LocalNed& site,
                               const Eigen::Vector3d& gps_antenna, unsigned seed, const FaultPlan& faults)
    : cfg_(cfg),
      site_(site),
      beacon_(beaconConfig(cfg.beacon, cfg.mount, gps_antenna, seed, faults)),
      beacon_mount_(beaconConfig(cfg.beacon, cfg.mount, gps_antenna, seed, faults).mount),
      session_(cfg.session),
      positioner_(cfg.mount, cfg.limits),
      nav_(cfg.filter) {}

void UsblNavigation::usvGps(double stamp, const geo::LatLonAlt& fix) {
  positioner_.addUsvPosition(stamp, site_.toNed(fix));
}

void UsblNavigation::usvHeading(double stamp, double yaw) {
  positioner_.addUsvAttitude(stamp, Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())));
}

void UsblNavigation::depth(double t, double pressure_pa) {
  const double z = cfg_.params.depthOf(pressure_pa);
  positioner_.addRemoteDepth(t, z);  // the USBL node's depth gate
  nav_.depth(t, z);
}

void UsblNavigation::ahrs(double t, double roll, double pitch, double yaw, const Eigen::Vector3d& rate_frd) {
  roll_ = roll;
  pitch_ = pitch;
  rate_pq_ = rate_frd.head<2>();
  nav_.heading(t, yaw, rate_frd.z());
}

void UsblNavigation::dvl(double t, const Eigen::Vector3d& v_body) {
  if (cfg_.params.use_dvl) nav_.dvl(t, v_body);
}


void UsblNavigation::exchange(double t, const usbl::Pose& usv, const Eigen::Vector3d& auv_ned) {
  std::vector<usbl::StreamDecoder::Event> events;
  const auto deliver = [&](const std::string& bytes) {  // the beacon's replies, read by the transceiver's session
    if (bytes.empty()) return;
    events.clear();
    to_transceiver_.feed(bytes, events);
    for (const auto& e : events) {
      const usbl::SessionEvent ev = session_.handle(e, t);
      if (ev.kind != usbl::SessionEvent::kNone) pending_.emplace_back(ev.fix, t);
    }
  };
  beacon_.setCurrentRange(usbl::transceiverRange(beacon_mount_, usv, auv_ned));
  if (const std::optional<usbl::Message> m = session_.due(t)) {
    session_.sent(*m, t);
    std::vector<usbl::StreamDecoder::Event> cmds;
    to_beacon_.feed(usbl::encodeFrame(*m), cmds);
    for (const auto& e : cmds)
      if (e.message) deliver(beacon_.handle(*e.message, t));
  }
  deliver(beacon_.poll(t, usv, auv_ned));
}

void UsblNavigation::place(double t) {
  while (!pending_.empty() && positioner_.ready(pending_.front().second, t)) {
    const auto [fix, t_reply] = pending_.front();
    pending_.pop_front();
    const usbl::FixResult r = positioner_.process(fix, t_reply, t);
    UsblFixRecord rec;
    rec.t = r.stamp;
    rec.quality = r.quality;
    if (r.ned) rec.ned = *r.ned;
    if (r.quality == usbl::Q_OK && r.ned && fix.has(usbl::AcoFix::RANGE)) {
      rec.fused = nav_.usblFix(r.stamp, *r.ned, cfg_.params.fixCovariance(fix.rangeM()));
      accepted_now_.push_back(r.stamp);
    }
    fixes_.push_back(rec);
  }
}

void UsblNavigation::step(double t, const VehicleState& usv_truth, const VehicleState& auv_truth) {
  accepted_now_.clear();
  exchange(t, poseOf(usv_truth), auv_truth.position);
  place(t);
}

std::optional<VehicleState> UsblNavigation::estimate(double t) const {
  const navigation::AuvNavEstimate e = nav_.estimate(t);
  if (e.status == navigation::NavStatus::kNoFix || e.status == navigation::NavStatus::kNoHeading) return std::nullopt;
  // as the AuvNavigation nodelet's /auv/odom: the filter's position and velocity, the AHRS's attitude and rates
  VehicleState s;
  s.t = t;
  s.position = e.position;
  s.roll = roll_;
  s.pitch = pitch_;
  s.yaw = e.yaw;
  const Eigen::Matrix3d R_nb = (Eigen::AngleAxisd(e.yaw, Eigen::Vector3d::UnitZ()) *
                                Eigen::AngleAxisd(pitch_, Eigen::Vector3d::UnitY()) *
                                Eigen::AngleAxisd(roll_, Eigen::Vector3d::UnitX()))
                                   .toRotationMatrix();
  s.velocity = R_nb.transpose() * e.velocity;
  s.angular_rate = Eigen::Vector3d(rate_pq_.x(), rate_pq_.y(), e.yaw_rate);
  return s;
}

}  // namespace closed_loop
}  // namespace offshore_gnc

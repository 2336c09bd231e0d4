#include "offshore_gnc/usbl/beacon_sim.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/usbl/config.h"

namespace offshore_gnc {
namespace usbl {

namespace {
template <typename T>
T clampTo(double v) {
  const double lo = std::numeric_limits<T>::min(), hi = std::numeric_limits<T>::max();
  return static_cast<T>(std::lround(std::clamp(v, lo, hi)));
}
Message reply(Body b) {
  Message m;
  m.command = false;
  m.body = std::move(b);
  return m;
}
}  // namespace

void BeaconSimConfig::validate() const { beaconSimTable().validate(*this); }

double transceiverRange(const Mounting& mount, const Pose& usv, const Eigen::Vector3d& remote_ned) {
  return (remote_ned - (usv.ned + usv.q * mount.offset)).norm();
}

BeaconSimulator::BeaconSimulator(const BeaconSimConfig& cfg) : cfg_(cfg), rng_(cfg.seed) { cfg_.validate(); }

std::string BeaconSimulator::handle(const Message& cmd, double t) {
  if (!cmd.command) return "";
  std::uint8_t cid = 0, dest = 0, msg_type = 0;
  if (auto p = std::get_if<PingSend>(&cmd.body)) {
    cid = CID_PING_SEND, dest = p->dest_id, msg_type = p->msg_type;
  } else if (auto d = std::get_if<DatSend>(&cmd.body)) {
    cid = CID_DAT_SEND, dest = d->dest_id, msg_type = d->msg_type;
  } else {
    counters_.increment("ignored_commands");
    return "";
  }
  counters_.increment(cid == CID_PING_SEND ? "pings" : "data_sends");
  // The transceiver acknowledges at once; it is busy (one transaction at a time) until the reply or timeout.
  if (!pending_.empty()) {
    counters_.increment("busy");
    return encodeFrame(reply(StatusReply{cid, 0x30 /* XCVR_BUSY */, dest}));
  }
  std::string out = encodeFrame(reply(StatusReply{cid, kStatusOk, dest}));
  const bool wants_reply = cid == CID_PING_SEND || msg_type == MSG_REQ || msg_type == MSG_REQU || msg_type == MSG_REQX;
  if (!wants_reply) return out;
  // Dropouts: a ping lost on its own (dropout_probability), or one of a burst (Gilbert-Elliott: a bad state
  // entered with burst_probability per ping, left after a geometric number of pings).
  bool dropped = std::bernoulli_distribution(cfg_.dropout_probability)(rng_);
  if (burst_left_ > 0) {
    --burst_left_;
    dropped = true;
  } else if (std::bernoulli_distribution(cfg_.burst_probability)(rng_)) {
    counters_.increment("bursts");
    burst_left_ = std::geometric_distribution<int>(1.0 / cfg_.burst_pings)(rng_);  // the pings after this one
    dropped = true;
  }
  const bool timeout = dest != cfg_.remote_id || current_range_ > cfg_.max_range || dropped || cfg_.faults.active("usbl", t);
  const double due = timeout ? t + cfg_.timeout : t + 2.0 * current_range_ / cfg_.sound_speed;
  pending_.push_back({due, cid, dest, msg_type, timeout});
  return out;
}

AcoFix BeaconSimulator::makeFix(const Pose& usv, const Eigen::Vector3d& remote_ned, std::uint8_t msg_type) {
  std::normal_distribution<double> n01(0.0, 1.0);
  const Eigen::Matrix3d r_ned_xcvr = usv.q.toRotationMatrix() * cfg_.mount.rotation();
  const Eigen::Vector3d xcvr_ned = usv.ned + usv.q * cfg_.mount.offset;
  const Eigen::Vector3d v = r_ned_xcvr.transpose() * (remote_ned - xcvr_ned);
  double range, az, el;
  toRangeAngles(v, range, az, el);
  // The angles' noise: the phase differences get noisier as the signal weakens (spherical spreading: SNR falls
  // with range^2, the phase noise grows with range), and the USV's rotation during the reception (and its AHRS's
  // lag) blurs them. The fit error, the transceiver's own measure of how well the phases fit one direction,
  // follows the same conditions, with a scatter of its own.
  const double snr_growth = 1.0 + (range / cfg_.snr_range) * (range / cfg_.snr_range);
  const double blur = usv_rate_ * cfg_.motion_time;
  const double sigma = std::sqrt(cfg_.angle_sigma * cfg_.angle_sigma * snr_growth + blur * blur);
  double fit = cfg_.fit_error * (cfg_.angle_sigma > 0.0 ? sigma / cfg_.angle_sigma : std::sqrt(snr_growth));
  // A reflected arrival (off the surface, the bottom or a hull) stronger than the direct one: a longer path from
  // another direction, whose phases fit a plane wave poorly.
  double path = range;
  if (std::bernoulli_distribution(cfg_.multipath_probability)(rng_)) {
    counters_.increment("multipath");
    path += std::exponential_distribution<double>(1.0 / std::max(cfg_.multipath_extra_range, 1e-9))(rng_);
    az += cfg_.multipath_angle * n01(rng_);
    el += cfg_.multipath_angle * n01(rng_);
    fit = cfg_.multipath_fit_error;
  }
  fit *= std::exp(cfg_.fit_error_scatter * n01(rng_));
  path = std::max(0.0, path + cfg_.range_sigma * n01(rng_));
  az = wrapTwoPi(az + sigma * n01(rng_));
  el = std::clamp(el + sigma * n01(rng_), -kPi / 2, kPi / 2);
  // The travel time is the water's; the transceiver turns it into a range with its own velocity of sound.
  const double travel = path / cfg_.sound_speed;
  const double vos = cfg_.sound_speed + cfg_.sound_speed_error;
  range = travel * vos;
  // The device reports the position in its NED-aligned frame from its own attitude sensor.
  const Eigen::Vector3d meas_ned = r_ned_xcvr * fromRangeAngles(range, az, el);
  const Eigen::Vector3d ypr = r_ned_xcvr.eulerAngles(2, 1, 0);

  AcoFix f;
  f.dest_id = cfg_.local_id;
  f.src_id = cfg_.remote_id;
  f.flags = AcoFix::RANGE | AcoFix::USBL | AcoFix::POSITION;
  f.msg_type = msg_type;
  f.yaw = clampTo<std::int16_t>(rad2deg(wrapTwoPi(ypr[0])) * 10);
  f.pitch = clampTo<std::int16_t>(rad2deg(wrapAngle(ypr[1])) * 10);
  f.roll = clampTo<std::int16_t>(rad2deg(wrapAngle(ypr[2])) * 10);
  f.depth_local = clampTo<std::uint16_t>(std::max(0.0, xcvr_ned.z()) * 10);
  f.vos = clampTo<std::uint16_t>(vos * 10);
  f.rssi = clampTo<std::int16_t>(cfg_.rssi_db * 10);
  f.range_count = static_cast<std::uint32_t>(std::lround(travel * 16000.0));  // 16 kHz ticks
  f.range_time = clampTo<std::int32_t>(travel * 1e7);
  f.range_dist = clampTo<std::uint16_t>(range * 10);
  f.usbl_rssi.assign(4, f.rssi);
  f.azimuth = clampTo<std::int16_t>(rad2deg(az) * 10);
  f.elevation = clampTo<std::int16_t>(rad2deg(el) * 10);
  f.fit_error = clampTo<std::int16_t>(fit * 100);
  f.east = clampTo<std::int16_t>(meas_ned.y() * 10);
  f.north = clampTo<std::int16_t>(meas_ned.x() * 10);
  f.depth = clampTo<std::int16_t>((xcvr_ned.z() + meas_ned.z()) * 10);
  return f;
}

void BeaconSimulator::trackUsvRotation(double t, const Eigen::Quaterniond& q) {
  constexpr double kMinSpan = 0.05, kMaxSpan = 1.0;  // [s] a rate over less is noise, over more stale
  const double span = t - rate_t_;
  if (rate_t_ >= 0.0 && span < kMinSpan && span >= 0.0) return;
  if (rate_t_ >= 0.0 && span > 0.0 && span <= kMaxSpan) usv_rate_ = rate_q_.angularDistance(q) / span;
  rate_t_ = t;
  rate_q_ = q;
}

std::string BeaconSimulator::poll(double t, const Pose& usv, const Eigen::Vector3d& remote_ned) {
  trackUsvRotation(t, usv.q);
  std::string out;
  while (!pending_.empty() && pending_.front().due <= t) {
    const Pending p = pending_.front();
    pending_.pop_front();
    if (p.timeout) {
      counters_.increment("timeouts");
      out += encodeFrame(reply(StatusReply{p.cid == CID_PING_SEND ? std::uint8_t(CID_PING_ERROR) : std::uint8_t(CID_DAT_ERROR),
                                           kStatusXcvrRespTimeout, p.dest}));
      continue;
    }
    const std::uint8_t resp_type = static_cast<std::uint8_t>(p.msg_type + 1);  // REQ* -> RESP*
    if (p.cid == CID_PING_SEND) {
      counters_.increment("responses");
      out += encodeFrame(reply(FixMessage{CID_PING_RESP, makeFix(usv, remote_ned, resp_type)}));
    } else {
      counters_.increment("data_responses");
      out += encodeFrame(reply(DatReceive{makeFix(usv, remote_ned, resp_type), false, remote_queue_}));
    }
  }
  return out;
}

}  // namespace usbl
}  // namespace offshore_gnc

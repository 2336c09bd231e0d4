#include "offshore_gnc/usbl/beacon_sim.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"

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

void BeaconSimConfig::validate() const {
  requireRange("sound_speed", sound_speed, 1300, 1700);
  requireRange("range_sigma", range_sigma, 0, 100);
  requireRange("angle_sigma", angle_sigma, 0, 1);
  requireRange("dropout_probability", dropout_probability, 0, 1);
  requirePositive("max_range", max_range);
  requirePositive("timeout", timeout);
  requireRange("fit_error", fit_error, 0, 300);
}

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
  std::bernoulli_distribution drop(cfg_.dropout_probability);
  const bool timeout =
      dest != cfg_.remote_id || current_range_ > cfg_.max_range || drop(rng_) || cfg_.faults.active("usbl", t);
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
  range = std::max(0.0, range + cfg_.range_sigma * n01(rng_));
  az = wrapTwoPi(az + cfg_.angle_sigma * n01(rng_));
  el = std::clamp(el + cfg_.angle_sigma * n01(rng_), -kPi / 2, kPi / 2);
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
  f.vos = clampTo<std::uint16_t>(cfg_.sound_speed * 10);
  f.rssi = clampTo<std::int16_t>(cfg_.rssi_db * 10);
  f.range_count = static_cast<std::uint32_t>(std::lround(range / cfg_.sound_speed * 16000.0));  // 16 kHz ticks
  f.range_time = clampTo<std::int32_t>(range / cfg_.sound_speed * 1e7);
  f.range_dist = clampTo<std::uint16_t>(range * 10);
  f.usbl_rssi.assign(4, f.rssi);
  f.azimuth = clampTo<std::int16_t>(rad2deg(az) * 10);
  f.elevation = clampTo<std::int16_t>(rad2deg(el) * 10);
  f.fit_error = clampTo<std::int16_t>(cfg_.fit_error * 100);
  f.east = clampTo<std::int16_t>(meas_ned.y() * 10);
  f.north = clampTo<std::int16_t>(meas_ned.x() * 10);
  f.depth = clampTo<std::int16_t>((xcvr_ned.z() + meas_ned.z()) * 10);
  return f;
}

std::string BeaconSimulator::poll(double t, const Pose& usv, const Eigen::Vector3d& remote_ned) {
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

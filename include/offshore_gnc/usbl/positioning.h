#pragma once
// Turns a SeaTrac fix (range, azimuth, elevation in the transceiver frame) into the remote beacon's position in
// local NED, using the transceiver's mounting on the USV and the USV's position and attitude AT THE TIME OF
// THE FIX (interpolated from buffered GPS and heading samples), and applies the quality gates. ROS-free.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <iterator>
#include <optional>
#include <utility>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/usbl/seatrac.h"

namespace offshore_gnc {
namespace usbl {

// Transceiver mounting in the USV body frame (x forward, y starboard, z down).
struct Mounting {
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // [m]
  double roll = 0, pitch = 0, yaw = 0;               // [rad], ZYX
  Eigen::Matrix3d rotation() const;                  // transceiver -> body
};

// A vehicle pose in local NED: position and attitude body(FRD) -> NED.
struct Pose {
  Eigen::Vector3d ned = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
};

// The pose dt later at a constant body velocity and body rate (FRD), e.g. a pose received late carried to now.
Pose predictPose(const Pose& p, const Eigen::Vector3d& v_body, const Eigen::Vector3d& w_body, double dt);

// ROS map frame conventions (ENU world, FLU body) -> NED world, FRD body.
Eigen::Quaterniond enuFluToNedFrd(const Eigen::Quaterniond& q_enu_flu);

// Unit-consistent direction helpers: transceiver frame (x forward, y starboard, z down), azimuth clockwise
// from x, elevation positive up (UsblFix convention).
Eigen::Vector3d fromRangeAngles(double range, double azimuth, double elevation);
void toRangeAngles(const Eigen::Vector3d& v, double& range, double& azimuth, double& elevation);

// Time-stamped samples with linear interpolation (slerp for attitude); a bounded horizon.
template <typename T>
class TimedBuffer {
 public:
  explicit TimedBuffer(double horizon_s = 30.0) : horizon_(horizon_s) {}
  // A sample older than the newest is put in its place: relayed datagrams can come out of order. One older by
  // more than kTimeReset is the clock having gone back (a bag loop, a simulation reset): the buffer starts again.
  void add(double t, const T& v) {
    static constexpr double kTimeReset = 5.0;  // [s]
    if (!samples_.empty() && t < samples_.back().first) {
      if (t < samples_.back().first - kTimeReset) {
        samples_.clear();
      } else {
        auto it = samples_.end();
        while (it != samples_.begin() && std::prev(it)->first > t) --it;
        samples_.emplace(it, t, v);
        return;
      }
    }
    samples_.emplace_back(t, v);
    while (samples_.size() > 2 && samples_.front().first < t - horizon_) samples_.pop_front();
  }
  // Value at t: interpolated between neighbours closer than max_gap, or held from the nearest sample within
  // max_gap outside the covered span. nullopt when no sample is close enough.
  template <typename Lerp>
  std::optional<T> at(double t, double max_gap, Lerp lerp) const {
    if (samples_.empty()) return std::nullopt;
    if (t <= samples_.front().first)
      return samples_.front().first - t <= max_gap ? std::optional<T>(samples_.front().second) : std::nullopt;
    if (t >= samples_.back().first)
      return t - samples_.back().first <= max_gap ? std::optional<T>(samples_.back().second) : std::nullopt;
    for (std::size_t i = 1; i < samples_.size(); ++i) {
      const auto& a = samples_[i - 1];
      const auto& b = samples_[i];
      if (t <= b.first) {
        if (b.first - a.first > 2 * max_gap) return std::nullopt;  // hole in the data around t
        const double s = b.first > a.first ? (t - a.first) / (b.first - a.first) : 0.0;
        return lerp(a.second, b.second, s);
      }
    }
    return std::nullopt;
  }
  bool empty() const { return samples_.empty(); }
  double lastTime() const { return samples_.empty() ? -1e300 : samples_.back().first; }

 private:
  double horizon_;
  std::deque<std::pair<double, T>> samples_;
};

struct QualityLimits {
  double max_fit_error = 2.0;      // [-], SeaTrac fit error above this is rejected
  double max_age_s = 2.0;          // fix older than this when processed
  double max_pose_gap_s = 0.5;     // USV GPS/heading must be this close to the fix time
  double max_pose_wait_s = 1.5;    // a fix waits this long for the USV's GPS and heading to reach its time
                                   // (they come over the relay, later than the reply); below max_age_s
  double max_depth_error_m = 3.0;  // |USBL depth - depth sensor|
  double max_depth_gap_s = 1.0;    // depth sensor sample this close to the fix time, else the gate is skipped
  // The water's velocity of sound (measured: a sound velocity probe or profile) [m/s]: the range is the travel time
  // times it, not the transceiver's (computed with its own velocity of sound, from its temperature sensor and a
  // salinity setting, which is off by several m/s in a layered lake). 0: the transceiver's range as reported.
  double water_sound_speed = 0.0;
};

// Quality codes: the same values as offshore_gnc/UsblFix QUALITY_*.
enum Quality : std::uint8_t { Q_OK = 0, Q_FILTER_ERROR = 1, Q_FIT_ERROR = 2, Q_STALE = 3, Q_DEPTH = 4, Q_NO_POSITION = 5 };
const char* qualityName(std::uint8_t q);

struct FixResult {
  std::uint8_t quality = Q_NO_POSITION;
  double stamp = 0;                       // when the remote beacon was at `ned` (reply time - travel time)
  std::optional<Eigen::Vector3d> ned;     // remote beacon in local NED (set whenever computable)
  std::optional<Eigen::Vector3d> local;   // remote beacon from ACOFIX POSITION (NED-aligned, transceiver origin)
};

class Positioner {
 public:
  Positioner(const Mounting& mount, const QualityLimits& limits);
  void addUsvPosition(double t, const Eigen::Vector3d& ned) { usv_pos_.add(t, ned); }
  void addUsvAttitude(double t, const Eigen::Quaterniond& q_ned_frd) { usv_att_.add(t, q_ned_frd); }
  void addRemoteDepth(double t, double depth) { depth_.add(t, depth); }
  // True when the USV's position and attitude have samples at or after t_reply (the fix can be placed by
  // interpolation), or t_now is max_pose_wait_s past it (waiting longer would only make the fix stale).
  bool ready(double t_reply, double t_now) const;
  // t_reply: when the reply reached the transceiver; t_now: processing time. Counts the outcome.
  FixResult process(const AcoFix& fix, double t_reply, double t_now);
  // accepted, rejected_<quality name>
  const Counters& counters() const { return counters_; }

 private:
  Mounting mount_;
  Eigen::Matrix3d r_body_xcvr_;
  QualityLimits limits_;
  TimedBuffer<Eigen::Vector3d> usv_pos_;
  TimedBuffer<Eigen::Quaterniond> usv_att_;
  TimedBuffer<double> depth_;
  Counters counters_;
};

}  // namespace usbl
}  // namespace offshore_gnc

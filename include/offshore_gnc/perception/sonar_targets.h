#pragma once
// Mechanical imaging sonar target detection (paper section 3.1), ROS-free.
// Algorithm 1: per beam, ignore bins inside the minimum range, take the strongest bin, keep it when above the
// threshold. Algorithm 2: consecutive beams with detections form one target. Each beam is positioned with the
// sonar pose at the beam's own time (the head is mechanical and the vehicle moves during a sweep). A sweep
// ends at a sector-scan reversal (status bit or observed) or after a full turn; the 0/2pi wrap is continuous.
#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

#include "offshore_gnc/common/counters.h"
#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/perception/target_geometry.h"

namespace offshore_gnc {
namespace perception {

// Head status bits (same values as offshore_gnc/SonarBeam).
enum SonarStatus : std::uint16_t {
  kHeadReady = 1, kMotorOn = 2, kCentring = 4, kScanCw = 8, kSectorReverse = 16, kFault = 32
};

struct SonarBeamView {
  double stamp = 0.0;             // [s]
  double bearing = 0.0;           // clockwise from the head's x axis, [0, 2pi) [rad]
  double beam_width = 0.0;        // [rad]
  double range_resolution = 0.0;  // [m per bin]
  double range_offset = 0.0;      // [m] range of bin 0
  std::uint16_t status = kHeadReady;
  const std::uint8_t* bins = nullptr;
  std::size_t num_bins = 0;
};

struct SonarConfig {
  double min_range = 1.5;         // [m] Algorithm 1: returns from the vehicle's own structure
  double max_range = 0.0;         // [m] 0 = all bins
  int threshold = 90;             // 0..255 intensity a detection must reach
  double max_beam_gap = 6.0 * 3.14159265358979323846 / 180.0;  // [rad] larger bearing step: a new target
  double max_range_jump = 1.0;    // [m] larger range step between consecutive beams starts a new target
  int min_beams = 2;              // targets with fewer beams are dropped (speckle)
  static const ParamTable<SonarConfig>& table();
  void validate() const;
};

struct SonarDetection {
  double stamp = 0.0, bearing = 0.0, range = 0.0;
  std::uint8_t intensity = 0;
  Eigen::Vector3d point{0, 0, 0};   // in the world frame of the pose given with the beam
  Eigen::Vector3d sensor{0, 0, 0};  // sonar head position at that time, world frame
};

struct SonarTarget {
  TargetGeometry geometry;   // world frame; range = shortest beam range, bearing = head bearing (cw) of origin
  double first_bearing = 0.0, last_bearing = 0.0;
  double stamp = 0.0;        // time of the middle beam
};

struct SonarSweep {
  std::vector<SonarDetection> detections;  // acquisition order
  std::vector<SonarTarget> targets;
  double start_stamp = 0.0, end_stamp = 0.0;
  double swept_angle = 0.0;  // [rad]
  bool full_turn = false;
  std::size_t beams = 0;
};

class SonarTargetExtractor {
 public:
  explicit SonarTargetExtractor(const SonarConfig& cfg);

  enum class BeamStatus { Detection, NoDetection, Rejected, HeadNotReady };
  // `sonar_to_world`: pose of the sonar head frame (x forward, y starboard, z down) at the beam's stamp.
  // Returns what happened to the beam; when it completes a sweep, sweepReady() is true until takeSweep().
  BeamStatus addBeam(const SonarBeamView& beam, const Eigen::Isometry3d& sonar_to_world);
  // Validates a beam (bins, bearing in [0, 2pi), geometry, stamp); counts and returns false when unusable.
  // addBeam() does this itself; call it directly to classify a beam that cannot be positioned.
  bool check(const SonarBeamView& beam);
  // Algorithm 1 alone: the strongest bin beyond min_range above the threshold; false when none.
  bool detect(const SonarBeamView& beam, double& range, std::uint8_t& intensity) const;
  // A beam that could not be used (no pose): breaks the run of consecutive detections.
  void breakRun() { closeRun(false); }
  // Ends the current sweep now (e.g. on shutdown or a long pause).
  void flush();

  bool sweepReady() const { return ready_; }
  SonarSweep takeSweep();
  const Counters& counters() const { return counters_; }
  Counters& counters() { return counters_; }
  const SonarConfig& config() const { return cfg_; }

 private:
  struct Run {
    std::vector<SonarDetection> d;
    bool at_start = false, at_end = false;  // touches the sweep's first / last beam
  };
  void closeRun(bool at_end);
  void finishSweep(bool full_turn);
  bool adjacent(const SonarDetection& a, const SonarDetection& b) const;
  SonarTarget makeTarget(const std::vector<SonarDetection>& d) const;

  SonarConfig cfg_;
  Counters counters_;
  SonarSweep current_, done_;
  bool ready_ = false;
  Run run_;
  std::vector<Run> runs_;
  bool have_prev_ = false;
  double prev_bearing_ = 0.0;
  int direction_ = 0;  // +1 clockwise, -1 counter-clockwise, 0 unknown
};

}  // namespace perception
}  // namespace offshore_gnc

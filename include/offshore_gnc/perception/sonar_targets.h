#pragma once
// Mechanical imaging sonar target detection (paper section 3.1), ROS-free.
// Algorithm 1: per beam, ignore bins inside the minimum range, take the strongest bin, keep it when above the
// threshold. Two additions for a sonar in open water (docs/perception.md, "Surface, bottom and clutter"): a bin
// must also stand out of its surroundings (cell-averaging CFAR: surface and bottom reverberation are wide, speckled
// backgrounds, an echo is a peak on them), and bins beyond the range where the vertical beam reaches up to the
// floating hulls' drafts are ignored (the surface's own echoes and those of buoys and boats). Algorithm 2:
// consecutive beams with detections form one target. Each beam is positioned with the
// sonar pose at the beam's own time (the head is mechanical and the vehicle moves during a sweep). A sweep
// ends at a sector-scan reversal (status bit or observed) or after a full turn; the 0/2pi wrap is continuous.
#include <Eigen/Geometry>

#include <cstdint>
#include <limits>
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
  // Targets narrower than this once the beam's own width is taken off their angular extent (seen from the
  // sensor, in the world frame: the vehicle's yaw during the sweep removed) are point scatterers, dropped:
  // mooring lines, fish, bubbles. A point is seen across one beam width wherever it is.
  double min_width = 0.3;         // [m]
  // CFAR: a bin must reach cfar_factor x the mean of the training cells (cfar_window metres each side, past
  // cfar_guard metres of guard cells) on the louder side (greatest-of: the rising edge of reverberation).
  double cfar_factor = 8.0;       // 0 = off
  double cfar_window = 0.75;      // [m]
  double cfar_guard = 0.3;        // [m]
  // Surface gate: with the head's depth, bins beyond (depth - surface_clearance) / sin(e) are ignored, e the
  // elevation of the beam's upper edge (its axis' from the pose, plus vertical_beam / 2): from there on the beam
  // reaches the water just under the surface and the hulls floating there.
  double vertical_beam = 35.0 * 3.14159265358979323846 / 180.0;  // [rad] vertical beam width; 0 = no gate
  double surface_clearance = 0.6;  // [m] the deepest hull draft (and wave trough) under the surface
  // Walls: the sweep's detections through the wall detection (Publication II's split-and-merge, WallConfig's
  // defaults: straight runs of at least 2 m); a target with half or more of its detections within wall_margin of
  // a wall is a piece of that wall (a quay behind the speckle breaks into target-sized runs), dropped.
  double wall_margin = 0.5;        // [m] 0 = off
  static const ParamTable<SonarConfig>& table();
  void validate() const;
};

struct SonarDetection {
  double stamp = 0.0, bearing = 0.0, range = 0.0;
  double beam_width = 0.0;  // [rad]
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
  // `sonar_to_world`: pose of the sonar head frame (x forward, y starboard, z down) at the beam's stamp;
  // `head_depth`: the head's depth under the surface at that time [m] (NaN: unknown, no surface gate).
  // Returns what happened to the beam; when it completes a sweep, sweepReady() is true until takeSweep().
  BeamStatus addBeam(const SonarBeamView& beam, const Eigen::Isometry3d& sonar_to_world,
                     double head_depth = std::numeric_limits<double>::quiet_NaN());
  // Validates a beam (bins, bearing in [0, 2pi), geometry, stamp); counts and returns false when unusable.
  // addBeam() does this itself; call it directly to classify a beam that cannot be positioned.
  bool check(const SonarBeamView& beam);
  // Algorithm 1 alone: the strongest bin beyond min_range, within `max_range` (the surface gate), above the
  // threshold and the CFAR level; false when none.
  bool detect(const SonarBeamView& beam, double& range, std::uint8_t& intensity,
              double max_range = std::numeric_limits<double>::infinity()) const;
  // The surface gate's range for a head at `depth` whose beam axis points `elevation` up [rad] (infinity without
  // a gate, a depth, or when the beam's upper edge points down; 0 above the clearance).
  double surfaceGate(double depth, double elevation) const;
  // The world frame's z axis points up (map, ENU) rather than down (map_ned, the default).
  void setWorldZUp(bool up) { z_up_ = up; }
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
  // The run's width across the line of sight [m], the beam width taken off (0 for a point scatterer).
  static double width(const std::vector<SonarDetection>& d);

  SonarConfig cfg_;
  Counters counters_;
  mutable std::vector<double> cumulative_;  // detect()'s running sums, kept between beams
  bool z_up_ = false;
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

#pragma once
// Cartesian image of the latest sonar beams (what an operator expects from a Micron display), ROS-free.
// Beams are written into a polar buffer (one row per angular cell, one column per range cell); the
// Cartesian view is OpenCV's warpPolar inverse map. Forward (bearing 0) is up, starboard is right.
#include <opencv2/core.hpp>

#include <cstdint>

#include "offshore_gnc/common/param_table.h"

namespace offshore_gnc {
namespace perception {

// The SonarTargets nodelet's image of the beams: its scale and how often it is published.
struct SonarImageParams {
  double image_range = 30.0;  // [m]
  int image_radius_px = 250;
  int image_every_beams = 20;
  static const ParamTable<SonarImageParams>& table() {
    using P = SonarImageParams;
    static const ParamTable<P> t = ParamTable<P>()
        .number("image_range", &P::image_range, 0.1, 1e3, "m", "range at the image's edge")
        .integer("image_radius_px", &P::image_radius_px, 8, 4096, "the image's radius in pixels")
        .integer("image_every_beams", &P::image_every_beams, 1, 100000, "an image published every this many beams");
    return t;
  }
};

class SonarImage {
 public:
  // `max_range` [m] maps to `radius_px`; `angular_cells` rows cover the full turn.
  SonarImage(double max_range, int radius_px, int angular_cells = 720);
  // Writes one beam (bins resampled to the range cells) into every angular cell its beam width covers.
  void addBeam(double bearing, double beam_width, double range_resolution, double range_offset,
               const std::uint8_t* bins, std::size_t num_bins);
  // mono8, (2 radius + 1)^2, sonar head at the centre.
  cv::Mat render() const;
  const cv::Mat& polar() const { return polar_; }
  double metresPerPixel() const { return max_range_ / radius_px_; }

 private:
  double max_range_;
  int radius_px_;
  cv::Mat polar_;  // CV_8UC1, rows = angle cells, cols = range cells (radius_px)
};

}  // namespace perception
}  // namespace offshore_gnc

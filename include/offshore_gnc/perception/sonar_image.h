#pragma once
// Cartesian image of the latest sonar beams (what an operator expects from a Micron display), ROS-free.
// Beams are written into a polar buffer (one row per angular cell, one column per range cell); the
// Cartesian view is OpenCV's warpPolar inverse map. Forward (bearing 0) is up, starboard is right.
#include <opencv2/core.hpp>

#include <cstdint>

namespace offshore_gnc {
namespace perception {

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

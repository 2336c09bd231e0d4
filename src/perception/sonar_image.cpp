#include "offshore_gnc/perception/sonar_image.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace perception {

SonarImage::SonarImage(double max_range, int radius_px, int angular_cells)
    : max_range_(requireRange("image_range", max_range, 0.1, 1e3)),
      radius_px_(static_cast<int>(requireRange("image_radius_px", radius_px, 8, 4096))) {
  requireRange("angular_cells", angular_cells, 36, 36000);
  polar_ = cv::Mat::zeros(angular_cells, radius_px_, CV_8UC1);
}

void SonarImage::addBeam(double bearing, double beam_width, double res, double offset, const std::uint8_t* bins,
                         std::size_t n) {
  if (n == 0 || bins == nullptr || !std::isfinite(bearing) || !(res > 0.0) || !std::isfinite(offset)) return;
  const int rows = polar_.rows;
  // warpPolar's angle runs clockwise on screen from the +x (right) axis; bearing 0 (forward) is up = -90 deg.
  const double a = wrapTwoPi(bearing - 0.5 * kPi);
  const double cell = 2.0 * kPi / rows;
  const int half = std::max(0, static_cast<int>(std::lround(0.5 * std::max(beam_width, 0.0) / cell)));
  const int centre = static_cast<int>(std::lround(a / cell)) % rows;
  const double m_per_px = max_range_ / radius_px_;
  std::uint8_t* row0 = polar_.ptr<std::uint8_t>(centre);
  // Each pixel shows the strongest bin it covers: a one-bin echo must not vanish when pixels are coarser.
  for (int c = 0; c < radius_px_; ++c) {
    const long lo = std::max(0L, static_cast<long>(std::floor((c * m_per_px - offset) / res + 0.5)));
    const long hi = std::min(static_cast<long>(n), static_cast<long>(std::floor(((c + 1) * m_per_px - offset) / res + 0.5)));
    std::uint8_t v = 0;
    for (long i = lo; i < std::max(hi, lo + 1) && i < static_cast<long>(n); ++i) v = std::max(v, bins[i]);
    row0[c] = v;
  }
  for (int k = -half; k <= half; ++k) {
    if (k == 0) continue;
    polar_.row(centre).copyTo(polar_.row(((centre + k) % rows + rows) % rows));
  }
}

cv::Mat SonarImage::render() const {
  cv::Mat out;
  const int size = 2 * radius_px_ + 1;
  cv::warpPolar(polar_, out, cv::Size(size, size), cv::Point2f(radius_px_, radius_px_), radius_px_,
                cv::INTER_LINEAR | cv::WARP_FILL_OUTLIERS | cv::WARP_INVERSE_MAP);
  return out;
}

}  // namespace perception
}  // namespace offshore_gnc

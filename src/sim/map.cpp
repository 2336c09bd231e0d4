// Scenario map image -> occupancy grid and shoreline polygons (OpenCV), as Publication III processed the
// Tampere harbour map: threshold to land/water, trace land contours, simplify to about one cell.
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cmath>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/sim/scenario.h"

namespace offshore_gnc {
namespace sim {

bool MapGrid::occupied(const Eigen::Vector2d& ne) const {
  const int col = static_cast<int>(std::floor((ne.y() - east) / resolution));
  const int row = static_cast<int>(std::floor((ne.x() - north) / resolution));
  if (col < 0 || row < 0 || col >= width || row >= height) return false;
  return data[static_cast<std::size_t>(row) * width + col] > 50;
}

void mapFromImage(const std::string& path, double resolution, double north, double east, int threshold,
                  MapGrid& grid, std::vector<Polygon>& shorelines) {
  const cv::Mat img = cv::imread(path, cv::IMREAD_GRAYSCALE);
  if (img.empty()) throw ConfigError("image '" + path + "' cannot be decoded");
  if (img.cols > 8192 || img.rows > 8192) throw ConfigError("image '" + path + "' is larger than 8192 px");
  cv::Mat land;
  cv::threshold(img, land, threshold - 1, 255, cv::THRESH_BINARY_INV);  // dark = land
  grid.width = img.cols;
  grid.height = img.rows;
  grid.resolution = resolution;
  grid.north = north;
  grid.east = east;
  grid.data.assign(static_cast<std::size_t>(img.cols) * img.rows, 0);
  for (int r = 0; r < img.rows; ++r) {
    const std::size_t row = static_cast<std::size_t>(img.rows - 1 - r);  // image row 0 is the north edge
    for (int c = 0; c < img.cols; ++c)
      if (land.at<std::uint8_t>(r, c)) grid.data[row * img.cols + c] = 100;
  }
  std::vector<std::vector<cv::Point>> contours;
  cv::findContours(land, contours, cv::RETR_LIST, cv::CHAIN_APPROX_SIMPLE);
  for (const auto& c : contours) {
    std::vector<cv::Point> simple;
    cv::approxPolyDP(c, simple, 1.0, true);
    if (simple.size() < 2) continue;
    Polygon p;
    for (const auto& pt : simple)  // pixel centres -> local NED
      p.emplace_back(north + (img.rows - pt.y - 0.5) * resolution, east + (pt.x + 0.5) * resolution);
    shorelines.push_back(std::move(p));
  }
}

}  // namespace sim
}  // namespace offshore_gnc

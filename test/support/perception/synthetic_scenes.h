#pragma once
// Synthetic scenes (header-only) for the perception tests and benchmark: a multi-layer LiDAR ring (MRS1000-like or dense)
// that ray-casts circles (buoys) and boxes (vessels), written as a PointCloud2-layout buffer; sonar beams
// that ray-cast walls and circles from a moving vehicle.
#include <Eigen/Core>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "offshore_gnc/perception/lidar_targets.h"

namespace offshore_gnc {
namespace perception {
namespace scenes {

struct Circle { double x, y, r; };
struct Box { double cx, cy, yaw, l, w; };  // centre, heading, length (along yaw), width

// Ray from origin along (cos a, sin a): distance to the nearest object, +inf if none.
inline double castCircle(const Circle& c, double a) {
  const double dx = std::cos(a), dy = std::sin(a);
  const double b = dx * c.x + dy * c.y, q = c.x * c.x + c.y * c.y - c.r * c.r;
  const double disc = b * b - q;
  if (disc < 0 || b <= 0) return std::numeric_limits<double>::infinity();
  return b - std::sqrt(disc);
}
inline double castSegment(Eigen::Vector2d p, Eigen::Vector2d q, Eigen::Vector2d o, double a) {
  const Eigen::Vector2d d(std::cos(a), std::sin(a)), e = q - p;
  const double den = d.x() * e.y() - d.y() * e.x();
  if (std::abs(den) < 1e-12) return std::numeric_limits<double>::infinity();
  const Eigen::Vector2d w = p - o;
  const double t = (w.x() * e.y() - w.y() * e.x()) / den, s = (w.x() * d.y() - w.y() * d.x()) / den;
  return (t > 0 && s >= 0 && s <= 1) ? t : std::numeric_limits<double>::infinity();
}
inline double castBox(const Box& b, double a) {
  const Eigen::Vector2d c(b.cx, b.cy), u(std::cos(b.yaw), std::sin(b.yaw)), n(-u.y(), u.x());
  const Eigen::Vector2d k[4] = {c + u * b.l / 2 + n * b.w / 2, c - u * b.l / 2 + n * b.w / 2,
                                c - u * b.l / 2 - n * b.w / 2, c + u * b.l / 2 - n * b.w / 2};
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 4; ++i) best = std::min(best, castSegment(k[i], k[(i + 1) % 4], Eigen::Vector2d::Zero(), a));
  return best;
}

// A PointCloud2-layout buffer: x, y, z, intensity float32, ring uint16 (point_step 18: unaligned on purpose).
struct Cloud {
  std::vector<std::uint8_t> data;
  std::uint32_t width = 0, height = 0, point_step = 18;
  offshore_gnc::perception::CloudView view() const {
    offshore_gnc::perception::CloudView v;
    v.data = data.data();
    v.size = data.size();
    v.width = width;
    v.height = height;
    v.point_step = point_step;
    v.row_step = width * point_step;
    auto f = [](std::uint32_t off, std::uint8_t t) {
      offshore_gnc::perception::CloudField c;
      c.present = true; c.offset = off; c.datatype = t;
      return c;
    };
    v.x = f(0, 7); v.y = f(4, 7); v.z = f(8, 7); v.ring = f(16, 4);
    return v;
  }
};

struct Scene {
  std::vector<Circle> circles;
  std::vector<Box> boxes;
};

// layers x columns rays over [start, start + aperture), elevation spread +-spread; no hit -> NaN point.
// organised = height is the number of layers; otherwise one row, layers interleaved per column (ring field).
inline Cloud lidarFrame(const Scene& s, int layers, int columns, double aperture, double spread, bool organised,
                        double max_range = 120.0, double noise = 0.0) {
  Cloud c;
  c.width = organised ? columns : layers * columns;
  c.height = organised ? layers : 1;
  c.data.resize(std::size_t(layers) * columns * c.point_step);
  std::uint32_t seed = 12345;
  auto rnd = [&]() { seed = seed * 1664525u + 1013904223u; return (seed >> 8) / double(1 << 24) - 0.5; };
  for (int l = 0; l < layers; ++l) {
    const double el = layers > 1 ? -spread + 2 * spread * l / (layers - 1) : 0.0;
    for (int k = 0; k < columns; ++k) {
      const double a = -aperture / 2 + aperture * k / columns;
      double r = std::numeric_limits<double>::infinity();
      for (const auto& ci : s.circles) r = std::min(r, castCircle(ci, a));
      for (const auto& b : s.boxes) r = std::min(r, castBox(b, a));
      float p[4];
      if (r < max_range) {
        r += noise * rnd();
        p[0] = float(r * std::cos(a)); p[1] = float(r * std::sin(a)); p[2] = float(r * std::tan(el)); p[3] = 100.f;
      } else {
        p[0] = p[1] = p[2] = std::numeric_limits<float>::quiet_NaN(); p[3] = 0.f;
      }
      const std::size_t idx = organised ? std::size_t(l) * columns + k : std::size_t(k) * layers + l;
      std::uint8_t* dst = c.data.data() + idx * c.point_step;
      std::memcpy(dst, p, 16);
      const std::uint16_t ring = std::uint16_t(l);
      std::memcpy(dst + 16, &ring, 2);
    }
  }
  return c;
}


// Sonar: bins for one beam from a head at `o` (world 2-D, x north, y east), head bearing + vehicle yaw giving
// the world direction (NED, clockwise). Echo 200 at the first hit (circles, wall segments), speckle below.
struct Wall { Eigen::Vector2d p, q; };
inline std::vector<std::uint8_t> sonarBins(const std::vector<Circle>& circles, const std::vector<Wall>& walls,
                                           const Eigen::Vector2d& o, double world_angle, double res, int n) {
  double r = std::numeric_limits<double>::infinity();
  for (const auto& c : circles) r = std::min(r, castCircle(Circle{c.x - o.x(), c.y - o.y(), c.r}, world_angle));
  for (const auto& w : walls) r = std::min(r, castSegment(w.p, w.q, o, world_angle));
  std::vector<std::uint8_t> bins(static_cast<std::size_t>(n), 20);
  for (int i = 0; i < 4; ++i) bins[static_cast<std::size_t>(i)] = 250;  // ringing near the head (inside min range)
  if (std::isfinite(r)) {
    const long k = std::lround(r / res);
    if (k >= 0 && k < n) bins[static_cast<std::size_t>(k)] = 200;
    if (k + 1 >= 0 && k + 1 < n) bins[static_cast<std::size_t>(k + 1)] = 120;
  }
  return bins;
}

}  // namespace scenes
}  // namespace perception
}  // namespace offshore_gnc

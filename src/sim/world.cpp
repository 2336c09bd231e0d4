// Ray geometry for the sensor simulators: 2-D ray casts against circles and segments, with each shape's
// vertical extent, so that a multi-layer LiDAR can decide per layer whether the beam passes over an object.
#include "offshore_gnc/sim/world.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace offshore_gnc {
namespace sim {

namespace {
double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

// Squared distance from point p to segment [a, b].
double segmentDistSq(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double l2 = ab.squaredNorm();
  double t = l2 > 0 ? (p - a).dot(ab) / l2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return (a + t * ab - p).squaredNorm();
}
constexpr double kLandTop = -1e3;  // shorelines are higher than any beam reaches
constexpr double kDraft = 1e3;     // objects reach below the surface: rays aimed down hit them, not water
}  // namespace

double raySegment(const Eigen::Vector2d& o, const Eigen::Vector2d& d, const Eigen::Vector2d& a,
                  const Eigen::Vector2d& b) {
  const Eigen::Vector2d e = b - a;
  const double den = cross(d, e);
  if (std::abs(den) < 1e-12) return -1.0;  // parallel
  const Eigen::Vector2d ao = a - o;
  const double t = cross(ao, e) / den;
  const double u = cross(ao, d) / den;
  return (t >= 0.0 && u >= 0.0 && u <= 1.0) ? t : -1.0;
}

double rayCircle(const Eigen::Vector2d& o, const Eigen::Vector2d& d, const Eigen::Vector2d& c, double r) {
  const Eigen::Vector2d oc = o - c;
  const double b = oc.dot(d);
  const double cc = oc.squaredNorm() - r * r;
  if (cc < 0.0) return -1.0;  // inside
  const double disc = b * b - cc;
  if (disc < 0.0) return -1.0;
  const double t = -b - std::sqrt(disc);
  return t >= 0.0 ? t : -1.0;
}

VesselPose vesselPose(const Vessel& v, double t) {
  const VesselMotion& m = v.motion;
  switch (m.kind) {
    case VesselMotion::Kind::kMoored: return {v.centre, v.yaw};
    case VesselMotion::Kind::kCourse:
      return {v.centre + m.speed * t * Eigen::Vector2d(std::cos(m.course), std::sin(m.course)), m.course};
    case VesselMotion::Kind::kTrack: break;
  }
  // along the track: the legs in order (the closing leg too when it loops), `run` metres from the first point
  const std::size_t n = m.track.size(), legs = m.loop ? n : n - 1;
  double total = 0.0;
  for (std::size_t i = 0; i < legs; ++i) total += (m.track[(i + 1) % n] - m.track[i]).norm();
  double run = m.speed * std::max(t, 0.0);
  if (m.loop && total > 0.0) run = std::fmod(run, total);
  double yaw = v.yaw;
  for (std::size_t i = 0; i < legs; ++i) {
    const Eigen::Vector2d a = m.track[i], d = m.track[(i + 1) % n] - a;
    const double len = d.norm();
    if (len <= 0.0) continue;  // a repeated point: no leg, no heading
    yaw = std::atan2(d.y(), d.x());
    if (run <= len) return {a + run / len * d, yaw};
    run -= len;
  }
  return {m.track[m.loop ? 0 : n - 1], yaw};  // at its end (stopped), heading along its last leg
}

Polygon vesselFootprint(const Vessel& v, double t) {
  const VesselPose p = vesselPose(v, t);
  const Eigen::Vector2d ax(std::cos(p.yaw), std::sin(p.yaw)), ay(-std::sin(p.yaw), std::cos(p.yaw));
  const double hl = v.length / 2, hw = v.width / 2;
  return {p.centre + hl * ax + hw * ay, p.centre - hl * ax + hw * ay, p.centre - hl * ax - hw * ay,
          p.centre + hl * ax - hw * ay};
}

bool insidePolygon(const Polygon& poly, const Eigen::Vector2d& p) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const auto& a = poly[i];
    const auto& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

void RayScene::build(const World& w, double t, const Eigen::Vector2d& centre, double radius) {
  buoys.clear();
  segments.clear();
  segment_extent.clear();
  for (const auto& b : w.buoys)
    if ((b.centre - centre).norm() - b.radius <= radius) buoys.push_back(b);
  auto addPoly = [&](const Polygon& p, double top) {
    for (std::size_t i = 0; i < p.size(); ++i) {
      const auto& a = p[i];
      const auto& b = p[(i + 1) % p.size()];
      if (segmentDistSq(centre, a, b) <= radius * radius) {
        segments.emplace_back(a, b);
        segment_extent.emplace_back(top, kDraft);
      }
    }
  };
  for (const auto& v : w.vessels) addPoly(vesselFootprint(v, t), -v.height);
  for (const auto& p : w.shorelines) addPoly(p, kLandTop);
}

void RayScene::cast(const Eigen::Vector2d& o, const Eigen::Vector2d& d, double max_dist,
                    std::vector<Hit2d>& hits) const {
  for (const auto& b : buoys) {
    const double t = rayCircle(o, d, b.centre, b.radius);
    if (t >= 0.0 && t <= max_dist) hits.push_back({t, -b.height, kDraft});
  }
  for (std::size_t i = 0; i < segments.size(); ++i) {
    const double t = raySegment(o, d, segments[i].first, segments[i].second);
    if (t >= 0.0 && t <= max_dist) hits.push_back({t, segment_extent[i].first, segment_extent[i].second});
  }
}

}  // namespace sim
}  // namespace offshore_gnc

// Time to collision: a ray (the vehicle's course) against each obstacle's capsule grown by the vehicle's radius.
#include "offshore_gnc/safety/collision.h"

#include <algorithm>
#include <cmath>

namespace offshore_gnc {
namespace safety {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Distance along the ray o + s d (d unit) to where it enters the disc (c, r) from outside; inf when it misses.
double enterDisc(const Eigen::Vector2d& o, const Eigen::Vector2d& d, const Eigen::Vector2d& c, double r) {
  const Eigen::Vector2d oc = o - c;
  const double b = oc.dot(d), disc = b * b - (oc.squaredNorm() - r * r);
  if (disc < 0.0) return kInf;
  const double s = -b - std::sqrt(disc);
  return s >= 0.0 ? s : kInf;
}

// The same for the capsule of the segment [a, b] grown by r: the first entry into its two end discs or through
// one of its long sides (its short ends lie inside the discs). 0 when o is within reach and closing, inf when it
// is within reach and not closing.
double enterCapsule(const Eigen::Vector2d& o, const Eigen::Vector2d& d, const Eigen::Vector2d& a,
                    const Eigen::Vector2d& b, double r) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double k = len2 > 0.0 ? std::clamp((o - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  const Eigen::Vector2d off = o - (a + k * ab);  // from the nearest point of the segment
  if (off.norm() <= r) return off.dot(d) < 0.0 ? 0.0 : kInf;
  double best = std::min(enterDisc(o, d, a, r), enterDisc(o, d, b, r));
  if (len2 > 0.0) {
    const double len = std::sqrt(len2);
    const Eigen::Vector2d u = ab / len, n(-u.y(), u.x());
    const double x0 = (o - a).dot(u), y0 = (o - a).dot(n), dx = d.dot(u), dy = d.dot(n);
    if (std::abs(dy) > 1e-12)
      for (double side : {-r, r}) {
        const double s = (side - y0) / dy, x = x0 + s * dx;
        if (s >= 0.0 && x >= 0.0 && x <= len) best = std::min(best, s);
      }
  }
  return best;
}

}  // namespace

Collision timeToCollision(const Eigen::Vector2d& position, const Eigen::Vector2d& velocity,
                          const std::vector<SeenObstacle>& obstacles, double radius) {
  Collision c;
  if (!position.allFinite() || !velocity.allFinite() || !std::isfinite(radius)) {
    c.ttc = std::numeric_limits<double>::quiet_NaN();
    return c;
  }
  const double speed = velocity.norm();
  for (std::size_t i = 0; i < obstacles.size(); ++i) {
    const SeenObstacle& o = obstacles[i];
    if (!o.origin.allFinite() || !o.axis.allFinite() || !(o.length >= 0.0) || !(o.width >= 0.0) ||
        !std::isfinite(o.length) || !std::isfinite(o.width)) {
      ++c.skipped;
      continue;
    }
    if (speed <= 0.0) continue;  // still: closing on nothing (counted obstacles all the same)
    const double n = o.axis.norm();
    const Eigen::Vector2d half = n > 0.0 ? Eigen::Vector2d(o.axis / n * (o.length / 2)) : Eigen::Vector2d::Zero();
    const double r = std::max(radius, 0.0) + (n > 0.0 ? o.width / 2 : std::max(o.length, o.width) / 2);
    const double s = enterCapsule(position, velocity / speed, o.origin - half, o.origin + half, r);
    if (s < c.distance) {
      c.distance = s;
      c.obstacle = static_cast<int>(i);
    }
  }
  if (c.obstacle >= 0) c.ttc = c.distance / speed;
  return c;
}

bool safeSideExists(const std::vector<SafetyBoxView>& boxes, const Eigen::Vector2d& position) {
  for (const SafetyBoxView& b : boxes) {
    if (!b.cuts_path) continue;
    if (b.blocked) return false;
    // inside the convex box: on the same side of all four edges (either winding)
    int pos = 0, neg = 0;
    for (std::size_t i = 0; i < 4; ++i) {
      const Eigen::Vector2d e = b.corners[(i + 1) % 4] - b.corners[i], p = position - b.corners[i];
      const double cross = e.x() * p.y() - e.y() * p.x();
      pos += cross > 0.0;
      neg += cross < 0.0;
    }
    if (pos == 4 || neg == 4) return false;
  }
  return true;
}

}  // namespace safety
}  // namespace offshore_gnc

#pragma once
// Angle helpers shared by every module: radians inside the code, wrapped to (-pi, pi].
#include <cmath>

namespace offshore_gnc {

constexpr double kPi = 3.14159265358979323846;

inline double deg2rad(double d) { return d * kPi / 180.0; }
inline double rad2deg(double r) { return r * 180.0 / kPi; }

// Wrap to (-pi, pi]. Non-finite input is returned unchanged so callers can detect it.
inline double wrapAngle(double a) {
  if (!std::isfinite(a)) return a;
  a = std::fmod(a + kPi, 2.0 * kPi);
  if (a <= 0.0) a += 2.0 * kPi;
  return a - kPi;
}

// Wrap to [0, 2 pi): sonar bearings and compass headings.
inline double wrapTwoPi(double a) {
  if (!std::isfinite(a)) return a;
  a = std::fmod(a, 2.0 * kPi);
  if (a < 0.0) a += 2.0 * kPi;
  return a < 2.0 * kPi ? a : 0.0;  // a negative a within an ulp of 0 plus 2 pi rounds to 2 pi itself (360 degrees)
}

// Signed smallest difference a - b, in (-pi, pi].
inline double angleDiff(double a, double b) { return wrapAngle(a - b); }

}  // namespace offshore_gnc

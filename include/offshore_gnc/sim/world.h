#pragma once
// The simulated world the sensor models see: buoys (vertical cylinders, moored to the bottom), vessels (boxes,
// moored or under way), shorelines (closed polygons of land, infinitely high), underwater walls (vertical
// segments), underwater targets and a flat bottom. Time t is the simulation's [s] from the scenario's start: a
// vessel under way is where vesselPose(v, t) puts it, for every sensor and contact check alike.
// NED frame (x north, y east, z down), SI units. ROS-free.
#include <Eigen/Core>
#include <vector>

namespace offshore_gnc {
namespace sim {

struct Buoy {
  Eigen::Vector2d centre{0, 0};  // north, east [m]
  double radius = 0.5;
  double height = 1.0;  // above the waterline [m]
  double draft = 0.5;   // below it [m]; a vertical mooring line runs from there to the bottom
};

// How a vessel moves: not at all, on a constant course and speed from its centre, or along a track of waypoints
// at a speed (from the first point; it stops at the last, or with `loop` runs back to the first and round again).
// Under way its long axis points along its course.
struct VesselMotion {
  enum class Kind { kMoored, kCourse, kTrack };
  Kind kind = Kind::kMoored;
  double course = 0.0;  // [rad] NED, kCourse
  double speed = 0.0;   // over ground [m/s]
  std::vector<Eigen::Vector2d> track;  // kTrack: north, east [m], at least two points
  bool loop = false;                   // kTrack
  // false: keeps its course and speed whatever the rules ask of it (for the COLREGs work; the simulator moves
  // every vessel as its motion says either way)
  bool gives_way = true;
};

struct Vessel {
  Eigen::Vector2d centre{0, 0};  // moored, or where it is at t = 0 on a course (a track starts at its first point)
  double yaw = 0.0;  // heading of the long axis [rad]
  double length = 8.0, width = 3.0, height = 2.0;
  double draft = 0.5;  // [m]
  VesselMotion motion;
};

struct VesselPose {
  Eigen::Vector2d centre;
  double yaw;
};
// Where the vessel is at time t [s]; a moored vessel at its centre whatever t.
VesselPose vesselPose(const Vessel& v, double t);

struct Target {  // underwater object (sphere), e.g. the thesis' sunken target
  Eigen::Vector3d position{0, 0, 0};
  double radius = 0.5;
};

struct Wall {  // underwater vertical wall from the surface to the bottom (harbour quay, dam)
  Eigen::Vector2d a{0, 0}, b{0, 0};
};

using Polygon = std::vector<Eigen::Vector2d>;  // closed implicitly (last -> first)

struct World {
  std::vector<Buoy> buoys;
  std::vector<Vessel> vessels;
  std::vector<Polygon> shorelines;
  std::vector<Wall> walls;
  std::vector<Target> targets;
  double bottom_depth = 0.0;  // flat bottom [m]; 0 = none (deep water)
};

// Vertical extent a horizontal 2-D hit covers: z from `top` (negative = above water) to `bottom`.
struct Hit2d {
  double distance;  // horizontal distance along the ray [m]
  double top, bottom;
};

// All horizontal intersections of a ray (origin o, unit direction d, NED x/y) with the world's above-water
// objects, nearer than max_dist. Appends to `hits` (not sorted). Shapes are pre-culled by the caller.
struct RayScene {
  std::vector<Buoy> buoys;
  std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> segments;  // with their vertical extents below
  std::vector<std::pair<double, double>> segment_extent;
  // The shapes within `radius` of `centre`, vessels where they are at time t.
  void build(const World& w, double t, const Eigen::Vector2d& centre, double radius);
  void cast(const Eigen::Vector2d& o, const Eigen::Vector2d& d, double max_dist, std::vector<Hit2d>& hits) const;
};

// Distance along the ray (o + t d, d unit) to the segment [a, b], or a negative value when it misses.
double raySegment(const Eigen::Vector2d& o, const Eigen::Vector2d& d, const Eigen::Vector2d& a,
                  const Eigen::Vector2d& b);
// Distance along the ray to a circle's boundary from outside (negative when it misses or o is inside).
double rayCircle(const Eigen::Vector2d& o, const Eigen::Vector2d& d, const Eigen::Vector2d& c, double r);
// Corners of a vessel's footprint at time t (counter-clockwise in NED x/y order of construction).
Polygon vesselFootprint(const Vessel& v, double t);
// True when p lies inside the polygon (even-odd rule).
bool insidePolygon(const Polygon& poly, const Eigen::Vector2d& p);

}  // namespace sim
}  // namespace offshore_gnc

// Sensor simulators (GPS-compass, multi-layer LiDAR, mechanical imaging sonar, depth, AHRS, DVL, INS estimate).
#include "offshore_gnc/sim/sensors.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace sim {

namespace {
constexpr double kGravity = 9.80665;

Eigen::Vector2d rotate2(double yaw, const Eigen::Vector3d& body) {
  const double c = std::cos(yaw), s = std::sin(yaw);
  return {c * body.x() - s * body.y(), s * body.x() + c * body.y()};
}
Eigen::Matrix3d bodyToNed(const VehicleState& s) {
  return (Eigen::AngleAxisd(s.yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(s.pitch, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(s.roll, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}
void requireRate(const char* name, double hz) { requireRange(name, hz, 1e-3, 1e4); }
}  // namespace

// ---------------------------------------------------------------- GPS-compass
GpsCompass::GpsCompass(const GpsCompassConfig& cfg, const geo::LocalNed& frame, std::uint64_t seed)
    : cfg_(cfg), frame_(frame), rng_(seed) {
  GpsCompassConfig::table().validate(cfg);
}

namespace {
// An event of a Poisson process with this mean interval (0: never) starting within dt.
bool starts(double interval, double dt, double u) { return interval > 0.0 && dt > 0.0 && u < -std::expm1(-dt / interval); }
}  // namespace

GpsCompassReading GpsCompass::measure(const VehicleState& s) {
  const double dt = started_ ? std::max(0.0, s.t - last_t_) : 0.0;
  // Slow error: exact discretisation of a first-order Gauss-Markov process over the time since the last fix
  // (stationary from the first fix on, so its 1-sigma is position_sigma at every time).
  if (!started_) {
    slow_error_ = {cfg_.position_sigma * n_(rng_), cfg_.position_sigma * n_(rng_)};
    started_ = true;
  } else if (cfg_.position_tau <= 0.0) {
    slow_error_ = {cfg_.position_sigma * n_(rng_), cfg_.position_sigma * n_(rng_)};
  } else {
    const double phi = std::exp(-dt / cfg_.position_tau);
    const double q = cfg_.position_sigma * std::sqrt(1.0 - phi * phi);
    slow_error_ = phi * slow_error_ + Eigen::Vector2d(q * n_(rng_), q * n_(rng_));
  }
  last_t_ = s.t;
  // A jump steps the error and holds it; an outage silences the receiver. Both start as Poisson events.
  if (s.t >= jump_until_) jump_.setZero();
  if (s.t >= jump_until_ && starts(cfg_.jump_interval, dt, u_(rng_))) {
    jump_ = {cfg_.jump_sigma * n_(rng_), cfg_.jump_sigma * n_(rng_)};
    jump_until_ = s.t - cfg_.jump_duration * std::log(1.0 - u_(rng_));
  }
  if (s.t >= outage_until_ && valid_ && starts(cfg_.outage_interval, dt, u_(rng_)))  // not back to back
    outage_until_ = s.t + 0.2 + (cfg_.outage_duration - 0.2) * u_(rng_);
  valid_ = s.t >= outage_until_;
  const Eigen::Vector2d off = rotate2(s.yaw, cfg_.antenna);
  Eigen::Vector3d p(s.position.x() + off.x(), s.position.y() + off.y(), s.position.z() + cfg_.antenna.z());
  p.x() += slow_error_.x() + jump_.x() + cfg_.position_white_sigma * n_(rng_);
  p.y() += slow_error_.y() + jump_.y() + cfg_.position_white_sigma * n_(rng_);
  p.z() += cfg_.altitude_sigma * n_(rng_);
  GpsCompassReading r;
  r.t = s.t;
  r.valid = valid_;
  r.fix = frame_.toGeodetic(p);
  r.heading = wrapAngle(s.yaw + cfg_.heading_sigma * n_(rng_));
  // antenna velocity over ground: the vessel's plus the yaw rate acting on the lever arm (r x antenna)
  const double yaw_rate = s.angular_rate.z();
  const Eigen::Vector2d v_body(s.velocity.x() - yaw_rate * cfg_.antenna.y(), s.velocity.y() + yaw_rate * cfg_.antenna.x());
  r.velocity_ned = rotate2(s.yaw, Eigen::Vector3d(v_body.x(), v_body.y(), 0.0)) +
                   Eigen::Vector2d(cfg_.velocity_sigma * n_(rng_), cfg_.velocity_sigma * n_(rng_));
  r.rate_of_turn = yaw_rate + cfg_.rate_sigma * n_(rng_);
  r.position_sigma = std::hypot(cfg_.position_sigma, cfg_.position_white_sigma);
  r.heading_sigma = cfg_.heading_sigma;
  r.velocity_sigma = cfg_.velocity_sigma;
  return r;
}

// ---------------------------------------------------------------- LiDAR
Eigen::Vector3d LidarScan::pointFrd(int layer, int beam) const {
  const double r = ranges[static_cast<std::size_t>(layer) * beams + beam];
  const double e = elevation[layer], a = azimuth[beam];
  return {r * std::cos(e) * std::cos(a), r * std::cos(e) * std::sin(a), -r * std::sin(e)};
}

Eigen::Isometry3d sensorMount(const Eigen::Vector3d& mount_frd, double yaw_frd, bool frd_sensor, double pitch_frd) {
  Eigen::Isometry3d t = Eigen::Translation3d(mount_frd) * Eigen::AngleAxisd(yaw_frd, Eigen::Vector3d::UnitZ()) *
                        Eigen::AngleAxisd(pitch_frd, Eigen::Vector3d::UnitY());
  if (!frd_sensor) t = t * Eigen::AngleAxisd(kPi, Eigen::Vector3d::UnitX());  // FLU sensor axes
  return t;
}

void packCloud(const LidarScan& scan, PackedCloud& out) {
  out.width = static_cast<std::uint32_t>(scan.beams);
  out.height = static_cast<std::uint32_t>(scan.layers);
  out.data.assign(static_cast<std::size_t>(out.width) * out.height * PackedCloud::kPointStep, 0);
  std::uint8_t* d = out.data.data();
  for (int l = 0; l < scan.layers; ++l)
    for (int b = 0; b < scan.beams; ++b, d += PackedCloud::kPointStep) {
      const bool no_return = std::isnan(scan.ranges[static_cast<std::size_t>(l) * scan.beams + b]);
      const float nan = std::numeric_limits<float>::quiet_NaN();
      const Eigen::Vector3d p = no_return ? Eigen::Vector3d::Constant(nan) : scan.pointFrd(l, b);
      const float xyz[3] = {static_cast<float>(p.x()), static_cast<float>(-p.y()), static_cast<float>(-p.z())};
      const std::uint16_t ring = static_cast<std::uint16_t>(l);
      std::memcpy(d + PackedCloud::kX, xyz, sizeof xyz);
      std::memcpy(d + PackedCloud::kRing, &ring, sizeof ring);
    }
}

Lidar::Lidar(const LidarConfig& cfg, const World& world, std::uint64_t seed, const models::Environment* env)
    : cfg_(cfg), world_(world), env_(env), rng_(seed) {
  requireRate("lidar/rate", cfg.rate_hz);
  requireRange("lidar/layers", cfg.layers, 1, 64);
  if (static_cast<int>(cfg.layer_elevation.size()) != cfg.layers)
    throw ConfigError("parameter 'lidar/layer_elevation' must have one angle per layer");
  for (double e : cfg.layer_elevation) requireRange("lidar/layer_elevation", e, -1.4, 1.4);
  requireRange("lidar/aperture", cfg.aperture, 1e-3, 2 * kPi);
  requireRange("lidar/step", cfg.step, 1e-4, 1.0);
  requireRange("lidar/min_range", cfg.min_range, 0, 1e3);
  requireRange("lidar/max_range", cfg.max_range, cfg.min_range + 1e-3, 1e4);
  requireRange("lidar/range_sigma", cfg.range_sigma, 0, 10);
  LidarSeaConfig::table().validate(cfg.sea, "lidar/");
  beams_ = static_cast<int>(std::floor(cfg.aperture / cfg.step + 1e-9)) + 1;
  for (int b = 0; b < beams_; ++b) {
    cos_az_.push_back(std::cos(-cfg_.aperture / 2 + b * cfg_.step));
    sin_az_.push_back(std::sin(-cfg_.aperture / 2 + b * cfg_.step));
  }
}

void Lidar::scan(const VehicleState& s, LidarScan& out) {
  out.t = s.t;
  out.layers = cfg_.layers;
  out.beams = beams_;
  out.ranges.assign(static_cast<std::size_t>(cfg_.layers) * beams_, std::numeric_limits<float>::quiet_NaN());
  out.azimuth.resize(beams_);
  out.elevation = cfg_.layer_elevation;
  // The sensor's pose: the hull's roll, pitch and heave (its wave-frequency motion) move it and tilt its layers.
  const Eigen::Matrix3d to_ned = bodyToNed(s) * Eigen::AngleAxisd(cfg_.mount_yaw, Eigen::Vector3d::UnitZ());
  const Eigen::Vector3d sensor = s.position + bodyToNed(s) * cfg_.mount;
  const Eigen::Vector2d o = sensor.head<2>();
  const double zs = sensor.z();  // NED: negative above the mean water level
  // broad phase once per frame: only shapes within range of the sensor are tested per beam
  scene_.build(world_, s.t, o, cfg_.max_range);
  std::vector<double> sin_e(cfg_.layers), cos_e(cfg_.layers);
  for (int l = 0; l < cfg_.layers; ++l) {
    sin_e[l] = std::sin(cfg_.layer_elevation[l]);
    cos_e[l] = std::cos(cfg_.layer_elevation[l]);
  }
  const double hs = env_ ? env_->significantHeight() : 0.0;
  const models::SurfaceSection surface = hs > 0.0 ? env_->section(s.t, o, cfg_.max_range) : models::SurfaceSection();
  // whitecaps: the fraction for the wind at this moment (its gusts), once per frame
  const double foam = env_ ? models::whitecapFraction(env_->windSpeed(s.t)) : 0.0;
  for (int b = 0; b < beams_; ++b) {
    const double az = -cfg_.aperture / 2 + b * cfg_.step, ca = cos_az_[b], sa = sin_az_[b];
    out.azimuth[b] = az;
    // One 2-D cast per azimuth, along the level beam's horizontal direction; each layer then has its own slope
    // (tilted by roll and pitch). A tilted layer's horizontal direction differs from it by under 0.5 deg.
    const Eigen::Vector3d level = to_ned * Eigen::Vector3d(ca, sa, 0.0);
    if (level.head<2>().norm() < 1e-6) continue;
    const Eigen::Vector2d d = level.head<2>().normalized();
    hits_.clear();
    scene_.cast(o, d, cfg_.max_range, hits_);
    std::sort(hits_.begin(), hits_.end(), [](const Hit2d& a, const Hit2d& c) { return a.distance < c.distance; });
    for (int l = 0; l < cfg_.layers; ++l) {
      const Eigen::Vector3d dir = to_ned * Eigen::Vector3d(cos_e[l] * ca, cos_e[l] * sa, -sin_e[l]);
      const double horizontal = dir.head<2>().norm();
      if (horizontal < 1e-6) continue;
      const double slope = dir.z() / horizontal;  // down per metre across
      // where a beam aimed below the horizon meets the water (on the waves' surface there, one iteration)
      double t_water = std::numeric_limits<double>::infinity();
      // (a beam that would not meet even a crest 2 Hs high within range never meets the water)
      if (slope > 0 && zs < 0 && (-zs - 2.0 * hs) / slope <= cfg_.max_range) {
        t_water = -zs / slope;
        if (hs > 0.0) t_water = std::max(0.0, (-surface(o + t_water * d) - zs) / slope);
      }
      float& range = out.ranges[static_cast<std::size_t>(l) * beams_ + b];
      auto returns = [&](double t) {
        const double r = t / horizontal + cfg_.range_sigma * n_(rng_);
        if (r >= cfg_.min_range && r <= cfg_.max_range && u_(rng_) >= cfg_.sea.dropout) range = static_cast<float>(r);
      };
      bool hit = false;
      for (const auto& h : hits_) {
        if (h.distance > t_water) break;
        const double z = zs + h.distance * slope;
        if (z < h.top || z > h.bottom) continue;  // passes over (or under) this object
        returns(h.distance);
        hit = true;
        break;
      }
      // A beam that ends on the water returns only from a whitecap: a calm or rippled surface reflects the beam
      // away at these grazing angles.
      if (!hit && foam > 0.0 && t_water * horizontal <= cfg_.max_range &&
          env_->foam(s.t, o + t_water * d, cfg_.sea.foam_patch, cfg_.sea.foam_life, foam))
        returns(t_water);
    }
  }
  spray(s, sensor, to_ned, out);
  // the built-in IMU: the sensor frame's roll and pitch
  const double pitch = -std::asin(std::clamp(to_ned(2, 0), -1.0, 1.0)), roll = std::atan2(to_ned(2, 1), to_ned(2, 2));
  out.roll = roll + cfg_.sea.imu_sigma * n_(rng_);
  out.pitch = pitch + cfg_.sea.imu_sigma * n_(rng_);
}

// Spray about the bow: a Poisson number of returns per frame, growing with the sea and the boat's speed, each on a
// random beam of the spray zone at a random range, where that beam passes through the spray's layer of air.
void Lidar::spray(const VehicleState& s, const Eigen::Vector3d& sensor, const Eigen::Matrix3d& to_ned,
                  LidarScan& out) {
  const double hs = env_ ? env_->significantHeight() : 0.0, speed = s.velocity.head<2>().norm();
  const double mean = cfg_.sea.spray_rate * (hs / 1.0 + (speed / 4.0) * (speed / 4.0));
  if (mean <= 0.0 || cfg_.sea.spray_range <= cfg_.min_range) return;
  std::poisson_distribution<int> count(mean);
  const int n = count(rng_);
  const int half = static_cast<int>(0.5 * std::min(cfg_.sea.spray_sector, cfg_.aperture) / cfg_.step);
  for (int k = 0; k < n; ++k)
    for (int attempt = 0; attempt < 8; ++attempt) {  // a point of the zone some beam passes through
      const int b = std::clamp(beams_ / 2 + static_cast<int>(std::lround((2 * u_(rng_) - 1) * half)), 0, beams_ - 1);
      const int l = static_cast<int>(u_(rng_) * cfg_.layers) % cfg_.layers;
      const double r = cfg_.min_range + u_(rng_) * (cfg_.sea.spray_range - cfg_.min_range);
      const double e = cfg_.layer_elevation[l], az = out.azimuth[b];
      const double z = sensor.z() + r * (to_ned * Eigen::Vector3d(std::cos(e) * std::cos(az), std::cos(e) * std::sin(az),
                                                                  -std::sin(e))).z();
      if (z > 0.0 || z < -cfg_.sea.spray_height) continue;  // the beam is under the water or above the spray there
      float& range = out.ranges[static_cast<std::size_t>(l) * beams_ + b];
      if (!(range <= r)) range = static_cast<float>(r);  // a droplet nearer than what the beam saw hides it
      break;
    }
}

// ---------------------------------------------------------------- imaging sonar
Sonar::Sonar(const SonarConfig& cfg, const World& world, std::uint64_t seed, const models::Environment* env)
    : cfg_(cfg), world_(world), env_(env), angle_(-cfg.sector / 2), rng_(seed) {
  requireRate("sonar/ping_rate", cfg.ping_rate_hz);
  requireRange("sonar/step", cfg.step, 1e-3, 0.5);
  requireRange("sonar/sector", cfg.sector, cfg.step, 2 * kPi);
  requireRange("sonar/range", cfg.range, 0.5, 300);
  requireRange("sonar/bins", cfg.bins, 8, 1500);
  requireRange("sonar/beam_width", cfg.beam_width, 1e-3, 1.0);
  requireRange("sonar/vertical_width", cfg.vertical_width, 1e-3, kPi);
  requireRange("sonar/near_field", cfg.near_field, 0, cfg.range);
  requireRange("sonar/noise_level", cfg.noise_level, 0, 255);
  SonarWaterConfig::table().validate(cfg.water, "sonar/");
}

int Sonar::binOfRange(double r) const {
  const double res = cfg_.range / cfg_.bins;
  return static_cast<int>(std::floor(r / res));
}

double Sonar::reverb(double level, double off, double r) const {
  if (level <= 0.0) return 0.0;
  const double x = off / (0.5 * cfg_.vertical_width);
  return level * std::pow(10.0, -0.6 * x * x) * std::exp(-0.03 * r);  // -6 dB two way at the edge
}

void Sonar::ping(const VehicleState& s, SonarBeamReading& out) {
  const double res = cfg_.range / cfg_.bins;
  out.t = s.t;
  out.bearing = wrapTwoPi(angle_);
  out.beam_width = cfg_.beam_width;
  out.range_resolution = res;
  out.range_offset = res / 2;
  out.head_status = kHeadReady | kMotorOn | (direction_ > 0 ? kScanCw : 0) | (reversed_ ? kSectorReverse : 0);
  out.intensities.resize(cfg_.bins);

  // The head's frame in NED (the vehicle's attitude, then the tilt): every echo is placed in it, so that the beam's
  // 3 deg (across) and 35 deg (up and down) widths apply about its own axis.
  const Eigen::Matrix3d to_ned = bodyToNed(s) * Eigen::AngleAxisd(-cfg_.tilt, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Vector3d head = s.position + bodyToNed(s) * cfg_.mount;
  const Eigen::Vector3d axis = to_ned * Eigen::Vector3d(std::cos(angle_), std::sin(angle_), 0.0);
  const double elevation = std::asin(std::clamp(-axis.z(), -1.0, 1.0));  // the axis' [rad, up]
  const Eigen::Vector2d d = axis.head<2>().norm() > 1e-9 ? Eigen::Vector2d(axis.head<2>().normalized())
                                                         : Eigen::Vector2d(std::cos(s.yaw), std::sin(s.yaw));
  const double half_v = 0.5 * cfg_.vertical_width;
  const SonarWaterConfig& wc = cfg_.water;
  // the surface above the head (its waves' elevation there) and the bottom below it
  const double above = head.z() + (env_ ? env_->elevation(s.t, head.head<2>()) : 0.0);
  const double below = world_.bottom_depth > 0.0 ? world_.bottom_depth - head.z() : 0.0;
  const double wind = env_ ? env_->windSpeed(s.t) : 0.0;
  std::exponential_distribution<double> speckle(1.0);
  std::vector<double> level(cfg_.bins);
  for (int i = 0; i < cfg_.bins; ++i) {
    const double r = (i + 0.5) * res;
    // speckle: the intensity of a Rayleigh-distributed echo amplitude is exponential; reverberation's too. A
    // boundary at range r is seen at elevation asin(height / r), off the axis by that minus the axis'.
    double mean = cfg_.noise_level;
    if (above > 0.0 && r > above) mean += reverb(wc.surface_reverb * wind * wind, std::asin(above / r) - elevation, r);
    if (below > 0.0 && r > below) mean += reverb(wc.bottom_reverb, -std::asin(below / r) - elevation, r);
    double v = mean * speckle(rng_);
    if (r < cfg_.near_field) v += 160.0 * std::exp(-r / (0.3 * cfg_.near_field)) * (0.5 + u_(rng_));
    level[i] = v;
  }
  // volume clutter: scatterers uniform in the insonified volume (beam width x vertical width x range), new each ping
  if (wc.clutter_density > 0.0) {
    const double volume = cfg_.beam_width * cfg_.vertical_width * std::pow(cfg_.range, 3) / 3.0;
    std::poisson_distribution<int> count(wc.clutter_density * volume);
    for (int k = count(rng_); k > 0; --k) {
      const int i = binOfRange(cfg_.range * std::cbrt(u_(rng_)));
      if (i >= 0 && i < cfg_.bins) level[i] += wc.clutter_echo * speckle(rng_);
    }
  }
  auto echo = [&](double r, double strength, int thickness, bool shadow) {
    const int b0 = binOfRange(r);
    if (b0 < 0 || b0 >= cfg_.bins) return;
    for (int k = 0; k < thickness && b0 + k < cfg_.bins; ++k)
      level[b0 + k] += strength * std::exp(-0.03 * r) * (0.8 + 0.4 * u_(rng_)) / (1 + k);
    // acoustic shadow behind a strong reflector
    if (shadow)
      for (int k = b0 + thickness; k < cfg_.bins; ++k) level[k] *= 0.3;
  };
  // A point at `v` (NED, from the head) of angular half-size `half`: inside the beam's 3 deg across and its
  // 35 deg up and down about the axis.
  auto inBeam = [&](const Eigen::Vector3d& v, double half) {
    const Eigen::Vector3d h = to_ned.transpose() * v;  // head frame
    const double across = angleDiff(std::atan2(h.y(), h.x()), angle_), up = std::atan2(h.z(), std::hypot(h.x(), h.y()));
    return std::abs(across) <= cfg_.beam_width / 2 + half && std::abs(up) <= half_v + half && h.x() > 0.0;
  };
  // the axis' slant range to a vertical surface `t` metres away horizontally
  const double slant = 1.0 / std::max(1e-3, std::cos(elevation));
  double nearest_wall = cfg_.range;
  for (const auto& w : world_.walls) {
    const double t = raySegment(head.head<2>(), d, w.a, w.b) * slant;
    if (t >= 0 && t < nearest_wall) nearest_wall = t;
  }
  for (const auto& tg : world_.targets) {
    const Eigen::Vector3d v = tg.position - head;
    const double dh = v.head<2>().norm();
    const double dist = v.norm();
    if (dist - tg.radius > cfg_.range || dist - tg.radius >= nearest_wall || dh < 1e-6) continue;
    if (!inBeam(v, std::atan2(tg.radius, dist))) continue;
    echo(dist - tg.radius, 230.0, std::max(2, static_cast<int>(tg.radius / res)), true);
  }
  // Floating hulls, seen from below where their underside's edge (at their draft) is inside the beam; buoys'
  // mooring lines, from their draft down to the bottom, where they cross the beam's fan.
  for (const auto& b : world_.buoys) {
    const Eigen::Vector2d v = b.centre - head.head<2>();
    const double dh = v.norm();
    if (dh - b.radius > cfg_.range || dh < 1e-6) continue;
    const Eigen::Vector2d edge = v * std::max(0.0, dh - b.radius) / dh;
    const Eigen::Vector3d under(edge.x(), edge.y(), b.draft - head.z());
    if (under.norm() < nearest_wall && inBeam(under, std::atan2(b.radius, dh))) echo(under.norm(), wc.hull_echo, 3, true);
    // the line's depths inside the fan at its distance, then its nearest point there
    const double top = head.z() - dh * std::tan(std::min(elevation + half_v, 1.5));
    const double bottom = head.z() - dh * std::tan(std::max(elevation - half_v, -1.5));
    const double line_bottom = world_.bottom_depth > 0.0 ? world_.bottom_depth : std::numeric_limits<double>::infinity();
    const double lo = std::max(top, b.draft), hi = std::min(bottom, line_bottom);
    if (lo > hi) continue;
    const Eigen::Vector3d line(v.x(), v.y(), std::clamp(head.z(), lo, hi) - head.z());
    if (line.norm() < nearest_wall && inBeam(line, 0.0))  // thinner than the beam: only inside it
      echo(line.norm(), wc.mooring_echo, 1, false);        // and it casts no shadow worth the name
  }
  for (const auto& vsl : world_.vessels) {
    const Polygon hull = vesselFootprint(vsl, s.t);
    double t_hull = -1.0;
    for (std::size_t i = 0; i < hull.size(); ++i) {
      const double t = raySegment(head.head<2>(), d, hull[i], hull[(i + 1) % hull.size()]);
      if (t >= 0.0 && (t_hull < 0.0 || t < t_hull)) t_hull = t;
    }
    if (t_hull < 0.0) continue;
    const Eigen::Vector3d under(t_hull * d.x(), t_hull * d.y(), vsl.draft - head.z());
    if (under.norm() < nearest_wall && under.norm() < cfg_.range && inBeam(under, 0.0))
      echo(under.norm(), wc.hull_echo, 3, true);
  }
  if (nearest_wall < cfg_.range) echo(nearest_wall, 200.0, 3, true);
  for (int i = 0; i < cfg_.bins; ++i) out.intensities[i] = static_cast<std::uint8_t>(std::clamp(level[i], 0.0, 255.0));

  // step the head: sector scan back and forth
  reversed_ = false;
  angle_ += direction_ * cfg_.step;
  if (std::abs(angle_) > cfg_.sector / 2 + 1e-9) {
    direction_ = -direction_;
    angle_ += 2 * direction_ * cfg_.step;
    reversed_ = true;
  }
}

// ---------------------------------------------------------------- depth
DepthSensor::DepthSensor(const DepthConfig& cfg, std::uint64_t seed) : cfg_(cfg), rng_(seed) {
  DepthConfig::table().validate(cfg);
}

DepthReading DepthSensor::measure(const VehicleState& s) {
  const double depth = std::max(0.0, s.position.z());
  return {s.t, cfg_.atmosphere_pa + cfg_.water_density * kGravity * depth + cfg_.sigma_pa * n_(rng_), cfg_.sigma_pa};
}

double DepthSensor::depthOf(double p) const { return (p - cfg_.atmosphere_pa) / (cfg_.water_density * kGravity); }

// ---------------------------------------------------------------- AHRS
Ahrs::Ahrs(const AhrsConfig& cfg, std::uint64_t seed) : cfg_(cfg), rng_(seed) { AhrsConfig::table().validate(cfg); }

AhrsReading Ahrs::measure(const VehicleState& s, const Eigen::Vector3d& accel_body) {
  if (!started_) {
    bias_ = cfg_.heading_bias_sigma * n_(rng_);
    drift_ = cfg_.heading_drift_sigma * n_(rng_);  // stationary from the start
    started_ = true;
  } else {
    const double phi = std::exp(-std::max(0.0, s.t - last_t_) / cfg_.heading_drift_tau);
    drift_ = phi * drift_ + cfg_.heading_drift_sigma * std::sqrt(1.0 - phi * phi) * n_(rng_);
  }
  last_t_ = s.t;
  AhrsReading r;
  r.t = s.t;
  r.roll = wrapAngle(s.roll + cfg_.attitude_sigma * n_(rng_));
  r.pitch = wrapAngle(s.pitch + cfg_.attitude_sigma * n_(rng_));
  r.yaw = wrapAngle(s.yaw + bias_ + drift_ + cfg_.heading_sigma * n_(rng_));
  const Eigen::Vector3d noise_w(n_(rng_), n_(rng_), n_(rng_)), noise_a(n_(rng_), n_(rng_), n_(rng_));
  r.angular_rate = s.angular_rate + cfg_.gyro_sigma * noise_w;
  // accelerometers measure acceleration minus gravity (NED gravity is +z)
  r.specific_force = accel_body - bodyToNed(s).transpose() * Eigen::Vector3d(0, 0, kGravity) + cfg_.accel_sigma * noise_a;
  r.attitude_sigma = cfg_.attitude_sigma;
  r.heading_sigma = std::sqrt(cfg_.heading_bias_sigma * cfg_.heading_bias_sigma +
                              cfg_.heading_drift_sigma * cfg_.heading_drift_sigma + cfg_.heading_sigma * cfg_.heading_sigma);
  r.gyro_sigma = cfg_.gyro_sigma;
  r.accel_sigma = cfg_.accel_sigma;
  return r;
}

// ---------------------------------------------------------------- DVL
Dvl::Dvl(const DvlConfig& cfg, std::uint64_t seed) : cfg_(cfg), rng_(seed) {
  DvlConfig::table().validate(cfg);
  requireRange("dvl/max_altitude", cfg.max_altitude, cfg.min_altitude, 1e4);
  scale_ = cfg.scale_sigma * n_(rng_);
  misalignment_ = cfg.misalignment_sigma * n_(rng_);
  offset_ = cfg.offset_sigma * Eigen::Vector3d(n_(rng_), n_(rng_), n_(rng_));
}

std::optional<DvlReading> Dvl::measure(const VehicleState& s) {
  const Eigen::Vector3d noise(n_(rng_), n_(rng_), n_(rng_));  // drawn every sample: the sequence does not depend on lock
  const double altitude = cfg_.bottom_depth - s.position.z();
  if (altitude < cfg_.min_altitude || altitude > cfg_.max_altitude) return std::nullopt;
  const Eigen::Vector3d v = (1.0 + scale_) * (Eigen::AngleAxisd(misalignment_, Eigen::Vector3d::UnitZ()) * s.velocity) +
                            offset_ + cfg_.velocity_sigma * noise;
  return DvlReading{s.t, v, cfg_.velocity_sigma, altitude};
}

// ---------------------------------------------------------------- AUV GPS at the surface
SurfaceGps::SurfaceGps(const SurfaceGpsConfig& cfg, const geo::LocalNed& frame, std::uint64_t seed)
    : cfg_(cfg), frame_(frame), rng_(seed) {
  SurfaceGpsConfig::table().validate(cfg);
}

std::optional<SurfaceGpsReading> SurfaceGps::measure(const VehicleState& s) {
  const Eigen::Vector2d noise(n_(rng_), n_(rng_));  // drawn every sample: the sequence does not depend on depth
  if (s.position.z() > cfg_.max_depth) return std::nullopt;
  const Eigen::Vector3d ned(s.position.x() + cfg_.sigma * noise.x(), s.position.y() + cfg_.sigma * noise.y(), 0.0);
  return SurfaceGpsReading{s.t, frame_.toGeodetic(ned), cfg_.sigma};
}

// ---------------------------------------------------------------- INS estimate
InsEstimate::InsEstimate(const InsConfig& cfg, std::uint64_t seed) : cfg_(cfg), rng_(seed) {
  requireRange("ins/position_sigma", cfg.position_sigma, 0, 100);
  requireRange("ins/drift", cfg.drift_per_sqrt_s, 0, 10);
  requireRange("ins/depth_sigma", cfg.depth_sigma, 0, 10);
  requireRange("ins/yaw_sigma", cfg.yaw_sigma, 0, 1);
  requireRange("ins/velocity_sigma", cfg.velocity_sigma, 0, 10);
}

VehicleState InsEstimate::estimate(const VehicleState& truth) {
  if (last_t_ >= 0 && truth.t > last_t_) {
    const double sq = std::sqrt(truth.t - last_t_);
    drift_ += cfg_.drift_per_sqrt_s * sq * Eigen::Vector2d(n_(rng_), n_(rng_));
  }
  last_t_ = truth.t;
  VehicleState e = truth;
  e.position.x() += drift_.x() + cfg_.position_sigma * n_(rng_);
  e.position.y() += drift_.y() + cfg_.position_sigma * n_(rng_);
  e.position.z() += cfg_.depth_sigma * n_(rng_);
  e.yaw = wrapAngle(truth.yaw + cfg_.yaw_sigma * n_(rng_));
  e.velocity += cfg_.velocity_sigma * Eigen::Vector3d(n_(rng_), n_(rng_), n_(rng_));
  return e;
}

}  // namespace sim
}  // namespace offshore_gnc

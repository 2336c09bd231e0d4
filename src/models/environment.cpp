// The sea state: current, wind with gusts, an irregular long-crested sea; all randomness drawn once from the seed.
#include "offshore_gnc/models/environment.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/param_yaml.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace models {

namespace {
constexpr double kG = 9.81;
constexpr int kWaveComponents = 16;  // enough for an irregular record; each costs a sin/cos per query
constexpr int kGustComponents = 20;
constexpr double kSectionError = 0.0025;  // a SurfaceSection's interpolation error, a fraction of Hs

double sinc(double x) { return std::abs(x) < 1e-6 ? 1.0 - x * x / 6.0 : std::sin(x) / x; }

// splitmix64: a well-mixed hash of integer keys (whitecap cells), so that foam needs no stored state.
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}
double unit(std::uint64_t h) { return static_cast<double>(h >> 11) * (1.0 / 9007199254740992.0); }

// A sea state named in docs/simulation.md, "Sea state", with its sources.
EnvironmentParams preset(double current_north, double current_east, double variation, double wind, double from_deg,
                         const WindSea& sea) {
  EnvironmentParams p;
  p.current_north = current_north;
  p.current_east = current_east;
  p.current_variation = variation;
  p.wind_speed = wind;
  p.wind_direction = deg2rad(from_deg);
  p.wind_gust = 0.1 * wind;  // turbulence intensity over open water, about 10 % (our estimate)
  p.wave_height = sea.height;
  p.wave_period = sea.period;
  p.wave_direction = p.wind_direction;  // a wind sea runs with its wind
  return p;
}

// Remote Sensing 2020, section 5: the hydro-power plant's discharge flows south through the test area, "an
// estuary area of a narrow and shallow lake". Its cross-section is our estimate: 75 m wide, 4 m deep on average
// (the AUV ran at 1.5 m there), 300 m^2; the current is discharge / area, with 10 % slow variation.
constexpr double kEstuaryArea = 75.0 * 4.0;  // [m^2]
constexpr double kEstuaryFetch = 1500.0;     // [m] open water up-wind of the site (our estimate)
}  // namespace

const ParamTable<EnvironmentParams>& EnvironmentParams::table() {
  using P = EnvironmentParams;
  static const ParamTable<P> t = ParamTable<P>()
      .number("current/north", &P::current_north, -5.0, 5.0, "m/s", "current, north component")
      .number("current/east", &P::current_east, -5.0, 5.0, "m/s", "current, east component")
      .number("current/variation", &P::current_variation, 0.0, 2.0, "m/s", "amplitude of its slow seeded variation")
      .number("current/period", &P::current_period, 10.0, 1e6, "s", "period of that variation (and 1.37x it)")
      .integer("current/seed", &P::seed, 0, 2147483647, "seeds every random phase: current, gusts, waves, whitecaps")
      .number("wind/speed", &P::wind_speed, 0.0, 40.0, "m/s", "mean wind speed at 10 m (acts on the USV)")
      .degrees("wind/direction_deg", &P::wind_direction, -360.0, 360.0, "where the wind comes from, clockwise from north")
      .number("wind/gust", &P::wind_gust, 0.0, 20.0, "m/s", "gusts: 1-sigma of the turbulent speed (Harris spectrum)")
      .number("waves/height", &P::wave_height, 0.0, 10.0, "m", "significant wave height Hs (0 = no waves)")
      .number("waves/period", &P::wave_period, 0.5, 30.0, "s", "peak period Tp")
      .degrees("waves/direction_deg", &P::wave_direction, -360.0, 360.0, "where the waves come from")
      .number("waves/gamma", &P::wave_gamma, 1.0, 7.0, "", "JONSWAP peak enhancement (1 = Pierson-Moskowitz)")
      .number("waves/fetch", &P::wave_fetch, 0.0, 1e7, "m",
              "> 0: the wind's sea over this fetch (CEM growth; height and period from wind/speed, its direction)")
      .number("air_density", &P::air_density, 0.5, 2.0, "kg/m^3", "air density")
      .number("water_density", &P::water_density, 990.0, 1050.0, "kg/m^3", "water density (fresh 1000, sea 1025)");
  return t;
}

void EnvironmentParams::validate() const { table().validate(*this); }

WindSea fetchLimitedSea(double u10, double fetch) {
  const double cd = 0.001 * (1.1 + 0.035 * u10);  // CEM eq. II-2-35
  const double us = std::sqrt(cd) * u10;
  if (us <= 0.0 || fetch <= 0.0) return {0.0, 4.0};
  const double x = kG * fetch / (us * us);
  // growth limited by the fully developed sea (CEM eq. II-2-38)
  const double h = std::min(4.13e-2 * std::sqrt(x), 2.115e2) * us * us / kG;
  const double tp = std::min(0.651 * std::cbrt(x), 2.398e2) * us / kG;
  return {h, tp};
}

WindSea fullyDevelopedSea(double u10) {
  const double u195 = 1.026 * u10;
  if (u195 <= 0.0) return {0.0, 4.0};
  return {0.21 * u195 * u195 / kG, 2.0 * kPi / (0.877 * kG / u195)};
}

double whitecapFraction(double u10) { return std::min(1.0, 3.84e-6 * std::pow(std::max(0.0, u10), 3.41)); }

const std::vector<std::string>& seaStateNames() {
  static const std::vector<std::string> n = {"calm", "field_day", "field_day_auv", "moderate"};
  return n;
}

EnvironmentParams seaState(const std::string& name) {
  if (name == "calm") return EnvironmentParams();
  // USV test: 30 m^3/s to the south, wind 3.7 m/s from the south-south-west.
  if (name == "field_day")
    return preset(-30.0 / kEstuaryArea, 0.0, 0.01, 3.7, 202.5, fetchLimitedSea(3.7, kEstuaryFetch));
  // AUV test: 38 m^3/s to the south, wind 6 m/s from the south-west.
  if (name == "field_day_auv")
    return preset(-38.0 / kEstuaryArea, 0.0, 0.013, 6.0, 225.0, fetchLimitedSea(6.0, kEstuaryFetch));
  // Beaufort 4 (moderate breeze, 5.5-7.9 m/s; WMO: probable wave height 1 m), from the south-west: a fully
  // developed sea (Hs 1.0 m, Tp 5.0 s) and a wind drift current of 3 % of the wind speed down-wind.
  if (name == "moderate") {
    const double u = 6.7, from = deg2rad(225.0);
    return preset(-0.03 * u * std::cos(from), -0.03 * u * std::sin(from), 0.02, u, 225.0, fullyDevelopedSea(u));
  }
  std::string all;
  for (const auto& n : seaStateNames()) all += (all.empty() ? "" : ", ") + n;
  throw ConfigError("sea_state '" + name + "' is not one of: " + all);
}

EnvironmentParams environmentFromYaml(const YAML::Node& root, const std::string& source) {
  EnvironmentParams p;
  if (!root || root.IsNull()) return p;
  if (!root.IsMap()) throw ConfigError(source + ": must be a mapping");
  if (const YAML::Node s = root["sea_state"]) {
    if (!s.IsScalar()) throw ConfigError(source + ": key 'sea_state' must be a name");
    try {
      p = seaState(s.as<std::string>());
    } catch (const ConfigError& e) {
      throw ConfigError(source + ": " + e.what());
    }
  }
  // The groups' keys are the table's: a typo inside one is refused (readParamsYaml skips unknown keys).
  std::set<std::string> known;
  for (const auto& s : EnvironmentParams::table().specs()) known.insert(s.name);
  for (const char* group : {"current", "wind", "waves"}) {
    const YAML::Node g = root[group];
    if (!g) continue;
    if (!g.IsMap()) throw ConfigError(source + ": key '" + group + "' must be a mapping");
    for (const auto& kv : g)
      if (!kv.first.IsScalar() || !known.count(std::string(group) + "/" + kv.first.as<std::string>()))
        throw ConfigError(source + ": key '" + group + "." + kv.first.as<std::string>("?") +
                          "' is not a known key (typo?)");
  }
  readParamsYaml(root, EnvironmentParams::table(), p, source);
  const YAML::Node waves = root["waves"];
  if (waves && waves["fetch"]) {
    if (waves["height"] || waves["period"])
      throw ConfigError(source + ": key 'waves.fetch' makes the wind's sea: give it without waves.height and "
                        "waves.period");
    const WindSea sea = fetchLimitedSea(p.wind_speed, p.wave_fetch);
    const bool waves_at_all = sea.period >= 0.5;  // the table's shortest: below it, ripples
    p.wave_height = waves_at_all ? sea.height : 0.0;
    p.wave_period = waves_at_all ? sea.period : 4.0;
    if (!waves["direction_deg"]) p.wave_direction = p.wind_direction;
  }
  return p;
}

Environment::Environment() { p_.validate(); }

Environment::Environment(const EnvironmentParams& p) : p_(p) {
  p_.validate();
  std::mt19937_64 rng(static_cast<std::uint64_t>(p_.seed));
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (double& ph : phase_) ph = 2 * kPi * u(rng);
  for (double& a : angle_) a = 2 * kPi * u(rng);
  // Gusts: Harris spectrum S(f) ~ 1 / (2 + x^2)^(5/6), x = L f / U10, L = 1800 m (Fossen 2011, section 8.1), on
  // log-spaced frequencies 0.002-0.5 Hz, scaled so that the sum's 1-sigma is wind_gust.
  if (p_.wind_gust > 0.0) {
    const double U = std::max(p_.wind_speed, 1.0), f0 = 0.002, f1 = 0.5;
    double total = 0.0;
    for (int i = 0; i < kGustComponents; ++i) {
      const double lo = f0 * std::pow(f1 / f0, double(i) / kGustComponents);
      const double hi = f0 * std::pow(f1 / f0, double(i + 1) / kGustComponents);
      const double f = lo + (hi - lo) * u(rng);
      const double x = 1800.0 * f / U;
      const double e = (hi - lo) / std::pow(2.0 + x * x, 5.0 / 6.0);
      gusts_.push_back({e, 2 * kPi * f, 0.0, 2 * kPi * u(rng)});
      total += e;
    }
    for (auto& c : gusts_) c.a = p_.wind_gust * std::sqrt(2.0 * c.a / total);
  }
  // Waves: JONSWAP on 0.6-2.5 w_p, one random frequency per band, scaled so that 4 sqrt(m0) = Hs exactly.
  if (p_.wave_height > 0.0) {
    const double wp = 2 * kPi / p_.wave_period, lo = 0.6 * wp, dw = (2.5 * wp - lo) / kWaveComponents;
    double total = 0.0;
    for (int i = 0; i < kWaveComponents; ++i) {
      const double w = lo + dw * (i + u(rng));
      const double sigma = w <= wp ? 0.07 : 0.09;
      const double r = std::exp(-(w - wp) * (w - wp) / (2 * sigma * sigma * wp * wp));
      const double s = std::pow(w, -5.0) * std::exp(-1.25 * std::pow(wp / w, 4.0)) * std::pow(p_.wave_gamma, r) * dw;
      waves_.push_back({s, w, w * w / kG, 2 * kPi * u(rng)});
      total += s;
    }
    const double m0 = p_.wave_height * p_.wave_height / 16.0;
    for (auto& c : waves_) c.a = std::sqrt(2.0 * m0 * c.a / total);
  }
}

Eigen::Vector3d Environment::current(double t) const {
  // Two slow components in seeded directions; half the amplitude each so the sum stays within it.
  const double w1 = 2 * kPi / p_.current_period, w2 = w1 / 1.37;
  const double a1 = 0.5 * p_.current_variation * std::sin(w1 * t + phase_[0]);
  const double a2 = 0.5 * p_.current_variation * std::sin(w2 * t + phase_[1]);
  return {p_.current_north + a1 * std::cos(angle_[0]) + a2 * std::cos(angle_[1]),
          p_.current_east + a1 * std::sin(angle_[0]) + a2 * std::sin(angle_[1]), 0.0};
}

Eigen::Vector2d Environment::wind(double t) const {
  double speed = p_.wind_speed;
  for (const auto& g : gusts_) speed += g.a * std::sin(g.w * t + g.phase);
  speed = std::max(0.0, speed);
  // Meteorological direction: where the wind comes from; the air moves the opposite way.
  return {-speed * std::cos(p_.wind_direction), -speed * std::sin(p_.wind_direction)};
}

double Environment::elevation(double t, const Eigen::Vector2d& ne) const {
  const Eigen::Vector2d d(-std::cos(p_.wave_direction), -std::sin(p_.wave_direction));  // where they travel
  const double x = d.dot(ne);
  double eta = 0.0;
  for (const auto& c : waves_) eta += c.a * std::cos(c.w * t - c.k * x + c.phase);
  return eta;
}

SurfaceSection Environment::section(double t, const Eigen::Vector2d& centre, double radius) const {
  SurfaceSection s;
  s.env_ = this;
  s.t_ = t;
  s.travel_ = Eigen::Vector2d(-std::cos(p_.wave_direction), -std::sin(p_.wave_direction));
  if (waves_.empty()) return s;
  // cubic Hermite interpolation on the elevation and its slope is off by at most step^4 / 384 max|d4 eta / dx4|
  // <= step^4 / 384 sum(a k^4): held to kSectionError of Hs
  double bound = 0.0;
  for (const auto& c : waves_) bound += c.a * std::pow(c.k, 4);
  s.step_ = std::pow(384.0 * kSectionError * p_.wave_height / bound, 0.25);
  s.x0_ = s.travel_.dot(centre) - radius;
  const auto n = static_cast<std::size_t>(std::ceil(2.0 * radius / s.step_)) + 2;
  s.eta_.resize(n);
  s.slope_.resize(n);
  // each component's phasor a exp(i (w t - k x + phase)) at x0, turned by -k step per sample: no cosine per
  // sample (fixed-size arrays, so that the turns vectorise); its real part is the elevation, k times its
  // imaginary part the slope along the travel
  using Phasors = Eigen::Array<double, kWaveComponents, 1>;
  Phasors re, im, cr, ci, k;
  for (int j = 0; j < kWaveComponents; ++j) {
    const auto& c = waves_[static_cast<std::size_t>(j)];
    const double ph = c.w * t - c.k * s.x0_ + c.phase, turn = -c.k * s.step_;
    re[j] = c.a * std::cos(ph);
    im[j] = c.a * std::sin(ph);
    cr[j] = std::cos(turn);
    ci[j] = std::sin(turn);
    k[j] = c.k;
  }
  for (std::size_t i = 0; i < n; ++i) {
    s.eta_[i] = re.sum();
    s.slope_[i] = (k * im).sum();
    const Phasors r = re * cr - im * ci;
    im = re * ci + im * cr;
    re = r;
  }
  return s;
}

double SurfaceSection::operator()(const Eigen::Vector2d& ne) const {
  if (eta_.empty()) return 0.0;
  const double u = (travel_.dot(ne) - x0_) / step_;
  if (!(u >= 0.0) || u >= static_cast<double>(eta_.size() - 1)) return env_->elevation(t_, ne);
  const auto i = static_cast<std::size_t>(u);
  const double f = u - static_cast<double>(i), f2 = f * f, f3 = f2 * f;
  return (2 * f3 - 3 * f2 + 1) * eta_[i] + (f3 - 2 * f2 + f) * step_ * slope_[i] + (3 * f2 - 2 * f3) * eta_[i + 1] +
         (f3 - f2) * step_ * slope_[i + 1];
}

VehicleState withWave(const VehicleState& lf, const WaveMotion& w) {
  VehicleState out = lf;
  out.position += w.displacement;
  out.roll = wrapAngle(lf.roll + w.roll);
  out.pitch = wrapAngle(lf.pitch + w.pitch);
  out.yaw = wrapAngle(lf.yaw + w.yaw);
  const double c = std::cos(out.yaw), s = std::sin(out.yaw);
  out.velocity += Eigen::Vector3d(c * w.velocity.x() + s * w.velocity.y(), -s * w.velocity.x() + c * w.velocity.y(),
                                  w.velocity.z());
  out.angular_rate += w.rate;
  return out;
}

WaveMotion Environment::wave(double t, const VehicleState& lf, const Hull& hull) const {
  WaveMotion m;
  if (waves_.empty()) return m;
  const Eigen::Vector2d d(-std::cos(p_.wave_direction), -std::sin(p_.wave_direction));  // where they travel
  const Eigen::Vector2d fwd(std::cos(lf.yaw), std::sin(lf.yaw)), stbd(-std::sin(lf.yaw), std::cos(lf.yaw));
  const Eigen::Vector2d v = lf.velocity.x() * fwd + lf.velocity.y() * stbd;  // over ground, NED
  const double along = d.dot(fwd), across = d.dot(stbd), x = d.dot(lf.position.head<2>());
  const double depth = std::max(0.0, lf.position.z());
  for (const auto& c : waves_) {
    const double kl = c.k * along, kb = c.k * across;
    // the surface averaged over the hull: waves shorter than it cancel out along it
    const double a = c.a * std::exp(-c.k * depth) * sinc(0.5 * kl * hull.length) * sinc(0.5 * kb * hull.beam);
    const double ph = c.w * t - c.k * x + c.phase, we = c.w - c.k * d.dot(v);  // encounter frequency
    const double cs = std::cos(ph), sn = std::sin(ph);
    // elevation a cos(ph) up, orbital displacement a sin(ph) along the travel
    m.displacement += Eigen::Vector3d(a * sn * d.x(), a * sn * d.y(), -a * cs);
    m.velocity += Eigen::Vector3d(a * we * cs * d.x(), a * we * cs * d.y(), a * we * sn);
    // pitch: bow minus stern elevation over the length; roll: port minus starboard over the beam (starboard down
    // positive); yaw: the bow's sway minus the stern's over the length
    m.pitch += a * kl * sn;
    m.roll -= a * kb * sn;
    m.yaw -= a * kl * across * cs;
    m.rate += Eigen::Vector3d(-a * kb * we * cs, a * kl * we * cs, a * kl * across * we * sn);
  }
  return m;
}

Eigen::Vector2d Environment::driftForce(double heading, const Hull& hull) const {
  if (waves_.empty()) return Eigen::Vector2d::Zero();
  const Eigen::Vector2d d(-std::cos(p_.wave_direction), -std::sin(p_.wave_direction));
  const double facing = hull.length * std::abs(std::sin(std::atan2(d.y(), d.x()) - heading)) +
                        hull.beam * std::abs(std::cos(std::atan2(d.y(), d.x()) - heading));
  // A body small against the wavelength scatters little: Havelock's mean drift on a vertical cylinder of radius r,
  // (5/16) pi^2 rho g a^2 r (k r)^3 for small k r, is 3.08 (k r)^3 times the full reflection's rho g a^2 r over
  // its width 2r (Faltinsen, Sea Loads, 1990, ch. 5); capped at full reflection (k r >= 0.69). Without it a 1.5 m
  // Girona500 felt 420 N in a Beaufort 4 sea, 43 kgf, and no surfaced AUV could hold.
  const double r = 0.5 * facing;
  double e = 0.0;  // sum of a_i^2 / 2 R_i^2
  for (const auto& c : waves_) {
    const double kr = c.k * r, small = std::min(1.0, 3.08 * kr * kr * kr);
    e += 0.5 * c.a * c.a * (1.0 - std::exp(-2.0 * c.k * hull.draft)) * small;
  }
  return p_.water_density * kG * e * facing * d;
}

bool Environment::foam(double t, const Eigen::Vector2d& ne, double patch, double life, double w) const {
  if (w <= 0.0 || patch <= 0.0 || life <= 0.0) return false;
  const auto ix = static_cast<std::int64_t>(std::floor(ne.x() / patch));
  const auto iy = static_cast<std::int64_t>(std::floor(ne.y() / patch));
  const std::uint64_t cell = mix(mix(static_cast<std::uint64_t>(ix) ^ (static_cast<std::uint64_t>(p_.seed) << 32)) ^
                                 static_cast<std::uint64_t>(iy));
  // each cell lives through its own sequence of `life`-long slots, offset so that cells do not flip together
  const auto slot = static_cast<std::int64_t>(std::floor(t / life + unit(cell)));
  return unit(mix(cell ^ static_cast<std::uint64_t>(slot))) < w;
}

}  // namespace models
}  // namespace offshore_gnc

// Scenario loader (yaml-cpp). Strict: unknown keys, missing values, out-of-range numbers and impossible
// geometry are errors naming the key, because a typo in a scenario silently changes a test run otherwise.
#include "offshore_gnc/sim/scenario.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace sim {

namespace {
constexpr double kMaxCoord = 1e5;  // 100 km around the origin

class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw ConfigError("scenario '" + source_ + "': key '" + key + "' " + what);
  }
  void keys(const YAML::Node& n, const std::string& path, const std::set<std::string>& allowed) const {
    if (!n.IsMap()) fail(path, "must be a mapping");
    for (const auto& kv : n) {
      if (!kv.first.IsScalar()) fail(path, "has a key that is not text");
      const std::string k = kv.first.as<std::string>();
      if (!allowed.count(k)) fail(path.empty() ? k : path + "." + k, "is not a known key (typo?)");
    }
  }
  double number(const YAML::Node& n, const std::string& path, const std::string& key, double lo, double hi,
                const double* def = nullptr) const {
    const std::string full = path.empty() ? key : path + "." + key;
    if (!n.IsMap()) fail(path, "must be a mapping");
    const YAML::Node v = n[key];
    if (!v) {
      if (def) return *def;
      fail(full, "is missing");
    }
    double x;
    try {
      x = v.as<double>();
    } catch (const YAML::Exception&) {
      fail(full, "must be a number");
    }
    try {
      return requireRange(full, x, lo, hi);
    } catch (const ConfigError& e) {
      throw ConfigError("scenario '" + source_ + "': " + e.what());
    }
  }
  double opt(const YAML::Node& n, const std::string& path, const std::string& key, double def, double lo,
             double hi) const {
    return number(n, path, key, lo, hi, &def);
  }
  std::string text(const YAML::Node& n, const std::string& path, const std::string& key) const {
    if (!n.IsMap()) fail(path, "must be a mapping");
    const YAML::Node v = n[key];
    if (!v || !v.IsScalar()) fail(path.empty() ? key : path + "." + key, "is missing or not text");
    return v.as<std::string>();
  }

 private:
  std::string source_;
};

std::string idx(const std::string& list, std::size_t i) { return list + "[" + std::to_string(i) + "]"; }

bool flag(const Reader& r, const YAML::Node& n, const std::string& path, const std::string& key) {
  try {
    return n[key].as<bool>();
  } catch (const YAML::Exception&) {
    r.fail(path + "." + key, "must be true or false");
  }
}

constexpr double kMaxVesselSpeed = 30.0;  // [m/s] about 58 kn: faster is a typo

// A vessel under way (docs/simulation.md): `course_deg` and `speed` from its north/east, or `track` (two or more
// points) at `speed`; `gives_way: false` marks one that keeps its course and speed whatever the rules ask.
void readMotion(const Reader& r, const YAML::Node& n, const std::string& p, Vessel& v) {
  VesselMotion& m = v.motion;
  const bool course = static_cast<bool>(n["course_deg"]), track = static_cast<bool>(n["track"]);
  if (!course && !track) {
    for (const char* k : {"speed", "loop", "gives_way"})
      if (n[k]) r.fail(p + "." + k, "is for a vessel under way: give it course_deg or track");
    return;
  }
  if (course && track) r.fail(p + ".track", "and course_deg exclude each other: a vessel goes one way or the other");
  if (n["yaw_deg"]) r.fail(p + ".yaw_deg", "is for a moored vessel: one under way heads along its course");
  m.speed = r.number(n, p, "speed", 0.0, kMaxVesselSpeed);
  if (n["gives_way"]) m.gives_way = flag(r, n, p, "gives_way");
  if (course) {
    if (n["loop"]) r.fail(p + ".loop", "is for a track");
    m.kind = VesselMotion::Kind::kCourse;
    m.course = wrapAngle(deg2rad(r.number(n, p, "course_deg", -360.0, 360.0)));
    v.yaw = m.course;
    return;
  }
  for (const char* k : {"north", "east"})
    if (n[k]) r.fail(p + "." + k, "is not for a vessel on a track: it starts at the track's first point");
  const YAML::Node tr = n["track"];
  const std::string tp = p + ".track";
  if (!tr.IsSequence()) r.fail(tp, "must be a list of points {north, east}");
  if (tr.size() < 2) r.fail(tp, "needs at least 2 points, has " + std::to_string(tr.size()));
  double length = 0.0;
  for (std::size_t k = 0; k < tr.size(); ++k) {
    const std::string kp = idx(tp, k);
    r.keys(tr[k], kp, {"north", "east"});
    m.track.emplace_back(r.number(tr[k], kp, "north", -kMaxCoord, kMaxCoord),
                         r.number(tr[k], kp, "east", -kMaxCoord, kMaxCoord));
    if (k > 0) length += (m.track[k] - m.track[k - 1]).norm();
  }
  if (length < 0.1) r.fail(tp, "has no length: its points coincide");
  if (n["loop"]) m.loop = flag(r, n, p, "loop");
  m.kind = VesselMotion::Kind::kTrack;
  const VesselPose start = vesselPose(v, 0.0);
  v.centre = start.centre;
  v.yaw = start.yaw;
}
}  // namespace

namespace {
Scenario parseChecked(const std::string& yaml_text, const std::string& base_dir, const std::string& source) {
  Reader r(source);
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::Exception& e) {
    throw ConfigError("scenario '" + source + "': not valid YAML: " + e.what());
  }
  if (!root || !root.IsMap()) throw ConfigError("scenario '" + source + "': must be a YAML mapping");
  r.keys(root, "", {"name", "origin", "sea_state", "current", "wind", "waves", "air_density", "water_density",
                   "bottom", "usv", "auv", "obstacles", "targets", "walls", "map", "mission"});
  Scenario s;
  s.name = r.text(root, "", "name");

  const YAML::Node o = root["origin"];
  if (!o) r.fail("origin", "is missing");
  r.keys(o, "origin", {"latitude", "longitude", "altitude"});
  s.origin.lat_deg = r.number(o, "origin", "latitude", -90.0, 90.0);
  s.origin.lon_deg = r.number(o, "origin", "longitude", -180.0, 180.0);
  s.origin.alt_m = r.opt(o, "origin", "altitude", 0.0, -500.0, 9000.0);

  try {  // the models' own reader: the same names, ranges and presets as an environment file
    s.sea = models::environmentFromYaml(root, "scenario '" + source + "'");
  } catch (const YAML::Exception& e) {
    throw ConfigError("scenario '" + source + "': sea state: " + e.what());
  }
  if (const YAML::Node b = root["bottom"]) {
    r.keys(b, "bottom", {"depth"});
    s.world.bottom_depth = r.number(b, "bottom", "depth", 0.5, 11000.0);
  }

  const YAML::Node u = root["usv"];
  if (!u) r.fail("usv", "is missing");
  r.keys(u, "usv", {"start"});
  if (!u["start"]) r.fail("usv.start", "is missing");
  r.keys(u["start"], "usv.start", {"north", "east", "yaw_deg"});
  s.usv.north = r.number(u["start"], "usv.start", "north", -kMaxCoord, kMaxCoord);
  s.usv.east = r.number(u["start"], "usv.start", "east", -kMaxCoord, kMaxCoord);
  s.usv.yaw = deg2rad(r.opt(u["start"], "usv.start", "yaw_deg", 0.0, -360.0, 360.0));

  const YAML::Node a = root["auv"];
  if (!a) r.fail("auv", "is missing");
  r.keys(a, "auv", {"start", "coverage"});
  if (!a["start"]) r.fail("auv.start", "is missing");
  r.keys(a["start"], "auv.start", {"north", "east", "depth", "yaw_deg"});
  s.auv.north = r.number(a["start"], "auv.start", "north", -kMaxCoord, kMaxCoord);
  s.auv.east = r.number(a["start"], "auv.start", "east", -kMaxCoord, kMaxCoord);
  // above the bottom, when there is one
  const double floor = s.world.bottom_depth > 0.0 ? s.world.bottom_depth : 1000.0;
  s.auv.depth = r.number(a["start"], "auv.start", "depth", 0.0, floor);
  s.auv.yaw = deg2rad(r.opt(a["start"], "auv.start", "yaw_deg", 0.0, -360.0, 360.0));
  if (const YAML::Node cov = a["coverage"]) {  // read by the AUV mission; checked here so typos surface early
    r.keys(cov, "auv.coverage",
           {"north_min", "north_max", "east_min", "east_max", "depth", "spacing", "second_depth"});
    const double n0 = r.number(cov, "auv.coverage", "north_min", -kMaxCoord, kMaxCoord);
    r.number(cov, "auv.coverage", "north_max", n0 + 1e-3, kMaxCoord);
    const double e0 = r.number(cov, "auv.coverage", "east_min", -kMaxCoord, kMaxCoord);
    r.number(cov, "auv.coverage", "east_max", e0 + 1e-3, kMaxCoord);
    r.number(cov, "auv.coverage", "depth", 0.0, floor);
    r.opt(cov, "auv.coverage", "spacing", 5.0, 0.5, 1000.0);
    r.opt(cov, "auv.coverage", "second_depth", 0.0, 0.0, floor);
  }

  if (const YAML::Node obs = root["obstacles"]) {
    if (!obs.IsSequence()) r.fail("obstacles", "must be a list");
    for (std::size_t i = 0; i < obs.size(); ++i) {
      const std::string p = idx("obstacles", i);
      const std::string type = r.text(obs[i], p, "type");
      // a vessel on a track starts at its first point: no centre of its own
      const bool on_track = type == "vessel" && obs[i]["track"];
      const Eigen::Vector2d c = on_track ? Eigen::Vector2d::Zero()
                                         : Eigen::Vector2d(r.number(obs[i], p, "north", -kMaxCoord, kMaxCoord),
                                                           r.number(obs[i], p, "east", -kMaxCoord, kMaxCoord));
      if (type == "buoy") {
        r.keys(obs[i], p, {"type", "north", "east", "radius", "height", "draft"});
        const Buoy def;
        s.world.buoys.push_back({c, r.number(obs[i], p, "radius", 0.05, 50.0),
                                 r.opt(obs[i], p, "height", def.height, 0.05, 50.0),
                                 r.opt(obs[i], p, "draft", def.draft, 0.0, 50.0)});
      } else if (type == "vessel") {
        r.keys(obs[i], p, {"type", "north", "east", "length", "width", "height", "draft", "yaw_deg", "course_deg",
                           "speed", "track", "loop", "gives_way"});
        Vessel v;
        v.centre = c;
        v.length = r.number(obs[i], p, "length", 0.5, 400.0);
        v.width = r.number(obs[i], p, "width", 0.2, 100.0);
        v.height = r.opt(obs[i], p, "height", 2.0, 0.1, 60.0);
        v.draft = r.opt(obs[i], p, "draft", v.draft, 0.0, 30.0);
        v.yaw = deg2rad(r.opt(obs[i], p, "yaw_deg", 0.0, -360.0, 360.0));
        readMotion(r, obs[i], p, v);
        s.world.vessels.push_back(v);
      } else {
        r.fail(p + ".type", "= '" + type + "' must be 'buoy' or 'vessel'");
      }
    }
  }
  if (const YAML::Node tg = root["targets"]) {
    if (!tg.IsSequence()) r.fail("targets", "must be a list");
    for (std::size_t i = 0; i < tg.size(); ++i) {
      const std::string p = idx("targets", i);
      r.keys(tg[i], p, {"north", "east", "depth", "radius"});
      Target t;
      t.radius = r.number(tg[i], p, "radius", 0.05, 20.0);
      t.position = {r.number(tg[i], p, "north", -kMaxCoord, kMaxCoord), r.number(tg[i], p, "east", -kMaxCoord, kMaxCoord),
                    r.number(tg[i], p, "depth", t.radius, 1000.0)};  // a target sticking out of the water is impossible
      if (s.world.bottom_depth > 0.0 && t.position.z() + t.radius > s.world.bottom_depth + 1e-9)
        r.fail(p + ".depth", "puts it below the bottom (bottom.depth " + std::to_string(s.world.bottom_depth) + " m)");
      s.world.targets.push_back(t);
    }
  }
  if (const YAML::Node ws = root["walls"]) {
    if (!ws.IsSequence()) r.fail("walls", "must be a list");
    for (std::size_t i = 0; i < ws.size(); ++i) {
      const std::string p = idx("walls", i);
      r.keys(ws[i], p, {"north1", "east1", "north2", "east2"});
      Wall w;
      w.a = {r.number(ws[i], p, "north1", -kMaxCoord, kMaxCoord), r.number(ws[i], p, "east1", -kMaxCoord, kMaxCoord)};
      w.b = {r.number(ws[i], p, "north2", -kMaxCoord, kMaxCoord), r.number(ws[i], p, "east2", -kMaxCoord, kMaxCoord)};
      if ((w.b - w.a).norm() < 0.1) r.fail(p, "has zero length (its two ends coincide)");
      s.world.walls.push_back(w);
    }
  }
  if (const YAML::Node m = root["mission"]) {
    r.keys(m, "mission", {"expect", "max_sim_time", "hold_time", "target_tolerance"});
    if (m["expect"]) {
      const std::string e = r.text(m, "mission", "expect");
      if (e != "target_reached" && e != "no_target")
        r.fail("mission.expect", "= '" + e + "' is not one of: target_reached no_target");
      s.mission.expect_target = e == "target_reached";
    }
    s.mission.max_sim_time = r.opt(m, "mission", "max_sim_time", s.mission.max_sim_time, 10.0, 86400.0);
    s.mission.hold_time = r.opt(m, "mission", "hold_time", s.mission.hold_time, 0.0, 3600.0);
    s.mission.target_tolerance = r.opt(m, "mission", "target_tolerance", s.mission.target_tolerance, 0.01, 1000.0);
  }
  if (const YAML::Node m = root["map"]) {
    r.keys(m, "map", {"image", "resolution", "north", "east", "threshold"});
    std::string img = r.text(m, "map", "image");
    if (!img.empty() && img[0] != '/') img = base_dir + "/" + img;
    std::error_code ec;  // a directory or a device (/dev/stdin) is no image, and reading one may block
    if (!std::filesystem::is_regular_file(img, ec) || !std::ifstream(img).good())
      r.fail("map.image", "= '" + img + "' cannot be read (not a readable file)");
    s.map_image = img;
    const double res = r.number(m, "map", "resolution", 0.01, 100.0);
    const double n0 = r.number(m, "map", "north", -kMaxCoord, kMaxCoord);
    const double e0 = r.number(m, "map", "east", -kMaxCoord, kMaxCoord);
    const int thr = static_cast<int>(r.opt(m, "map", "threshold", 128.0, 1.0, 255.0));
    try {
      mapFromImage(img, res, n0, e0, thr, s.map, s.world.shorelines);
    } catch (const ConfigError& e) {
      r.fail("map.image", e.what());
    }
  }

  // impossible geometry: vehicles starting inside an obstacle or on land
  auto blocked = [&](const Eigen::Vector2d& p) -> std::string {
    for (std::size_t i = 0; i < s.world.buoys.size(); ++i)
      if ((p - s.world.buoys[i].centre).norm() < s.world.buoys[i].radius) return idx("obstacles buoy", i);
    for (std::size_t i = 0; i < s.world.vessels.size(); ++i)
      if (insidePolygon(vesselFootprint(s.world.vessels[i], 0.0), p)) return idx("obstacles vessel", i);
    if (!s.map.empty() && s.map.occupied(p)) return "map (land)";
    return "";
  };
  const std::string ub = blocked({s.usv.north, s.usv.east});
  if (!ub.empty()) r.fail("usv.start", "lies inside " + ub);
  const std::string ab = blocked({s.auv.north, s.auv.east});
  if (!s.map.empty() && ab == "map (land)") r.fail("auv.start", "lies on land");
  for (std::size_t i = 0; i < s.world.targets.size(); ++i)
    if (!s.map.empty() && s.map.occupied(s.world.targets[i].position.head<2>()))
      r.fail(idx("targets", i), "lies on land");
  return s;
}
}  // namespace

Scenario parseScenario(const std::string& yaml_text, const std::string& base_dir, const std::string& source) {
  try {
    return parseChecked(yaml_text, base_dir, source);
  } catch (const YAML::Exception& e) {  // a shape the checks above did not foresee: still the user's file
    throw ConfigError("scenario '" + source + "': " + e.what());
  }
}

Scenario loadScenario(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw ConfigError("scenario '" + path + "' cannot be read");
  std::stringstream ss;
  ss << in.rdbuf();
  const auto slash = path.find_last_of('/');
  return parseScenario(ss.str(), slash == std::string::npos ? "." : path.substr(0, slash), path);
}

}  // namespace sim
}  // namespace offshore_gnc

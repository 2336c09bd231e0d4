#pragma once
// Fault injection in simulation (docs/safety.md, "Fault injection"): a plan of named faults, each active over
// [start, end) of simulated time, written "NAME@START[+DURATION]" and separated by commas or spaces, e.g.
// "usbl@150+60, gps@200+10" (no duration: until the end of the run). The simulators ask `active(name, t)` at
// their own simulated time, so an injection does not depend on how fast the run goes. The kinds below are the
// one list of what can be injected, where, what it does and which of the safety supervisor's rules answers it.
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {

struct FaultKind {
  const char* name;
  const char* vehicle;  // the master whose simulator injects it; "both": the main job does, between the masters
  const char* effect;
  const char* rule;     // the supervisor's rule that answers it (default presets); "": none (docs/safety.md says
                        // what does: the navigation for dvl, the USV mission's region check for geofence)
};

// The geofence fault's target: this far north of the origin [m] (the main job publishes it, the ROS-free mission
// hands it to the USV), outside the USV's default operating region (a 2 km square about the origin).
constexpr double kGeofenceTargetNorth = 5000.0;

inline const std::vector<FaultKind>& faultKinds() {
  static const std::vector<FaultKind> kinds{
      {"gps", "usv", "the GPS-compass is silent (/usv_gps, /usv_heading, /usv/gps/velocity)", "gps_timeout"},
      {"lidar", "usv", "the LiDAR is silent (/usv/lidar/points)", "lidar_timeout"},
      {"jet", "usv",
       "the port waterjet's control unit stops: its jet stops pushing and it no longer answers on the bus "
       "(/usv/waterjet/answering)",
       "jet"},
      {"bus_off", "usv",
       "the CAN bus goes bus-off: no frame crosses it (/usv/can/bus_state; the jets neither answer nor get "
       "set-points and go neutral, the NMEA 2000 GPS-compass is silent)",
       "bus_off"},
      {"collision", "usv",
       "a barge broadside across the USV's course appears ahead the first time the USV is under way in the fault's "
       "window (sim::CollisionFault: 150 m long, 6 s ahead of its bow at its speed, from 0.8 m/s), gone at its end",
       "collision"},
      {"nav", "auv", "the AUV's AHRS, DVL and INS-like estimate are silent: its navigation has no estimate",
       "navigation_timeout"},
      {"sonar", "auv", "the mechanical sonar is silent (/auv/sonar/beam)", "sonar_timeout"},
      {"depth", "auv", "the pressure sensor is silent (/auv/pressure)", "depth_timeout"},
      {"dvl", "auv", "the DVL is silent (/auv/dvl; the Girona500's)", ""},
      {"usbl", "auv", "the AUV's beacon does not reply: every USBL ping times out", "usbl_timeout"},
      {"link", "both", "the radio between the vehicles' relays is down (the main job's simulated radio)",
       "link_timeout"},
      {"geofence", "both",
       "a target 5 km north of the origin, outside the USV's operating region, is published on the AUV's /target "
       "(the main job) and crosses the relay as a detection would",
       ""},
  };
  return kinds;
}

inline const FaultKind* findFaultKind(const std::string& name) {
  for (const auto& k : faultKinds())
    if (name == k.name) return &k;
  return nullptr;
}

struct Fault {
  std::string name;
  double start = 0.0;
  double end = std::numeric_limits<double>::infinity();  // exclusive
  bool activeAt(double t) const { return t >= start && t < end; }
};

class FaultPlan {
 public:
  // Throws ConfigError naming the item and what is wrong with it.
  static FaultPlan parse(const std::string& text) {
    FaultPlan plan;
    std::string spec = text;
    for (char& c : spec)
      if (c == ',') c = ' ';
    std::istringstream in(spec);
    std::string item;
    while (in >> item) plan.faults_.push_back(parseOne(item));
    return plan;
  }

  bool active(const std::string& name, double t) const { return activeFault(name, t) != nullptr; }
  // The first fault of that name active at t (nullptr: none).
  const Fault* activeFault(const std::string& name, double t) const {
    for (const auto& f : faults_)
      if (f.name == name && f.activeAt(t)) return &f;
    return nullptr;
  }
  const std::vector<Fault>& faults() const { return faults_; }
  bool empty() const { return faults_.empty(); }
  // The faults of one vehicle's simulators (FaultKind::vehicle).
  FaultPlan of(const std::string& vehicle) const {
    FaultPlan p;
    for (const auto& f : faults_)
      if (vehicle == findFaultKind(f.name)->vehicle) p.faults_.push_back(f);
    return p;
  }

 private:
  static Fault parseOne(const std::string& item) {
    auto fail = [&](const std::string& why) {
      std::string names;
      for (const auto& k : faultKinds()) names += std::string(names.empty() ? "" : " ") + k.name;
      throw ConfigError("fault '" + item + "': " + why + " (write NAME@START_S[+DURATION_S], NAME one of: " + names +
                        ")");
    };
    const auto at = item.find('@');
    if (at == std::string::npos) fail("no '@START_S'");
    Fault f;
    f.name = item.substr(0, at);
    if (!findFaultKind(f.name)) fail("unknown fault '" + f.name + "'");
    const std::string times = item.substr(at + 1);
    const auto plus = times.find('+');
    auto number = [&](const std::string& s, const char* what) {
      std::size_t used = 0;
      double v = NAN;
      try {
        v = std::stod(s, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != s.size() || !std::isfinite(v)) fail(std::string("the ") + what + " is not a number");
      return v;
    };
    f.start = number(times.substr(0, plus), "start");
    if (f.start < 0.0) fail("the start is negative");
    if (plus != std::string::npos) {
      const double d = number(times.substr(plus + 1), "duration");
      if (d <= 0.0) fail("the duration is not positive");
      f.end = f.start + d;
    }
    return f;
  }

  std::vector<Fault> faults_;
};

}  // namespace offshore_gnc

// param_docs: docs/parameters.md from the parameter tables (names, defaults per vehicle, ranges, units, docs), so
// the reference a user reads is the one the code validates against; with --cfg FORM, cfg/FORM.cfg (the nodelet's
// dynamic_reconfigure script) from the same tables. Tests compare the checked-in files with this output.
//   param_docs > docs/parameters.md
//   param_docs --cfg Guidance > cfg/Guidance.cfg   (and Control)
// With --launch FILE, the launch file with its component block written from the vehicles' manifests
// (config/vehicles/, docs/launch_block.h); --launch-files lists the launch files that have one.
//   param_docs --launch launch/guidance_usv.launch > /tmp/g && mv /tmp/g launch/guidance_usv.launch
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "offshore_gnc/can/emulator.h"
#include "offshore_gnc/can/gateway.h"
#include "offshore_gnc/closed_loop/stacks.h"
#include "offshore_gnc/cola2/mapping.h"
#include "offshore_gnc/common/param_yaml.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/control/control_loop.h"
#include "offshore_gnc/docs/cfg_script.h"
#include "offshore_gnc/docs/launch_block.h"
#include "offshore_gnc/geo/geo.h"
#include "offshore_gnc/guidance/pipeline.h"
#include "offshore_gnc/micron/session.h"
#include "offshore_gnc/micron_sim/emulator.h"
#include "offshore_gnc/mission/mission.h"
#include "offshore_gnc/navigation/auv_navigation_params.h"
#include "offshore_gnc/navigation/auv_navigator.h"
#include "offshore_gnc/navigation/gps_navigator.h"
#include "offshore_gnc/perception/lidar_targets.h"
#include "offshore_gnc/perception/sensor_frame.h"
#include "offshore_gnc/perception/sonar_image.h"
#include "offshore_gnc/perception/sonar_targets.h"
#include "offshore_gnc/perception/target_tracker.h"
#include "offshore_gnc/perception/wall_detection.h"
#include "offshore_gnc/relay/config.h"
#include "offshore_gnc/safety/supervisor.h"
#include "offshore_gnc/sim/contact.h"
#include "offshore_gnc/sim/radio.h"
#include "offshore_gnc/sim/sensors.h"
#include "offshore_gnc/sim/simulation.h"
#include "offshore_gnc/sim/simulator_params.h"
#include "offshore_gnc/usbl/config.h"
#include "offshore_gnc/usbl/session.h"

using namespace offshore_gnc;

namespace {

const std::string kConfigDir = OFFSHORE_GNC_CONFIG_DIR;

std::vector<closed_loop::VehicleManifest> manifests() {
  std::vector<closed_loop::VehicleManifest> ms;
  for (const auto& v : closed_loop::VehicleManifest::vehicles(kConfigDir))
    ms.push_back(closed_loop::VehicleManifest::load(kConfigDir, v));
  return ms;
}

// A column per value a choice parameter offers (the presets `vehicle` selects).
template <class P>
std::vector<std::pair<std::string, P>> perChoice(const ParamTable<P>& t, const std::string& name, P (*of)(const std::string&)) {
  std::vector<std::pair<std::string, P>> columns;
  for (const auto& s : t.specs())
    if (s.name == name)
      for (const auto& c : s.choices) columns.emplace_back(c, of(c));
  return columns;
}

// Each vehicle's simulator run as its manifest's sim component sets it (the seeds' defaults).
std::vector<std::pair<std::string, sim::RunParams>> runPerVehicle() {
  std::vector<std::pair<std::string, sim::RunParams>> columns;
  for (const auto& m : manifests()) {
    sim::RunParams run;
    for (const auto& s : m.sources("sim", m.models().empty() ? "" : m.models().front()))
      readParamsYaml(s.yaml, sim::RunParams::table(), run, s.name);
    columns.emplace_back(m.vehicle(), run);
  }
  return columns;
}

template <class P>
void table(const char* title, const char* where, const ParamTable<P>& t,
           const std::vector<std::pair<std::string, P>>& columns, const std::string& prefix = "") {
  std::printf("## %s\n\n%s\n\n| parameter |", title, where);
  for (const auto& c : columns) std::printf(" %s |", c.first.c_str());
  std::printf(" range | unit | what |\n| --- |");
  for (std::size_t i = 0; i < columns.size(); ++i) std::printf(" --- |");
  std::printf(" --- | --- | --- |\n");
  for (const auto& s : t.specs()) {
    std::printf("| `%s%s` |", prefix.c_str(), s.name.c_str());
    for (const auto& c : columns) std::printf(" %s |", ParamTable<P>::text(s, c.second).c_str());
    std::string r;
    const std::string range = paramNumberText(s.lo) + " .. " + paramNumberText(s.hi);
    switch (s.kind) {
      case ParamKind::kNumber:
      case ParamKind::kInteger: r = range; break;
      case ParamKind::kNumbers:
        r = (s.size ? std::to_string(s.size) + " values, " : std::string()) + range + " each";
        break;
      case ParamKind::kFlag: r = "true, false"; break;
      case ParamKind::kChoice:
        for (const auto& c : s.choices) r += (r.empty() ? "" : ", ") + c;
        break;
      case ParamKind::kText: r = "text"; break;
    }
    std::printf(" %s | %s | %s |\n", r.c_str(), s.unit.c_str(), s.doc.c_str());
  }
  std::printf("\n");
}

void printParameters() {
  std::printf(
      "# Parameters\n\n"
      "Generated by `param_docs` from the parameter tables in the code (the one place for each name, default, range\n"
      "and unit; a test fails when this file differs). The nodelets read these through `ros_util::readParams`,\n"
      "the ROS-free loops through `readParamsYaml`. dynamic_reconfigure's `cfg/*.cfg` are generated from the same\n"
      "tables (`param_docs --cfg Guidance`, `--cfg Control`; a field is the table's name with `/` written `_`).\n"
      "A key in a vehicle's YAML file replaces the default shown here.\n\n");
  using G = guidance::GuidanceParams;
  table("Guidance", "`config/guidance/<vehicle>.yaml` -> the Guidance nodelet; `vehicle` selects the preset.",
        G::table(), perChoice(G::table(), "vehicle", &G::preset));
  table("Control loop", "`config/control/<vehicle>.yaml` -> the Control nodelet (with the vehicle's own table below).",
        control::ControlLoopParams::table(), {{"default", control::ControlLoopParams()}});
  table("USV control", "`config/control/usv.yaml` (thesis Table 4.1, eq. 4.15-4.16).",
        control::UsvControlParams::table(), {{"default", control::UsvControlParams()}});
  table("Girona500 control", "`config/control/girona500.yaml` (thesis Table 4.3).",
        control::Girona500ControlParams::table(), {{"default", control::Girona500ControlParams()}});
  table("Girona500 thruster layout", "`config/control/girona500.yaml` -> the Control nodelet: another thruster layout "
        "than the model's (both lists with another count).", control::ThrusterLayout::table(),
        {{"default", control::ThrusterLayout::of(control::Girona500ControlParams())}});
  table("aColor control",
        "`config/control/acolor.yaml` (thesis Table 4.2); in simulation `config/control/acolor_sim.yaml` over it "
        "(the simulated aColor's yaw gains, docs/guidance-control.md). The surge PWM is the one that holds guidance's "
        "speed on the aColor model (no parameter).",
        control::AcolorControlParams::table(), {{"default", control::AcolorControlParams()}});
  table("USV mission", "`config/mission/usv.yaml` -> the UsvMission nodelet.", mission::UsvMissionParams::table(),
        {{"default", mission::UsvMissionParams()}});
  table("AUV mission", "`config/mission/auv.yaml` -> the AuvMission nodelet.", mission::AuvMissionParams::table(),
        {{"default", mission::AuvMissionParams()}});
  table("AUV coverage area", "`coverage/` in `config/mission/auv.yaml`, or `auv/coverage/` in a scenario (which wins).",
        mission::CoverageArea::table(), {{"default", mission::CoverageArea()}}, "coverage/");
  table("GPS-compass navigation", "`config/usv.yaml` -> the GpsNavigation nodelet.",
        navigation::GpsNavigatorConfig::table(), {{"default", navigation::GpsNavigatorConfig()}});
  table("GPS-compass navigation node", "`config/usv.yaml` -> the GpsNavigation nodelet around its navigator.",
        navigation::GpsNavigationParams::table(), {{"default", navigation::GpsNavigationParams()}});
  table("USV hull", "`config/usv.yaml`: the outline a mission's outcome judges contact with (sim/contact.h), guidance "
        "keeps clear of obstacles when it holds, and the recovery's bow distance is measured from (models/hull.h).",
        sim::HullFootprint::table(), {{"default", sim::HullFootprint()}});
  table("AUV navigation inputs", "`config/navigation/auv_<model>.yaml` -> the AuvNavigation nodelet around its filter.",
        navigation::AuvNavigationParams::table(), {{"default", navigation::AuvNavigationParams()}});
  table("USBL mounting", "`config/usbl/usbl.yaml` -> the Usbl nodelet (and its simulator's mounting).",
        usbl::mountingTable(), {{"default", usbl::Mounting()}});
  table("USBL quality gates", "`config/usbl/usbl.yaml` -> the Usbl nodelet's positioning.",
        usbl::qualityLimitsTable(), {{"default", usbl::QualityLimits()}});
  table("Simulated USBL pair", "`config/usbl/usbl.yaml` -> the UsblSim nodelet and the ROS-free mission.",
        usbl::beaconSimTable(), {{"default", usbl::BeaconSimConfig()}});
  table("USBL node",
        "`config/usbl/usbl.yaml` -> the Usbl nodelet: its line, its frame, the AUV's depth from its pressure.",
        usbl::UsblNodeParams::table(), {{"default", usbl::UsblNodeParams()}});
  table("Simulated USBL pair node", "`config/usbl/usbl.yaml` -> the UsblSim nodelet beside the pair's acoustics.",
        usbl::BeaconSimNodeParams::table(), {{"default", usbl::BeaconSimNodeParams()}});
  table("Simulated GPS-compass", "the UsvSim nodelet's private `gps/...` parameters (docs/simulation.md); the "
        "ROS-free mission uses these defaults.", sim::GpsCompassConfig::table(), {{"default", sim::GpsCompassConfig()}});
  table("Simulator run", "the UsvSim and AuvSim nodelets' private parameters (docs/simulation.md); each vehicle's "
        "column as its manifest's `sim` sets it (`config/vehicles/`).",
        sim::RunParams::table(), runPerVehicle());
  table("Simulated USV", "the UsvSim nodelet's private `lidar/...` parameters: the simulated MRS1000.",
        sim::UsvSimulation::Config::table(), {{"default", sim::UsvSimulation::Config()}});
  table("USV simulator", "the UsvSim nodelet's model and ROS names.", sim::UsvSimNodeParams::table(),
        {{"default", sim::UsvSimNodeParams()}});
  table("Simulated AUV", "the AuvSim nodelet's private `sonar/...` (the simulated Micron) and `odom/...` parameters.",
        sim::AuvSimulation::Config::table(), {{"default", sim::AuvSimulation::Config()}});
  table("AUV simulator", "the AuvSim nodelet's model and ROS names.", sim::AuvSimNodeParams::table(),
        {{"default", sim::AuvSimNodeParams()}});
  table("Simulated depth sensor", "the AuvSim nodelet's private `depth/...` parameters.", sim::DepthConfig::table(),
        {{"default", sim::DepthConfig()}});
  table("Simulated AHRS", "the AuvSim nodelet's private `ahrs/...` parameters.", sim::AhrsConfig::table(),
        {{"default", sim::AhrsConfig()}});
  table("Simulated DVL", "the AuvSim nodelet's private `dvl/...` parameters.", sim::DvlConfig::table(),
        {{"default", sim::DvlConfig()}});
  table("Simulated GPS at the surface", "the AuvSim nodelet's private `surface_gps/...` parameters: the Girona500's "
        "GPS, /auv/gps/fix while the antenna is out of the water, fused by the AUV navigation as a position fix "
        "(docs/mission.md, SURFACED); the aColor has none. The ROS-free mission uses these defaults.",
        sim::SurfaceGpsConfig::table(), {{"default", sim::SurfaceGpsConfig()}});
  table("Simulated radio", "`config/relay/radio.yaml` -> the main job's radio between the relays "
        "(python/offshore_gnc/radio.py) and the ROS-free mission's (docs/relay.md).", sim::RadioParams::table(),
        {{"default", sim::RadioParams()}});
  table("AUV navigation", "`config/navigation/auv_<model>.yaml` -> the AuvNavigation nodelet (USBL + depth + AHRS + DVL).",
        navigation::AuvNavigatorConfig::table(), {{"default", navigation::AuvNavigatorConfig()}});
  table("Site origin",
        "`/site/origin` on each vehicle's master, shared by every node (launch/site.launch): `origin:=LAT,LON[,ALT]`, "
        "or the `origin:` of a site file (`site:=FILE`, e.g. `config/sites/pyhajarvi.yaml`; in simulation the "
        "scenario). Required: there is no default site. The two vehicles' relays refuse each other when their "
        "origins differ (docs/relay.md).",
        geo::LatLonAlt::table(), {}, "origin/");
  table("World frames", "the WorldFrames nodelet's private parameters (launch/site.launch).",
        geo::WorldFramesParams::table(), {{"default", geo::WorldFramesParams()}});
  table("LiDAR targets", "`config/perception/lidar_usv.yaml` -> the LidarTargets nodelet.",
        perception::LidarConfig::table(), {{"default", perception::LidarConfig()}});
  table("LiDAR tracks", "`config/perception/lidar_usv.yaml` (`tracker/...`) -> the LidarTargets nodelet's tracks "
        "(/usv/tracks: docs/perception.md, \"LiDAR tracks\").",
        perception::TrackerParams::table(), {{"default", perception::TrackerParams()}}, "tracker/");
  table("Sonar targets", "`config/perception/sonar_auv.yaml` -> the SonarTargets nodelet, the only one "
        "fed the beams (WallDetection takes its sweeps on `sonar/sweep`).",
        perception::SonarConfig::table(), {{"default", perception::SonarConfig()}});
  table("Sonar image", "`config/perception/sonar_auv.yaml` -> the SonarTargets nodelet's image of the beams.",
        perception::SonarImageParams::table(), {{"default", perception::SonarImageParams()}});
  table("Wall detection", "`config/perception/sonar_auv.yaml` -> the WallDetection nodelet (Publication II), "
        "on the SonarTargets nodelet's sweeps.",
        perception::WallConfig::table(), {{"default", perception::WallConfig()}});
  table("Sensor frames", "both perception files: where targets are put and how long a frame waits for its pose.",
        perception::SensorFrameParams::table(), {{"default", perception::SensorFrameParams()}});
  table("LiDAR's IMU", "`config/perception/lidar_usv.yaml` -> the LidarTargets nodelet: the clouds levelled.",
        perception::LidarImuParams::table(), {{"default", perception::LidarImuParams()}});
  table("USBL session", "`config/usbl/usbl.yaml` -> the Usbl nodelet's transceiver session.",
        usbl::SessionParams::table(), {{"default", usbl::SessionParams()}});
  table("Micron sonar", "`config/micron/micron.yaml` -> the MicronSonar driver (docs/hardware.md).",
        micron::DriverConfig::table(), {{"default", micron::DriverConfig()}});
  table("Micron emulator", "the MicronEmulator nodelet's private parameters (a head on a pseudo-terminal).",
        micron_sim::EmulatorConfig::table(), {{"default", micron_sim::EmulatorConfig()}});
  table("Relay", "`config/relay/<vehicle>.yaml` -> relay_node or the Relay nodelet (docs/relay.md).",
        relay::RelayConfig::table(), {{"default", relay::RelayConfig()}});
  table("Relay peers", "each entry of the relay's `peers` list.", relay::PeerEntry::table(),
        {{"default", relay::PeerEntry()}}, "peers[]/");
  table("Relay topics", "each entry of the relay's `topics` list (and `peers`: the peers it goes to or is taken from, "
        "all when empty).", relay::TopicConfig::table(), {{"default", relay::TopicConfig()}}, "topics[]/");
  table("CAN gateway", "`config/can/usv.yaml` -> the CanGateway nodelet (docs/can.md).", can::GatewayConfig::table(),
        {{"default", can::GatewayConfig()}});
  table("CAN gateway node", "`config/can/usv.yaml` -> the CanGateway nodelet: its bus, the jets' model, its frames.",
        can::GatewayNodeParams::table(), {{"default", can::GatewayNodeParams()}});
  table("CAN emulator",
        "`config/can/usv.yaml` -> the CanEmulator nodelet (`launch/can_usv.launch emulate:=true`, docs/can.md).",
        can::EmulatorConfig::table(), {{"default", can::EmulatorConfig()}});
  table("Safety supervisor node", "`config/safety/<vehicle>.yaml` -> the SafetySupervisor nodelet.",
        safety::SupervisorNodeParams::table(), {{"default", safety::SupervisorNodeParams()}});
  table("Safety supervisor", "the vehicles' supervisor rules (docs/safety.md); `usv` and `auv` are the presets.",
        safety::SupervisorConfig::table(), {{"usv", safety::usvDefaults()}, {"auv", safety::auvDefaults()}});
  for (const auto& v : {std::make_pair("USV", safety::usvDefaults()), std::make_pair("AUV", safety::auvDefaults())}) {
    std::printf("### %s safety rules (the preset's enabled rules)\n\n| rule | condition | detection | release | action | "
                "recovery |\n| --- | --- | --- | --- | --- | --- |\n", v.first);
    for (const auto& r : safety::ruleTable(v.second))
      std::printf("| `%s` | %s | %.6g s | %.6g s | %s | %s |\n", r.name.c_str(), r.condition.c_str(), r.detection,
                  r.release, safety::actionName(r.action), r.recovery ? "when clear" : "latched until reset");
    std::printf("\n");
  }
  table("COLA2 bridge", "`config/cola2/girona500.yaml` -> the Cola2Bridge nodelet (the Girona500's own stack).",
        cola2::BridgeParams::table(), {{"default", cola2::BridgeParams()}});
}

std::string generatedBy(const std::string& form, const std::string& from) {
  return "Generated by `param_docs --cfg " + form + " > cfg/" + form + ".cfg` from " + from +
         ": edit those, not this file (a test fails when it differs).\n";
}

// The nodelets' forms; false for an unknown one.
bool printCfg(const std::string& form) {
  std::string script;
  if (form == "Guidance") {
    using G = guidance::GuidanceParams;
    script = docs::cfgScript(
        "Run-time tuning of LOS guidance and the SBB planner (the Guidance nodelet).\n" +
            generatedBy(form, "guidance::GuidanceParams::table() and ::reconfigurable()") +
            "At start-up the server takes the loaded values (the vehicle's preset and YAML); the defaults here, the "
            "struct's, only fill the form.",
        "guidance", form, G::reconfigurable(), {docs::cfgSource("", G::table(), G())});
  } else if (form == "Control") {
    using namespace control;
    script = docs::cfgScript(
        "Run-time tuning of the vehicle controllers (the Control nodelet; thesis Tables 4.1-4.3).\n" +
            generatedBy(form, "control::ControlLoopParams::reconfigurable() and the vehicles' tables "
                              "(Usv/Girona500/AcolorControlParams::table())") +
            "One form serves the three vehicles (one runs per nodelet): at start-up the server takes its loaded "
            "values; a default here is the first of usv, girona500, acolor that has the field.",
        "control", form, ControlLoopParams::reconfigurable(),
        {docs::cfgSource("usv", UsvControlParams::table(), UsvControlParams()),
         docs::cfgSource("girona500", Girona500ControlParams::table(), Girona500ControlParams()),
         docs::cfgSource("acolor", AcolorControlParams::table(), AcolorControlParams())});
  } else {
    return false;
  }
  std::fputs(script.c_str(), stdout);
  return true;
}
}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc == 1) {
      printParameters();
      return 0;
    }
    if (argc == 3 && std::string(argv[1]) == "--cfg" && printCfg(argv[2])) return 0;
    if (argc == 2 && std::string(argv[1]) == "--launch-files") {
      for (const auto& f : docs::launchFiles(manifests())) std::printf("%s\n", f.c_str());
      return 0;
    }
    if (argc == 3 && std::string(argv[1]) == "--launch") {
      const std::string path = argv[2];
      std::ifstream in(path);
      if (!in) throw ConfigError("cannot read '" + path + "'");
      const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      const std::string name = path.substr(path.find_last_of('/') + 1);
      std::fputs(docs::withLaunchBlock(text, manifests(), name).c_str(), stdout);
      return 0;
    }
  } catch (const ConfigError& e) {
    std::fprintf(stderr, "param_docs: %s\n", e.what());
    return 1;
  }
  std::fprintf(stderr, "usage: param_docs [--cfg Guidance|Control | --launch launch/FILE.launch | --launch-files]\n");
  return 2;
}

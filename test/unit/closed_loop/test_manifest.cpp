// The vehicles' manifests (config/vehicles/): what the ROS-free stacks load comes from them, and a bad manifest
// fails when it is read, naming the manifest and the entry.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include "offshore_gnc/closed_loop/manifest.h"
#include "offshore_gnc/closed_loop/stacks.h"
#include "offshore_gnc/common/validate.h"

using namespace offshore_gnc;
using namespace offshore_gnc::closed_loop;

namespace {

// A copy of config/ to edit.
std::string configCopy(const std::string& name) {
  const std::string dir = testing::TempDir() + "/" + name;
  EXPECT_EQ(std::system(("rm -rf " + dir + " && cp -r config " + dir).c_str()), 0);
  return dir;
}

std::string read(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// `what` replaced by `with` in the file, once (it must be there).
void edit(const std::string& path, const std::string& what, const std::string& with) {
  std::string s = read(path);
  const std::size_t p = s.find(what);
  ASSERT_NE(p, std::string::npos) << what << " not in " << path;
  s.replace(p, what.size(), with);
  std::ofstream(path) << s;
}

// The ConfigError's message of loading `vehicle` from `dir` (empty when it loads).
std::string loadError(const std::string& dir, const std::string& vehicle) {
  try {
    VehicleManifest::load(dir, vehicle);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(VehicleManifest, ListsEachComponentsFilesInOrderWithTheModelSubstituted) {
  EXPECT_EQ(VehicleManifest::vehicles("config"), (std::vector<std::string>{"auv", "usv"}));
  const VehicleManifest auv = VehicleManifest::load("config", "auv");
  EXPECT_EQ(auv.models(), (std::vector<std::string>{"girona500", "acolor"}));
  const std::vector<ParamSource> control = auv.sources("control", "acolor");
  ASSERT_EQ(control.size(), 2u);  // the vehicle's tuning, then the simulated vehicle's over it (sim:=true)
  EXPECT_TRUE(has(control[0].name, "config/control/acolor.yaml")) << control[0].name;
  EXPECT_TRUE(has(control[1].name, "config/control/acolor_sim.yaml")) << control[1].name;
  EXPECT_TRUE(has(auv.vehicleConfigPath("girona500"), "config/auv_girona500.yaml"));
  // the scenario the mission also loads is the run's (auv.launch's arg), not a file the manifest names
  ASSERT_EQ(auv.sources("mission", "girona500").size(), 1u);
  // the seeds' defaults come as the component's last source
  const std::vector<ParamSource> sim = auv.sources("sim", "girona500");
  ASSERT_EQ(sim.size(), 1u);
  EXPECT_EQ(sim[0].yaml["seed"].as<int>(), 2);
  EXPECT_EQ(auv.component("safety").nodelet, "offshore_gnc/SafetySupervisor");
  EXPECT_THROW(auv.sources("control", "nautilus"), ConfigError);
  const VehicleManifest usv = VehicleManifest::load("config", "usv");
  EXPECT_TRUE(usv.models().empty());
  EXPECT_EQ(usv.sources("sim").back().yaml["seed"].as<int>(), 1);
  EXPECT_TRUE(has(usv.sources("safety").front().name, "config/safety/usv.yaml"));  // {vehicle}
}

TEST(VehicleManifest, ABadManifestNamesItselfAndTheEntry) {
  const std::string dir = configCopy("manifest_bad");
  const std::string usv = dir + "/vehicles/usv.yaml", auv = dir + "/vehicles/auv.yaml";
  const std::string original = read(usv);
  // a file that is not there (a typo), for one model of the AUV only
  edit(auv, "control/{model}_sim.yaml", "control/{model}_simulated.yaml");
  std::string e = loadError(dir, "auv");
  EXPECT_TRUE(has(e, "vehicles/auv.yaml") && has(e, "'control'") && has(e, "control/{model}_simulated.yaml") &&
              has(e, "model girona500")) << e;
  ASSERT_EQ(std::remove((dir + "/control/acolor_sim.yaml").c_str()), 0);
  edit(auv, "control/{model}_simulated.yaml", "control/{model}_sim.yaml");
  e = loadError(dir, "auv");
  EXPECT_TRUE(has(e, "model acolor")) << e;
  // an unknown field, a missing one, a component asked for that is not there
  edit(usv, "    launch: guidance_usv.launch\n", "    launch: guidance_usv.launch\n    rate: 10\n");
  e = loadError(dir, "usv");
  EXPECT_TRUE(has(e, "component 'guidance'") && has(e, "unknown field 'rate'")) << e;
  std::ofstream(usv) << original;
  edit(usv, "    nodelet: offshore_gnc/LidarTargets\n", "");
  e = loadError(dir, "usv");
  EXPECT_TRUE(has(e, "component 'lidar_targets'") && has(e, "lacks 'nodelet'")) << e;
  std::ofstream(usv) << original;
  try {
    VehicleManifest::load(dir, "usv").sources("sonar_targets");
    FAIL() << "the USV has no sonar";
  } catch (const ConfigError& x) {
    EXPECT_TRUE(has(x.what(), "no component 'sonar_targets'") && has(x.what(), "lidar_targets")) << x.what();
  }
  // a file on a launch arg the ROS-free stacks do not set
  edit(usv, "[{file: guidance/usv.yaml, arg: guidance_config}]",
       "[{file: guidance/usv.yaml, arg: guidance_config}, {file: guidance/usv.yaml, if: hardware}]");
  EXPECT_THROW(VehicleManifest::load(dir, "usv").sources("guidance"), ConfigError);
  std::ofstream(usv) << original;
  EXPECT_TRUE(has(loadError(dir, "rov"), "vehicles/rov.yaml")) << loadError(dir, "rov");
  EXPECT_THROW(loadUsvStack(testing::TempDir() + "/no_such_config"), ConfigError);
}

// The stacks load what the manifest lists: another file added to a component, or another seed, reaches the stack.
TEST(VehicleManifest, TheStacksLoadWhatItLists) {
  const std::string dir = configCopy("manifest_stacks");
  std::ofstream(dir + "/control/usv_trial.yaml") << "rate: 20.0\n";
  edit(dir + "/vehicles/usv.yaml", "[{file: control/usv.yaml, arg: control_config}]",
       "[{file: control/usv.yaml, arg: control_config}, control/usv_trial.yaml]");
  edit(dir + "/vehicles/usv.yaml", "{name: seed, default: 1}", "{name: seed, default: 7}");
  const UsvStackConfig shipped = loadUsvStack("config"), u = loadUsvStack(dir);
  EXPECT_DOUBLE_EQ(u.control.rate, 20.0);
  EXPECT_NE(shipped.control.rate, 20.0);
  EXPECT_EQ(shipped.sim.seed, 1u);
  EXPECT_EQ(u.sim.seed, 7u);
  EXPECT_DOUBLE_EQ(u.control.usv.surge.kp, shipped.control.usv.surge.kp);  // the vehicle's file still under it
  edit(dir + "/vehicles/auv.yaml", "models: [girona500, acolor]", "models: [girona500]");
  EXPECT_NO_THROW(loadAuvStack(dir, "girona500"));
  try {
    loadAuvStack(dir, "acolor");
    FAIL() << "a model the manifest does not list was loaded";
  } catch (const ConfigError& e) {
    EXPECT_TRUE(has(e.what(), "vehicle_model 'acolor' is not one of: girona500")) << e.what();
  }
  const AuvStackConfig a = loadAuvStack("config", "girona500");
  EXPECT_EQ(a.sim.seed, 2u);   // sim_auv.launch's seed
  EXPECT_EQ(a.usbl_seed, 1u);  // usbl_sim.launch's
  EXPECT_DOUBLE_EQ(a.usbl.session.ping_rate, 0.5);  // usbl_auv.launch's ping_rate
}

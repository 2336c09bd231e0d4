// The launch files' component blocks from the manifests (param_docs --launch): what a component becomes in XML,
// the hand-written rest of the file kept, and the manifests' contradictions refused.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/docs/launch_block.h"

using namespace offshore_gnc;
using closed_loop::VehicleManifest;

namespace {

std::vector<VehicleManifest> load(const std::string& dir) {
  return {VehicleManifest::load(dir, "auv"), VehicleManifest::load(dir, "usv")};
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

std::string errorOf(const std::vector<VehicleManifest>& ms, const std::string& launch) {
  try {
    docs::launchBlock(ms, launch);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

// A copy of config/ whose manifest `vehicle` has `what` replaced by `with`.
std::string editedCopy(const std::string& name, const std::string& vehicle, const std::string& what,
                       const std::string& with) {
  const std::string dir = testing::TempDir() + "/" + name;
  EXPECT_EQ(std::system(("rm -rf " + dir + " && cp -r config " + dir).c_str()), 0);
  const std::string path = dir + "/vehicles/" + vehicle + ".yaml";
  std::ifstream in(path);
  std::string s{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const std::size_t p = s.find(what);
  EXPECT_NE(p, std::string::npos) << what;
  if (p != std::string::npos) s.replace(p, what.size(), with);
  std::ofstream(path) << s;
  return dir;
}

}  // namespace

TEST(LaunchBlock, AComponentBecomesItsArgsAndNode) {
  const auto ms = load("config");
  const std::string b = docs::launchBlock(ms, "guidance_auv.launch");
  // the files' args with the manifest's paths as defaults, {model} as the launch file's own arg
  EXPECT_TRUE(has(b, "<arg name=\"control_config\" default=\"$(find offshore_gnc)/config/control/$(arg model).yaml\"/>"))
      << b;
  EXPECT_TRUE(has(b, "<node pkg=\"nodelet\" type=\"nodelet\" name=\"control\" ns=\"auv\" args=\"load "
                     "offshore_gnc/Control $(arg manager)\">")) << b;
  EXPECT_TRUE(has(b, "<rosparam if=\"$(arg sim)\" command=\"load\" file=\"$(find offshore_gnc)/config/control/"
                     "$(arg model)_sim.yaml\"/>")) << b;
  // a seed's default is the arg's, the run's value reaches the node through it
  const std::string sim = docs::launchBlock(ms, "sim_auv.launch");
  EXPECT_TRUE(has(sim, "<arg name=\"seed\" default=\"2\"/>")) << sim;
  EXPECT_TRUE(has(sim, "<param name=\"odom/enabled\" value=\"$(arg odom)\"/>")) << sim;
  // both vehicles include safety.launch: {vehicle} is its arg, and both manifests are named
  const std::string safety = docs::launchBlock(ms, "safety.launch");
  EXPECT_TRUE(has(safety, "config/vehicles/auv.yaml and config/vehicles/usv.yaml")) << safety;
  EXPECT_TRUE(has(safety, "ns=\"$(arg vehicle)\"")) << safety;
  EXPECT_EQ(docs::launchFiles(ms).size(), 12u);
  EXPECT_TRUE(has(errorOf(ms, "relay.launch"), "no vehicle manifest names launch/relay.launch"));
}

TEST(LaunchBlock, TheHandWrittenRestOfTheFileIsKept) {
  const auto ms = load("config");
  const std::string file = "<launch>\n  <arg name=\"manager\"/>\n  <!-- BEGIN generated stale -->\n  <node/>\n"
                           "  <!-- END generated -->\n  <include file=\"x\"/>\n</launch>\n";
  const std::string out = docs::withLaunchBlock(file, ms, "navigation_auv.launch");
  EXPECT_EQ(out.substr(0, 36), "<launch>\n  <arg name=\"manager\"/>\n  <");
  EXPECT_TRUE(has(out, "-->\n  <include file=\"x\"/>\n</launch>\n")) << out;
  EXPECT_FALSE(has(out, "stale")) << out;
  EXPECT_FALSE(has(out, "<node/>")) << out;
  EXPECT_EQ(docs::withLaunchBlock(out, ms, "navigation_auv.launch"), out);  // written again: the same
  EXPECT_THROW(docs::withLaunchBlock("<launch>\n</launch>\n", ms, "navigation_auv.launch"), ConfigError);
}

TEST(LaunchBlock, ContradictionsAreRefused) {
  // the two vehicles describe the launch file they share differently
  std::string e = errorOf(load(editedCopy("launch_shared", "usv", "    vehicle_arg: vehicle\n    output: screen\n",
                                          "    vehicle_arg: vehicle\n")),
                          "safety.launch");
  EXPECT_TRUE(has(e, "describe its components differently")) << e;
  // one arg with two defaults in one launch file
  e = errorOf(load(editedCopy("launch_args", "usv", "[{file: control/usv.yaml, arg: control_config}]",
                              "[{file: control/usv.yaml, arg: guidance_config}]")),
              "guidance_usv.launch");
  EXPECT_TRUE(has(e, "arg 'guidance_config' is declared with two defaults")) << e;
}

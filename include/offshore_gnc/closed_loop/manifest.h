#pragma once
// A vehicle described once: config/vehicles/<vehicle>.yaml lists each component its launch files start (nodelet
// type and name, namespace, the launch file that starts it) with the configuration files it loads in order and the
// parameters set after them (a seed's default, a rate). The ROS-free stacks (closed_loop/stacks.h) read their files
// and parameters from it; `param_docs --launch` prints the launch files' component blocks from it (docs module).
// ROS-free; strict: an unknown field, a missing required one, a file that does not exist or an unknown component
// throws ConfigError naming the manifest and the entry.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace offshore_gnc {
namespace closed_loop {

// One rosparam load. `file` is relative to config/ and may hold {model} and {vehicle}; `arg` names the launch arg
// that can replace it (declared by the generated block with `file` as its default; without `file`, the launch
// file's own arg, such as the run's scenario, which the ROS-free stacks take from their caller).
struct ManifestFile {
  std::string file;
  std::string arg;
  std::string ns;       // loaded under this namespace of the node
  std::string when;     // loaded only if this launch arg is true ("sim": always in the ROS-free stacks)
  std::string doc;      // the arg's doc
};

// A node parameter set from a launch arg: `<param name=name value="$(arg arg)"/>`. With a default the generated
// block declares the arg and the ROS-free stacks use the default (the seeds); without, the launch file's own arg.
struct ManifestArgParam {
  std::string name;
  std::string arg;
  std::string default_value;  // empty: the launch file's own arg
  std::string doc;
};

struct ManifestComponent {
  std::string key;       // what the stacks ask for ("guidance")
  std::string node;      // the node's name
  std::string ns;        // its namespace (may be {vehicle}); empty: the launch file's own
  std::string nodelet;   // the nodelet type (offshore_gnc/Guidance)
  std::string manager = "$(arg manager)";
  std::string launch;    // the launch file (under launch/) whose generated block starts it
  std::string when;      // started only if this launch arg is true
  std::string unless;    // started only if this launch arg is false
  std::string output;    // the node's output (screen), empty: roslaunch's default
  bool required = false;
  std::string model_arg;    // the launch arg {model} stands for in its launch file
  std::string vehicle_arg;  // the launch arg {vehicle} stands for (a launch file both vehicles include), else literal
  std::vector<ManifestFile> files;
  std::vector<std::pair<std::string, std::string>> params;  // set after the files: name, value (YAML scalar text)
  std::vector<ManifestArgParam> arg_params;
};

// What a run loads into a component, in order: the files, then the manifest's parameters (as one YAML map).
struct ParamSource {
  std::string name;  // the file's path, or "<manifest>: <component> params"
  YAML::Node yaml;
};

class VehicleManifest {
 public:
  // config_dir/vehicles/<vehicle>.yaml, every file it names checked to exist (for each model).
  static VehicleManifest load(const std::string& config_dir, const std::string& vehicle);
  // The vehicles described under config_dir/vehicles/ (the file names without .yaml, sorted).
  static std::vector<std::string> vehicles(const std::string& config_dir);

  const std::string& vehicle() const { return vehicle_; }
  const std::string& path() const { return path_; }  // config/vehicles/<vehicle>.yaml as given
  const std::vector<std::string>& models() const { return models_; }  // empty: one model
  // ConfigError "vehicle_model 'x' is not one of: ..." unless `model` is one of models() (or both are empty).
  void requireModel(const std::string& model) const;
  const std::vector<ManifestComponent>& components() const { return components_; }
  const ManifestComponent& component(const std::string& key) const;  // ConfigError for an unknown one
  const ManifestFile& vehicleConfig() const { return vehicle_config_; }
  const std::string& vehicleConfigLaunch() const { return vehicle_config_launch_; }
  const std::string& modelArg() const { return model_arg_; }

  // The vehicle's own config (config/usv.yaml, config/auv_<model>.yaml), absolute.
  std::string vehicleConfigPath(const std::string& model = "") const;
  // What `key` loads in a simulation run of `model` (sim:=true): its files in order, then its parameters and the
  // arg parameters' defaults. A file loaded on another launch arg than sim is a ConfigError (the stacks cannot tell).
  std::vector<ParamSource> sources(const std::string& key, const std::string& model = "") const;

 private:
  std::string resolve(const std::string& file, const std::string& model) const;  // {model}, {vehicle}; absolute

  std::string dir_, path_, vehicle_, model_arg_, vehicle_config_launch_;
  std::vector<std::string> models_;
  ManifestFile vehicle_config_;
  std::vector<ManifestComponent> components_;
};

}  // namespace closed_loop
}  // namespace offshore_gnc

#include "offshore_gnc/closed_loop/manifest.h"

#include <algorithm>
#include <filesystem>

#include "offshore_gnc/common/param_yaml.h"
#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace closed_loop {

namespace {

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
  return s;
}

// A map whose keys are all among `known`; ConfigError naming `where` otherwise.
void requireMap(const YAML::Node& n, const std::string& where, const std::vector<std::string>& known) {
  if (!n.IsMap()) throw ConfigError(where + " must be a map");
  for (const auto& kv : n) {
    const std::string k = kv.first.as<std::string>();
    if (std::find(known.begin(), known.end(), k) == known.end())
      throw ConfigError(where + " has an unknown field '" + k + "' (known: " + joined(known) + ")");
  }
}

std::string text(const YAML::Node& n, const std::string& key, const std::string& where, bool required = false) {
  const YAML::Node v = n[key];
  if (!v) {
    if (required) throw ConfigError(where + " lacks '" + key + "'");
    return "";
  }
  if (!v.IsScalar()) throw ConfigError(where + ": '" + key + "' must be a scalar");
  return v.as<std::string>();
}

bool flag(const YAML::Node& n, const std::string& key, const std::string& where) {
  if (!n[key]) return false;
  try {
    return n[key].as<bool>();
  } catch (const YAML::Exception&) {
    throw ConfigError(where + ": '" + key + "' must be true or false");
  }
}

// A file entry: "path" or {file, arg, ns, if, doc} with at least a file or an arg.
ManifestFile fileOf(const YAML::Node& n, const std::string& where) {
  ManifestFile f;
  if (n.IsScalar()) {
    f.file = n.as<std::string>();
    return f;
  }
  requireMap(n, where, {"file", "arg", "ns", "if", "doc"});
  f.file = text(n, "file", where);
  f.arg = text(n, "arg", where);
  f.ns = text(n, "ns", where);
  f.when = text(n, "if", where);
  f.doc = text(n, "doc", where);
  if (f.file.empty() && f.arg.empty()) throw ConfigError(where + " names neither a file nor an arg");
  return f;
}

ManifestArgParam argParamOf(const YAML::Node& n, const std::string& where) {
  ManifestArgParam p;
  if (n.IsScalar()) {
    p.name = p.arg = n.as<std::string>();
    return p;
  }
  requireMap(n, where, {"name", "arg", "default", "doc"});
  p.name = text(n, "name", where, true);
  p.arg = n["arg"] ? text(n, "arg", where) : p.name;
  p.default_value = text(n, "default", where);
  p.doc = text(n, "doc", where);
  return p;
}

ManifestComponent componentOf(const std::string& key, const YAML::Node& n, const std::string& where) {
  requireMap(n, where, {"node", "ns", "nodelet", "manager", "launch", "if", "unless", "output", "required",
                        "model_arg", "vehicle_arg", "files", "params", "arg_params"});
  ManifestComponent c;
  c.key = key;
  c.node = text(n, "node", where, true);
  c.ns = n["ns"] ? text(n, "ns", where) : "{vehicle}";
  c.nodelet = text(n, "nodelet", where, true);
  if (n["manager"]) c.manager = text(n, "manager", where);
  c.launch = text(n, "launch", where, true);
  c.when = text(n, "if", where);
  c.unless = text(n, "unless", where);
  c.output = text(n, "output", where);
  c.required = flag(n, "required", where);
  c.model_arg = text(n, "model_arg", where);
  c.vehicle_arg = text(n, "vehicle_arg", where);
  if (const YAML::Node fs = n["files"]) {
    if (!fs.IsSequence()) throw ConfigError(where + ": 'files' must be a list");
    for (std::size_t i = 0; i < fs.size(); ++i)
      c.files.push_back(fileOf(fs[i], where + " files[" + std::to_string(i) + "]"));
  }
  if (const YAML::Node ps = n["params"]) {
    if (!ps.IsMap()) throw ConfigError(where + ": 'params' must be a map");
    for (const auto& kv : ps) {
      if (!kv.second.IsScalar()) throw ConfigError(where + ": params/" + kv.first.as<std::string>() + " must be a scalar");
      c.params.emplace_back(kv.first.as<std::string>(), kv.second.as<std::string>());
    }
  }
  if (const YAML::Node as = n["arg_params"]) {
    if (!as.IsSequence()) throw ConfigError(where + ": 'arg_params' must be a list");
    for (std::size_t i = 0; i < as.size(); ++i)
      c.arg_params.push_back(argParamOf(as[i], where + " arg_params[" + std::to_string(i) + "]"));
  }
  return c;
}

// params["a/b"] = value as the nested map a: {b: value}, the way rosparam and yamlAt read a name.
void setAt(YAML::Node root, const std::string& name, const std::string& value) {
  const std::size_t slash = name.find('/');
  if (slash == std::string::npos) {
    root[name] = YAML::Load(value);
    return;
  }
  const std::string head = name.substr(0, slash);
  if (!root[head]) root[head] = YAML::Node(YAML::NodeType::Map);
  setAt(root[head], name.substr(slash + 1), value);
}

std::string replaced(std::string s, const std::string& what, const std::string& with) {
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + with.size()))
    s.replace(p, what.size(), with);
  return s;
}

}  // namespace

std::vector<std::string> VehicleManifest::vehicles(const std::string& config_dir) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::path(config_dir) / "vehicles";
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().extension() == ".yaml") names.push_back(e.path().stem().string());
  if (ec) throw ConfigError("cannot list '" + dir.string() + "': " + ec.message());
  std::sort(names.begin(), names.end());
  return names;
}

VehicleManifest VehicleManifest::load(const std::string& config_dir, const std::string& vehicle) {
  VehicleManifest m;
  m.dir_ = config_dir;
  m.path_ = config_dir + "/vehicles/" + vehicle + ".yaml";
  const YAML::Node y = loadYamlFile(m.path_);
  const std::string& where = m.path_;
  requireMap(y, where, {"vehicle", "models", "model_arg", "vehicle_config", "components"});
  m.vehicle_ = text(y, "vehicle", where, true);
  if (m.vehicle_ != vehicle) throw ConfigError(where + " describes '" + m.vehicle_ + "', not '" + vehicle + "'");
  if (const YAML::Node ms = y["models"]) {
    if (!ms.IsSequence() || ms.size() == 0) throw ConfigError(where + ": 'models' must be a non-empty list");
    for (const auto& x : ms) m.models_.push_back(x.as<std::string>());
  }
  m.model_arg_ = text(y, "model_arg", where);
  const YAML::Node vc = y["vehicle_config"];
  if (!vc) throw ConfigError(where + " lacks 'vehicle_config'");
  requireMap(vc, where + " vehicle_config", {"file", "arg", "launch"});
  m.vehicle_config_.file = text(vc, "file", where + " vehicle_config", true);
  m.vehicle_config_.arg = text(vc, "arg", where + " vehicle_config", true);
  m.vehicle_config_launch_ = text(vc, "launch", where + " vehicle_config", true);
  const YAML::Node cs = y["components"];
  if (!cs || !cs.IsMap()) throw ConfigError(where + " lacks its 'components' map");
  for (const auto& kv : cs) {
    const std::string key = kv.first.as<std::string>();
    m.components_.push_back(componentOf(key, kv.second, where + " component '" + key + "'"));
    ManifestComponent& c = m.components_.back();
    if (c.model_arg.empty()) c.model_arg = m.model_arg_;
  }
  // every file there is to load, for every model: a typo fails here, not when a launch file is started
  const std::vector<std::string> models = m.models_.empty() ? std::vector<std::string>{""} : m.models_;
  auto check = [&](const std::string& file, const std::string& what) {
    if (file.empty()) return;
    if (file.find("{model}") != std::string::npos && m.models_.empty())
      throw ConfigError(where + ": " + what + " names {model} but the vehicle lists no models");
    for (const auto& model : models)
      if (!std::filesystem::exists(m.resolve(file, model)))
        throw ConfigError(where + ": " + what + " loads '" + file + "'" + (model.empty() ? "" : " (model " + model + ")") +
                          ", which is not under " + config_dir);
  };
  check(m.vehicle_config_.file, "vehicle_config");
  for (const auto& c : m.components_)
    for (const auto& f : c.files) check(f.file, "component '" + c.key + "'");
  return m;
}

void VehicleManifest::requireModel(const std::string& model) const {
  if (models_.empty() ? model.empty() : std::count(models_.begin(), models_.end(), model) == 1) return;
  throw ConfigError("vehicle_model '" + model + "' is not one of: " + joined(models_) + " (" + path_ + ")");
}

const ManifestComponent& VehicleManifest::component(const std::string& key) const {
  for (const auto& c : components_)
    if (c.key == key) return c;
  std::vector<std::string> keys;
  for (const auto& c : components_) keys.push_back(c.key);
  throw ConfigError(path_ + " has no component '" + key + "' (it has: " + joined(keys) + ")");
}

std::string VehicleManifest::resolve(const std::string& file, const std::string& model) const {
  return dir_ + "/" + replaced(replaced(file, "{model}", model), "{vehicle}", vehicle_);
}

std::string VehicleManifest::vehicleConfigPath(const std::string& model) const {
  requireModel(model);
  return resolve(vehicle_config_.file, model);
}

std::vector<ParamSource> VehicleManifest::sources(const std::string& key, const std::string& model) const {
  requireModel(model);
  const ManifestComponent& c = component(key);
  std::vector<ParamSource> out;
  for (const auto& f : c.files) {
    if (!f.when.empty() && f.when != "sim")
      throw ConfigError(path_ + ": component '" + key + "' loads '" + f.file + "' on launch arg '" + f.when +
                        "', which a ROS-free stack does not set (only sim)");
    if (f.file.empty()) continue;  // the run's own file (the scenario): the stack's caller gives it
    if (!f.ns.empty())
      throw ConfigError(path_ + ": component '" + key + "' loads '" + f.file + "' under ns '" + f.ns +
                        "', which a ROS-free stack does not read");
    const std::string path = resolve(f.file, model);
    out.push_back({path, loadYamlFile(path)});
  }
  YAML::Node params(YAML::NodeType::Map);
  for (const auto& p : c.params) setAt(params, p.first, p.second);
  for (const auto& a : c.arg_params)
    if (!a.default_value.empty()) setAt(params, a.name, a.default_value);
  if (params.size() > 0) out.push_back({path_ + ": component '" + key + "' params", params});
  return out;
}

}  // namespace closed_loop
}  // namespace offshore_gnc

#include "offshore_gnc/docs/launch_block.h"

#include <set>
#include <utility>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace docs {

using closed_loop::ManifestComponent;
using closed_loop::ManifestFile;
using closed_loop::VehicleManifest;

namespace {

const char* const kBegin = "<!-- BEGIN generated";
const char* const kEnd = "<!-- END generated";

std::string shortPath(const VehicleManifest& m) { return "config/vehicles/" + m.vehicle() + ".yaml"; }

std::string escaped(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string replaced(std::string s, const std::string& what, const std::string& with) {
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + with.size()))
    s.replace(p, what.size(), with);
  return s;
}

std::string arg(const std::string& name) { return "$(arg " + name + ")"; }

// {model} and {vehicle} as the launch file says them: the component's launch args, or the vehicle itself.
std::string launchText(const std::string& s, const VehicleManifest& m, const ManifestComponent* c) {
  const std::string model_arg = c ? c->model_arg : m.modelArg();
  if (s.find("{model}") != std::string::npos && model_arg.empty())
    throw ConfigError(shortPath(m) + ": '" + s + "' names {model} but no model_arg says which launch arg it is");
  const std::string vehicle = c && !c->vehicle_arg.empty() ? arg(c->vehicle_arg) : m.vehicle();
  return replaced(replaced(s, "{model}", arg(model_arg)), "{vehicle}", vehicle);
}

std::string configPath(const std::string& file, const VehicleManifest& m, const ManifestComponent* c) {
  return "$(find offshore_gnc)/config/" + launchText(file, m, c);
}

std::string attr(const std::string& name, const std::string& value) {
  return value.empty() ? "" : " " + name + "=\"" + escaped(value) + "\"";
}

// The args a block declares, in order, each once.
class Args {
 public:
  explicit Args(std::string where) : where_(std::move(where)) {}
  void add(const std::string& name, const std::string& value, const std::string& doc) {
    const std::string line = "  <arg name=\"" + name + "\" default=\"" + escaped(value) + "\"" + attr("doc", doc) + "/>\n";
    for (const auto& d : decls_) {
      if (d.first != name) continue;
      if (d.second != line) throw ConfigError(where_ + ": arg '" + name + "' is declared with two defaults");
      return;
    }
    decls_.emplace_back(name, line);
  }
  std::string text() const {
    std::string s;
    for (const auto& d : decls_) s += d.second;
    return s;
  }

 private:
  std::string where_;
  std::vector<std::pair<std::string, std::string>> decls_;
};

std::string nodeOf(const ManifestComponent& c, const VehicleManifest& m, Args& args) {
  std::string s = "  <node" + attr("if", c.when.empty() ? "" : arg(c.when)) +
                  attr("unless", c.unless.empty() ? "" : arg(c.unless)) + " pkg=\"nodelet\" type=\"nodelet\"" +
                  attr("name", c.node) + attr("ns", launchText(c.ns, m, &c)) +
                  attr("args", "load " + c.nodelet + " " + c.manager) + attr("output", c.output) +
                  (c.required ? " required=\"true\"" : "") + ">\n";
  for (const ManifestFile& f : c.files) {
    if (!f.file.empty() && !f.arg.empty()) args.add(f.arg, configPath(f.file, m, &c), f.doc);
    const std::string file = f.arg.empty() ? configPath(f.file, m, &c) : arg(f.arg);
    s += "    <rosparam" + attr("if", f.when.empty() ? "" : arg(f.when)) + " command=\"load\"" + attr("file", file) +
         attr("ns", f.ns) + "/>\n";
  }
  for (const auto& p : c.arg_params) {
    if (!p.default_value.empty()) args.add(p.arg, p.default_value, p.doc);
    s += "    <param" + attr("name", p.name) + attr("value", arg(p.arg)) + "/>\n";
  }
  for (const auto& p : c.params) s += "    <param" + attr("name", p.first) + attr("value", p.second) + "/>\n";
  return s + "  </node>\n";
}

// One manifest's part of the block (empty when it names no component of `launch`).
std::string bodyOf(const VehicleManifest& m, const std::string& launch) {
  Args args(shortPath(m) + " in launch/" + launch);
  std::string nodes;
  bool named = false;
  if (m.vehicleConfigLaunch() == launch) {
    args.add(m.vehicleConfig().arg, configPath(m.vehicleConfig().file, m, nullptr), "");
    named = true;
  }
  for (const auto& c : m.components())
    if (c.launch == launch) {
      nodes += nodeOf(c, m, args);
      named = true;
    }
  return named ? args.text() + nodes : "";
}

}  // namespace

std::vector<std::string> launchFiles(const std::vector<VehicleManifest>& manifests) {
  std::set<std::string> files;
  for (const auto& m : manifests) {
    files.insert(m.vehicleConfigLaunch());
    for (const auto& c : m.components()) files.insert(c.launch);
  }
  return {files.begin(), files.end()};
}

std::string launchBlock(const std::vector<VehicleManifest>& manifests, const std::string& launch) {
  std::string body, from;
  const VehicleManifest* first = nullptr;
  for (const auto& m : manifests) {
    const std::string b = bodyOf(m, launch);
    if (b.empty()) continue;
    if (first && b != body)
      throw ConfigError("launch/" + launch + " is named by " + shortPath(*first) + " and " + shortPath(m) +
                        ", which describe its components differently");
    if (!first) first = &m;
    body = b;
    from += (from.empty() ? "" : " and ") + shortPath(m);
  }
  if (!first) throw ConfigError("no vehicle manifest names launch/" + launch);
  // (an XML comment cannot hold a double hyphen: the command is in docs/architecture.md, "Vehicle manifests")
  return "  " + std::string(kBegin) + " from " + from +
         " by param_docs: edit the manifest, not this block -->\n" + body + "  " + kEnd + " -->\n";
}

std::string withLaunchBlock(const std::string& text, const std::vector<VehicleManifest>& manifests,
                            const std::string& launch) {
  const std::size_t b = text.find(kBegin), e = text.find(kEnd);
  if (b == std::string::npos || e == std::string::npos || e < b)
    throw ConfigError("launch/" + launch + " has no generated block: put a line with '" + kBegin + " -->' and one "
                      "with '" + kEnd + " -->' where its components go");
  const std::size_t start = text.rfind('\n', b) == std::string::npos ? 0 : text.rfind('\n', b) + 1;
  const std::size_t eol = text.find('\n', e);
  const std::size_t end = eol == std::string::npos ? text.size() : eol + 1;
  return text.substr(0, start) + launchBlock(manifests, launch) + text.substr(end);
}

}  // namespace docs
}  // namespace offshore_gnc

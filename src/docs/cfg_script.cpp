#include "offshore_gnc/docs/cfg_script.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <set>
#include <sstream>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace docs {
namespace {

// The shortest text Python reads back as exactly `v`, so the generated Config.h holds the table's double (a
// rounded 1.5708 for pi/2 would be a range the core rejects at its edge).
std::string pyFloat(double v) {
  char b[40];
  for (int digits = 1; digits <= 17; ++digits) {
    std::snprintf(b, sizeof b, "%.*g", digits, v);
    if (std::strtod(b, nullptr) == v) break;
  }
  std::string s = b;
  if (s.find('e') != std::string::npos && v == std::trunc(v) && std::abs(v) < 1e15) {
    std::snprintf(b, sizeof b, "%.1f", v);  // 1000.0, not 1e+03
    s = b;
  }
  if (s.find_first_of(".e") == std::string::npos) s += ".0";  // a double_t default reads as a float, not an int
  return s;
}

// `text` as comment lines of at most 116 columns ('\n' keeps a break).
std::string comment(const std::string& text) {
  std::string out;
  std::istringstream paragraphs(text);
  for (std::string para; std::getline(paragraphs, para);) {
    std::istringstream words(para);
    std::string line = "#";
    for (std::string w; words >> w;) {
      if (line.size() > 1 && line.size() + 1 + w.size() > 116) {
        out += line + "\n";
        line = "#";
      }
      line += " " + w;
    }
    out += line + "\n";
  }
  return out;
}

std::string pyString(const std::string& text) {
  std::string s = "\"";
  for (char c : text) {
    if (c == '\\' || c == '"') s += '\\';
    s += c;
  }
  return s + "\"";
}

bool isIdentifier(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

const char* cfgType(const CfgField& f) {
  switch (f.kind) {
    case ParamKind::kNumber: return "double_t";
    case ParamKind::kInteger: return "int_t";
    case ParamKind::kFlag: return "bool_t";
    default: throw ConfigError("parameter '" + f.name + "' is a list, a choice or text: no reconfigure field");
  }
}

// "usv, girona500: proportional gain [N/m]": the doc and its unit, after which sources have it when there are several.
std::string description(const CfgField& f, const std::vector<std::string>& owners, std::size_t sources) {
  const std::string d = f.doc + (f.unit.empty() ? "" : " [" + f.unit + "]");
  if (sources < 2) return d;
  std::string who;
  for (const auto& o : owners) who += (who.empty() ? "" : ", ") + o;
  return who + ": " + d;
}

}  // namespace

std::string cfgScript(const std::string& header, const std::string& node, const std::string& form,
                      const std::vector<ReconfigureGroup>& groups, const std::vector<CfgSource>& sources) {
  std::ostringstream body;
  std::set<std::string> types, seen;
  for (const auto& g : groups) {
    if (!isIdentifier(g.name)) throw ConfigError("reconfigure group '" + g.name + "' is not an identifier");
    body << g.name << " = gen.add_group(" << pyString(g.name) << ")\n";
    for (const auto& name : g.params) {
      if (!seen.insert(cfgName(name)).second) throw ConfigError("reconfigure field '" + cfgName(name) + "' twice");
      const CfgField* field = nullptr;
      std::vector<std::string> owners;
      for (const auto& src : sources) {
        for (const auto& f : src.fields) {
          if (f.name != name) continue;
          if (field && (f.kind != field->kind || f.lo != field->lo || f.hi != field->hi))
            throw ConfigError("parameter '" + name + "': " + owners.front() + " and " + src.owner +
                              " differ in kind or range; one reconfigure field cannot hold both");
          if (!field) field = &f;
          owners.push_back(src.owner);
        }
      }
      if (!field) throw ConfigError("reconfigure field '" + name + "' is in no parameter table");
      const char* type = cfgType(*field);
      types.insert(type);
      body << g.name << ".add(" << pyString(cfgName(name)) << ", " << type << ", 0, "
           << pyString(description(*field, owners, sources.size())) << ", ";
      if (field->kind == ParamKind::kFlag) body << (field->value != 0.0 ? "True" : "False");
      else if (field->kind == ParamKind::kInteger)
        body << static_cast<long long>(field->value) << ", " << static_cast<long long>(field->lo) << ", "
             << static_cast<long long>(field->hi);
      else body << pyFloat(field->value) << ", " << pyFloat(field->lo) << ", " << pyFloat(field->hi);
      body << ")\n";
    }
  }
  std::ostringstream out;
  out << "#!/usr/bin/python3\n";
  out << comment(header);
  out << "from dynamic_reconfigure.parameter_generator_catkin import ParameterGenerator";
  for (const auto& t : types) out << ", " << t;  // std::set: bool_t, double_t, int_t
  out << "\n\ngen = ParameterGenerator()\n"
      << body.str() << "exit(gen.generate(\"offshore_gnc\", " << pyString(node) << ", " << pyString(form) << "))\n";
  return out.str();
}

}  // namespace docs
}  // namespace offshore_gnc

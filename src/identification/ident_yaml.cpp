// Writes fitted coefficients into a copy of the start parameter file (config/models/ schema), line by line so
// that the file's comments and order stay, then proves the result loads with the models' own loader.
#include <cmath>
#include <cstdio>
#include <map>
#include <regex>
#include <sstream>

#include "ident_plant.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/identification/identification.h"

namespace offshore_gnc {
namespace identification {

namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.7g", v);
  return b;
}

std::string listKey(const std::string& key, std::size_t* index) {
  const auto b = key.find('[');
  if (b == std::string::npos) return "";
  *index = std::stoul(key.substr(b + 1));
  return key.substr(0, b);
}

// Replaces the top-level line `key: ...` (or appends one); the old trailing comment gives way to `comment`.
void setLine(std::vector<std::string>& lines, const std::string& key, const std::string& value,
             const std::string& comment) {
  const std::regex re("^" + key + "\\s*:.*$");
  const std::string line = key + ": " + value + "  # " + comment;
  for (auto& l : lines)
    if (std::regex_match(l, re)) {
      l = line;
      return;
    }
  lines.push_back(line);
}

}  // namespace

std::string fittedParamsYaml(FitVehicle v, const std::string& start_text, const std::string& source,
                             const FitReport& r) {
  const auto start = ident::makePlant(v, start_text, source);
  std::vector<std::string> lines;
  {
    std::istringstream in(start_text);
    std::string l;
    while (std::getline(in, l)) lines.push_back(l);
  }
  // list parameters: the whole list is rewritten once, with the estimated elements replaced
  std::map<std::string, std::vector<double>> lists, list_se;
  for (const auto& p : r.parameters) {
    std::size_t i = 0;
    const std::string lk = listKey(p.param.key, &i);
    if (lk.empty() || !p.estimated || lists.count(lk)) continue;
    auto& vals = lists[lk];
    for (std::size_t k = 0;; ++k) {
      try {
        vals.push_back(start->get(lk + "[" + std::to_string(k) + "]"));
      } catch (const ConfigError&) {
        break;
      }
    }
    list_se[lk].assign(vals.size(), 0.0);
  }
  for (const auto& p : r.parameters) {
    if (!p.estimated) continue;
    std::size_t i = 0;
    const std::string lk = listKey(p.param.key, &i);
    if (!lk.empty()) {
      lists[lk].at(i) = p.value;
      list_se[lk].at(i) = p.se;
      continue;
    }
    setLine(lines, p.param.key, num(p.value),
            "fitted: standard error " + num(p.se) + " (start " + num(p.start) + ")");
  }
  for (const auto& kv : lists) {
    std::string value = "[", se = "[";
    for (std::size_t k = 0; k < kv.second.size(); ++k) {
      value += (k ? ", " : "") + num(kv.second[k]);
      se += (k ? ", " : "") + num(list_se[kv.first][k]);
    }
    setLine(lines, kv.first, value + "]", "fitted: standard errors " + se + "] (0: kept)");
  }
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  // The simulator must load it unchanged and see exactly the estimates.
  const auto check = ident::makePlant(v, out, source + " (fitted)");
  for (const auto& p : r.parameters) {
    if (!p.estimated) continue;
    const double got = check->get(p.param.key);
    if (std::abs(got - p.value) > 1e-6 * std::max(1.0, std::abs(p.value)))
      throw ConfigError(source + ": writing '" + p.param.key + "' did not round-trip (" + num(got) + " instead of " +
                        num(p.value) + ")");
  }
  check->validate();
  return out;
}

}  // namespace identification
}  // namespace offshore_gnc

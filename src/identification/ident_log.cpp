// Identification logs from CSV files (named columns, missing values allowed).
#include "offshore_gnc/identification/ident_log.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/geo/geo.h"

namespace offshore_gnc {
namespace identification {

const std::vector<std::string> kLogSignals{"north", "east", "down", "yaw_rad", "u", "v", "w", "r_rad_s", "rpm",
                                           "nozzle"};

std::size_t IdentLog::count(const std::string& signal) const {
  const auto it = measured.find(signal);
  if (it == measured.end()) return 0;
  return static_cast<std::size_t>(
      std::count_if(it->second.begin(), it->second.end(), [](double v) { return std::isfinite(v); }));
}

bool IdentLog::has(const std::string& signal, std::size_t min_samples) const {
  return count(signal) >= std::max<std::size_t>(1, min_samples);
}

IdentLog identLogFromCsv(const models::CsvTable& csv, const std::vector<std::string>& command_names,
                         const std::string& source) {
  IdentLog log;
  log.source = source;
  log.command_names = command_names;
  if (csv.header.empty())
    throw ConfigError(source + ": the log needs a header line naming its columns (t, " +
                      [&] {
                        std::string s;
                        for (const auto& c : command_names) s += c + ", ";
                        return s;
                      }() + "north, east, yaw_rad, ...)");
  if (csv.column("t") != 0) throw ConfigError(source + ": the first column must be 't' (time [s])");
  const std::size_t n = csv.rows.size();
  log.t.resize(n);
  for (std::size_t i = 0; i < n; ++i) log.t[i] = csv.rows[i][0];
  log.commands.resize(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(command_names.size()));
  std::vector<bool> used(csv.header.size(), false);
  used[0] = true;
  for (std::size_t k = 0; k < command_names.size(); ++k) {
    const int c = csv.column(command_names[k]);
    if (c < 0) throw ConfigError(source + ": command column '" + command_names[k] + "' is missing");
    used[c] = true;
    for (std::size_t i = 0; i < n; ++i) log.commands(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) = csv.rows[i][c];
  }
  for (const auto& s : kLogSignals) {
    const int c = csv.column(s);
    if (c < 0) continue;
    used[c] = true;
    auto& v = log.measured[s];
    v.resize(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = csv.rows[i][c];
  }
  const int lat = csv.column("lat_deg"), lon = csv.column("lon_deg");
  if (lat >= 0 && lon >= 0 && !log.measured.count("north") && !log.measured.count("east")) {
    used[lat] = used[lon] = true;
    std::size_t first = 0;
    while (first < n && !(std::isfinite(csv.rows[first][lat]) && std::isfinite(csv.rows[first][lon]))) ++first;
    if (first < n) {
      const geo::LocalNed frame(geo::LatLonAlt{csv.rows[first][lat], csv.rows[first][lon], 0.0});
      auto& north = log.measured["north"];
      auto& east = log.measured["east"];
      north.assign(n, std::numeric_limits<double>::quiet_NaN());
      east = north;
      for (std::size_t i = first; i < n; ++i) {
        if (!std::isfinite(csv.rows[i][lat]) || !std::isfinite(csv.rows[i][lon])) continue;
        const Eigen::Vector3d p = frame.toNed(geo::LatLonAlt{csv.rows[i][lat], csv.rows[i][lon], 0.0});
        north[i] = p.x();
        east[i] = p.y();
      }
      log.notes.push_back("lat_deg/lon_deg converted to north/east in a local frame at the first fix");
    }
  }
  for (std::size_t c = 0; c < csv.header.size(); ++c)
    if (!used[c]) log.notes.push_back("column '" + csv.header[c] + "' is not used");
  bool any = false;
  for (const auto& kv : log.measured) any = any || log.has(kv.first);
  if (!any)
    throw ConfigError(source + ": no measured column (north, east, yaw_rad, u, v, r_rad_s, rpm, nozzle, ...) has a value");
  return log;
}

IdentLog readIdentLogCsv(const std::string& path, const std::vector<std::string>& command_names) {
  models::CsvOptions opt;
  opt.empty_is_nan = true;
  return identLogFromCsv(models::readCsvFile(path, opt), command_names, path);
}

}  // namespace identification
}  // namespace offshore_gnc

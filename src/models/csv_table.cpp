// Numeric CSV tables for the model tools (one reader, one set of error messages).
#include "offshore_gnc/models/csv_table.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace models {

namespace {
std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}
}  // namespace

int CsvTable::column(const std::string& name) const {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return static_cast<int>(i);
  return -1;
}

CsvTable readCsvTable(std::istream& in, const std::string& source, const CsvOptions& opt) {
  CsvTable t;
  std::string line;
  int n = 0;
  bool first = true;
  std::size_t columns = opt.columns;
  auto fail = [&](const std::string& what) {
    throw ConfigError(source + ": line " + std::to_string(n) + ": " + what);
  };
  while (std::getline(in, line)) {
    ++n;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (trim(line).empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    std::string cell;
    while (std::getline(ss, cell, ',')) cells.push_back(trim(cell));
    if (!line.empty() && line.back() == ',') cells.emplace_back();
    std::vector<double> v;
    bool numeric = true;
    for (const auto& c : cells) {
      if (c.empty() && opt.empty_is_nan) {
        v.push_back(std::numeric_limits<double>::quiet_NaN());
        continue;
      }
      try {
        std::size_t used = 0;
        v.push_back(std::stod(c, &used));
        if (used != c.size()) numeric = false;
      } catch (const std::exception&) {
        numeric = false;
      }
    }
    const bool was_first = first;
    first = false;
    if (!numeric) {
      if (was_first) {  // a header
        t.header = cells;
        if (columns == 0) columns = cells.size();
        continue;
      }
      fail("not a list of numbers");
    }
    if (columns == 0) columns = v.size();
    if (v.size() != columns)
      fail("expected " + std::to_string(columns) + " columns, got " + std::to_string(v.size()));
    if (!std::isfinite(v[0]) || (!t.rows.empty() && v[0] < t.rows.back()[0]))
      fail("time must be finite and non-decreasing");
    t.rows.push_back(std::move(v));
    t.lines.push_back(n);
  }
  if (!t.header.empty() && opt.columns != 0 && t.header.size() != opt.columns)
    throw ConfigError(source + ": the header has " + std::to_string(t.header.size()) + " columns, expected " +
                      std::to_string(opt.columns));
  return t;
}

CsvTable readCsvFile(const std::string& path, const CsvOptions& opt) {
  std::ifstream f(path);
  if (!f) throw ConfigError(path + ": cannot open the file");
  return readCsvTable(f, path, opt);
}

std::string readTextFile(const std::string& path) {
  std::ifstream f(path);
  if (!f) throw ConfigError(path + ": cannot open the file");
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

}  // namespace models
}  // namespace offshore_gnc

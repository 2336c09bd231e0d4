#pragma once
// Numeric CSV tables as the model tools read them (model_run, model_fit, sim_log): an optional header line,
// blank lines and '#' comments skipped, a time column first that is finite and non-decreasing. One reader so
// that every tool accepts the same files and reports a bad line the same way (with its number).
#include <istream>
#include <string>
#include <vector>

namespace offshore_gnc {
namespace models {

struct CsvTable {
  std::vector<std::string> header;        // column names; empty when the file has no header line
  std::vector<std::vector<double>> rows;  // one vector per data row, all of the same size
  std::vector<int> lines;                 // the file line of each row (1-based), for messages
  // Index of a named column, -1 when absent (or when there is no header).
  int column(const std::string& name) const;
};

struct CsvOptions {
  std::size_t columns = 0;     // required column count; 0 = any (all rows as many as the first)
  bool empty_is_nan = false;   // an empty cell is a missing value (NaN) instead of an error
};

// Throws ConfigError("<source>: line N: ...") on a non-numeric cell, a wrong column count or a time (first
// column) that is not finite or goes backwards.
CsvTable readCsvTable(std::istream& in, const std::string& source, const CsvOptions& opt = CsvOptions());
CsvTable readCsvFile(const std::string& path, const CsvOptions& opt = CsvOptions());
// A whole text file (parameter files); ConfigError("<path>: cannot open the file").
std::string readTextFile(const std::string& path);

}  // namespace models
}  // namespace offshore_gnc

// Command-line options of the model tools.
#include "offshore_gnc/models/cli.h"

#include <stdexcept>

#include "offshore_gnc/common/validate.h"

namespace offshore_gnc {
namespace models {

CliOptions& CliOptions::text(const std::string& name, std::string* out) {
  options_.push_back({name, true, [out](const std::string& v) { *out = v; }});
  return *this;
}

CliOptions& CliOptions::number(const std::string& name, double* out, double lo, double hi) {
  options_.push_back({name, true, [=](const std::string& v) {
                        std::size_t used = 0;
                        double x = 0;
                        try {
                          x = std::stod(v, &used);
                        } catch (const std::exception&) {
                          used = std::string::npos;
                        }
                        if (used != v.size()) throw std::invalid_argument("'" + v + "' is not a number");
                        *out = requireRange(name, x, lo, hi);
                      }});
  return *this;
}

CliOptions& CliOptions::flag(const std::string& name, bool* out) {
  options_.push_back({name, false, [out](const std::string&) { *out = true; }});
  return *this;
}

std::string CliOptions::parse(int argc, char** argv) const {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-h" || a == "--help") return "help";
    const Option* o = nullptr;
    for (const auto& x : options_)
      if (x.name == a) o = &x;
    if (!o) return "unknown option " + a;
    if (!o->takes_value) {
      o->set("");
      continue;
    }
    if (i + 1 >= argc) return "missing value for " + a;
    try {
      o->set(argv[++i]);
    } catch (const std::exception& e) {
      return "bad value for " + a + ": " + e.what();
    }
  }
  return "";
}

}  // namespace models
}  // namespace offshore_gnc

#pragma once
// Command-line options of the model tools (model_run, model_manoeuvre, model_fit, sim_log): `--name value`
// pairs and flags, numbers range-checked; one parser so that every tool refuses a bad option the same way.
#include <functional>
#include <string>
#include <vector>

namespace offshore_gnc {
namespace models {

class CliOptions {
 public:
  CliOptions& text(const std::string& name, std::string* out);
  CliOptions& number(const std::string& name, double* out, double lo, double hi);
  CliOptions& flag(const std::string& name, bool* out);
  // "" when all went well, "help" for -h/--help, else what is wrong (unknown option, missing or bad value).
  std::string parse(int argc, char** argv) const;

 private:
  struct Option {
    std::string name;
    bool takes_value;
    std::function<void(const std::string&)> set;
  };
  std::vector<Option> options_;
};

}  // namespace models
}  // namespace offshore_gnc

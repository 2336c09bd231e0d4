// model_fit: estimate a vehicle model's coefficients from a log (thesis chapter 3), or validate a parameter file
// against one (--validate). The simulated response is the models module's own model; Ceres fits it.
//   model_fit --vehicle usv|girona500|acolor --params START.yaml --input LOG.csv|LOG.bag [--output FIT.yaml]
//             [--report DIR] [--validate] [--env ENV.yaml] [--dt S] [--segment S] [--warmup S] [--max-gap S]
//             [--max-rel-se X] [--fix KEY,KEY] [--no-plots]
// Exit status: 0 done; 1 bad input (message names it); 2 usage; 3 nothing could be estimated (no file written).
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/models/cli.h"
#include "offshore_gnc/models/csv_table.h"
#include "offshore_gnc/identification/identification.h"
#include "offshore_gnc/models/params_yaml.h"
#include "ros_identification_bag.h"

using namespace offshore_gnc;
using namespace offshore_gnc::models;
using namespace offshore_gnc::identification;

namespace {

int usage(const std::string& msg) {
  std::cerr << "model_fit: " << msg << "\n"
            << "usage: model_fit --vehicle usv|girona500|acolor --params START.yaml --input LOG.csv|LOG.bag\n"
               "                 [--output FIT.yaml] [--report DIR] [--validate] [--env ENV.yaml] [--dt S]\n"
               "                 [--segment S] [--warmup S] [--max-gap S] [--max-rel-se X] [--fix KEY,KEY] [--no-plots]\n";
  return 2;
}

bool endsWith(const std::string& s, const std::string& e) {
  return s.size() >= e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
}

std::string num(double v, int prec = 6) {
  if (!std::isfinite(v)) return "null";
  char b[40];
  std::snprintf(b, sizeof b, "%.*g", prec, v);
  return b;
}

std::string jsonString(const std::string& s) {
  std::string o = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') o += '\\';
    if (c == '\n') {
      o += "\\n";
      continue;
    }
    o += c;
  }
  return o + "\"";
}

void printReport(const FitReport& r, const std::string& input, bool validate) {
  std::printf("model_fit: %s (%s), %s: %zu rows, %zu piece(s), %zu segment(s), %d iterations, %.1f s CPU\n",
              fitVehicleName(r.vehicle).c_str(), r.model.c_str(), input.c_str(), r.rows, r.pieces, r.segments,
              r.iterations, r.cpu_seconds);
  std::printf("model_fit: CPU per stage:");
  for (const auto& kv : r.stage_cpu_seconds) std::printf(" %s %.1f s", kv.first.c_str(), kv.second);
  std::printf("\n");
  if (!validate) {
    std::printf("%-22s %13s %13s %13s  %s\n", "parameter", "start", "fitted", "std. error", "");
    for (const auto& p : r.parameters) {
      if (p.estimated) {
        const double rel = 100.0 * p.se / std::max(std::abs(p.value), 1e-300);
        std::printf("%-22s %13s %13s %13s  (%.2g %%)\n", p.param.key.c_str(), num(p.start).c_str(),
                    num(p.value).c_str(), num(p.se, 3).c_str(), rel);
      } else {
        std::printf("%-22s %13s %13s %13s  not estimated\n", p.param.key.c_str(), num(p.start).c_str(), "-", "-");
      }
    }
  }
  std::printf("%-10s %8s %12s %15s %17s\n", "signal", "samples", "residual", "segment fit %", "open-loop fit %");
  for (const auto& f : r.fits)
    std::printf("%-10s %8zu %12s %15s %17s%s\n", f.signal.c_str(), f.samples, num(f.noise, 3).c_str(),
                num(f.segment_fit, 4).c_str(), num(f.open_loop_fit, 4).c_str(),
                f.motion ? "" : "  (noise only: no motion to fit)");
  for (const auto& m : r.messages) std::printf("note: %s\n", m.c_str());
}

void writeJson(const FitReport& r, const std::string& path, const std::string& input, const std::string& params,
               bool validate) {
  std::ofstream o(path);
  o << "{\"vehicle\": " << jsonString(fitVehicleName(r.vehicle)) << ", \"model\": " << jsonString(r.model)
    << ", \"input\": " << jsonString(input) << ", \"params\": " << jsonString(params)
    << ", \"mode\": " << jsonString(validate ? "validate" : "fit") << ", \"rows\": " << r.rows
    << ", \"pieces\": " << r.pieces << ", \"segments\": " << r.segments << ", \"iterations\": " << r.iterations
    << ", \"cpu_s\": " << num(r.cpu_seconds, 4) << ",\n \"parameters\": [";
  for (std::size_t i = 0; i < r.parameters.size(); ++i) {
    const auto& p = r.parameters[i];
    o << (i ? ",\n  " : "\n  ") << "{\"key\": " << jsonString(p.param.key) << ", \"group\": " << jsonString(p.param.group)
      << ", \"start\": " << num(p.start, 10) << ", \"value\": " << num(p.value, 10) << ", \"se\": "
      << (p.estimated ? num(p.se, 6) : "null") << ", \"estimated\": " << (p.estimated ? "true" : "false")
      << ", \"note\": " << jsonString(p.note) << "}";
  }
  o << "],\n \"fits\": [";
  for (std::size_t i = 0; i < r.fits.size(); ++i) {
    const auto& f = r.fits[i];
    o << (i ? ",\n  " : "\n  ") << "{\"signal\": " << jsonString(f.signal) << ", \"samples\": " << f.samples
      << ", \"residual_rms\": " << num(f.noise) << ", \"segment_fit_pct\": " << num(f.segment_fit, 5)
      << ", \"open_loop_fit_pct\": " << num(f.open_loop_fit, 5) << ", \"motion\": " << (f.motion ? "true" : "false")
      << "}";
  }
  o << "],\n \"messages\": [";
  for (std::size_t i = 0; i < r.messages.size(); ++i) o << (i ? ",\n  " : "\n  ") << jsonString(r.messages[i]);
  o << "]}\n";
}

void writeSeries(const FitReport& r, const std::string& path) {
  std::ofstream o(path);
  o << "t";
  std::vector<std::string> sig;
  for (const auto& kv : r.series.measured) {
    sig.push_back(kv.first);
    o << "," << kv.first << "," << kv.first << "_open_loop," << kv.first << "_segments";
  }
  o << "\n";
  auto cell = [](double v) { return std::isfinite(v) ? num(v, 10) : std::string(); };
  for (std::size_t i = 0; i < r.series.t.size(); ++i) {
    o << num(r.series.t[i], 12);
    for (const auto& s : sig)
      o << "," << cell(r.series.measured.at(s)[i]) << "," << cell(r.series.open_loop.at(s)[i]) << ","
        << cell(r.series.segments.at(s)[i]);
    o << "\n";
  }
}

// The plots are matplotlib's (python/offshore_gnc/model_report.py), run on the files just written.
int plot(const std::string& dir) {
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/usr/bin/python3", "/usr/bin/python3", "-m", "offshore_gnc.model_report", dir.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  if (pid < 0 || waitpid(pid, &status, 0) < 0) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

int main(int argc, char** argv) {
  std::string vehicle, params, input, output, report, env_file;
  bool validate = false, plots = true;
  FitOptions opt;
  std::string fix;
  bool no_plots = false;
  const std::string err = CliOptions()
                              .text("--vehicle", &vehicle)
                              .text("--params", &params)
                              .text("--input", &input)
                              .text("--output", &output)
                              .text("--report", &report)
                              .text("--env", &env_file)
                              .flag("--validate", &validate)
                              .flag("--no-plots", &no_plots)
                              .number("--dt", &opt.dt, 1e-4, 1.0)
                              .number("--segment", &opt.segment, 1.0, 1e5)
                              .number("--warmup", &opt.warmup, 0.0, 1e4)
                              .number("--max-gap", &opt.max_gap, 1e-3, 1e5)
                              .number("--max-rel-se", &opt.max_rel_se, 1e-3, 1e3)
                              .text("--fix", &fix)
                              .parse(argc, argv);
  if (err == "help") return usage(err), 0;
  if (!err.empty()) return usage(err);
  plots = !no_plots;
  std::stringstream fixes(fix);
  for (std::string k; std::getline(fixes, k, ',');) opt.fixed.push_back(k);
  if (vehicle.empty() || params.empty() || input.empty()) return usage("--vehicle, --params and --input are required");
  if (validate && !output.empty()) return usage("--validate writes no parameter file (drop --output)");
  opt.estimate = !validate;
  try {
    const FitVehicle v = fitVehicleFromName(vehicle);
    const std::string text = readTextFile(params);
    if (!env_file.empty()) opt.environment = loadEnvironmentParams(env_file);
    const auto columns = fitCommandColumns(v, text, params);
    IdentLog log;
    if (endsWith(input, ".bag")) {
      identification_ros::BagOptions bo;
      if (v == FitVehicle::Usv) bo.nozzle_max = models::usvParamsFromYaml(text, params).nozzle_max;
      log = identification_ros::readIdentLogBag(input, v, static_cast<int>(columns.size()), bo);
    } else {
      log = readIdentLogCsv(input, columns);
    }
    for (const auto& n : log.notes) std::printf("model_fit: %s: %s\n", input.c_str(), n.c_str());
    const FitReport r = fitModel(v, text, params, log, opt);
    printReport(r, input, validate);
    if (!report.empty()) {
      mkdir(report.c_str(), 0755);
      writeJson(r, report + "/fit.json", input, params, validate);
      writeSeries(r, report + "/series.csv");
    }
    int rc = 0;
    if (!validate && !r.anything_estimated()) {
      std::fprintf(stderr, "model_fit: nothing could be estimated from %s (see the notes above); no file written\n",
                   input.c_str());
      rc = 3;
    } else if (!output.empty()) {
      const std::string fitted = fittedParamsYaml(v, text, params, r);
      std::ofstream f(output);
      if (!f) throw ConfigError(output + ": cannot open the file for writing");
      f << "# Fitted by model_fit from " << input << " (start: " << params << "); see the '# fitted' lines.\n"
        << fitted;
      std::printf("model_fit: wrote %s\n", output.c_str());
    }
    if (!report.empty() && plots) {
      if (plot(report) != 0) {
        std::fprintf(stderr, "model_fit: the plots were not drawn (python3 -m offshore_gnc.model_report %s failed: "
                             "source the workspace's setup.bash); the numbers are in %s/fit.json\n",
                     report.c_str(), report.c_str());
        return rc ? rc : 1;
      }
      std::printf("model_fit: report in %s\n", report.c_str());
    }
    return rc;
  } catch (const ConfigError& e) {
    std::fprintf(stderr, "model_fit: %s\n", e.what());
    return 1;
  }
}

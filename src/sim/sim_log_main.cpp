// sim_log: the vehicle simulation without ROS, as a field log: a command CSV (model_manoeuvre, model_run's
// format) drives the simulators' own UsvSimulation / AuvSimulation (models + sensor models), and the sensors'
// readings are written as the log model_fit reads. For trying the identification on a boat whose true
// coefficients are known (docs/model-identification.md).
//   sim_log --vehicle usv|girona500|acolor --params TRUE.yaml --input CMD.csv [--output LOG.csv|-]
//           [--scenario FILE.yaml] [--seed N] [--dt S] [--rpm-sigma RPM]
// Without --scenario: calm water at the default origin, starting at rest (the AUV at 3 m depth).
// USV columns: t,surge,sway,yaw,north,east,yaw_rad,u,v,r_rad_s,rpm,nozzle at the GPS-compass rate (fix in the
// scenario's local frame, Doppler velocity turned into body axes with the measured heading, rate of turn;
// engine rpm and nozzle of the port jet as the waterjet status reports them, rpm optionally with noise).
// AUV columns: t,c1..cn,north,east,down,yaw_rad,u,v,w,r_rad_s from the navigation estimate (INS stand-in).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <random>
#include <string>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/models/cli.h"
#include "offshore_gnc/models/cli.h"
#include "offshore_gnc/models/csv_table.h"
#include "offshore_gnc/models/params_yaml.h"
#include "offshore_gnc/sim/simulation.h"

using namespace offshore_gnc;

namespace {

int usage(const std::string& msg) {
  std::cerr << "sim_log: " << msg << "\n"
            << "usage: sim_log --vehicle usv|girona500|acolor --params TRUE.yaml --input CMD.csv [--output LOG.csv|-]\n"
               "               [--scenario FILE.yaml] [--seed N] [--dt S] [--rpm-sigma RPM]\n";
  return 2;
}

// Command rows held until the next row (zero-order hold), looked up as time advances.
class Commands {
 public:
  explicit Commands(const models::CsvTable& t) : t_(t) {}
  const std::vector<double>& at(double t) {
    while (i_ + 1 < t_.rows.size() && t_.rows[i_ + 1][0] <= t + 1e-9) ++i_;
    return t_.rows[i_];
  }
  double end() const { return t_.rows.back()[0]; }

 private:
  const models::CsvTable& t_;
  std::size_t i_ = 0;
};

std::string cells(const std::vector<double>& row) {
  std::string s;
  char b[32];
  for (std::size_t k = 1; k < row.size(); ++k) {
    std::snprintf(b, sizeof b, ",%.6g", row[k]);
    s += b;
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  std::string vehicle, params, input, output = "-", scenario_file;
  double dt = 0.01, rpm_sigma = 0.0;
  std::uint64_t seed = 1;
  double seed_n = 1;
  const std::string err = models::CliOptions()
                              .text("--vehicle", &vehicle)
                              .text("--params", &params)
                              .text("--input", &input)
                              .text("--output", &output)
                              .text("--scenario", &scenario_file)
                              .number("--dt", &dt, 1e-4, 0.1)
                              .number("--rpm-sigma", &rpm_sigma, 0, 1e4)
                              .number("--seed", &seed_n, 0, 1e9)
                              .parse(argc, argv);
  if (err == "help") return usage(err), 0;
  if (!err.empty()) return usage(err);
  seed = static_cast<std::uint64_t>(seed_n);
  if (params.empty() || input.empty()) return usage("--params and --input are required");
  if (vehicle != "usv" && vehicle != "girona500" && vehicle != "acolor")
    return usage("--vehicle must be usv, girona500 or acolor");
  try {
    sim::Scenario sc;  // default: calm water at the default origin, the AUV submerged at 3 m
    sc.auv.depth = 3.0;
    if (!scenario_file.empty()) sc = sim::loadScenario(scenario_file);
    std::ofstream f;
    if (output != "-") {
      f.open(output);
      if (!f) throw ConfigError(output + ": cannot open the file for writing");
    }
    std::ostream& out = output == "-" ? std::cout : f;
    out.precision(10);
    const geo::LocalNed frame(sc.origin);
    if (vehicle == "usv") {
      models::CsvOptions copt;
      copt.columns = 4;
      const models::CsvTable cmd = models::readCsvFile(input, copt);
      if (cmd.rows.empty()) throw ConfigError(input + ": no command rows");
      sim::UsvSimulation::Config cfg;
      cfg.dt = dt;
      cfg.seed = seed;
      cfg.lidar_on = false;
      cfg.usv = models::loadUsvParams(params);
      sim::UsvSimulation s(sc, cfg);
      std::mt19937_64 rng(seed * 7919 + 11);
      std::normal_distribution<double> n01(0.0, 1.0);
      Commands c(cmd);
      out << "t,surge,sway,yaw,north,east,yaw_rad,u,v,r_rad_s,rpm,nozzle\n";
      const double t0 = cmd.rows.front()[0];
      const long steps = std::lround((c.end() - t0) / dt);
      for (long k = 0; k < steps; ++k) {
        const auto& row = c.at(t0 + k * dt);
        s.setCommand({row[1], row[2], row[3]});
        const auto& o = s.step();
        if (!o.gps) continue;
        const auto& g = *o.gps;
        const Eigen::Vector3d p = frame.toNed(g.fix);
        const double ch = std::cos(g.heading), sh = std::sin(g.heading);
        const auto jet = s.model().jet(0);
        out << t0 + (k + 1) * dt << cells(c.at(t0 + (k + 1) * dt)) << ',' << p.x() << ',' << p.y() << ','
            << g.heading << ',' << ch * g.velocity_ned.x() + sh * g.velocity_ned.y() << ','
            << -sh * g.velocity_ned.x() + ch * g.velocity_ned.y() << ',' << g.rate_of_turn << ','
            << jet.rpm + rpm_sigma * n01(rng) << ',' << jet.nozzle << '\n';
      }
    } else {
      sim::AuvSimulation::Config cfg;
      cfg.dt = dt;
      cfg.seed = seed;
      cfg.sonar_on = false;
      cfg.auv = models::loadAuvParams(params);
      const std::size_t n = cfg.auv.thrusters.size();
      models::CsvOptions copt;
      copt.columns = n + 1;
      const models::CsvTable cmd = models::readCsvFile(input, copt);
      if (cmd.rows.empty()) throw ConfigError(input + ": no command rows");
      sim::AuvSimulation s(sc, cfg);
      Commands c(cmd);
      out << "t";
      for (std::size_t i = 0; i < n; ++i) out << ",c" << i + 1;
      out << ",north,east,down,yaw_rad,u,v,w,r_rad_s\n";
      const double t0 = cmd.rows.front()[0];
      const long steps = std::lround((c.end() - t0) / dt);
      for (long k = 0; k < steps; ++k) {
        const auto& row = c.at(t0 + k * dt);
        s.setThrusters(std::vector<double>(row.begin() + 1, row.end()));
        const auto& o = s.step();
        if (!o.odom) continue;
        const VehicleState& e = *o.odom;
        out << t0 + (k + 1) * dt << cells(c.at(t0 + (k + 1) * dt)) << ',' << e.position.x() << ',' << e.position.y()
            << ',' << e.position.z() << ',' << e.yaw << ',' << e.velocity.x() << ',' << e.velocity.y() << ','
            << e.velocity.z() << ',' << e.angular_rate.z() << '\n';
      }
    }
    return 0;
  } catch (const ConfigError& e) {
    std::cerr << "sim_log: " << e.what() << "\n";
    return 1;
  }
}

// model_run: run a vehicle model on a CSV of timed commands and write a CSV of states, to compare the model
// with a field log (thesis Fig. 3.10). Commands are held between rows (zero-order hold).
//   model_run --vehicle usv|auv --params config/models/usv.yaml [--env env.yaml] [--dt 0.01]
//             [--every 1] [--input in.csv|-] [--output out.csv|-]
// USV input columns: t,surge,sway,yaw (normalised joystick). AUV: t,c1..cn (normalised thruster commands).
// A header line is optional; blank lines and lines starting with '#' are skipped.
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/models/cli.h"
#include "offshore_gnc/models/auv.h"
#include "offshore_gnc/models/csv_table.h"
#include "offshore_gnc/models/params_yaml.h"
#include "offshore_gnc/models/usv.h"

using namespace offshore_gnc;
using namespace offshore_gnc::models;

namespace {

int usage(const std::string& msg) {
  std::cerr << "model_run: " << msg << "\n"
            << "usage: model_run --vehicle usv|auv --params FILE.yaml [--env FILE.yaml] [--dt S] [--every N]\n"
            << "                 [--input FILE.csv|-] [--output FILE.csv|-]\n";
  return 2;
}

void writeState(std::ostream& out, const VehicleState& s) {
  out << s.t << ',' << s.position.x() << ',' << s.position.y() << ',' << s.position.z() << ',' << s.yaw << ','
      << s.velocity.x() << ',' << s.velocity.y() << ',' << s.velocity.z() << ',' << s.angular_rate.z();
}

}  // namespace

int main(int argc, char** argv) {
  std::string vehicle, params, env_file, input = "-", output = "-";
  double dt = 0.01;
  long every = 1;
  double every_n = 1;
  const std::string err = CliOptions()
                              .text("--vehicle", &vehicle)
                              .text("--params", &params)
                              .text("--env", &env_file)
                              .text("--input", &input)
                              .text("--output", &output)
                              .number("--dt", &dt, 1e-4, 1.0)
                              .number("--every", &every_n, 1, 1e6)
                              .parse(argc, argv);
  if (err == "help") return usage(err), 0;
  if (!err.empty()) return usage(err);
  every = static_cast<long>(every_n);
  if (vehicle != "usv" && vehicle != "auv") return usage("--vehicle must be usv or auv");
  if (params.empty()) return usage("--params is required");

  try {
    const Environment env(env_file.empty() ? EnvironmentParams() : loadEnvironmentParams(env_file));
    std::unique_ptr<UsvModel> usv;
    std::unique_ptr<AuvModel> auv;
    std::size_t columns;
    if (vehicle == "usv") {
      usv = std::make_unique<UsvModel>(loadUsvParams(params));
      columns = 4;
    } else {
      auv = std::make_unique<AuvModel>(loadAuvParams(params));
      columns = 1 + auv->thrusters();
    }
    CsvTable rows;
    try {
      CsvOptions opt;
      opt.columns = columns;
      rows = input == "-" ? readCsvTable(std::cin, "-", opt) : readCsvFile(input, opt);
    } catch (const ConfigError& e) {
      std::cerr << "model_run: " << e.what() << "\n";
      return 1;
    }
    if (rows.rows.empty()) {
      std::cerr << "model_run: " << input << ": no command rows\n";
      return 1;
    }
    std::ofstream fout;
    if (output != "-") {
      fout.open(output);
      if (!fout) throw ConfigError(output + ": cannot open the file for writing");
    }
    std::ostream& out = output == "-" ? std::cout : fout;
    out.precision(10);
    out << "t,north,east,down,yaw_rad,u,v,w,r_rad_s";
    if (usv) out << ",rpm,nozzle,bucket,tau_u,tau_r\n";
    else out << ",tau_x,tau_y,tau_z,tau_n\n";

    VehicleState s0;
    s0.t = rows.rows.front()[0];
    if (usv) usv->reset(s0);
    else auv->reset(s0);
    long k = 0;
    for (std::size_t i = 0; i < rows.rows.size(); ++i) {
      const auto& v = rows.rows[i];
      bool ok;
      if (usv) {
        ok = usv->setCommand({v[1], v[2], v[3]});
      } else {
        ok = auv->setCommand(Eigen::Map<const Eigen::VectorXd>(v.data() + 1, columns - 1));
      }
      if (!ok) std::cerr << "model_run: line " << rows.lines[i] << ": command rejected (non-finite), previous kept\n";
      const double t_end = i + 1 < rows.rows.size() ? rows.rows[i + 1][0] : v[0];
      const double now = [&] { return usv ? usv->state().t : auv->state().t; }();
      long n = std::lround((t_end - now) / dt);
      for (long j = 0; j < n; ++j) {
        if (usv) usv->step(dt, env);
        else auv->step(dt, env);
        if (++k % every) continue;
        if (usv) {
          writeState(out, usv->state());
          const JetState jet = usv->jet(0);
          out << ',' << jet.rpm << ',' << jet.nozzle << ',' << jet.bucket << ',' << usv->tau()(0) << ','
              << usv->tau()(2) << '\n';
        } else {
          writeState(out, auv->state());
          const Eigen::Vector4d tau = auv->tau();
          out << ',' << tau(0) << ',' << tau(1) << ',' << tau(2) << ',' << tau(3) << '\n';
        }
      }
    }
    const Counters& c = usv ? usv->counters() : auv->counters();
    for (const auto& kv : c.snapshot()) std::cerr << "model_run: " << kv.first << " = " << kv.second << "\n";
    return 0;
  } catch (const ConfigError& e) {
    std::cerr << "model_run: " << e.what() << "\n";
    return 1;
  }
}

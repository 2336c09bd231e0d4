// Model identification core: CSV logs, the NRMSE fit measure, models::UsvModel::setState, a noise-free fit of a log the
// model itself made (30 % off coefficients recovered), the fitted YAML file, and logs that cannot identify.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/models/csv_table.h"
#include "offshore_gnc/identification/ident_log.h"
#include "offshore_gnc/identification/identification.h"
#include "offshore_gnc/models/params_yaml.h"
#include "offshore_gnc/models/usv.h"

using namespace offshore_gnc;
using namespace offshore_gnc::models;
using namespace offshore_gnc::identification;

namespace {

std::string fileText(const std::string& path) {
  std::ifstream f(path);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

// A log made by the model itself (noise-free): commands every 0.1 s, the state sampled at each row.
IdentLog modelLog(const models::UsvParams& p, const std::function<UsvCommand(double)>& cmd, double seconds) {
  models::UsvModel m(p);
  m.reset(VehicleState());
  const models::Environment env;
  IdentLog log;
  log.source = "model";
  log.command_names = {"surge", "sway", "yaw"};
  const int n = static_cast<int>(seconds / 0.1) + 1;
  log.commands.resize(n, 3);
  for (const char* s : {"north", "east", "yaw_rad", "u", "v", "r_rad_s", "rpm", "nozzle"}) log.measured[s].resize(n);
  for (int i = 0; i < n; ++i) {
    const double t = 0.1 * i;
    const UsvCommand c = cmd(t);
    const VehicleState& s = m.state();
    log.t.push_back(t);
    log.commands.row(i) << c.surge, c.sway, c.yaw;
    log.measured["north"][i] = s.position.x();
    log.measured["east"][i] = s.position.y();
    log.measured["yaw_rad"][i] = s.yaw;
    log.measured["u"][i] = s.velocity.x();
    log.measured["v"][i] = s.velocity.y();
    log.measured["r_rad_s"][i] = s.angular_rate.z();
    log.measured["rpm"][i] = m.jet(0).rpm;
    log.measured["nozzle"][i] = m.jet(0).nozzle;
    m.setCommand(c);
    for (int k = 0; k < 10; ++k) m.step(0.01, env);
  }
  return log;
}

// Surge steps and a square-wave yaw command: enough to excite rpm, nozzle, surge and yaw.
UsvCommand manoeuvre(double t) {
  const double surge = t < 40 ? 0.5 : (t < 80 ? 1.0 : 0.7);
  const double yaw = t < 20 ? 0.0 : (std::fmod(t, 16.0) < 8.0 ? 0.8 : -0.8);
  return {surge, 0.0, yaw};
}

std::string startText() { return fileText("config/models/usv.yaml"); }

}  // namespace

TEST(CsvTable, HeaderEmptyCellsAndErrorsWithLineNumbers) {
  std::istringstream in("# comment\nt,a,b\n0,1,\n\n0.5,nan,2\n");
  models::CsvOptions opt;
  opt.empty_is_nan = true;
  const models::CsvTable t = readCsvTable(in, "x.csv", opt);
  ASSERT_EQ(t.rows.size(), 2u);
  EXPECT_EQ(t.column("b"), 2);
  EXPECT_TRUE(std::isnan(t.rows[0][2]));
  EXPECT_TRUE(std::isnan(t.rows[1][1]));
  EXPECT_EQ(t.lines[1], 5);
  std::istringstream back("t,a\n1,0\n0.5,0\n");
  try {
    readCsvTable(back, "y.csv");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("y.csv: line 3: time must be finite and non-decreasing"), std::string::npos);
  }
  std::istringstream empty("t,a\n1,\n");
  EXPECT_THROW(readCsvTable(empty, "z.csv"), ConfigError);  // empty cells only where allowed
}

TEST(IdentLog, NamedColumnsLatLonAndMissingCommands) {
  std::istringstream in("t,surge,sway,yaw,lat_deg,lon_deg,extra\n0,0.5,0,0,61.45,23.727,1\n1,0.5,0,0,61.45001,23.727,2\n");
  models::CsvOptions opt;
  opt.empty_is_nan = true;
  const IdentLog log = identLogFromCsv(readCsvTable(in, "l.csv", opt), {"surge", "sway", "yaw"}, "l.csv");
  ASSERT_TRUE(log.has("north"));
  EXPECT_NEAR(log.measured.at("north")[0], 0.0, 1e-9);
  EXPECT_NEAR(log.measured.at("north")[1], 1.113, 0.01);  // 1e-5 deg of latitude
  EXPECT_NEAR(log.measured.at("east")[1], 0.0, 1e-6);
  bool noted = false;
  for (const auto& n : log.notes) noted = noted || n.find("'extra' is not used") != std::string::npos;
  EXPECT_TRUE(noted);
  std::istringstream nocmd("t,surge,north\n0,0,0\n");
  EXPECT_THROW(identLogFromCsv(readCsvTable(nocmd, "n.csv"), {"surge", "sway", "yaw"}, "n.csv"), ConfigError);
}

TEST(NrmseFit, PerfectMeanAndNaN) {
  const std::vector<double> y{1, 2, 3, 4}, mean(4, 2.5);
  EXPECT_DOUBLE_EQ(nrmseFit(y, y), 100.0);
  EXPECT_NEAR(nrmseFit(y, mean), 0.0, 1e-12);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_DOUBLE_EQ(nrmseFit({1, nan, 3, 5}, {1, 7, 3, 5}), 100.0);  // rows without a value are skipped
  EXPECT_TRUE(std::isnan(nrmseFit({1, 1, 1}, {1, 2, 3})));          // a constant signal has no fit
}

TEST(UsvModel, SetStateKeepsTheWaterjetChain) {
  models::UsvModel m(loadUsvParams("config/models/usv.yaml"));
  const models::Environment env;
  m.reset(VehicleState());
  m.setCommand({1.0, 0.0, 0.5});
  for (int i = 0; i < 2000; ++i) m.step(0.01, env);
  const models::JetState before = m.jet(0);
  VehicleState s;
  s.position = {10, 20, 0};
  s.yaw = 1.0;
  s.velocity = {0.5, 0, 0};
  m.setState(s);
  EXPECT_EQ(m.state().position.x(), 10.0);
  EXPECT_EQ(m.state().velocity.x(), 0.5);
  EXPECT_EQ(m.jet(0).rpm, before.rpm);
  m.step(0.01, env);
  EXPECT_NEAR(m.jet(0).rpm, before.rpm, 1.0);  // the engine keeps running where it was
  s.yaw = std::numeric_limits<double>::quiet_NaN();
  m.setState(s);
  EXPECT_EQ(m.counters().get("rejected_states"), 1u);
}

TEST(Identification, RecoversCoefficientsFromANoiseFreeModelLog) {
  models::UsvParams truth = loadUsvParams("config/models/usv.yaml");
  truth.X_uu *= 1.3;
  truth.N_r *= 0.7;
  truth.N_rr *= 1.3;
  truth.rpm_num = {0.317 * 1.3, 2.793 * 0.7, 1.828 * 1.3};
  truth.rpm_den = {1.0, 3.499 * 1.3, 1.828 * 1.3};
  truth.nozzle_time_constant = 0.15;
  const IdentLog log = modelLog(truth, manoeuvre, 150.0);
  const FitReport r = fitModel(FitVehicle::Usv, startText(), "usv.yaml", log, FitOptions());
  auto value = [&](const char* k) {
    const ParameterResult* p = r.find(k);
    EXPECT_TRUE(p && p->estimated) << k << ": " << (p ? p->note : "missing");
    return p ? std::abs(p->value) : 0.0;
  };
  EXPECT_NEAR(value("X_uu"), truth.X_uu, 0.02 * truth.X_uu);
  EXPECT_NEAR(value("N_r"), truth.N_r, 0.02 * truth.N_r);
  EXPECT_NEAR(value("N_rr"), truth.N_rr, 0.02 * truth.N_rr);
  EXPECT_NEAR(value("rpm_num[1]"), truth.rpm_num[1], 0.01 * truth.rpm_num[1]);
  EXPECT_NEAR(value("rpm_den[1]"), truth.rpm_den[1], 0.01 * truth.rpm_den[1]);
  EXPECT_NEAR(value("nozzle_time_constant"), 0.15, 0.005);
  EXPECT_NEAR(value("nozzle_delay"), 0.25, 0.011);
  for (const auto& f : r.fits)
    if (f.motion) EXPECT_GT(f.open_loop_fit, 95.0) << f.signal;
  // The file: the estimates on their lines with the standard error, everything else and the comments kept.
  const std::string out = fittedParamsYaml(FitVehicle::Usv, startText(), "usv.yaml", r);
  EXPECT_NE(out.find("# Table 3.3"), std::string::npos);
  EXPECT_NE(out.find("X_uu: "), std::string::npos);
  EXPECT_NE(out.find("# fitted: standard error"), std::string::npos);
  const models::UsvParams back = models::usvParamsFromYaml(out, "fitted");
  EXPECT_NEAR(back.X_uu, value("X_uu"), 1e-3 * back.X_uu);
  // The twin jets' nozzles push the stern sideways (the lumped jets did not), so sway is excited and Y_vv found.
  EXPECT_NEAR(std::abs(back.Y_vv), 3000.0, 0.02 * 3000.0);
}

TEST(Identification, ConstantCommandsEstimateNothingAndSayWhy) {
  const IdentLog log = modelLog(loadUsvParams("config/models/usv.yaml"), [](double) { return UsvCommand{0.4, 0, 0}; }, 60.0);
  const FitReport r = fitModel(FitVehicle::Usv, startText(), "usv.yaml", log, FitOptions());
  EXPECT_FALSE(r.anything_estimated());
  std::string all;
  for (const auto& m : r.messages) all += m + "\n";
  EXPECT_NE(all.find("(rpm): not estimated"), std::string::npos) << all;
  EXPECT_NE(all.find("(yaw): not estimated"), std::string::npos) << all;
  EXPECT_NE(all.find("surge constant at 0.4"), std::string::npos) << all;
  for (const auto& p : r.parameters) EXPECT_EQ(p.value, p.start) << p.param.key;
}

TEST(Identification, GapsSplitTheLogAndShortPiecesAreDropped) {
  IdentLog log = modelLog(loadUsvParams("config/models/usv.yaml"), manoeuvre, 100.0);
  for (std::size_t i = 600; i < log.rows(); ++i) log.t[i] += 30.0;  // 30 s without a record after t = 59.9
  for (int i = 300; i < 310; ++i) log.commands(i, 0) = std::numeric_limits<double>::quiet_NaN();
  FitOptions opt;
  opt.estimate = false;
  const FitReport r = fitModel(FitVehicle::Usv, startText(), "usv.yaml", log, opt);
  EXPECT_EQ(r.pieces, 3u);
  std::string all;
  for (const auto& m : r.messages) all += m + "\n";
  EXPECT_NE(all.find("30.1 s between t 59.9 and 90 s"), std::string::npos) << all;
  EXPECT_NE(all.find("rows 301-310"), std::string::npos) << all;
  for (const auto& f : r.fits)
    if (f.motion) EXPECT_GT(f.open_loop_fit, 99.0) << f.signal;  // the right model, restarted after each break
}

TEST(Identification, RefusesLogsItCannotUse) {
  IdentLog log = modelLog(loadUsvParams("config/models/usv.yaml"), manoeuvre, 10.0);  // shorter than a piece
  EXPECT_THROW(fitModel(FitVehicle::Usv, startText(), "usv.yaml", log, FitOptions()), ConfigError);
  log.command_names = {"c1", "c2", "c3"};
  EXPECT_THROW(fitModel(FitVehicle::Usv, startText(), "usv.yaml", log, FitOptions()), ConfigError);
  EXPECT_THROW(fitModel(FitVehicle::Girona500, startText(), "usv.yaml", log, FitOptions()), ConfigError);
}

// mission_rosfree: the co-operative mission ROS-free in one process (closed_loop::runMission), on the same
// scenario, configuration files and seeds as ./scripts/mission. Prints one JSON object with the figures the
// mission report gives (metrics.json's keys; `outcome` one of closed_loop/outcome.h's, `reason` the sentence);
// --out DIR also writes the tracks as CSV, and each vehicle's trace for tuning (usv_trace.csv: truth, guidance's
// reference, the joystick command; auv_trace.csv: truth, the navigation estimate, the reference, the wrench;
// usv_plans.csv: each path the USV's guidance planned, with what it planned round; usbl_fixes.csv: each USBL fix,
// its verdict and where it put the AUV).
// --fault PLAN injects the faults (offshore_gnc::FaultPlan, as ./scripts/mission --fault: the simulators', and link
// and geofence between the vehicles); each vehicle's supervisor's activations are listed (usv_safety, auv_safety).
// --seed S draws every sensor's noise anew (the USV simulator seed 2S-1, the AUV's 2S: S = 1 is the launch files'
// seeds 1 and 2); the scenario's own seeds (its current's) stay as written.
// --kill V@T stops one vehicle's stack at simulated time T (as ./scripts/mission --kill) and runs on for --after-kill
// seconds (default 60). The recovery figures (docs/mission.md, "Recovery") and the times of the search's end, the
// ascent, the surface and RECOVERED come with the rest.
// The AUV navigates on USBL fixes as in the main job (--auv-navigation ins: the simulator's INS-like estimate);
// the radio between the vehicles is the main job's (sim/radio.h: latency, jitter, rate, losses in bursts) with
// its parameters from CONFIG/relay/radio.yaml or --radio FILE, its losses drawn from the seed too.
//   mission_rosfree --scenario FILE [--auv-model girona500|acolor] [--auv-navigation usbl|ins] [--config DIR]
//                   [--radio FILE] [--fault PLAN] [--seed S] [--kill V@T] [--after-kill S] [--out DIR]
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <string>

#include "offshore_gnc/closed_loop/mission.h"
#include "offshore_gnc/common/faults.h"
#include "offshore_gnc/common/validate.h"

using namespace offshore_gnc;

namespace {
std::string num(double v) {
  if (!std::isfinite(v)) return "null";
  char b[64];
  std::snprintf(b, sizeof b, "%.4f", v);
  return b;
}
std::string str(const std::string& s) {
  std::string o = "\"";
  for (char c : s) o += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  return o + "\"";
}
// The supervisor's activations as a JSON list: "T s RULE -> ACTION: REASON".
std::string activations(const std::vector<safety::Transition>& transitions) {
  std::string o;
  for (const auto& tr : transitions) {
    if (!tr.to_active || tr.rule == "manual") continue;
    char b[64];
    std::snprintf(b, sizeof b, "%.2f s ", tr.t);
    o += (o.empty() ? "" : ", ") + str(b + tr.rule + " -> " + safety::actionName(tr.action) + ": " + tr.reason);
  }
  return "[" + o + "]";
}
// The USBL fixes' scores as the main job's metrics.json has them (report.py).
std::string usblScores(const closed_loop::UsblFixScores& u) {
  std::string by;
  for (const auto& [k, n] : u.rejected_by) by += (by.empty() ? "" : ", ") + str(k) + ": " + std::to_string(n);
  char b[512];
  std::snprintf(b, sizeof b,
                "\"usbl_rejected_by\": {%s}, \"usbl_outliers\": %zu, \"usbl_rejected_outliers\": %zu, "
                "\"usbl_outliers_accepted\": %zu, \"usbl_outlier_threshold_m\": %s, \"usbl_rejected_by_gates\": %zu, "
                "\"usbl_rejected_by_gates_outliers\": %zu, \"usbl_rejected_by_gates_unplaced\": %zu, "
                "\"usbl_multipath_replies\": %zu",
                by.c_str(), u.outliers, u.rejected_outliers, u.outliers_accepted, num(closed_loop::kUsblOutlierM).c_str(),
                u.by_gates, u.by_gates_outliers, u.by_gates_unplaced, u.multipath_replies);
  return b;
}
// A command-line number; exits 2 naming the option when the text is not one.
double number(const std::string& option, const std::string& text) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v)) {
    std::fprintf(stderr, "mission_rosfree: %s '%s' is not a number\n", option.c_str(), text.c_str());
    std::exit(2);
  }
  return v;
}
void writeCsv(const std::string& path, const char* header, const std::vector<Eigen::Vector4d>& rows) {
  std::ofstream f(path);
  f << header << "\n";
  for (const auto& r : rows) f << r(0) << "," << r(1) << "," << r(2) << "," << r(3) << "\n";
}
template <std::size_t N>
void writeTrace(const std::string& path, const char* header, const std::vector<std::array<double, N>>& rows) {
  std::ofstream f(path);
  f << header << "\n";
  for (const auto& row : rows)
    for (std::size_t i = 0; i < N; ++i) f << row[i] << (i + 1 < N ? "," : "\n");
}
// One row a plan: t, status, its waypoints "n e;n e;...", what it was planned round "id n e extent;..."
void writePlans(const std::string& path, const std::vector<closed_loop::MissionResult::Plan>& plans) {
  std::ofstream f(path);
  f << "t,status,path,round\n";
  for (const auto& p : plans) {
    f << p.t << ",\"" << p.status << "\",";
    for (std::size_t i = 0; i < p.path.size(); ++i) f << (i ? ";" : "") << p.path[i].x() << " " << p.path[i].y();
    f << ",";
    for (std::size_t i = 0; i < p.round.size(); ++i)
      f << (i ? ";" : "") << p.round[i].id << " " << p.round[i].origin.x() << " " << p.round[i].origin.y() << " "
        << std::max(p.round[i].length, p.round[i].width);
    f << "\n";
  }
}
// Each USBL fix: when the beacon was there, the gates' verdict (a quality name, or fused / gated by the filter),
// where it placed the AUV (auv_truth.csv has where it was).
void writeFixes(const std::string& path, const std::vector<closed_loop::UsblFixRecord>& fixes) {
  std::ofstream f(path);
  f << "t,verdict,north,east,down\n";
  for (const auto& x : fixes)
    f << x.t << "," << x.verdict() << "," << x.ned.x() << "," << x.ned.y() << "," << x.ned.z() << "\n";
}
}  // namespace

int main(int argc, char** argv) {
  std::string scenario, model = "girona500", config = OFFSHORE_GNC_CONFIG_DIR, out, faults;
  std::string navigation = "usbl", radio, kill;
  double after_kill = 60.0;
  long seed = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "mission_rosfree: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--scenario") scenario = next();
    else if (a == "--auv-model") model = next();
    else if (a == "--auv-navigation") navigation = next();
    else if (a == "--radio") radio = next();
    else if (a == "--config") config = next();
    else if (a == "--out") out = next();
    else if (a == "--fault") faults += " " + next();
    else if (a == "--seed") seed = static_cast<long>(number(a, next()));
    else if (a == "--kill") kill = next();
    else if (a == "--after-kill") after_kill = number(a, next());
    else {
      std::fprintf(stderr,
                   "usage: mission_rosfree --scenario FILE [--auv-model girona500|acolor] [--auv-navigation usbl|ins] "
                   "[--config DIR] [--radio FILE] [--fault PLAN] [--seed S] [--kill V@T] [--after-kill S] "
                   "[--out DIR]\n");
      return 2;
    }
  }
  if (scenario.empty()) {
    std::fprintf(stderr, "mission_rosfree: --scenario FILE is required\n");
    return 2;
  }
  try {
    closed_loop::MissionConfig cfg = closed_loop::loadMission(config, scenario, model);
    if (!radio.empty()) cfg.radio = sim::loadRadioParams(radio);
    cfg.auv.navigation = navigation;
    requireRange("--seed", static_cast<double>(seed), 1, 1e9);
    cfg.usv.sim.seed = static_cast<std::uint64_t>(2 * seed - 1);
    cfg.auv.sim.seed = static_cast<std::uint64_t>(2 * seed);
    cfg.auv.usbl_seed = static_cast<unsigned>(2 * seed - 1);  // config/usbl/usbl.yaml's seed 1 for S = 1
    cfg.radio_seed = static_cast<std::uint64_t>(seed);
    const FaultPlan plan = FaultPlan::parse(faults);  // ConfigError naming a bad item
    cfg.link_faults = plan.of("both");  // link, geofence: between the vehicles
    cfg.usv.sim.faults = plan.of("usv");
    cfg.auv.sim.faults = plan.of("auv");
    if (!kill.empty()) {
      const auto at = kill.find('@');
      cfg.kill = kill.substr(0, at);
      if (at == std::string::npos || (cfg.kill != "usv" && cfg.kill != "auv"))
        throw ConfigError("--kill '" + kill + "' is not VEHICLE@SIM_S with VEHICLE usv or auv");
      cfg.kill_at = number("--kill", kill.substr(at + 1));
      cfg.after_kill = requireRange("--after-kill", after_kill, 0, 1e5);
    }
    const closed_loop::MissionResult r = closed_loop::runMission(cfg);
    if (!out.empty()) {
      writeCsv(out + "/usv_truth.csv", "t,north,east,down", r.usv.truth);
      writeCsv(out + "/auv_truth.csv", "t,north,east,down", r.auv.truth);
      writeTrace(out + "/usv_trace.csv", closed_loop::kUsvTraceHeader, r.usv_trace);
      writeTrace(out + "/auv_trace.csv", closed_loop::kAuvTraceHeader, r.auv_trace);
      writePlans(out + "/usv_plans.csv", r.usv_plans);
      writeFixes(out + "/usbl_fixes.csv", r.usbl_fixes);
    }
    std::printf(
        "{\"success\": %s, \"outcome\": %s, \"reason\": %s, \"usv_xte_est_rmse_m\": %s, \"usv_xte_est_sd_m\": %s, "
        "\"usv_xte_est_mae_m\": %s, \"usv_xte_est_samples\": %zu, \"usv_xte_true_rmse_m\": %s, \"usv_xte_true_samples\": %zu, "
        "\"auv_xte_true_rmse_m\": %s, \"auv_xte_true_sd_m\": %s, \"auv_xte_true_mae_m\": %s, \"auv_xte_true_samples\": %zu, "
        "\"auv_approach_xte_true_rmse_m\": %s, \"auv_xte_est_rmse_m\": %s, "
        "\"target_error_m\": %s, \"detection_time_s\": %s, \"min_clearance_m\": %s, "
        "\"usv_final_distance_to_target_m\": %s, \"usv_wait_drift_m\": %s, \"usv_hold_p95_m\": %s, "
        "\"usv_recovery_hold_p95_m\": %s, \"usv_recovery_xte_true_rmse_m\": %s, "
        "\"usv_final_phase\": %s, \"auv_final_phase\": %s, \"usv_safety\": %s, \"auv_safety\": %s, "
        "\"auv_nav_source\": %s, \"auv_nav_rmse_m\": %s, \"auv_nav_max_m\": %s, \"usbl_fixes_received\": %zu, "
        "\"usbl_fixes_rejected\": %zu, %s, \"relay_lost\": %zu, \"recovered\": %s, \"auv_hold_excursion_m\": %s, "
        "\"auv_ascent_drift_m\": %s, \"auv_surface_excursion_m\": %s, \"recovery_distance_m\": %s, \"usv_auv_min_clearance_m\": %s, "
        "\"find_to_recovery_s\": %s, \"found_at_s\": %s, \"ascent_at_s\": %s, \"surfaced_at_s\": %s, "
        "\"recovered_at_s\": %s, \"stacks_died\": %s, %s\"sim_time_s\": %s, \"wall_time_s\": %s}\n",
        r.success ? "true" : "false", str(closed_loop::toString(r.outcome)).c_str(), str(r.reason).c_str(),
        num(r.usv.metrics.rmse).c_str(), num(r.usv.metrics.sd).c_str(), num(r.usv.metrics.mae).c_str(),
        r.usv.metrics.samples, num(r.usv.metrics_truth.rmse).c_str(), r.usv.metrics_truth.samples,
        num(r.auv.tracking_truth.rmse).c_str(), num(r.auv.tracking_truth.sd).c_str(),
        num(r.auv.tracking_truth.mae).c_str(), r.auv.tracking_truth.samples, num(r.auv.approach_truth.rmse).c_str(),
        num(r.auv.tracking.rmse).c_str(), num(r.target_error_m).c_str(), num(r.detection_time_s).c_str(),
        num(r.min_clearance_m).c_str(), num(r.usv_final_distance_to_target_m).c_str(),
        num(r.usv_wait_drift_m).c_str(), num(r.usv_hold_p95_m).c_str(), num(r.usv_recovery_hold_p95_m).c_str(),
        num(r.usv_recovery_xte_truth.rmse).c_str(), str(r.usv.final_phase).c_str(), str(r.auv.final_phase).c_str(),
        activations(r.usv_safety).c_str(), activations(r.auv_safety).c_str(), str(navigation).c_str(),
        num(r.auv_nav_rmse_m).c_str(), num(r.auv_nav_max_m).c_str(), r.usbl.received, r.usbl.rejected,
        usblScores(r.usbl).c_str(), r.relay_lost, r.recovered ? "true" : "false", num(r.auv_hold_excursion_m).c_str(),
        num(r.auv_ascent_drift_m).c_str(), num(r.auv_surface_excursion_m).c_str(), num(r.recovery_distance_m).c_str(), num(r.usv_auv_min_clearance_m).c_str(),
        num(r.find_to_recovery_s).c_str(), num(r.found_at_s).c_str(), num(r.ascent_at_s).c_str(),
        num(r.surfaced_at_s).c_str(), num(r.recovered_at_s).c_str(),
        r.stack_died.empty() ? "{}" : ("{" + str(r.stack_died) + ": " + num(cfg.kill_at) + "}").c_str(),
        std::isnan(r.traffic_min_clearance_m) ? ""
                                              : ("\"traffic_min_clearance_m\": " + num(r.traffic_min_clearance_m) + ", ").c_str(),
        num(r.sim_time_s).c_str(),
        num(r.wall_time_s).c_str());
    return r.success ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mission_rosfree: %s\n", e.what());
    return 2;
  }
}

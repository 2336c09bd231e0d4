// `./scripts/bench tracking`: the closed-loop scenarios (0.2 m/s cross current) with and without crab-angle
// compensation; cross-track RMSE / SD / MAE as thesis Tables 4.4 and 5.1, measured like the thesis on the
// navigation estimate (simulated GPS-compass / INS), plus the same runs on the true state (controller alone).
// Last line: one JSON object.
#include <chrono>
#include <cstdio>
#include <cstring>

#include "offshore_gnc/closed_loop/scenarios.h"

using namespace offshore_gnc;
using namespace offshore_gnc::closed_loop;

namespace {
void line(const char* name, const ClosedLoopResult& r) {
  std::printf("%-28s RMSE %.3f m  SD %.3f m  MAE %.3f m  max %.2f m  finished %s in %.0f s  hold %.2f m  %s\n", name,
              r.metrics.rmse, r.metrics.sd, r.metrics.mae, r.metrics.max_abs, r.finished ? "yes" : "NO", r.time,
              r.hold_error, r.status.c_str());
}
}  // namespace

int main(int argc, char** argv) {
  const char* csv = argc > 2 && std::strcmp(argv[1], "--csv") == 0 ? argv[2] : nullptr;
  const auto t0 = std::chrono::steady_clock::now();
  const auto usv = runUsv(scenarios::usvStraight(true));
  const auto usv_nc = runUsv(scenarios::usvStraight(false));
  const auto buoy = runUsv(scenarios::usvBuoy(true));
  const auto near = runUsv(scenarios::usvNearBuoy(true));
  const auto hold = runUsv(scenarios::usvHoldFromRest());
  const auto transit = runUsv(scenarios::usvShortTransit());
  const auto auv = runAuv(scenarios::auvCoverage(true));
  auto nc = scenarios::auvCoverage(false);
  nc.auv = [](AuvStackConfig& a) {
    a.guidance.los.adaptive_crab = false;
    a.control.girona500.cross_ki = 0.0;
  };
  const auto auv_nc = runAuv(nc);
  auto truth_usv = scenarios::usvStraight(true);
  truth_usv.navigation = false;
  const auto usv_t = runUsv(truth_usv);
  auto truth_auv = scenarios::auvCoverage(true);
  truth_auv.navigation = false;
  const auto auv_t = runAuv(truth_auv);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  line("usv straight (crab)", usv);
  line("usv straight (no crab)", usv_nc);
  line("usv buoy SBB (crab)", buoy);
  std::printf("%-28s min clearance %.2f m, samples inside the box %zu\n", "", buoy.min_clearance,
              buoy.inside_box_samples);
  line("usv buoy 25 m ahead (rostest)", near);
  std::printf("%-28s min clearance %.2f m, samples inside the box %zu\n", "", near.min_clearance,
              near.inside_box_samples);
  line("usv hold from rest", hold);
  line("usv short transit (mission)", transit);
  line("girona500 coverage (crab)", auv);
  line("girona500 coverage (no crab)", auv_nc);
  line("usv straight, true state", usv_t);
  line("girona500, true state", auv_t);
  std::printf("thesis: USV field test RMSE 1.55 m; Girona500 sea trial RMSE 0.2346 SD 0.2345 MAE 0.1525 (Table 4.4)\n");
  if (csv) {
    if (FILE* f = std::fopen(csv, "w")) {
      std::fprintf(f, "scenario,north,east,down\n");
      for (const auto& p : usv.track) std::fprintf(f, "usv,%.3f,%.3f,%.3f\n", p.x(), p.y(), p.z());
      for (const auto& p : buoy.track) std::fprintf(f, "buoy,%.3f,%.3f,%.3f\n", p.x(), p.y(), p.z());
      for (const auto& p : auv.track) std::fprintf(f, "auv,%.3f,%.3f,%.3f\n", p.x(), p.y(), p.z());
      for (const auto& p : hold.track) std::fprintf(f, "hold,%.3f,%.3f,%.3f\n", p.x(), p.y(), p.z());
      std::fclose(f);
    }
  }
  std::printf(
      "{\"usv_xte_est_rmse_m\": %.4f, \"usv_xte_est_sd_m\": %.4f, \"usv_xte_est_mae_m\": %.4f, \"usv_rmse_m_no_crab\": %.4f, "
      "\"usv_buoy_rmse_m\": %.4f, \"usv_min_clearance_m\": %.3f, \"usv_inside_box_samples\": %zu, "
      "\"auv_xte_est_rmse_m\": %.4f, \"auv_xte_est_sd_m\": %.4f, \"auv_xte_est_mae_m\": %.4f, \"auv_rmse_m_no_crab\": %.4f, "
      "\"usv_rmse_m_true_state\": %.4f, \"auv_rmse_m_true_state\": %.4f, \"usv_hold_m\": %.3f, \"usv_hold_from_rest_m\": %.3f, \"usv_short_transit_rmse_m\": %.4f, "
      "\"thesis_usv_rmse_m\": 1.55, \"thesis_auv_rmse_m\": 0.2346, \"wall_time_s\": %.3f}\n",
      usv.metrics.rmse, usv.metrics.sd, usv.metrics.mae, usv_nc.metrics.rmse, buoy.metrics.rmse, buoy.min_clearance,
      buoy.inside_box_samples, auv.metrics.rmse, auv.metrics.sd, auv.metrics.mae, auv_nc.metrics.rmse,
      usv_t.metrics.rmse, auv_t.metrics.rmse, usv.hold_error, hold.hold_error, transit.metrics.rmse, wall);
  return 0;
}

// The simulated SeaTrac pair's field effects and their statistics (docs/usbl.md, "The simulated pair"): the range
// scaled by the velocity-of-sound error, angle noise and fit error growing with range and the USV's rotation,
// replies by a reflected path (outliers) and what the quality gates make of them, dropouts alone and in bursts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/usbl/beacon_sim.h"
#include "offshore_gnc/usbl/positioning.h"

using namespace offshore_gnc;
using namespace offshore_gnc::usbl;

namespace {
double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

struct Reply {
  AcoFix fix;
  double at;  // the poll that gave it: the fix is made from the USV's pose then
};
// One ping at t (the USV's pose polled every 0.1 s until the reply, as the nodelet's I/O loop does): the fix, or
// nothing on a timeout.
std::optional<Reply> ping(BeaconSimulator& sim, const BeaconSimConfig& cfg, double t,
                          const std::function<Pose(double)>& usv, const Eigen::Vector3d& auv) {
  StreamDecoder dec;
  std::vector<StreamDecoder::Event> ev;
  dec.feed(sim.poll(t - 0.1, usv(t - 0.1), auv), ev);  // nothing due: the I/O loop polls all the time
  sim.setCurrentRange(transceiverRange(cfg.mount, usv(t), auv));
  dec.feed(sim.handle(Message{true, PingSend{2, MSG_REQU}}, t), ev);
  for (int k = 1; k <= static_cast<int>(cfg.timeout / 0.1) + 1; ++k) {
    const double u = t + 0.1 * k;
    ev.clear();
    dec.feed(sim.poll(u, usv(u), auv), ev);
    for (const auto& e : ev)
      if (e.message)
        if (auto f = std::get_if<FixMessage>(&e.message->body)) return Reply{f->fix, u};
  }
  return std::nullopt;
}

Pose still(double) { return Pose{}; }
}  // namespace

TEST(BeaconSimField, RangeIsScaledByTheVelocityOfSoundError) {
  BeaconSimConfig cfg;
  cfg.range_sigma = cfg.angle_sigma = 0.0;
  cfg.multipath_probability = cfg.dropout_probability = cfg.burst_probability = 0.0;
  cfg.sound_speed = 1480.0;
  cfg.sound_speed_error = 15.0;  // the transceiver assumes 1495 m/s in 1480 m/s water: ranges 1 % long
  BeaconSimulator sim(cfg);
  const Eigen::Vector3d auv(60, 80, 0);  // 100 m
  const auto r = ping(sim, cfg, 0.0, still, auv);
  ASSERT_TRUE(r);
  const AcoFix* f = &r->fix;
  EXPECT_NEAR(f->rangeTimeS(), 100.0 / cfg.sound_speed, 1e-6);  // the travel time is the water's
  EXPECT_NEAR(f->rangeM(), 100.0 * 1495.0 / 1480.0, 0.051);      // 101.0 m, to the wire's 0.1 m
  EXPECT_NEAR(f->vos * 0.1, 1495.0, 1e-9);
}

// The default pair at 50 m, the USV steady: ranges 0.47 % long (7 m/s), direct replies with a fit error about
// 0.3, about 4 % by a reflected path with a fit error about 2, about 10 % of pings lost (5 % alone, 5 % in bursts).
TEST(BeaconSimField, DefaultsGiveOutliersWithPoorFitsAndDropoutBursts) {
  BeaconSimConfig cfg;
  cfg.sound_speed = 1480.0;  // config/usbl/usbl.yaml's
  cfg.seed = 11;
  BeaconSimulator sim(cfg);
  Positioner pos(cfg.mount, QualityLimits{});
  const Eigen::Vector3d auv(40, 25, 15);  // 49.5 m from the transceiver at the USV's origin
  const double range = transceiverRange(cfg.mount, Pose{}, auv);
  const int n = 20000;
  std::vector<double> range_ratio, fit_direct, fit_outlier;
  std::vector<int> lost_runs;
  int lost = 0, run = 0, outliers = 0, outliers_fit_gated = 0, outliers_depth_gated = 0, direct_gated = 0;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * i;
    for (double u = t; u < t + 2.0; u += 0.5) {
      pos.addUsvPosition(u, Eigen::Vector3d::Zero());
      pos.addUsvAttitude(u, Eigen::Quaterniond::Identity());
      pos.addRemoteDepth(u, auv.z());
    }
    const auto reply = ping(sim, cfg, t, still, auv);
    if (!reply) {
      ++lost, ++run;
      continue;
    }
    const AcoFix* f = &reply->fix;
    if (run) lost_runs.push_back(run);
    run = 0;
    const FixResult r = pos.process(*f, t + f->rangeTimeS() * 2, t + 1.2);
    const bool outlier = r.ned && (*r.ned - auv).norm() > 3.0;  // 3 sigma of the navigation's 1 m fix sigma
    if (outlier) {
      ++outliers;
      fit_outlier.push_back(f->fitError());
      outliers_fit_gated += r.quality == Q_FIT_ERROR;
      outliers_depth_gated += r.quality == Q_DEPTH;
    } else {
      range_ratio.push_back(f->rangeM() / range);
      fit_direct.push_back(f->fitError());
      direct_gated += r.quality != Q_OK;
    }
  }
  const auto& c = sim.counters();
  const double replies = n - lost;
  EXPECT_NEAR(c.get("multipath") / replies, cfg.multipath_probability, 0.006);  // standard error 0.0015
  // range: the 0.47 % of the velocity-of-sound error (the 0.1 m steps of the wire average out)
  double mean_ratio = 0;
  for (double x : range_ratio) mean_ratio += x / range_ratio.size();
  EXPECT_NEAR(mean_ratio, 1487.0 / 1480.0, 0.0008);
  // fit error: direct replies near the nominal 0.3, those off by more than 3 m near the reflected path's 2
  EXPECT_NEAR(median(fit_direct), cfg.fit_error * std::sqrt(1 + std::pow(range / cfg.snr_range, 2)), 0.02);
  EXPECT_NEAR(median(fit_outlier), cfg.multipath_fit_error, 0.4);
  // most reflected replies are outliers (their extra path or direction error exceeds 3 m at 50 m)
  EXPECT_GT(outliers, 0.6 * c.get("multipath"));
  EXPECT_LE(outliers, c.get("multipath"));
  // the positioner's fit gate (2.0) takes about half of them, its depth gate (3 m) some more; the rest are left
  // to the navigation filter's gate. Only reflected replies are gated (some of them within 3 m).
  EXPECT_NEAR(static_cast<double>(outliers_fit_gated) / outliers, 0.5, 0.1);
  EXPECT_GT(outliers_depth_gated, 0.1 * outliers);
  EXPECT_LT(outliers_fit_gated + outliers_depth_gated, outliers);
  EXPECT_LE(direct_gated, static_cast<int>(c.get("multipath")) - outliers);
  // dropouts: alone (5 %) and in bursts of 6 pings on average starting with 1 % per ping (about 5.7 % of pings)
  const double expected_lost = 6.0 / (100.0 - 1.0 + 6.0);
  EXPECT_NEAR(static_cast<double>(lost) / n, expected_lost + cfg.dropout_probability * (1 - expected_lost), 0.01);
  EXPECT_NEAR(static_cast<double>(c.get("bursts")) / n, 1.0 / 105.0, 0.002);
  // runs of 4 and more lost pings: bursts (independent 5 % dropouts would give one run in 160000 pings)
  const auto long_runs = std::count_if(lost_runs.begin(), lost_runs.end(), [](int r) { return r >= 4; });
  EXPECT_GT(long_runs, 0.4 * c.get("bursts"));
}

// The angle noise and the fit error grow with range (the signal's spreading loss) and with the USV's rotation.
TEST(BeaconSimField, AngleNoiseAndFitErrorTrackRangeAndTheUsvsRotation) {
  BeaconSimConfig cfg;
  cfg.multipath_probability = cfg.dropout_probability = cfg.burst_probability = 0.0;
  cfg.seed = 3;
  auto stats = [&](const Eigen::Vector3d& auv, double yaw_rate, double& az_sd, double& fit) {
    BeaconSimulator sim(cfg);
    auto usv = [yaw_rate](double t) {
      Pose p;
      p.q = Eigen::AngleAxisd(yaw_rate * t, Eigen::Vector3d::UnitZ());
      return p;
    };
    std::vector<double> err, fits;
    for (int i = 0; i < 3000; ++i) {
      const double t = 2.0 * i;
      const auto r = ping(sim, cfg, t, usv, auv);
      ASSERT_TRUE(r);
      // the true azimuth in the transceiver's frame when the reply was made
      const Eigen::Vector3d v = usv(r->at).q.inverse() * auv;
      err.push_back(angleDiff(r->fix.azimuthRad(), std::atan2(v.y(), v.x())));
      fits.push_back(r->fix.fitError());
    }
    double q = 0;
    for (double e : err) q += e * e;
    az_sd = std::sqrt(q / err.size());
    fit = median(fits);
  };
  double sd_near, fit_near, sd_far, fit_far, sd_turn, fit_turn;
  stats({20, 0, 5}, 0.0, sd_near, fit_near);
  stats({500, 0, 5}, 0.0, sd_far, fit_far);    // sqrt(1 + (500 / 300)^2) = 1.94 times
  stats({20, 0, 5}, 0.35, sd_turn, fit_turn);  // 20 deg/s: blur 0.0175 rad beside 0.0087: 2.2 times
  const double far = std::sqrt(1 + std::pow(500.0 / cfg.snr_range, 2));
  const double turn = std::hypot(1.0, 0.35 * cfg.motion_time / cfg.angle_sigma);
  // the wire's 0.1 deg resolution adds 0.03 deg to the near figure
  EXPECT_NEAR(sd_near, cfg.angle_sigma, 0.08 * cfg.angle_sigma);
  EXPECT_NEAR(sd_far / sd_near, far, 0.1 * far);
  EXPECT_NEAR(sd_turn / sd_near, turn, 0.1 * turn);
  EXPECT_NEAR(fit_far / fit_near, far, 0.1 * far);
  EXPECT_NEAR(fit_turn / fit_near, turn, 0.1 * turn);
}

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/control/allocation.h"
#include "offshore_gnc/control/filters.h"
#include "offshore_gnc/control/pid.h"

using namespace offshore_gnc;
using namespace offshore_gnc::control;

TEST(Filters, CascadeUnityDcGainAndStable) {
  for (double dt : {0.01, 0.1, 0.5}) {
    FeedbackFilter f(FilterParams(), dt);
    EXPECT_EQ(f.sections().size(), 4u);
    EXPECT_NEAR(std::abs(f.response(1e-6)), 1.0, 1e-6) << dt;
    EXPECT_TRUE(f.stable()) << dt;
    for (const auto& s : f.sections()) EXPECT_NEAR((s.b0 + s.b1 + s.b2) / (1 + s.a1 + s.a2), 1.0, 1e-9);
  }
}

TEST(Filters, EachNotchHasDepthXiAtItsCentre) {
  // eq. 4.16: |(s^2 + 2 xi w s + w^2) / (s + w)^2| at s = j w equals xi; prewarping keeps this exact at any rate.
  FilterParams p;
  p.xi = 0.1;
  for (double dt : {0.05, 0.2}) {
    FeedbackFilter f(p, dt);
    for (std::size_t i = 0; i < p.notch_w.size(); ++i) {
      const double w = p.notch_w[i];
      EXPECT_NEAR(std::abs(f.sections()[i + 1].response(w, dt)), p.xi, 1e-9);
      // a minimum: slightly off the centre the section passes more
      EXPECT_GT(std::abs(f.sections()[i + 1].response(w * 1.3, dt)), p.xi);
      EXPECT_GT(std::abs(f.sections()[i + 1].response(w / 1.3, dt)), p.xi);
      // whole cascade attenuates at every centre
      EXPECT_LT(std::abs(f.response(w)), p.xi + 1e-9);
    }
  }
}

TEST(Filters, NotchWidthKeepsTheDepthAndShortensTheLowFrequencyLag) {
  // The lag below a notch, 2 zeta (1 - xi) / w: eq. 4.16's three (zeta = 1, xi = 0.8) delay a slow heading by 7 s,
  // the USV heading loop's undoing (docs/guidance-control.md); a narrow notch keeps the depth and lags less.
  const double dt = 0.1, w_slow = 0.005;
  for (double zeta : {1.0, 0.2}) {
    FilterParams p;
    p.tf = 0.0;
    p.notch_width = zeta;
    FeedbackFilter f(p, dt);
    double expected = 0.0;
    for (std::size_t i = 0; i < p.notch_w.size(); ++i) {
      EXPECT_NEAR(std::abs(f.sections()[i].response(p.notch_w[i], dt)), p.xi, 1e-9) << zeta;
      expected += 2.0 * zeta * (1.0 - p.xi) / p.notch_w[i];
    }
    const double delay = -std::arg(f.response(w_slow)) / w_slow;  // phase delay at a slow frequency
    EXPECT_NEAR(delay, expected, 0.05 * expected) << zeta;
    EXPECT_TRUE(f.stable());
  }
  FilterParams thesis;
  EXPECT_NEAR(2.0 * (1.0 - thesis.xi) * (1 / 0.1 + 1 / 0.2 + 1 / 0.4), 7.0, 1e-9);
}

TEST(Filters, LowPassCornerAndHighFrequencyRejection) {
  FilterParams p;
  p.notch_w.clear();
  p.tf = 0.1;
  const double dt = 0.01;
  FeedbackFilter f(p, dt);
  EXPECT_NEAR(std::abs(f.response(10.0)), 1.0 / std::sqrt(2.0), 1e-9);  // -3 dB at 1/T_f (prewarped)
  EXPECT_LT(std::abs(f.response(100.0)), 0.12);
}

TEST(Filters, TimeDomainStepSettlesToInputAndRejectsNaN) {
  FeedbackFilter f(FilterParams(), 0.1);
  double y = f.step(0.0);
  for (int i = 0; i < 3000; ++i) y = f.step(1.0);
  EXPECT_NEAR(y, 1.0, 1e-6);
  EXPECT_EQ(f.step(std::numeric_limits<double>::quiet_NaN()), y);
  // A sinusoid at a notch centre with xi = 0.1 comes out attenuated to ~xi (plus the other notches).
  FilterParams p;
  p.xi = 0.1;
  p.tf = 0.0;
  p.notch_w = {0.2};
  FeedbackFilter g(p, 0.1);
  double peak = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const double out = g.step(std::sin(0.2 * i * 0.1));
    if (i > 15000) peak = std::max(peak, std::abs(out));
  }
  EXPECT_NEAR(peak, 0.1, 0.01);
}

TEST(Filters, BadSettingsThrowNamingTheParameter) {
  FilterParams p;
  p.xi = 2.0;
  try {
    FeedbackFilter f(p, 0.1);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("filter/xi"), std::string::npos);
  }
}

TEST(Pid, SaturationAndAntiWindup) {
  PidGains g{2.0, 1.0, 0.0, 1.0, 10.0};
  Pid pid(g);
  for (int i = 0; i < 1000; ++i) EXPECT_LE(std::abs(pid.update(5.0, 0.0, 0.1)), 1.0);
  EXPECT_TRUE(pid.saturated());
  // Conditional integration: the integral did not grow while saturated, so the output leaves saturation
  // as soon as the error changes sign.
  EXPECT_LT(pid.integral(), 1.0);
  EXPECT_LT(pid.update(-0.6, 0.0, 0.1), 0.0);
  EXPECT_EQ(pid.update(std::nan(""), 0.0, 0.1), 0.0);
}

TEST(Pid, IntegralClampAndProportionalDerivative) {
  PidGains g{1.0, 0.5, 2.0, 100.0, 1.0};
  Pid pid(g);
  EXPECT_NEAR(pid.update(1.0, -0.5, 0.1), 1.0 - 1.0 + 0.5 * 0.1, 1e-12);
  for (int i = 0; i < 1000; ++i) pid.update(1.0, 0.0, 0.1);
  EXPECT_NEAR(pid.update(0.0, 0.0, 0.1), 1.0, 1e-12);  // ki * I clamped at i_limit
}

TEST(Allocation, PseudoinverseReproducesTheWrench) {
  Eigen::MatrixXd T(4, 5);
  T << 1, 1, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 1, 1, 0, 0.25, -0.25, 0, 0, 0;
  ThrustAllocator a(T, Eigen::VectorXd::Constant(5, 60.0));
  Eigen::Vector4d tau(30, -10, 20, 3);
  const auto r = a.allocate(tau);
  EXPECT_FALSE(r.saturated);
  EXPECT_NEAR((T * r.thrust - tau).norm(), 0.0, 1e-9);
  EXPECT_NEAR(r.thrust[0], 21.0, 1e-9);  // (30 + 3 / 0.25) / 2
  EXPECT_NEAR(r.setpoint[4], -10.0 / 60.0, 1e-12);
  // saturation keeps the direction of each group's part of the wrench, every thrust within its limit
  const auto s = a.allocate(tau * 10);
  EXPECT_TRUE(s.saturated);
  EXPECT_LE(s.thrust.cwiseAbs().maxCoeff(), 60.0 + 1e-9);
  const Eigen::VectorXd w = T * s.thrust;
  EXPECT_NEAR(w[3] / w[0], tau[3] / tau[0], 1e-12);
  EXPECT_NEAR(std::abs(w[1]), 60.0, 1e-9);  // sway and heave at their limits
  EXPECT_NEAR(std::abs(w[2]), 120.0, 1e-9);
  // thrusters on disjoint degrees of freedom saturate apart: (surge, yaw), heave, sway
  EXPECT_EQ(a.groups(), (std::vector<int>{0, 0, 1, 1, 2}));
  const auto h = a.allocate(Eigen::Vector4d(600, -10, 20, 3));  // the surge pair saturates, heave and sway not
  EXPECT_TRUE(h.saturated);
  const Eigen::VectorXd wh = T * h.thrust;
  EXPECT_NEAR(wh[1], -10.0, 1e-9);
  EXPECT_NEAR(wh[2], 20.0, 1e-9);
  EXPECT_NEAR(wh[3] / wh[0], 3.0 / 600.0, 1e-12);  // the surge-yaw pair keeps its direction
  EXPECT_LE(h.thrust.cwiseAbs().maxCoeff(), 60.0 + 1e-9);
  // bad input: zero thrust, never NaN
  const auto n = a.allocate(Eigen::Vector4d(std::nan(""), 0, 0, 0));
  EXPECT_TRUE(n.thrust.allFinite());
  EXPECT_EQ(n.thrust.norm(), 0.0);
  EXPECT_THROW(ThrustAllocator(T, Eigen::VectorXd::Constant(4, 60.0)), ConfigError);
}

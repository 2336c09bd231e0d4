// Vehicle models against the thesis' equations: exact transfer-function step responses, steady states where
// forces balance, the thruster configuration matrix of eq. 3.18, bad input, parameter files.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <complex>
#include <functional>

#include <Eigen/LU>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/models/auv.h"
#include "offshore_gnc/models/environment.h"
#include "offshore_gnc/models/integrator.h"
#include "offshore_gnc/models/params_yaml.h"
#include "offshore_gnc/models/usv.h"

using namespace offshore_gnc;
using namespace offshore_gnc::models;

namespace {

// Root of f on [a, b] by bisection (f(a), f(b) of opposite signs).
double bisect(const std::function<double(double)>& f, double a, double b) {
  double fa = f(a);
  for (int i = 0; i < 200; ++i) {
    const double m = 0.5 * (a + b), fm = f(m);
    if ((fm < 0) == (fa < 0)) {
      a = m;
      fa = fm;
    } else {
      b = m;
    }
  }
  return 0.5 * (a + b);
}

// Exact unit step response of num(s)/den(s) (monic den of order 2, distinct real poles), by partial fractions:
// y(t) = G(0) + sum_i N(p_i) / (p_i (p_i - p_j)) exp(p_i t).
double exactStep2(const double num[3], const double den[3], double t) {
  const double a = den[1], b = den[2];
  const double disc = std::sqrt(a * a - 4 * b);
  const double p[2] = {(-a + disc) / 2, (-a - disc) / 2};
  double y = num[2] / den[2];
  for (int i = 0; i < 2; ++i) {
    const double n = num[0] * p[i] * p[i] + num[1] * p[i] + num[2];
    y += n / (p[i] * (p[i] - p[1 - i])) * std::exp(p[i] * t);
  }
  return y;
}

UsvParams usvParams() { return loadUsvParams("config/models/usv.yaml"); }

}  // namespace

TEST(UsvParams, MomentOfInertiaFromTable33) {
  EXPECT_NEAR(usvParams().inertiaZ(), 11284.61, 0.01);  // eq. 3.5-3.7, Table 3.3
}

TEST(UsvModel, EngineRpmMatchesEq324StepResponse) {
  UsvModel m(usvParams());
  const double dt = 0.01, rpm0 = m.jet(0).rpm, rpm1 = m.rpmSetpoint(1.0);
  EXPECT_DOUBLE_EQ(rpm0, 600.0);
  EXPECT_DOUBLE_EQ(rpm1, 1820.0);  // Publication IV Table 2: joystick 1000 -> 1820 rpm
  const double num[3] = {0.317, 2.793, 1.828}, den[3] = {1.0, 3.499, 1.828};
  double worst = 0.0;
  for (int k = 1; k <= 1000; ++k) {
    m.step(dt, UsvCommand{1.0, 0.0, 0.0}, Environment());
    const double expected = rpm0 + (rpm1 - rpm0) * exactStep2(num, den, k * dt);
    worst = std::max(worst, std::abs(m.jet(0).rpm - expected));
    ASSERT_DOUBLE_EQ(m.jet(0).rpm, m.jet(1).rpm);
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_NEAR(m.jet(0).rpm, rpm1, 1.0);  // settled after 10 s (slowest pole -0.64 /s)
}

TEST(UsvModel, NozzleMatchesEq325DelayAndLag) {
  UsvModel m(usvParams());
  const double dt = 0.01, target = -9325.0;  // eq. 3.25's minus sign: full starboard joystick -> P < 0
  double worst = 0.0;
  for (int k = 1; k <= 200; ++k) {
    m.step(dt, UsvCommand{0.5, 0.0, 1.0}, Environment());
    const double t = k * dt;
    const double expected = t <= 0.25 ? 0.0 : target * (1.0 - std::exp(-(t - 0.25) / 0.1));
    worst = std::max(worst, std::abs(m.jet(0).nozzle - expected));
  }
  EXPECT_LT(worst, 1e-6);
  // Different sample time, same continuous response.
  UsvModel m2(usvParams());
  for (int k = 0; k < 40; ++k) m2.step(0.025, UsvCommand{0.5, 0.0, 1.0}, Environment());
  EXPECT_NEAR(m2.jet(0).nozzle, target * (1.0 - std::exp(-(1.0 - 0.25) / 0.1)), 1e-6);
}

TEST(UsvModel, SteadySurgeWhereThrustEqualsDamping) {
  const UsvParams p = usvParams();
  UsvModel m(p);
  for (int k = 0; k < 20000; ++k) m.step(0.01, UsvCommand{1.0, 0.0, 0.0}, Environment());
  const double u = m.state().velocity.x();
  const double damping = std::abs(p.X_u) * u + std::abs(p.X_uu) * u * u;
  // Still air still drags on the moving hull: thrust + (negative) air drag = hydrodynamic damping.
  EXPECT_LT(m.tauWind()(0), 0.0);
  EXPECT_NEAR(m.tau()(0) + m.tauWind()(0), damping, 1e-6 * damping);
  // Independent balance: 2 F(u, 1820 rpm) = |X_u| u + |X_uu| u^2 + air drag (Table 3.1 + affinity law).
  const double air = 0.5 * 1.225 * p.wind_cx * p.wind_area_front;
  const double u_star = bisect(
      [&](double x) {
        return 2 * m.jetThrust(x, 1820.0) - std::abs(p.X_u) * x - std::abs(p.X_uu) * x * x - air * x * x;
      },
      0.1, 10);
  EXPECT_NEAR(u, u_star, 1e-4);
  EXPECT_GT(u, 3.0);  // about 6.5 kt at the field table's top rpm
  EXPECT_LT(u, 4.0);
  EXPECT_NEAR(m.state().velocity.y(), 0.0, 1e-9);
  EXPECT_NEAR(m.state().angular_rate.z(), 0.0, 1e-9);
  EXPECT_NEAR(m.state().position.x(), u * 200.0, 60.0);  // went north (yaw 0)
}

TEST(UsvModel, ThrustTableFollowsTable31AndAffinityLaw) {
  UsvModel m(usvParams());
  const double kt = 1852.0 / 3600.0;
  EXPECT_NEAR(m.jetThrust(4 * kt, 1800), 1850.0, 1e-6);
  EXPECT_NEAR(m.jetThrust(4 * kt, 900), 1850.0 / 4, 1e-6);
  EXPECT_NEAR(m.jetThrust(2 * kt, 2400), 2000.0 * 16.0 / 9.0, 1e-6);
  EXPECT_NEAR(m.nozzleEfficiency(10000), std::exp(-0.9163), 1e-12);  // eq. 3.12: 40 % at full deflection
  EXPECT_DOUBLE_EQ(m.nozzleEfficiency(-5000), m.nozzleEfficiency(5000));
}

TEST(UsvModel, TurnsToStarboardForPositiveYawAndSettles) {
  UsvModel m(usvParams());
  for (int k = 0; k < 6000; ++k) m.step(0.01, UsvCommand{1.0, 0.0, 1.0}, Environment());
  const double r = m.state().angular_rate.z();
  EXPECT_GT(r, 0.05);
  EXPECT_LT(r, 0.6);
  // Yaw balance: tau_r = |N_r| r + |N_rr| r^2 at steady state.
  const UsvParams& p = m.params();
  EXPECT_NEAR(m.tau()(2), std::abs(p.N_r) * r + std::abs(p.N_rr) * r * r, 1e-2 * m.tau()(2));
}

TEST(UsvModel, NomotoSteadyStatesAreTheTable32Gains) {
  UsvParams p = usvParams();
  p.type = UsvModelType::Nomoto;
  UsvModel m(p);
  for (int k = 0; k < 6000; ++k) m.step(0.01, UsvCommand{1.0, 0.0, 1.0}, Environment());
  EXPECT_NEAR(m.state().velocity.x(), 2.930e-3 * 1820.0, 1e-3);
  EXPECT_NEAR(m.state().angular_rate.z(), -3.177e-5 * -9325.0, 1e-4);
}

TEST(UsvModel, NanCommandIsRejectedCountedAndNotIntegrated) {
  UsvModel m(usvParams());
  m.step(0.1, UsvCommand{0.5, 0.0, 0.2}, Environment());
  EXPECT_FALSE(m.setCommand(UsvCommand{std::nan(""), 0.0, 0.0}));
  EXPECT_FALSE(m.setCommand(UsvCommand{0.0, 0.0, INFINITY}));
  EXPECT_EQ(m.counters().get("rejected_commands"), 2u);
  EXPECT_DOUBLE_EQ(m.command().surge, 0.5);  // previous command kept
  EXPECT_TRUE(m.setCommand(UsvCommand{3.0, 0.0, 0.0}));
  EXPECT_DOUBLE_EQ(m.command().surge, 1.0);
  EXPECT_EQ(m.counters().get("clamped_commands"), 1u);
  m.step(std::nan(""), Environment());
  m.step(-1.0, Environment());
  EXPECT_EQ(m.counters().get("rejected_steps"), 2u);
  for (int k = 0; k < 100; ++k) m.step(0.01, Environment());
  EXPECT_TRUE(isFinite(m.state()));
}

TEST(UsvModel, LargeStepIsSubSteppedAndMatchesSmallSteps) {
  UsvModel a(usvParams()), b(usvParams());
  for (int k = 0; k < 100; ++k) a.step(0.01, UsvCommand{0.8, 0, 0.3}, Environment());
  for (int k = 0; k < 10; ++k) b.step(0.1, UsvCommand{0.8, 0, 0.3}, Environment());
  EXPECT_NEAR(a.state().velocity.x(), b.state().velocity.x(), 2e-2);
  EXPECT_NEAR(a.state().angular_rate.z(), b.state().angular_rate.z(), 2e-2);
}

TEST(UsvModel, DriftsWithTheCurrent) {
  EnvironmentParams ep;
  ep.current_east = 0.3;
  const Environment env(ep);
  UsvModel m(usvParams());
  for (int k = 0; k < 12000; ++k) m.step(0.01, UsvCommand{}, env);  // bucket neutral: no thrust
  // After the start-up lag the hull moves with the water: ground velocity = current.
  const VehicleState& s = m.state();
  const Eigen::Vector2d ground(std::cos(s.yaw) * s.velocity.x() - std::sin(s.yaw) * s.velocity.y(),
                               std::sin(s.yaw) * s.velocity.x() + std::cos(s.yaw) * s.velocity.y());
  EXPECT_NEAR(ground.x(), 0.0, 0.01);
  EXPECT_NEAR(ground.y(), 0.3, 0.01);
  EXPECT_NEAR(s.position.y(), 0.3 * 120.0, 6.0);
}

TEST(AuvParams, Girona500MatrixIsEq318) {
  const Eigen::MatrixXd t = AuvParams::girona500().tcm();
  Eigen::MatrixXd expected(4, 5);
  expected << -1, -1, 0, 0, 0,  //
      0, 0, 0, 0, 1,            //
      0, 0, -1, -1, 0,          //
      -0.2432, 0.2432, 0, 0, 0;
  EXPECT_TRUE(t.isApprox(expected, 1e-12)) << t;
  EXPECT_TRUE(loadAuvParams("config/models/girona500.yaml").tcm().isApprox(expected, 1e-12));
  const Eigen::MatrixXd ac = loadAuvParams("config/models/acolor.yaml").tcm();
  EXPECT_EQ(ac.cols(), 6);
  Eigen::FullPivLU<Eigen::MatrixXd> lu(ac);
  EXPECT_EQ(lu.rank(), 4);  // surge, sway, heave and yaw all controllable
}

TEST(AuvModel, ThrusterCurveAsymmetricAndSaturated) {
  AuvModel m(AuvParams::girona500());
  EXPECT_DOUBLE_EQ(m.thrust(2, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(m.thrust(2, 0.05), 0.0);  // dead band
  EXPECT_GT(m.thrust(2, 1.0), -m.thrust(2, -1.0));  // forward stronger than reverse
  EXPECT_DOUBLE_EQ(m.thrust(2, 1.0), 51.5);
  EXPECT_DOUBLE_EQ(m.thrust(2, 2.0), 51.5);  // saturation
  EXPECT_DOUBLE_EQ(m.thrust(2, NAN), 0.0);
  EXPECT_DOUBLE_EQ(m.thrust(0, -1.0), -51.5);  // surge thrusters: strong branch drives ahead (eq. 3.18 sign)
  EXPECT_NEAR(AuvParams::girona500().maxThrust()(0), 51.5, 1e-12);
  const AuvParams file = loadAuvParams("config/models/girona500.yaml");
  for (int i = 0; i < 5; ++i) EXPECT_EQ(file.thrusters[i].curve_thrust, AuvParams::girona500().thrusters[i].curve_thrust);
}

TEST(AuvModel, HeaveSettlesWhereWeightBuoyancyAndDampingBalance) {
  const AuvParams p = loadAuvParams("config/models/girona500.yaml");
  AuvModel m(p);
  VehicleState s;
  s.position.z() = 20.0;
  m.reset(s);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(5);
  for (int k = 0; k < 6000; ++k) m.step(0.01, zero, Environment());
  const double w_minus_b = p.weight() - p.buoyancy(1000.0);  // -36.3 N: the Girona500 floats up
  EXPECT_LT(w_minus_b, 0.0);
  const double w_star =
      bisect([&](double w) { return w_minus_b - std::abs(p.Z_w) * w - std::abs(p.Z_ww) * std::abs(w) * w; }, -2, 2);
  EXPECT_NEAR(m.state().velocity.z(), w_star, 1e-6);
  EXPECT_LT(m.state().position.z(), 20.0);
}

TEST(AuvModel, HeaveThrustBalancingBuoyancyHoldsDepth) {
  const AuvParams p = loadAuvParams("config/models/girona500.yaml");
  AuvModel m(p);
  VehicleState s;
  s.position.z() = 10.0;
  m.reset(s);
  // Both heave thrusters (T3, T4: positive pushes up) pull down by (B - W) / 2 each.
  const double each = -(p.buoyancy(1000.0) - p.weight()) / 2.0;
  const double c = bisect([&](double x) { return m.thrust(2, x) - each; }, -1.0, -0.1);
  Eigen::VectorXd cmd = Eigen::VectorXd::Zero(5);
  cmd(2) = cmd(3) = c;
  for (int k = 0; k < 6000; ++k) ASSERT_TRUE(m.step(0.01, cmd, Environment()));
  EXPECT_NEAR(m.tau()(2), p.buoyancy(1000.0) - p.weight(), 1e-6);
  EXPECT_NEAR(m.state().velocity.z(), 0.0, 1e-9);
  EXPECT_NEAR(m.state().position.z(), 10.0, 1e-6);
}

TEST(AuvModel, ABuoyantAuvFloatsAtTheSurfaceAndNeverAboveIt) {
  const AuvParams p = loadAuvParams("config/models/girona500.yaml");
  ASSERT_LT(p.weight(), p.buoyancy(1000.0));
  AuvModel m(p);
  VehicleState s;
  s.position.z() = 5.0;
  m.reset(s);
  Eigen::VectorXd cmd = Eigen::VectorXd::Zero(5);
  double highest = 1e9;
  for (int k = 0; k < 12000; ++k) {  // 60 s rising on its own buoyancy
    m.step(0.01, cmd, Environment());
    highest = std::min(highest, m.state().position.z());
  }
  EXPECT_GT(highest, -0.1);  // at most the emergence band out of the water
  EXPECT_NEAR(m.state().velocity.z(), 0.0, 1e-3);
  // Full heave thrust upward for 20 s, then released: it may lift the hull out a little, then falls back.
  cmd(2) = cmd(3) = 1.0;
  for (int k = 0; k < 2000; ++k) {
    m.step(0.01, cmd, Environment());
    highest = std::min(highest, m.state().position.z());
  }
  EXPECT_GT(highest, -0.5);
  cmd.setZero();
  for (int k = 0; k < 6000; ++k) m.step(0.01, cmd, Environment());
  EXPECT_GT(m.state().position.z(), -0.1);
  EXPECT_LT(m.state().position.z(), 0.0);
}

TEST(AuvModel, SurgeSteadyStateAndBadCommands) {
  const AuvParams p = AuvParams::girona500();
  AuvModel m(p);
  Eigen::VectorXd cmd = Eigen::VectorXd::Zero(5);
  cmd(0) = cmd(1) = -1.0;  // eq. 3.18: negative command pushes ahead
  Eigen::VectorXd cmd_depth = cmd;
  for (int k = 0; k < 6000; ++k) m.step(0.01, cmd, Environment());
  const double u = m.state().velocity.x(), x_force = m.tau()(0);
  EXPECT_NEAR(x_force, 2 * 51.5, 1e-9);
  EXPECT_NEAR(x_force, std::abs(p.X_u) * u + std::abs(p.X_uu) * u * u, 1e-6);
  EXPECT_FALSE(m.setCommand(Eigen::VectorXd::Zero(4)));
  Eigen::VectorXd bad = cmd;
  bad(3) = std::nan("");
  EXPECT_FALSE(m.setCommand(bad));
  EXPECT_EQ(m.counters().get("rejected_commands"), 2u);
  EXPECT_DOUBLE_EQ(m.command()(0), -1.0);
}

TEST(Environment, DeterministicForASeedAndIrregular) {
  EnvironmentParams p = loadEnvironmentParams("config/models/environment_lake.yaml");
  const Environment a(p), b(p);
  p.seed = 99;
  const Environment c(p);
  bool differs = false;
  VehicleState s;
  for (double t = 0; t < 600; t += 7.3) {
    EXPECT_EQ(a.current(t), b.current(t));
    EXPECT_EQ(a.wind(t), b.wind(t));
    EXPECT_EQ(a.wave(t, s, Hull()).pitch, b.wave(t, s, Hull()).pitch);
    differs |= (a.current(t) - c.current(t)).norm() > 1e-6;
    EXPECT_LE((a.current(t) - Eigen::Vector3d(-38.0 / 300.0, 0.0, 0)).norm(), 0.05 + 1e-12);
  }
  EXPECT_TRUE(differs);
  p.wave_period = 0.1;  // below the table's 0.5 s
  EXPECT_THROW(Environment{p}, ConfigError);
}

// Statistics over a long record: mean and 1-sigma of a signal sampled every dt.
struct Stats {
  double mean = 0, sd = 0;
};
Stats stats(double t1, double dt, const std::function<double(double)>& f) {
  double s = 0, s2 = 0;
  int n = 0;
  for (double t = 0; t < t1; t += dt, ++n) {
    const double v = f(t);
    s += v;
    s2 += v * v;
  }
  return {s / n, std::sqrt(std::max(0.0, s2 / n - (s / n) * (s / n)))};
}

TEST(Environment, GustsHaveTheirSigmaAndWavesTheirSignificantHeight) {
  EnvironmentParams p;
  p.wind_speed = 6.7;
  p.wind_gust = 0.67;
  p.wave_height = 1.0;
  p.wave_period = 5.0;
  const Environment env(p);
  const Stats wind = stats(20000, 0.5, [&](double t) { return env.windSpeed(t); });
  EXPECT_NEAR(wind.mean, 6.7, 0.1);
  EXPECT_NEAR(wind.sd, 0.67, 0.15);
  // 4 sigma of the elevation is Hs; irregular: it does not repeat after a peak period
  const Stats eta = stats(4000, 0.1, [&](double t) { return env.elevation(t, Eigen::Vector2d(10, 20)); });
  EXPECT_NEAR(4 * eta.sd, 1.0, 0.1);
  EXPECT_NEAR(eta.mean, 0.0, 0.02);
  EXPECT_GT(std::abs(env.elevation(100.0, {0, 0}) - env.elevation(105.0, {0, 0})), 1e-3);
}


TEST(Environment, ASurfaceSectionIsTheElevationWithinItsStatedError) {
  EnvironmentParams p;
  p.wave_height = 1.2;
  p.wave_period = 3.0;  // short waves: the shortest component about 2.3 m long
  p.wave_direction = 0.7;
  const Environment env(p);
  const Eigen::Vector2d centre(30.0, -12.0);
  const SurfaceSection s = env.section(250.0, centre, 64.0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-64.0, 64.0);
  double worst = 0.0;
  for (int i = 0; i < 5000; ++i) {
    const Eigen::Vector2d q = centre + Eigen::Vector2d(u(rng), u(rng)) * 0.7;
    worst = std::max(worst, std::abs(s(q) - env.elevation(250.0, q)));
  }
  EXPECT_LT(worst, 0.0025 * 1.2);  // the stated 0.25 % of Hs
  EXPECT_GT(worst, 0.0);  // interpolated, not the exact sum
  // off the section: exact
  const Eigen::Vector2d far = centre + Eigen::Vector2d(500.0, 0.0);
  EXPECT_EQ(s(far), env.elevation(250.0, far));
  EXPECT_EQ(Environment().section(1.0, centre, 10.0)(centre), 0.0);  // calm
}
TEST(Environment, SeaStatesFromTheFieldDayAndBeaufort4) {
  // Remote Sensing 2020, section 5: 30 m^3/s southward through the estuary's 300 m^2, 3.7 m/s from SSW
  const EnvironmentParams f = seaState("field_day");
  EXPECT_NEAR(f.current_north, -0.1, 1e-12);
  EXPECT_NEAR(f.current_east, 0.0, 1e-12);
  EXPECT_NEAR(f.wind_speed, 3.7, 1e-12);
  EXPECT_NEAR(rad2deg(f.wind_direction), 202.5, 1e-9);
  EXPECT_NEAR(seaState("field_day_auv").current_north, -38.0 / 300.0, 1e-12);
  // a fetch-limited lake chop: centimetres, about a second
  EXPECT_NEAR(f.wave_height, 0.066, 0.005);
  EXPECT_NEAR(f.wave_period, 0.82, 0.05);
  // Beaufort 4 fully developed: the WMO's probable height of 1 m, Tp 5 s
  const EnvironmentParams m = seaState("moderate");
  EXPECT_NEAR(m.wave_height, 1.0, 0.05);
  EXPECT_NEAR(m.wave_period, 5.0, 0.1);
  EXPECT_NEAR(std::hypot(m.current_north, m.current_east), 0.2, 0.01);
  EXPECT_EQ(seaState("calm").wave_height, 0.0);
  EXPECT_THROW(seaState("storm"), ConfigError);
  // limits: the fetch-limited sea grows to the fully developed one, never past it
  EXPECT_LT(fetchLimitedSea(6.7, 1e4).height, fetchLimitedSea(6.7, 1e9).height);
  EXPECT_LT(fetchLimitedSea(6.7, 1e12).height, 1.5 * fullyDevelopedSea(6.7).height);
  EXPECT_NEAR(whitecapFraction(6.7), 0.0025, 0.0003);
  // a preset with keys overriding it
  const EnvironmentParams o = environmentParamsFromYaml("sea_state: moderate\nwind: {speed: 3.0}\n", "e.yaml");
  EXPECT_EQ(o.wind_speed, 3.0);
  EXPECT_EQ(o.wave_height, m.wave_height);
  // the wind's sea over a fetch (what a campaign draws): the field day's wind over its 1.5 km is its chop, from the
  // wind's direction unless the file says otherwise; a breath of wind makes no waves; height and fetch together
  // are refused
  const EnvironmentParams w =
      environmentParamsFromYaml("wind: {speed: 3.7, direction_deg: 202.5}\nwaves: {fetch: 1500}\n", "e.yaml");
  EXPECT_NEAR(w.wave_height, f.wave_height, 1e-12);
  EXPECT_NEAR(w.wave_period, f.wave_period, 1e-12);
  EXPECT_NEAR(rad2deg(w.wave_direction), 202.5, 1e-9);
  EXPECT_NEAR(rad2deg(environmentParamsFromYaml("sea_state: moderate\nwaves: {fetch: 1e6, direction_deg: 90}\n",
                                                "e.yaml").wave_direction), 90.0, 1e-9);
  EXPECT_EQ(environmentParamsFromYaml("wind: {speed: 0.5}\nwaves: {fetch: 1000}\n", "e.yaml").wave_height, 0.0);
  EXPECT_THROW(environmentParamsFromYaml("wind: {speed: 5}\nwaves: {fetch: 1000, height: 0.3}\n", "e.yaml"),
               ConfigError);
}

TEST(Environment, TheHullFollowsLongWavesAndAveragesShortOnes) {
  EnvironmentParams p;
  p.wave_height = 1.0;
  p.wave_period = 5.0;  // lambda 39 m
  p.wave_direction = M_PI / 2;  // from the east: beam seas for a hull heading north
  const Environment env(p);
  VehicleState s;
  const Hull small{1.0, 0.5, 0.2}, usv{8.0, 2.5, 0.5};
  const double heave = stats(3000, 0.1, [&](double t) { return env.wave(t, s, small).displacement.z(); }).sd;
  EXPECT_NEAR(4 * heave, 1.0, 0.12);  // a small hull heaves with the surface
  const double roll = stats(3000, 0.1, [&](double t) { return env.wave(t, s, usv).roll; }).sd;
  const double pitch = stats(3000, 0.1, [&](double t) { return env.wave(t, s, usv).pitch; }).sd;
  EXPECT_GT(roll, deg2rad(2.0));  // beam seas roll it (the slope of 1 m, 39 m waves: about 4 deg peak)
  EXPECT_LT(pitch, 0.02 * roll);  // and do not pitch it
  // head seas of a lake chop, 0.1 m and 1.2 s (lambda 2.2 m) on the 8 m hull: nearly nothing
  p.wave_height = 0.1;
  p.wave_period = 1.2;
  p.wave_direction = 0.0;
  const Environment chop(p);
  const double small_pitch = stats(300, 0.02, [&](double t) { return chop.wave(t, s, usv).pitch; }).sd;
  EXPECT_LT(small_pitch, deg2rad(0.5));
  // below the surface the motion decays as exp(-k z)
  s.position.z() = 10.0;
  EXPECT_LT(stats(3000, 0.1, [&](double t) { return env.wave(t, s, small).displacement.z(); }).sd, 0.3 * heave);
}

TEST(Environment, DriftForceAlongTheWavesLargestBeamOn) {
  EnvironmentParams p;
  p.wave_height = 1.0;
  p.wave_period = 5.0;
  p.wave_direction = 0.0;  // from the north: pushing south
  const Environment env(p);
  const Hull usv{8.0, 2.5, 0.5};
  const Eigen::Vector2d head = env.driftForce(0.0, usv), beam = env.driftForce(M_PI / 2, usv);
  EXPECT_LT(head.x(), 0.0);
  EXPECT_NEAR(head.y(), 0.0, 1e-9);
  // beam on: more width facing the waves, and a width less small against their length (Havelock)
  EXPECT_GT(beam.x() / head.x(), 8.0 / 2.5);
  // a 0.5 m body, small against the 39 m waves, lets them pass round it: per metre of width, a few % of the beam-on hull
  EXPECT_LT(env.driftForce(0.0, Hull{0.5, 0.5, 0.5}).norm() / 0.5, 0.05 * beam.norm() / 8.0);
  // quadratic in the height; long waves pass under a shallow draft
  p.wave_height = 2.0;
  EXPECT_NEAR(Environment(p).driftForce(0.0, usv).x() / head.x(), 4.0, 1e-9);
  EXPECT_LT(env.driftForce(0.0, Hull{8.0, 2.5, 0.1}).norm(), 0.3 * head.norm());
  EXPECT_EQ(Environment().driftForce(0.0, usv).norm(), 0.0);
}

TEST(Blocks, TransferFunctionAndLookups) {
  TransferFunction tf("tf", {2.0}, {3.0, 1.0});
  EXPECT_DOUBLE_EQ(tf.dcGain(), 2.0);
  double y = 0;
  for (int k = 0; k < 30; ++k) y = tf.step(0.1, 1.0);
  EXPECT_NEAR(y, 2.0 * (1 - std::exp(-1.0)), 1e-12);
  EXPECT_THROW(TransferFunction("bad", {1, 2, 3}, {1, 2}), ConfigError);
  EXPECT_THROW(TransferFunction("integrator", {1}, {1, 0}), ConfigError);
  const Lookup1D l("l", {0, 1, 2}, {0, 10, 0});
  EXPECT_DOUBLE_EQ(l(0.5), 5.0);
  EXPECT_DOUBLE_EQ(l(-3), 0.0);
  EXPECT_THROW(Lookup1D("unsorted", {0, 2, 1}, {0, 1, 2}), ConfigError);
  // NaN looks up NaN (it used to index past the table: a heap overflow found under AddressSanitizer).
  EXPECT_TRUE(std::isnan(l(NAN)));
  const Lookup2D l2("l2", {0, 1}, {0, 1}, {0, 1, 2, 3});
  EXPECT_DOUBLE_EQ(l2(0.5, 0.5), 1.5);
  EXPECT_TRUE(std::isnan(l2(NAN, 0.5)));
  EXPECT_TRUE(std::isnan(l2(0.5, NAN)));
  TransportDelay d(0.3);
  EXPECT_DOUBLE_EQ(d.push(0.0, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(d.push(0.2, 2.0), 0.0);
  EXPECT_DOUBLE_EQ(d.push(0.3, 3.0), 1.0);
  EXPECT_DOUBLE_EQ(d.push(0.55, 3.0), 2.0);
  EXPECT_EQ(substeps(0.1, 0.02), 5);
  EXPECT_EQ(substeps(0.01, 0.02), 1);
}

TEST(ParamsYaml, ConfigFilesLoadAndBadValuesAreNamed) {
  EXPECT_NO_THROW(loadUsvParams("config/models/usv.yaml"));
  EXPECT_NO_THROW(loadAuvParams("config/models/acolor.yaml"));
  EXPECT_NO_THROW(loadEnvironmentParams("config/models/environment_calm.yaml"));
  auto message = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const ConfigError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string girona = "type: girona500\nmass: 180\nvolume: 0.1837\nI_z: 40.7\nX_u: 21.75\nX_udot: -250\n"
                             "X_uu: 216\nY_v: 6.2\nY_vdot: -581\nY_vv: 485\nZ_w: 92\nZ_wdot: -471\nZ_ww: 189\n"
                             "N_r: 15.5\nN_rdot: -44\nN_rr: 69\nmax_step: 0.02\n"
                             "thrusters:\n  - {position: [0, 0, 0], direction: [1, 0, 0]}\n";
  EXPECT_NO_THROW(auvParamsFromYaml(girona, "g.yaml"));
  std::string missing = girona;
  missing.replace(missing.find("Z_w: 92\n"), 8, "");
  EXPECT_EQ(message([&] { auvParamsFromYaml(missing, "g.yaml"); }), "g.yaml: parameter 'Z_w' is missing");
  std::string range = girona;
  range.replace(range.find("mass: 180"), 9, "mass: -5");
  EXPECT_NE(message([&] { auvParamsFromYaml(range, "g.yaml"); }).find("'mass' = -5 is out of range"),
            std::string::npos);
  EXPECT_NE(message([&] { auvParamsFromYaml(girona + "Z_wwdot: 1\n", "g.yaml"); }).find("'Z_wwdot' is not a known"),
            std::string::npos);
  std::string dir = girona;
  dir.replace(dir.find("direction: [1, 0, 0]"), 20, "direction: [1, 1, 0]");
  EXPECT_NE(message([&] { auvParamsFromYaml(dir, "g.yaml"); }).find("thrusters[0]/direction"), std::string::npos);
  EXPECT_NE(message([] { loadUsvParams("/nonexistent.yaml"); }).find("cannot open"), std::string::npos);
  EXPECT_NE(message([] { environmentParamsFromYaml("waves: {period: 0.1}\n", "e.yaml"); }).find("waves/period"),
            std::string::npos);
  EXPECT_NE(message([] { environmentParamsFromYaml("waves: {frequency: 0.3}\n", "e.yaml"); }).find("waves.frequency"),
            std::string::npos);
  EXPECT_NE(message([] { environmentParamsFromYaml("sea_state: storm\n", "e.yaml"); }).find("moderate"),
            std::string::npos);
  EXPECT_NE(message([] { usvParamsFromYaml("model: nomoto\n", "u.yaml"); }).find("'mass' is missing"),
            std::string::npos);
}

TEST(UsvModel, WindPushesDownwindAndWavesOnlyShowInTheReportedState) {
  EnvironmentParams ep;
  ep.wind_speed = 10.0;
  ep.wind_direction = M_PI / 2;  // from the east: the air moves west
  ep.wave_height = 1.0;
  ep.wave_period = 5.0;
  ep.wave_direction = M_PI / 4;  // oblique seas: heave, roll, pitch and yaw
  const Environment env(ep);
  UsvModel m(usvParams());
  double max_yaw = 0, max_roll = 0, max_pitch = 0, max_heave = 0;
  for (int k = 0; k < 12000; ++k) {
    m.step(0.01, UsvCommand{}, env);
    max_yaw = std::max(max_yaw, std::abs(angleDiff(m.state().yaw, m.lowFrequencyState().yaw)));
    max_roll = std::max(max_roll, std::abs(m.state().roll));
    max_pitch = std::max(max_pitch, std::abs(m.state().pitch));
    max_heave = std::max(max_heave, std::abs(m.state().position.z()));
    ASSERT_EQ(m.lowFrequencyState().roll, 0.0);  // the 3-DOF model itself never rolls
  }
  EXPECT_LT(m.lowFrequencyState().position.y(), -1.0);  // drifted west
  EXPECT_GT(m.tauWind().norm(), 0.0);
  EXPECT_GT(m.waveDrift().norm(), 50.0);  // and the waves push it too
  EXPECT_GT(max_yaw, deg2rad(0.5));
  EXPECT_GT(max_roll, deg2rad(1.0));
  EXPECT_GT(max_pitch, deg2rad(1.0));
  EXPECT_GT(max_heave, 0.3);
  EXPECT_TRUE(isFinite(m.state()));
}

TEST(UsvModel, TheWaveDriftForceCarriesItDownWave) {
  EnvironmentParams ep;
  ep.wave_height = 1.0;
  ep.wave_period = 5.0;
  ep.wave_direction = 0.0;  // from the north
  const Environment env(ep);
  UsvModel m(usvParams());
  for (int k = 0; k < 12000; ++k) m.step(0.01, UsvCommand{}, env);
  EXPECT_LT(m.lowFrequencyState().position.x(), -3.0);  // 120 s later, well south
  EXPECT_NEAR(m.lowFrequencyState().position.y(), 0.0, 0.5);
}

TEST(AuvModel, WavesMoveASubmergedAuvLittleAndDoNotDriftIt) {
  EnvironmentParams ep;
  ep.wave_height = 1.0;
  ep.wave_period = 5.0;
  const Environment env(ep);
  AuvModel deep(AuvParams::girona500()), surfaced(AuvParams::girona500());
  VehicleState s;
  s.position.z() = 3.0;
  deep.reset(s);
  surfaced.reset(VehicleState());
  const Eigen::VectorXd hold = Eigen::VectorXd::Zero(deep.thrusters());
  double max_heave = 0;
  for (int k = 0; k < 100; ++k) {
    deep.step(0.01, hold, env);
    surfaced.step(0.01, hold, env);
    max_heave = std::max(max_heave, std::abs(deep.state().position.z() - deep.lowFrequencyState().position.z()));
  }
  EXPECT_EQ(deep.waveDrift().norm(), 0.0);
  EXPECT_GT(surfaced.waveDrift().norm(), 1.0);
  EXPECT_LT(max_heave, 0.5);
}

TEST(AuvModel, InverseCurveRoundTrips) {
  for (const AuvParams& p : {AuvParams::girona500(), AuvParams::aColor()}) {
    AuvModel m(p);
    for (int i = 0; i < m.thrusters(); ++i) {
      for (double f : {-39.0, -20.0, -1.0, 0.5, 10.0, 40.0}) {  // within every curve
        const double c = m.commandFor(i, f);
        EXPECT_NEAR(m.thrust(i, c), f, 1e-9) << "thruster " << i << " f " << f;
      }
      EXPECT_DOUBLE_EQ(m.commandFor(i, 0.0), 0.0);
      EXPECT_DOUBLE_EQ(std::abs(m.commandFor(i, 1e4)), 1.0);  // saturated
      EXPECT_DOUBLE_EQ(m.commandFor(i, NAN), 0.0);
    }
  }
}

// Positioning (mounting, pose at the time of the fix, quality gates) and the beacon simulator's protocol timing.
#include <gtest/gtest.h>

#include <cmath>

#include "offshore_gnc/common/angles.h"
#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/usbl/beacon_sim.h"
#include "offshore_gnc/usbl/positioning.h"

using namespace offshore_gnc;
using namespace offshore_gnc::usbl;

namespace {
Eigen::Quaterniond yawQ(double yaw) { return Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ())); }
BeaconSimConfig noiseless() {
  BeaconSimConfig c;
  c.range_sigma = 0;
  c.angle_sigma = 0;
  c.dropout_probability = 0;
  c.sound_speed_error = 0;  // the field's effects off (their statistics: test_beacon_sim.cpp)
  c.multipath_probability = 0;
  c.burst_probability = 0;
  c.mount.offset = {1.5, -0.4, 0.8};
  c.mount.yaw = deg2rad(20);
  c.mount.pitch = deg2rad(3);
  return c;
}
}  // namespace

TEST(UsblGeometry, RangeAnglesRoundTripAndConventions) {
  double r, az, el;
  toRangeAngles({0, 10, 0}, r, az, el);  // starboard: azimuth 90 deg clockwise
  EXPECT_NEAR(az, kPi / 2, 1e-12);
  toRangeAngles({10, 0, 10}, r, az, el);  // below: negative elevation
  EXPECT_NEAR(el, -kPi / 4, 1e-12);
  const Eigen::Vector3d v(-3, 4, 12);
  toRangeAngles(v, r, az, el);
  EXPECT_NEAR(r, 13, 1e-12);
  EXPECT_LT((fromRangeAngles(r, az, el) - v).norm(), 1e-9);
}

TEST(UsblGeometry, EnuFluToNedFrd) {
  // ROS yaw 0 (facing east) is NED heading 90 deg.
  const Eigen::Quaterniond q = enuFluToNedFrd(Eigen::Quaterniond::Identity());
  EXPECT_LT((q * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(), 1e-12);
  EXPECT_LT((q * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ()).norm(), 1e-12);
}

TEST(UsblPositioner, RecoversTheSimulatedBeaconThroughMountingAndHeading) {
  const BeaconSimConfig cfg = noiseless();
  BeaconSimulator sim(cfg);
  Positioner pos(cfg.mount, QualityLimits{});
  Pose usv;
  usv.ned = {100, -50, 0};
  usv.q = yawQ(deg2rad(135));
  pos.addUsvPosition(9.5, usv.ned);
  pos.addUsvPosition(10.5, usv.ned);
  pos.addUsvAttitude(9.5, usv.q);
  pos.addUsvAttitude(10.5, usv.q);
  for (const Eigen::Vector3d& auv : {Eigen::Vector3d(160, -20, 25), Eigen::Vector3d(20, -90, 5), Eigen::Vector3d(101, -49, 40)}) {
    const AcoFix f = sim.makeFix(usv, auv, MSG_RESPU);
    const FixResult r = pos.process(f, 10.0, 10.0);
    ASSERT_EQ(r.quality, Q_OK);
    ASSERT_TRUE(r.ned);
    // Wire quantisation: 0.1 m range, 0.1 deg angles -> about 0.2 % of the range.
    EXPECT_LT((*r.ned - auv).norm(), 0.05 + 0.003 * (auv - usv.ned).norm()) << r.ned->transpose();
    ASSERT_TRUE(r.local);
    // ACOFIX POSITION: north/east from the transceiver, depth absolute.
    const Eigen::Vector3d xcvr = usv.ned + usv.q * cfg.mount.offset;
    EXPECT_LT((r.local->head<2>() - (auv - xcvr).head<2>()).norm(), 0.1 + 0.003 * (auv - xcvr).norm());
    EXPECT_NEAR(r.local->z(), auv.z(), 0.1 + 0.003 * (auv - xcvr).norm());
    EXPECT_NEAR(r.stamp, 10.0 - f.rangeTimeS(), 1e-9);
  }
  EXPECT_EQ(pos.counters().get("accepted"), 3u);
}

// The transceiver's velocity of sound 15 m/s off (1 % long ranges, 1.5 m at 150 m): with the water's measured one
// (water_sound_speed) the positioning takes the range from the travel time instead and the fix is where the beacon is.
TEST(UsblPositioner, RangesFromTheTravelTimeWithTheWatersVelocityOfSound) {
  BeaconSimConfig cfg = noiseless();
  cfg.sound_speed = 1480.0;
  cfg.sound_speed_error = 15.0;
  BeaconSimulator sim(cfg);
  QualityLimits timed;
  timed.water_sound_speed = 1480.0;
  Positioner as_reported(cfg.mount, QualityLimits{}), from_time(cfg.mount, timed);
  Pose usv;
  usv.q = yawQ(deg2rad(30));
  for (Positioner* p : {&as_reported, &from_time}) {
    p->addUsvPosition(9.5, usv.ned);
    p->addUsvPosition(10.5, usv.ned);
    p->addUsvAttitude(9.5, usv.q);
    p->addUsvAttitude(10.5, usv.q);
  }
  const Eigen::Vector3d auv(120, 85, 20);
  const AcoFix f = sim.makeFix(usv, auv, MSG_RESPU);
  const FixResult off = as_reported.process(f, 10.0, 10.0), on = from_time.process(f, 10.0, 10.0);
  ASSERT_TRUE(off.ned && on.ned);
  const double range = (auv - usv.ned - usv.q * cfg.mount.offset).norm();
  EXPECT_NEAR((*off.ned - auv).norm(), range * 15.0 / 1480.0, 0.3);
  EXPECT_LT((*on.ned - auv).norm(), 0.05 + 0.003 * range);
  QualityLimits bad;
  bad.water_sound_speed = 2000.0;
  EXPECT_THROW(Positioner(cfg.mount, bad), ConfigError);
}

// Relayed samples may come out of order (datagrams): a late one takes its place instead of emptying the buffer (it
// did: with the simulated radio's jitter every fifth USV GPS message came late and a tenth of the fixes went
// stale). A clock gone back by seconds (a bag loop) still starts the buffer again.
TEST(UsblTimedBuffer, ALateSampleTakesItsPlaceAClockGoneBackStartsAgain) {
  TimedBuffer<double> b;
  const auto lerp = [](double a, double c, double s) { return a + s * (c - a); };
  for (const double t : {0.0, 0.1, 0.3, 0.2, 0.4}) b.add(t, 10.0 * t);  // 0.2 after 0.3
  for (const double t : {0.05, 0.15, 0.25, 0.35}) {
    ASSERT_TRUE(b.at(t, 0.15, lerp)) << t;
    EXPECT_NEAR(*b.at(t, 0.15, lerp), 10.0 * t, 1e-12) << t;
  }
  b.add(0.0, 7.0);  // older than the newest by 0.4 s: a late sample at the front
  EXPECT_DOUBLE_EQ(b.lastTime(), 0.4);
  b.add(-10.0, -1.0);  // 10 s back: the clock went back
  EXPECT_DOUBLE_EQ(b.lastTime(), -10.0);
  EXPECT_FALSE(b.at(0.2, 0.15, lerp));
}

TEST(UsblPositioner, UsesThePoseAtTheTimeOfTheFixNotTheLatest) {
  const BeaconSimConfig cfg = noiseless();
  BeaconSimulator sim(cfg);
  Positioner pos(cfg.mount, QualityLimits{});
  // USV moving north at 2 m/s and turning at 5 deg/s; samples at 10 Hz up to t = 20 s.
  auto usvAt = [](double t) {
    Pose p;
    p.ned = {2.0 * t, 0, 0};
    p.q = yawQ(deg2rad(5.0 * t));
    return p;
  };
  for (double t = 0; t <= 20.0001; t += 0.1) {
    pos.addUsvPosition(t, usvAt(t).ned);
    pos.addUsvAttitude(t, usvAt(t).q);
  }
  const Eigen::Vector3d auv(40, 60, 20);
  const double t_fix = 12.34;  // between samples
  const FixResult r = pos.process(sim.makeFix(usvAt(t_fix), auv, MSG_RESPU), t_fix, t_fix + 0.1);
  ASSERT_EQ(r.quality, Q_OK);
  EXPECT_LT((*r.ned - auv).norm(), 0.4);
  // With the latest pose instead the error would be metres: the buffer matters.
  Positioner latest(cfg.mount, QualityLimits{});
  latest.addUsvPosition(20, usvAt(20).ned);
  latest.addUsvAttitude(20, usvAt(20).q);
  const FixResult wrong = latest.process(sim.makeFix(usvAt(t_fix), auv, MSG_RESPU), 20, 20);
  EXPECT_GT((*wrong.ned - auv).norm(), 10.0);
}

TEST(UsblPositioner, QualityGatesEachCounted) {
  const BeaconSimConfig cfg = noiseless();
  BeaconSimulator sim(cfg);
  QualityLimits lim;
  Positioner pos(cfg.mount, lim);
  Pose usv;
  for (double t = 0; t <= 10; t += 0.5) {
    pos.addUsvPosition(t, usv.ned);
    pos.addUsvAttitude(t, usv.q);
    pos.addRemoteDepth(t, 20.0);
  }
  const Eigen::Vector3d auv(30, 10, 20);
  const AcoFix good = sim.makeFix(usv, auv, MSG_RESPU);
  EXPECT_EQ(pos.process(good, 5, 5).quality, Q_OK);
  AcoFix filt = good;
  filt.flags |= AcoFix::FILTER_ERROR;
  EXPECT_EQ(pos.process(filt, 5, 5).quality, Q_FILTER_ERROR);
  AcoFix fit = good;
  fit.fit_error = static_cast<std::int16_t>(lim.max_fit_error * 100 + 1);
  EXPECT_EQ(pos.process(fit, 5, 5).quality, Q_FIT_ERROR);
  EXPECT_EQ(pos.process(good, 5, 5 + lim.max_age_s + 0.5).quality, Q_STALE);  // processed too late
  EXPECT_EQ(pos.process(good, 30, 30).quality, Q_STALE);                     // no USV pose near the fix
  const AcoFix deep = sim.makeFix(usv, Eigen::Vector3d(30, 10, 20 + lim.max_depth_error_m + 1), MSG_RESPU);
  EXPECT_EQ(pos.process(deep, 5, 5).quality, Q_DEPTH);
  AcoFix range_only = good;
  range_only.flags = AcoFix::RANGE;
  EXPECT_EQ(pos.process(range_only, 5, 5).quality, Q_NO_POSITION);
  const auto& c = pos.counters();
  for (const char* k : {"accepted", "rejected_filter_error", "rejected_fit_error", "rejected_depth", "rejected_no_position"})
    EXPECT_EQ(c.get(k), 1u) << k;
  EXPECT_EQ(c.get("rejected_stale"), 2u);
}

TEST(UsblPositioner, InvalidLimitsAreRefusedByName) {
  QualityLimits lim;
  lim.max_fit_error = -1;
  try {
    Positioner p(Mounting{}, lim);
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("max_fit_error"), std::string::npos);
  }
}

TEST(BeaconSim, AcknowledgesThenRepliesAfterTheTwoWayDelay) {
  BeaconSimConfig cfg = noiseless();
  BeaconSimulator sim(cfg);
  Pose usv;
  const Eigen::Vector3d auv(300, 400, 0);
  const double range = transceiverRange(cfg.mount, usv, auv);
  sim.setCurrentRange(range);
  const Message ping{true, PingSend{2, MSG_REQU}};
  StreamDecoder dec;
  std::vector<StreamDecoder::Event> ev;
  dec.feed(sim.handle(ping, 100.0), ev);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_TRUE(std::get<StatusReply>(ev[0].message->body) == (StatusReply{CID_PING_SEND, kStatusOk, 2}));
  // Busy until the reply: a second ping is refused.
  ev.clear();
  dec.feed(sim.handle(ping, 100.01), ev);
  EXPECT_NE(std::get<StatusReply>(ev[0].message->body).status, kStatusOk);
  const double due = 100.0 + 2 * range / cfg.sound_speed;
  EXPECT_EQ(sim.poll(due - 1e-3, usv, auv), "");
  ev.clear();
  dec.feed(sim.poll(due + 1e-3, usv, auv), ev);
  ASSERT_EQ(ev.size(), 1u);
  const auto& f = std::get<FixMessage>(ev[0].message->body).fix;
  EXPECT_EQ(f.src_id, 2);
  EXPECT_EQ(f.msg_type, MSG_RESPU);
  EXPECT_NEAR(f.rangeM(), range, 0.051);
  EXPECT_NEAR(f.rangeTimeS(), range / cfg.sound_speed, 1e-6);
  EXPECT_NEAR(f.vos * 0.1, cfg.sound_speed, 1e-9);
}

TEST(BeaconSim, DropoutsAndOutOfRangeGiveTimeoutErrors) {
  BeaconSimConfig cfg = noiseless();
  cfg.dropout_probability = 0.3;
  cfg.seed = 42;
  BeaconSimulator sim(cfg);
  Pose usv;
  const Eigen::Vector3d auv(50, 0, 10);
  StreamDecoder dec;
  int fixes = 0, timeouts = 0;
  for (int i = 0; i < 200; ++i) {
    const double t = i * 2.0;
    sim.setCurrentRange(i < 190 ? transceiverRange(cfg.mount, usv, auv) : 5000.0);
    std::vector<StreamDecoder::Event> ev;
    dec.feed(sim.handle(Message{true, PingSend{2, MSG_REQU}}, t), ev);
    dec.feed(sim.poll(t + cfg.timeout + 0.01, usv, auv), ev);
    for (const auto& e : ev) {
      ASSERT_TRUE(e.message);
      if (std::holds_alternative<FixMessage>(e.message->body)) ++fixes;
      if (auto s = std::get_if<StatusReply>(&e.message->body); s && s->cid == CID_PING_ERROR) {
        EXPECT_EQ(s->status, kStatusXcvrRespTimeout);
        ++timeouts;
      }
    }
  }
  EXPECT_EQ(fixes + timeouts, 200);
  EXPECT_GT(timeouts, 10 + 40);  // ~30 % of 190 plus the 10 out of range
  EXPECT_LT(timeouts, 10 + 80);
}

TEST(BeaconSim, DataRequestIsAnsweredWithTheRemoteQueue) {
  BeaconSimulator sim(noiseless());
  sim.setCurrentRange(15);
  sim.setRemoteQueue({0xCA, 0xFE});
  sim.handle(Message{true, DatSend{2, MSG_REQ, {1, 2, 3}}}, 0);
  StreamDecoder dec;
  std::vector<StreamDecoder::Event> ev;
  dec.feed(sim.poll(1.0, Pose{}, Eigen::Vector3d(15, 0, 0)), ev);
  ASSERT_EQ(ev.size(), 1u);
  const auto& d = std::get<DatReceive>(ev[0].message->body);
  EXPECT_EQ(d.data, (std::vector<std::uint8_t>{0xCA, 0xFE}));
  EXPECT_EQ(d.fix.msg_type, MSG_RESP);
}

TEST(BeaconSim, AUsblFaultTimesOutEveryPingWhileItLasts) {
  BeaconSimConfig cfg = noiseless();
  cfg.faults = FaultPlan::parse("usbl@100+60");
  BeaconSimulator sim(cfg);
  Pose usv;
  const Eigen::Vector3d auv(50, 0, 10);
  sim.setCurrentRange(transceiverRange(cfg.mount, usv, auv));
  StreamDecoder dec;
  int fixes_in = 0, fixes_out = 0, timeouts_in = 0;
  for (int i = 0; i < 100; ++i) {
    const double t = i * 2.0;
    std::vector<StreamDecoder::Event> ev;
    dec.feed(sim.handle(Message{true, PingSend{2, MSG_REQU}}, t), ev);
    dec.feed(sim.poll(t + cfg.timeout + 0.01, usv, auv), ev);
    const bool fault = t >= 100 && t < 160;
    for (const auto& e : ev) {
      if (std::holds_alternative<FixMessage>(e.message->body)) ++(fault ? fixes_in : fixes_out);
      if (auto s = std::get_if<StatusReply>(&e.message->body); s && s->cid == CID_PING_ERROR && fault) ++timeouts_in;
    }
  }
  EXPECT_EQ(fixes_in, 0);
  EXPECT_EQ(timeouts_in, 30);
  EXPECT_EQ(fixes_out, 70);  // no dropouts otherwise (noiseless)
}

TEST(UsblGeometry, APosePredictedAlongATurnStaysOnTheCircle) {
  Pose p;
  p.ned = {10, -5, 0.5};
  const double yaw0 = deg2rad(30), speed = 2.0, rate = 0.2;  // turning to starboard at 0.2 rad/s
  p.q = yawQ(yaw0);
  for (double dt : {0.1, 0.5, 1.0, -1.0}) {
    const Pose q = predictPose(p, {speed, 0, 0}, {0, 0, rate}, dt);
    const double yaw1 = yaw0 + rate * dt, radius = speed / rate;
    const Eigen::Vector3d exact = p.ned + Eigen::Vector3d(radius * (std::sin(yaw1) - std::sin(yaw0)),
                                                          -radius * (std::cos(yaw1) - std::cos(yaw0)), 0.0);
    EXPECT_LT((q.ned - exact).norm(), 2e-3 * std::abs(dt) * speed) << dt;
    EXPECT_NEAR(q.q.angularDistance(yawQ(yaw1)), 0.0, 1e-9) << dt;
  }
  const Pose still = predictPose(p, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 0.7);  // no motion: no change
  EXPECT_LT((still.ned - p.ned).norm(), 1e-12);
  EXPECT_NEAR(still.q.angularDistance(p.q), 0.0, 1e-12);
}

// The simulated radio between the masters (sim/radio.h): the ROS-free mission's channel, the same model and
// parameters as the main job's (test/py/test_sim_radio.py checks that one's statistics with the same figures).
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <optional>
#include <vector>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/sim/radio.h"

using namespace offshore_gnc;
using namespace offshore_gnc::sim;

TEST(RadioChannel, TheShippedFileIsTheDefaultsAndBadOnesAreRefused) {
  const RadioParams shipped = loadRadioParams("config/relay/radio.yaml"), d;
  for (const auto& s : RadioParams::table().specs())
    EXPECT_EQ(ParamTable<RadioParams>::text(s, shipped), ParamTable<RadioParams>::text(s, d)) << s.name;
  const std::string bad = ::testing::TempDir() + "radio_bad.yaml";
  std::ofstream(bad) << "loss: 2\n";
  EXPECT_THROW(loadRadioParams(bad), ConfigError);
  RadioParams p;
  p.loss_burst = 0.5;
  EXPECT_THROW(RadioChannel(p, 1), ConfigError);
}

// Datagrams every 10 ms (never queued): lost at the mean rate, in runs of loss_burst on average.
TEST(RadioChannel, LossesComeInBurstsAtTheMeanRate) {
  RadioChannel ch(RadioParams{}, 4);
  std::vector<int> runs;
  int run = 0, lost = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const bool l = !ch.schedule(0.01 * i, 100, false);
    lost += l;
    if (l) {
      ++run;
    } else if (run) {
      runs.push_back(run);
      run = 0;
    }
  }
  EXPECT_NEAR(static_cast<double>(lost) / n, 0.02, 0.003);
  double mean_run = 0.0;
  for (int r : runs) mean_run += static_cast<double>(r) / runs.size();
  EXPECT_NEAR(mean_run, 3.0, 0.3);
  EXPECT_EQ(ch.stats().lost, static_cast<std::size_t>(lost));
}

TEST(RadioChannel, DelayRateAndOrder) {
  RadioParams p;
  p.loss = 0.0;
  RadioChannel alone(p, 1);
  double mean_delay = 0.0, min_delay = 1e9;
  const int n = 5000;
  for (int i = 0; i < n; ++i) {
    const double d = *alone.schedule(10.0 * i, 100, false) - 10.0 * i;
    mean_delay += d / n;
    min_delay = std::min(min_delay, d);
  }
  // one packet alone: its time on the air (128 bytes at 2 Mbit/s) + latency + exponential jitter
  const double air = 128 * 8 / 2e6;
  EXPECT_NEAR(mean_delay, air + 0.01 + 0.005, 0.0005);
  EXPECT_GE(min_delay, air + 0.01);
  // datagrams handed over together arrive in the order they were sent: the jitter delays, never reorders
  double last = 0.0;
  for (int i = 0; i < 200; ++i) {
    const double d = *alone.schedule(1e6, 100, false);
    EXPECT_GE(d, last);
    last = d;
  }
  // a burst of 1000 reliable segments queues at the channel's rate and arrives in order, none lost
  p.loss = 0.1;
  RadioChannel burst(p, 2);
  std::vector<double> due;
  for (int i = 0; i < 1000; ++i) {
    const std::optional<double> d = burst.schedule(0.0, 1448, true);
    ASSERT_TRUE(d.has_value());
    if (!due.empty()) {
      EXPECT_GE(*d, due.back());
    }
    due.push_back(*d);
  }
  EXPECT_NEAR(due.back(), 1000 * 1500 * 8 / 2e6, 0.25);  // the rate, plus a retransmission at most
  EXPECT_GT(burst.stats().retransmitted, 50u);
  // datagrams that would wait longer than `queue` for the channel are dropped
  p.loss = 0.0;
  p.bandwidth = 1e4;
  RadioChannel slow(p, 1);
  int dropped = 0;
  for (int i = 0; i < 20; ++i) dropped += !slow.schedule(0.0, 1000, false);
  EXPECT_GT(dropped, 10);
  EXPECT_EQ(slow.stats().dropped_queue, static_cast<std::size_t>(dropped));
}

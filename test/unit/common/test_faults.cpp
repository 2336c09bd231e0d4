// The fault plan of the simulators' fault injection: its syntax, its errors, its time windows.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "offshore_gnc/common/faults.h"

using namespace offshore_gnc;

TEST(FaultPlan, ParsesStartsDurationsAndSeparators) {
  const FaultPlan p = FaultPlan::parse("usbl@150+60, gps@200.5+10  lidar@30");
  ASSERT_EQ(p.faults().size(), 3u);
  EXPECT_EQ(p.faults()[0].name, "usbl");
  EXPECT_DOUBLE_EQ(p.faults()[0].start, 150.0);
  EXPECT_DOUBLE_EQ(p.faults()[0].end, 210.0);
  EXPECT_DOUBLE_EQ(p.faults()[1].start, 200.5);
  EXPECT_TRUE(std::isinf(p.faults()[2].end));  // no duration: to the end of the run
  // [start, end): active from its start, over at its end
  EXPECT_FALSE(p.active("usbl", 149.99));
  EXPECT_TRUE(p.active("usbl", 150.0));
  EXPECT_TRUE(p.active("usbl", 209.99));
  EXPECT_FALSE(p.active("usbl", 210.0));
  EXPECT_TRUE(p.active("lidar", 1e6));
  EXPECT_FALSE(p.active("sonar", 200.0));  // not planned
  EXPECT_TRUE(FaultPlan::parse("").empty());
  EXPECT_TRUE(FaultPlan::parse("  , ").empty());
}

TEST(FaultPlan, EachVehicleGetsItsOwnFaults) {
  const FaultPlan p = FaultPlan::parse("gps@10+5 usbl@20+5 lidar@30+5 depth@40+5");
  const FaultPlan usv = p.of("usv"), auv = p.of("auv");
  ASSERT_EQ(usv.faults().size(), 2u);
  EXPECT_EQ(usv.faults()[0].name, "gps");
  EXPECT_EQ(usv.faults()[1].name, "lidar");
  ASSERT_EQ(auv.faults().size(), 2u);
  EXPECT_TRUE(auv.active("depth", 42.0));
  EXPECT_FALSE(usv.active("depth", 42.0));
  // the radio is the job's, between the masters: no simulator injects it
  EXPECT_TRUE(FaultPlan::parse("link@5+5").of("usv").empty());
  EXPECT_TRUE(FaultPlan::parse("link@5+5").of("auv").empty());
  EXPECT_EQ(FaultPlan::parse("link@5+5").of("both").faults().size(), 1u);
  for (const auto& k : faultKinds()) {  // every kind names its vehicle and its effect
    const std::string v = k.vehicle;
    EXPECT_TRUE(v == "usv" || v == "auv" || v == "both") << k.name;
    EXPECT_GT(std::string(k.effect).size(), 10u) << k.name;
  }
}

TEST(FaultPlan, RefusesWhatMakesNoSenseNamingTheItem) {
  for (const char* bad : {"gpss@10", "gps", "gps@", "gps@ten", "gps@-5", "gps@10+0", "gps@10+-3", "gps@10+x",
                          "gps@nan", "gps@10+inf", "@10", "gps@10+5+5"}) {
    try {
      FaultPlan::parse(std::string("usbl@1+1 ") + bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const ConfigError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(std::string("'") + bad + "'"), std::string::npos) << m;
      EXPECT_NE(m.find("NAME@START_S"), std::string::npos) << m;  // says how to write it
    }
  }
}

// ParamTable: one place for a parameter's name, range, unit and doc; the struct holds the default.
#include <gtest/gtest.h>

#include <cmath>

#include "offshore_gnc/common/param_table.h"

using namespace offshore_gnc;

namespace {
struct Inner {
  double gain = 2.0;
  static const ParamTable<Inner>& table() {
    static const ParamTable<Inner> t = ParamTable<Inner>().number("gain", &Inner::gain, 0.0, 10.0, "", "a gain");
    return t;
  }
};
struct Outer {
  double speed = 1.5;
  double angle = 0.1;  // radians inside, degrees in files
  int count = 3;
  bool on = true;
  std::string mode = "a";
  std::string device;  // free text
  std::vector<double> list{1.0, 2.0};
  Inner inner;
  static const ParamTable<Outer>& table() {
    static const ParamTable<Outer> t = ParamTable<Outer>()
                                           .number("speed", &Outer::speed, 0.0, 5.0, "m/s", "speed")
                                           .degrees("angle_deg", &Outer::angle, 0.0, 90.0, "angle")
                                           .integer("count", &Outer::count, 1, 9, "count")
                                           .flag("on", &Outer::on, "switch")
                                           .choice("mode", &Outer::mode, {"a", "b"}, "mode")
                                           .string("device", &Outer::device, "any text")
                                           .numbers("list", &Outer::list, 2, -1.0, 5.0, "", "two values")
                                           .nest("inner/", &Outer::inner, Inner::table());
    return t;
  }
};
}  // namespace

TEST(ParamTable, ValidatesEveryKindAndNamesTheParameter) {
  Outer o;
  EXPECT_NO_THROW(Outer::table().validate(o, "ns/"));
  o.speed = 7.0;
  try {
    Outer::table().validate(o, "ns/");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("'ns/speed' = 7"), std::string::npos) << e.what();
  }
  o = Outer();
  o.angle = 2.0;  // 115 degrees
  EXPECT_THROW(Outer::table().validate(o), ConfigError);
  o = Outer();
  o.mode = "c";
  EXPECT_THROW(Outer::table().validate(o), ConfigError);
  o = Outer();
  o.list = {1.0};
  EXPECT_THROW(Outer::table().validate(o), ConfigError);
  o = Outer();
  o.inner.gain = NAN;
  EXPECT_THROW(Outer::table().validate(o), ConfigError);
}

TEST(ParamTable, NestedNamesAndFileText) {
  const auto* g = Outer::table().find("inner/gain");
  ASSERT_NE(g, nullptr);
  Outer o;
  g->number(o) = 4.0;
  EXPECT_DOUBLE_EQ(o.inner.gain, 4.0);
  EXPECT_EQ(ParamTable<Outer>::text(*Outer::table().find("angle_deg"), o), "5.72958");
  EXPECT_EQ(ParamTable<Outer>::text(*Outer::table().find("list"), o), "[1, 2]");
  EXPECT_EQ(ParamTable<Outer>::text(*Outer::table().find("on"), o), "true");
  EXPECT_EQ(ParamTable<Outer>::text(*Outer::table().find("device"), o), "\"\"");  // empty text as a file writes it
  Outer::table().find("device")->string(o) = "/dev/ttyUSB0";
  EXPECT_EQ(ParamTable<Outer>::text(*Outer::table().find("device"), o), "/dev/ttyUSB0");
  EXPECT_NO_THROW(Outer::table().validate(o));  // any text
  EXPECT_EQ(paramNumberText(67108864.0), "67108864");  // whole numbers in full
  EXPECT_EQ(paramNumberText(-1e6), "-1000000");
  EXPECT_EQ(paramNumberText(0.001), "0.001");
  EXPECT_EQ(paramNumberText(1e20), "1e+20");
  EXPECT_EQ(Outer::table().find("nope"), nullptr);
}

// Parameters through their tables from a list parameter's entry (an XmlRpc map, as roscpp hands it over): each key
// present replaces the struct's value, with its type and range checked and the entry named in the error.
#include <gtest/gtest.h>

#include <string>

#include "offshore_gnc/ros/params.h"

using namespace offshore_gnc;

namespace {
struct Entry {
  std::string name;
  double rate = 0.0;
  int count = 3;
  bool on = true;
  std::string mode = "a";
  static const ParamTable<Entry>& table() {
    static const ParamTable<Entry> t = ParamTable<Entry>()
                                           .string("name", &Entry::name, "text")
                                           .number("rate", &Entry::rate, 0.0, 10.0, "Hz", "a rate")
                                           .integer("count", &Entry::count, 1, 9, "a count")
                                           .flag("on", &Entry::on, "a switch")
                                           .choice("mode", &Entry::mode, {"a", "b"}, "a choice");
    return t;
  }
};

std::string error(XmlRpc::XmlRpcValue v) {
  Entry e;
  try {
    ros_util::readEntry(v, Entry::table(), e, "list[1]");
  } catch (const ConfigError& x) {
    return x.what();
  }
  return "";
}
}  // namespace

TEST(ReadEntry, FillsWhatIsPresentAndKeepsTheDefaults) {
  XmlRpc::XmlRpcValue v;
  v["name"] = std::string("/target");
  v["rate"] = 2;  // an integer where a number is asked: taken
  v["mode"] = std::string("b");
  Entry e;
  ros_util::readEntry(v, Entry::table(), e, "list[0]");
  EXPECT_EQ(e.name, "/target");
  EXPECT_DOUBLE_EQ(e.rate, 2.0);
  EXPECT_EQ(e.mode, "b");
  EXPECT_EQ(e.count, 3);
  EXPECT_TRUE(e.on);
}

TEST(ReadEntry, WrongTypesRangesAndChoicesNameTheEntry) {
  XmlRpc::XmlRpcValue v;
  v["rate"] = 11.0;
  EXPECT_NE(error(v).find("list[1]/rate"), std::string::npos) << error(v);
  XmlRpc::XmlRpcValue w;
  w["on"] = std::string("yes");
  EXPECT_NE(error(w).find("'list[1]/on' is not a boolean"), std::string::npos) << error(w);
  XmlRpc::XmlRpcValue c;
  c["mode"] = std::string("z");
  EXPECT_NE(error(c).find("mode"), std::string::npos) << error(c);
  XmlRpc::XmlRpcValue n;
  n["count"] = 2.5;
  EXPECT_NE(error(n).find("not an integer"), std::string::npos) << error(n);
  EXPECT_NE(error(XmlRpc::XmlRpcValue(3)).find("must be a map"), std::string::npos);
}

// cfg/*.cfg from the tables (param_docs --cfg): the exact doubles, the kinds a form can show, and the form's
// mistakes refused rather than written into a script the build would turn into a wrong Config.h.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "offshore_gnc/common/validate.h"
#include "offshore_gnc/docs/cfg_script.h"

using namespace offshore_gnc;

namespace {
struct A {
  double gain = 0.1, limit = M_PI / 4, angle = M_PI / 4;
  int count = 3;
  bool on = true;
  std::string mode = "x";
  static const ParamTable<A>& table() {
    static const ParamTable<A> t = ParamTable<A>()
                                       .number("pid/gain", &A::gain, 1e-4, 1e6, "1/m", "a \"gain\"")
                                       .number("limit", &A::limit, 0.0, M_PI / 2, "rad", "a limit")
                                       .degrees("angle_deg", &A::angle, 0.0, 90.0, "an angle")
                                       .integer("count", &A::count, 1, 18, "a count")
                                       .flag("on", &A::on, "switched on")
                                       .choice("mode", &A::mode, {"x", "y"}, "a mode");
    return t;
  }
};
struct B {  // another vehicle: pid/gain as A's, limit with another range
  double gain = 5.0, limit = 0.2;
  static const ParamTable<B>& table() {
    static const ParamTable<B> t = ParamTable<B>()
                                       .number("pid/gain", &B::gain, 1e-4, 1e6, "1/m", "a \"gain\"")
                                       .number("limit", &B::limit, 0.0, 1.0, "rad", "a limit");
    return t;
  }
};

std::string script(const std::vector<ReconfigureGroup>& groups, bool two_sources = false) {
  std::vector<docs::CfgSource> src{docs::cfgSource("a", A::table(), A())};
  if (two_sources) src.push_back(docs::cfgSource("b", B::table(), B()));
  return docs::cfgScript("first line\n\nthird", "node", "Form", groups, src);
}
}  // namespace

TEST(CfgScript, WritesEachKindWithTheExactDefaultAndRange) {
  const std::string s = script({{"g", {"pid/gain", "limit", "angle_deg", "count", "on"}}});
  EXPECT_EQ(s.rfind("#!/usr/bin/python3\n# first line\n#\n# third\n", 0), 0u) << s;
  EXPECT_NE(s.find("import ParameterGenerator, bool_t, double_t, int_t\n"), std::string::npos) << s;
  EXPECT_NE(s.find("g = gen.add_group(\"g\")\n"), std::string::npos) << s;
  EXPECT_NE(s.find("g.add(\"pid_gain\", double_t, 0, \"a \\\"gain\\\" [1/m]\", 0.1, 0.0001, 1000000.0)\n"),
            std::string::npos) << s;
  // pi/4 and pi/2 to the last bit: a rounded bound would differ from the range the core validates against
  EXPECT_NE(s.find("g.add(\"limit\", double_t, 0, \"a limit [rad]\", 0.7853981633974483, 0.0, 1.5707963267948966)"),
            std::string::npos) << s;
  EXPECT_NE(s.find("g.add(\"angle_deg\", double_t, 0, \"an angle [deg]\", 45.0, 0.0, 90.0)"),
            std::string::npos) << s;  // in the file's unit
  EXPECT_NE(s.find("g.add(\"count\", int_t, 0, \"a count\", 3, 1, 18)\n"), std::string::npos) << s;
  EXPECT_NE(s.find("g.add(\"on\", bool_t, 0, \"switched on\", True)\n"), std::string::npos) << s;
  EXPECT_NE(s.find("exit(gen.generate(\"offshore_gnc\", \"node\", \"Form\"))\n"), std::string::npos) << s;
}

TEST(CfgScript, SeveralSourcesTheFirstsDefaultAndWhoHasIt) {
  const std::string s = script({{"g", {"pid/gain", "on"}}}, true);
  EXPECT_NE(s.find("import ParameterGenerator, bool_t, double_t\n"), std::string::npos) << s;
  EXPECT_NE(s.find("\"a, b: a \\\"gain\\\" [1/m]\", 0.1,"), std::string::npos) << s;
  EXPECT_NE(s.find("\"a: switched on\", True)"), std::string::npos) << s;
}

TEST(CfgScript, RefusesWhatNoFormCanHold) {
  EXPECT_THROW(script({{"g", {"missing"}}}), ConfigError);
  EXPECT_THROW(script({{"g", {"on"}}, {"h", {"on"}}}), ConfigError);  // one field twice
  EXPECT_THROW(script({{"g", {"mode"}}}), ConfigError);              // a choice
  EXPECT_THROW(script({{"g", {"limit"}}}, true), ConfigError);       // a and b differ in range
  EXPECT_THROW(script({{"1g", {"on"}}}), ConfigError);               // not an identifier
  EXPECT_NO_THROW(script({{"g", {"limit"}}}));
}

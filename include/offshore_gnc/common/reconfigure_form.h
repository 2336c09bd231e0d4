#pragma once
// A nodelet's dynamic_reconfigure form, stated beside the tables it shows: which table entries, in which groups.
// cfg/<Form>.cfg is written from the form and the tables by `param_docs --cfg <Form>` (checked in; a test fails
// when it differs), so a field's name, default, range and description have one source; the ROS side
// (ros/reconfigure.h) finds each field's table entry again by cfgName.
#include <string>
#include <vector>

namespace offshore_gnc {

// A table name as a .cfg field, which cannot hold '/' ("los/kp" -> "los_kp").
inline std::string cfgName(const std::string& table_name) {
  std::string n = table_name;
  for (auto& c : n)
    if (c == '/') c = '_';
  return n;
}

struct ReconfigureGroup {
  std::string name;                 // the form's group (an identifier: it names a class in the generated header)
  std::vector<std::string> params;  // table names, in the form's order
};

}  // namespace offshore_gnc

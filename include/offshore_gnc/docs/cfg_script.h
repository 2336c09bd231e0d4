#pragma once
// The dynamic_reconfigure script of a form (common/reconfigure_form.h), written from the parameter tables:
// `param_docs --cfg <Form>` prints it into cfg/<Form>.cfg. A form field is a table entry: its name with '/' as
// '_', its kind, range and doc, the default of a struct of the table's type.
#include <string>
#include <vector>

#include "offshore_gnc/common/param_table.h"
#include "offshore_gnc/common/reconfigure_form.h"

namespace offshore_gnc {
namespace docs {

// A table entry as a form field needs it, whatever the table's struct.
struct CfgField {
  std::string name;  // the table's ("los/kp")
  ParamKind kind = ParamKind::kNumber;
  double lo = 0.0, hi = 0.0, value = 0.0;  // in the file's unit (degrees for an angle kept in radians)
  std::string unit, doc;
};

// The entries one table offers a form, each with its default in `defaults`; `owner` names the table when a form
// serves several (the Control form: one vehicle's controller runs per nodelet).
struct CfgSource {
  std::string owner;
  std::vector<CfgField> fields;
};

template <class P>
CfgSource cfgSource(const std::string& owner, const ParamTable<P>& t, P defaults) {
  CfgSource src{owner, {}};
  for (const auto& s : t.specs()) {
    CfgField f{s.name, s.kind, s.lo, s.hi, 0.0, s.unit, s.doc};
    if (s.number) f.value = s.number(defaults) / s.scale;
    else if (s.integer) f.value = s.integer(defaults);
    else if (s.flag) f.value = s.flag(defaults) ? 1.0 : 0.0;
    src.fields.push_back(std::move(f));
  }
  return src;
}

// The .cfg script (Python, dynamic_reconfigure's ParameterGenerator) of `groups` for ConfigType `form` (the
// generated <form>Config.h), `node` its node name. A field's default is the first source's that has it; its
// description the doc and unit, after the sources that have it when there are several. `header` is the comment
// under the shebang, wrapped (a '\n' starts a paragraph). Throws ConfigError for a name no source has, a field twice, a
// kind a form cannot show (lists, choices, text), or sources that disagree on a field's kind or range (the
// nodelet writes a change into every source's struct).
std::string cfgScript(const std::string& header, const std::string& node, const std::string& form,
                      const std::vector<ReconfigureGroup>& groups, const std::vector<CfgSource>& sources);

}  // namespace docs
}  // namespace offshore_gnc

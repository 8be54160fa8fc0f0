// pcrf._pcrf.settings: every setting a case or a study takes, from the settings tables.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "pcrf/post/script_vocabulary.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/solver/settings.hpp"
#include "pcrf/study/study.hpp"

namespace pcrf::python {
namespace {

template <class Target>
void describe(py::list& out, const SettingTable<Target>& table) {
  for (const auto& s : table.settings) {
    py::dict d;
    d["table"] = std::string(table.name);
    d["key"] = std::string(s.key);
    d["kind"] = setting_kind_text(s);
    d["unit"] = std::string(s.unit);
    d["default"] = setting_display(s.get(table.defaults));
    d["doc"] = std::string(s.doc);
    out.append(d);
  }
}

py::list settings() {
  py::list out;
  describe(out, physics_settings());
  describe(out, solver_settings());
  describe(out, intensity_settings());
  describe(out, study::run_settings());
  return out;
}

}  // namespace

void bind_settings(py::module_& m) {
  m.def("settings", &settings,
        "Every setting (table, key, kind, unit, default, doc): the [physics] and [solver] keys pcrf.run takes, "
        "the intensity keys (with intensity=), the [run] keys pcrf.study takes.");
  m.def("vocabulary", &post::script_vocabulary_json,
        "The JSON of `pcrf settings --json`: statuses with their kind, history event flags, frame parameters, curve states.");
}

}  // namespace pcrf::python

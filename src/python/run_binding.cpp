// pcrf._pcrf.run: one case in process, by the steps `pcrf run` takes (api/one_case.hpp).
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cstddef>
#include <memory>
#include <vector>

#include "bindings.hpp"
#include "keywords.hpp"
#include "pcrf/api/one_case.hpp"
#include "pcrf/record/horizontal_pair.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/solver/history.hpp"
#include "pcrf/solver/settings.hpp"

namespace pcrf::python {
namespace {

/// The result record with the keys and values of `pcrf run`'s JSON (NaN where it writes null).
py::dict result_dict(double scale_factor, const CaseResult& result, double rest_rise_rad) {
  py::dict d;
  d["scale_factor"] = scale_factor;
  for (const auto& m : all_metrics()) {
    if (m.is_count)
      d[py::str(std::string(m.name))] = static_cast<long long>(m.get(result));
    else
      d[py::str(std::string(m.name))] = m.get(result);
  }
  d["status"] = std::string(status_name(result.status));
  d["reinits"] = result.counts.reinits;
  d["message"] = result.message;
  d["rest_rise_rad"] = rest_rise_rad;  // the cut-off that defines `impacts`
  return d;
}

/// The history rows as a numpy structured array whose fields are the history's columns (the
/// CSV header of `pcrf run --history`), laid over the rows as they are in memory.
py::array history_array(const std::vector<HistorySample>& rows) {
  py::list names, formats, offsets;
  const HistorySample probe{};
  for (const auto& c : history_columns()) {
    names.append(std::string(c.name));
    formats.append("f8");
    offsets.append(reinterpret_cast<const char*>(&(probe.*c.member)) - reinterpret_cast<const char*>(&probe));
  }
  const py::dtype dtype(names, formats, offsets, sizeof(HistorySample));
  return py::array(dtype, {static_cast<py::ssize_t>(rows.size())}, {static_cast<py::ssize_t>(sizeof(HistorySample))},
                   rows.data());
}

/// What the call asks for, read from the keywords while the interpreter is held.
struct CaseCall {
  StationRecord station{GroundMotion("none", 1.0, {0.0}), {}, {}, {}, {}};
  std::vector<std::string> notes;
  std::vector<std::string> warnings;  ///< the record's (implausible_records, implausible_arrays)
  std::optional<double> incidence_deg;
  api::Scaling scaling;
  api::GivenSettings<PhysicsOptions> physics;
  api::GivenSettings<SolverSettings> solver;
  std::unique_ptr<Scene> scene;
  bool history = false;
  double history_dt_s = 0.0;
};

CaseCall read_call(const py::kwargs& kwargs) {
  Keywords keywords(kwargs);
  CaseCall call;
  call.station = keywords.take_station(call.notes, nullptr, &call.warnings);
  call.incidence_deg = keywords.take_number("incidence_deg");
  if (call.incidence_deg) {
    std::vector<UserError> found;
    if (auto problem = radians_problem({*call.incidence_deg}); !problem.empty())
      found.emplace_back("incidence_deg", std::move(problem), std::vector<std::string>{"incidence_deg"});
    keywords.add_warnings(found, call.warnings);
  }
  if (const auto scale = keywords.take_number("scale")) {
    call.scaling.scale = *scale;
    call.scaling.scale_given = true;
  }
  call.scaling.intensity = keywords.take_number("intensity");
  call.scaling.measure = keywords.take_settings(intensity_settings());
  call.scene = keywords.take_scene();
  call.physics = keywords.take_settings(physics_settings());
  call.solver = keywords.take_settings(solver_settings());
  if (const auto history = keywords.take("history")) call.history = py::bool_(*history);
  if (const auto dt = keywords.take_number("history_dt_s")) {
    if (!(*dt > 0.0)) throw UserError("history_dt_s", "must be positive");
    call.history_dt_s = *dt;
  }
  keywords.finish();
  return call;
}

py::tuple run(const py::kwargs& kwargs) {
  CaseCall call = read_call(kwargs);
  std::vector<HistorySample> rows;
  double scale_factor = 1.0, rest_rise_rad = 0.0;
  CaseResult result;
  {
    py::gil_scoped_release released;  // the case is pure C++: other Python threads run meanwhile
    const ScaledExcitation scaled = api::scaled_excitation(call.station, call.incidence_deg, call.scaling);
    scale_factor = scaled.factor();
    const PhysicsOptions physics = api::resolve_settings(physics_settings(), call.physics);
    rest_rise_rad = physics.rest_rise_rad;
    const SolverSettings solver = api::resolve_settings(solver_settings(), call.solver);
    HistorySink sink;
    if (call.history) sink = [&rows](const HistorySample& s) { rows.push_back(s); };
    result = api::solve_one_case(std::move(call.scene), physics, scaled.view(), solver,
                                 call.history_dt_s, sink);
    if (auto note = api::verdict_note(result, physics); !note.empty()) call.notes.push_back(std::move(note));
  }
  py::object history = call.history ? py::object(history_array(rows)) : py::none();
  return py::make_tuple(result_dict(scale_factor, result, rest_rise_rad), history, py::cast(call.notes), py::cast(call.warnings));
}

}  // namespace

void bind_run(py::module_& m) {
  m.def("run", &run,
        "One case, as `pcrf run`: returns (result dict, history structured array or None, notes, record warnings). "
        "See pcrf.run for the keywords.");
}

}  // namespace pcrf::python

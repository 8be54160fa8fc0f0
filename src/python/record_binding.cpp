// pcrf._pcrf.record_measures: what `pcrf record` prints (api/record_measures.hpp), as its JSON.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "keywords.hpp"
#include "pcrf/api/record_measures.hpp"

namespace pcrf::python {
namespace {

/// (the JSON text `pcrf record` prints, the notes of padding, the record warnings).
py::tuple record_measures(const py::kwargs& kwargs) {
  Keywords keywords(kwargs);
  api::MeasureRequest request;
  if (const auto periods = keywords.take("periods_s")) request.periods_s = to_doubles(*periods, "periods_s");
  if (const auto damping = keywords.take_number("damping")) request.damping = *damping;
  api::check_measure_request(request);
  std::vector<std::string> notes;
  api::RecordInput input;  // the files' names, for their headers' metadata
  std::vector<std::string> warnings;
  const StationRecord station = keywords.take_station(notes, &input, &warnings);
  keywords.finish();
  std::string json;
  {
    py::gil_scoped_release released;
    json = api::record_measures(station, input, request).str();
  }
  return py::make_tuple(json, py::cast(notes), py::cast(warnings));
}

}  // namespace

void bind_record(py::module_& m) {
  m.def("record_measures", &record_measures, "What `pcrf record` prints, as (JSON text, notes, record warnings); see pcrf.record_measures.");
}

}  // namespace pcrf::python

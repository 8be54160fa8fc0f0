// pcrf._pcrf.pulse, record_spectra and select: what `pcrf record pulse|spectra|select` print
// (api/record_pulse.hpp, record/record_library.hpp, record/selection.hpp), as text.
#include <pybind11/stl.h>

#include <filesystem>
#include <sstream>

#include "bindings.hpp"
#include "keywords.hpp"
#include "pcrf/api/record_pulse.hpp"
#include "pcrf/api/record_selection.hpp"
#include "pcrf/record/record_library.hpp"
#include "pcrf/record/selection.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf::python {
namespace {

/// (the JSON of `pcrf record pulse [--series]`, the notes of padding).
py::tuple pulse(const py::kwargs& kwargs) {
  Keywords keywords(kwargs);
  bool series = false;
  if (const auto s = keywords.take("series")) series = py::cast<bool>(*s);
  std::vector<std::string> notes;
  const StationRecord station = keywords.take_station(notes);
  keywords.finish();
  std::string json;
  {
    py::gil_scoped_release released;
    json = api::pulse_json(api::classify_station_pulse(station), series).str();
  }
  return py::make_tuple(json, py::cast(notes));
}

/// (the CSV of `pcrf record spectra`, the notes of files left out).
py::tuple record_spectra(const std::vector<std::string>& paths, const std::vector<double>& periods_s, double damping) {
  std::vector<std::string> skipped;
  std::ostringstream out;
  {
    py::gil_scoped_release released;
    const std::vector<std::filesystem::path> files =
        library_files(std::vector<std::filesystem::path>(paths.begin(), paths.end()), skipped);
    if (files.empty()) throw UserError("no .AT2 record files found");
    write_spectra_csv(out, compute_spectra(files, periods_s.empty() ? default_spectra_periods_s() : periods_s, damping, skipped));
  }
  return py::make_tuple(out.str(), py::cast(skipped));
}

/// The selection as JSON: the records (name, kind, files, scale, scaled ln Sa) and the fit.
std::string select(const std::string& target_path, const std::string& library_path, std::size_t count,
                   const std::string& kind, double scale_min, double scale_max, std::uint64_t seed) {
  const SelectionTarget target = api::read_selection_target_file(target_path);
  const SpectraTable table = api::read_spectra_table_file(library_path);
  SelectionSettings settings;
  settings.count = count;
  settings.kind = kind;
  settings.scale_min = scale_min;
  settings.scale_max = scale_max;
  settings.seed = seed;
  SelectionResult r;
  {
    py::gil_scoped_release released;
    r = select_records(target, table, settings);
  }
  return api::selection_json(target, table, r).str();
}

}  // namespace

void bind_record_library(py::module_& m) {
  m.def("pulse", &pulse, "What `pcrf record pulse` prints, as (JSON text, notes); see pcrf.pulse.");
  m.def("record_spectra", &record_spectra, py::arg("paths"), py::arg("periods_s"), py::arg("damping"),
        "What `pcrf record spectra` writes, as (CSV text, notes); see pcrf.record_spectra.");
  m.def("select", &select, py::arg("target"), py::arg("library"), py::arg("n"), py::arg("kind"), py::arg("scale_min"),
        py::arg("scale_max"), py::arg("seed"), "What `pcrf record select --json` prints; see pcrf.select.");
}

}  // namespace pcrf::python

// pcrf._pcrf.cube_info, cube_export, cube_history: what `pcrf cube info --json` and `pcrf cube
// export` read from a cube, in process, from the same C++ (cube/cube_query.hpp), with the
// notes the command line prints on stderr (post/cube_notes.hpp) returned beside them.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <unistd.h>

#include <sstream>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "pcrf/cube/cube_query.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/io/checked_stream.hpp"
#include "pcrf/io/file_kind.hpp"
#include "pcrf/post/cube_notes.hpp"
#include "pcrf/post/cube_reports.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf::python {
namespace {

/// Runs `read` on the cube at `file`; a cube problem is a UserError of that file, as the
/// command line reports it.
template <class Read>
auto reading(const std::string& file, Read read) {
  try {
    const cube::CubeReader reader(file);
    return read(reader);
  } catch (const cube::CubeError& e) {
    throw post::unreadable_cube(file, e);
  }
}

/// (the JSON of `pcrf cube info --json FILE`, [notes]): the notes say that a run holds the
/// cube or that cases were never run, as the command line's stderr does.
py::tuple cube_info(const std::string& file) {
  return reading(file, [&](const cube::CubeReader& reader) {
    std::vector<std::string> notes;
    for (const auto& note : {post::running_note(file), post::journal_note(file, reader), post::parts_note(file, reader),
                              post::partial_note(file, reader)})
      if (!note.empty()) notes.push_back(note);
    std::ostringstream json;
    cube::print_info_json(reader, json, schema::completion(reader));
    return py::make_tuple(json.str(), notes);
  });
}

/// (header, rows) of `pcrf cube export FILE -m METRIC… -w NAME=VALUE…`: each field the text
/// the CSV holds (a coordinate's label, a status's name, a number's shortest text, "" for NaN).
py::tuple cube_export(const std::string& file, const std::vector<std::string>& metrics,
                      const std::vector<std::string>& where) {
  return reading(file, [&](const cube::CubeReader& reader) {
    std::vector<cube::Selector> selectors;
    for (const auto& w : where) selectors.push_back(cube::parse_selector(w));
    py::list header, rows;
    bool first = true;
    cube::export_rows(reader, metrics, selectors, [&](const std::vector<std::string>& fields) {
      if (first) header = py::cast(fields), first = false;
      else rows.append(py::cast(fields));
    });
    return py::make_tuple(header, rows);
  });
}

/// {column: float64 array} of the history group /histories/NAME (`pcrf cube export --history NAME`).
py::dict cube_history(const std::string& file, const std::string& name) {
  return reading(file, [&](const cube::CubeReader& reader) {
    const auto table = reader.read_history(name);
    py::dict columns;
    for (std::size_t c = 0; c < table.columns.size(); ++c)
      columns[py::str(table.columns[c].name)] =
          py::array_t<double>(static_cast<py::ssize_t>(table.values[c].size()), table.values[c].data());
    return columns;
  });
}

/// Refuses a path that is not a regular file (a FIFO, on which netCDF's open would wait for
/// ever; a folder), as `pcrf cube` does, before xarray opens it. Opened without blocking.
void check_cube_file(const std::string& file) {
  try {
    ::close(io::open_regular_to_read(file));
  } catch (const io::OutputError& e) {
    throw post::unreadable_cube(file, cube::CubeError(e.what()));
  }
}

}  // namespace

void bind_cube_read(py::module_& m) {
  m.def("check_cube_file", &check_cube_file, py::arg("file"),
        "InputError unless FILE is a regular file (checked without blocking: a FIFO is refused at once)");
  m.def("cube_info", &cube_info, py::arg("file"),
        "(JSON of `pcrf cube info --json FILE`, notes): the notes as the command line's stderr says them");
  m.def("cube_export", &cube_export, py::arg("file"), py::arg("metrics") = std::vector<std::string>{},
        py::arg("where") = std::vector<std::string>{},
        "(header, rows) of `pcrf cube export`: one row of texts per selected case, \"\" for NaN");
  m.def("cube_history", &cube_history, py::arg("file"), py::arg("name"),
        "{column: array} of the cube's history group NAME (`pcrf cube export --history NAME`)");
}

}  // namespace pcrf::python

// pcrf._pcrf: the engine in process for Python. Every function calls the C++ the command
// line calls (src/api, the study layer); a bad input raises pcrf.InputError (a ValueError)
// whose message names the keyword ("tail_s=: must be positive (got -1)") and whose `key`
// is the key path's last key that is a name, not an entry's index (None for the input as a
// whole).
#include <pybind11/pybind11.h>

#include <exception>

#include "bindings.hpp"
#include "pcrf/user_error.hpp"
#include "pcrf/version.hpp"

namespace {

namespace py = pybind11;

/// A UserError as pcrf.InputError, its keys spelt as keywords.
void raise_input_error(const pcrf::UserError& e) {
  const py::object type = py::module_::import("pcrf._pcrf").attr("InputError");
  py::object error = type(e.message(pcrf::Dialect::kKeyword));
  const auto& where = e.where();
  const std::string key = pcrf::last_key_name(where.keys);
  error.attr("key") = key.empty() ? py::object(py::none()) : py::object(py::str(key));
  error.attr("file") = where.file.empty() ? py::object(py::none()) : py::object(py::str(where.file));
  error.attr("line") = where.line > 0 ? py::object(py::int_(where.line)) : py::object(py::none());
  PyErr_SetObject(type.ptr(), error.ptr());
}

}  // namespace

PYBIND11_MODULE(_pcrf, m) {
  m.doc() = "pcrf engine, compiled (use the package pcrf)";
  m.attr("__version__") = pcrf::kVersion;
  py::exception<pcrf::UserError>(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const pcrf::UserError& e) {
      raise_input_error(e);
    }
  });
  pcrf::python::bind_run(m);
  pcrf::python::bind_frame(m);
  pcrf::python::bind_record(m);
  pcrf::python::bind_record_library(m);
  pcrf::python::bind_study(m);
  pcrf::python::bind_settings(m);
  pcrf::python::bind_cube(m);
  pcrf::python::bind_cube_read(m);
  pcrf::python::bind_output(m);
}

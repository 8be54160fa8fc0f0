// pcrf._pcrf: the engine in process for Python. Every function calls the C++ the command
// line calls (src/api, the study layer); a bad input raises ValueError with its message.
#include <pybind11/pybind11.h>

#include "bindings.hpp"
#include "pcrf/api/input_error.hpp"
#include "pcrf/study/study_error.hpp"
#include "pcrf/version.hpp"

PYBIND11_MODULE(_pcrf, m) {
  namespace py = pybind11;
  m.doc() = "pcrf engine, compiled (use the package pcrf)";
  m.attr("__version__") = pcrf::kVersion;
  py::register_exception<pcrf::api::InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<pcrf::study::StudyError>(m, "StudyError", PyExc_ValueError);
  pcrf::python::bind_run(m);
  pcrf::python::bind_frame(m);
  pcrf::python::bind_record(m);
  pcrf::python::bind_study(m);
  pcrf::python::bind_settings(m);
  pcrf::python::bind_cube(m);
  pcrf::python::bind_cube_read(m);
  pcrf::python::bind_output(m);
}

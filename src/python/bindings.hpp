/// \file bindings.hpp
/// \brief The parts of the compiled module `pcrf._pcrf`, one concept each; the package
/// `pcrf` (src/python/pcrf) wraps them in Python (pandas, xarray, mpirun).
#pragma once

#include <pybind11/pybind11.h>

namespace pcrf::python {

namespace py = pybind11;

void bind_run(py::module_& m);       ///< run(**keywords): one case, as `pcrf run`
void bind_frame(py::module_& m);     ///< frame(**keywords): a frame's properties, as `pcrf frame`
void bind_record(py::module_& m);    ///< record_measures(**keywords): as `pcrf record`
void bind_record_library(py::module_& m);  ///< pulse, record_spectra, select: as `pcrf record pulse|spectra|select`
void bind_study(py::module_& m);     ///< study(source, **keywords): a study in process, as `pcrf study`
void bind_settings(py::module_& m);  ///< settings(): every setting's description, as `pcrf settings`
void bind_cube(py::module_& m);      ///< cube_report(kind, file, **keywords): as `pcrf cube KIND --json`
void bind_cube_read(py::module_& m); ///< cube_info, cube_export, cube_history: as `pcrf cube info --json`, `cube export`
void bind_output(py::module_& m);    ///< check_output, write_output: the rule of every output file (io::OutputFile)

}  // namespace pcrf::python

// pcrf._pcrf.check_output, write_output: the one rule of every file pcrf writes
// (io::OutputFile), for files made in Python (pcrf.plot's figures): never one of the inputs,
// an existing file replaced only with overwrite, written beside the target and renamed over it
// when complete, no success for a failed write. A refusal or failure raises pcrf.OutputError
// (an OSError) naming the file.
#include <pybind11/stl.h>

#include <filesystem>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "pcrf/io/output_file.hpp"

namespace pcrf::python {
namespace {

std::vector<std::filesystem::path> paths(const std::vector<std::string>& texts) { return {texts.begin(), texts.end()}; }

void check_output(const std::string& file, const std::vector<std::string>& inputs, bool overwrite) {
  io::check_output(file, paths(inputs), overwrite);
}

void write_output(const std::string& file, const py::bytes& content, const std::vector<std::string>& inputs,
                  bool overwrite) {
  const std::string bytes = content;
  py::gil_scoped_release unlocked;
  io::OutputFile out(file, paths(inputs), overwrite);
  out.stream().write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.commit();
}

}  // namespace

void bind_output(py::module_& m) {
  py::register_exception<io::OutputError>(m, "OutputError", PyExc_OSError);
  m.def("check_output", &check_output, py::arg("file"), py::arg("inputs") = std::vector<std::string>{},
        py::arg("overwrite") = false, "Refuses FILE now, as write_output would (OutputError), before it is made");
  m.def("write_output", &write_output, py::arg("file"), py::arg("content"), py::arg("inputs") = std::vector<std::string>{},
        py::arg("overwrite") = false, "Writes the bytes to FILE by the rule of every pcrf output (OutputError)");
}

}  // namespace pcrf::python

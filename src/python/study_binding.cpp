// pcrf._pcrf.study: a study in process, on one rank, as `pcrf study` runs it
// (study/study_run.hpp); a dict study is read by the same parser as a file, from TOML tables
// built here, its messages naming the key path in place of a line.
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "keywords.hpp"
#include "pcrf/user_error.hpp"
#include "pcrf/parallel/mpi_session.hpp"
#include "pcrf/user_error.hpp"
#include "pcrf/study/study_parser.hpp"
#include "pcrf/run/study_run.hpp"

namespace pcrf::python {
namespace {

/// How a dict study is named in messages and in the cube ("study: [axes] kappa: …").
constexpr const char* kDictSource = "study";

/// The key path of a value of the dict, as the study parser's messages give it.
using KeyPath = std::vector<std::string>;

KeyPath with_key(KeyPath path, std::string key) {
  path.push_back(std::move(key));
  return path;
}

[[noreturn]] void refuse(const py::handle& value, const KeyPath& path) {
  throw UserError(Where{path, kDictSource, 0}, "a " + py::str(value.get_type().attr("__name__")).cast<std::string>() +
                                                   " cannot be a study value (expected a dict, list, bool, int, float or str)");
}

toml::table toml_table(const py::dict& dict, const KeyPath& path);
toml::array toml_array(const py::handle& list, const KeyPath& path);

/// Hands one value of a dict study, as its TOML type, to `put` (tables, arrays, booleans,
/// integers, floats, strings; numpy arrays and scalars through their Python values). The dict
/// was checked by check_nesting; what a numpy array's tolist() makes (an object array may hold
/// itself) is bounded here by its key path's length, so that no recursion below is deeper
/// than kMaxNestingDepth.
template <class Put>
void with_toml_value(const py::handle& value, const KeyPath& path, Put put) {
  if (path.size() > kMaxNestingDepth) throw nested_too_deep(Where{path, kDictSource, 0});
  if (py::isinstance<py::dict>(value)) return put(toml_table(value.cast<py::dict>(), path));
  if (py::hasattr(value, "tolist") && !py::isinstance<py::str>(value)) {
    const py::object listed = value.attr("tolist")();
    if (py::hasattr(listed, "tolist") && !py::isinstance<py::list>(listed) && !py::isinstance<py::tuple>(listed))
      refuse(value, path);  // a tolist() that gives neither a list nor a plain value: no end to follow
    return with_toml_value(listed, path, put);
  }
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) return put(toml_array(value, path));
  if (py::isinstance<py::bool_>(value)) return put(value.cast<bool>());
  if (py::isinstance<py::int_>(value)) return put(whole_number(value, Where{path, kDictSource, 0}));
  if (py::isinstance<py::float_>(value)) return put(value.cast<double>());
  if (py::isinstance<py::str>(value)) return put(value.cast<std::string>());
  if (py::hasattr(value, "__fspath__")) return put(py::str(value.attr("__fspath__")()).cast<std::string>());
  refuse(value, path);
}

toml::table toml_table(const py::dict& dict, const KeyPath& path) {
  toml::table table;
  for (const auto& [key, item] : dict) {
    const std::string name = py::str(key).cast<std::string>();
    with_toml_value(item, with_key(path, name),
                    [&](auto&& value) { table.insert(name, std::forward<decltype(value)>(value)); });
  }
  return table;
}

toml::array toml_array(const py::handle& list, const KeyPath& path) {
  toml::array array;
  std::size_t i = 0;
  for (const auto& item : list)
    with_toml_value(item, with_key(path, key_index(i++)),
                    [&](auto&& value) { array.push_back(std::forward<decltype(value)>(value)); });
  return array;
}

/// The dict as a study, read by the study parser (UserError naming the key path); the cube
/// keeps its TOML text.
study::Study parsed_study(const py::dict& study) {
  check_nesting(study, Where{{}, kDictSource, 0});  // before toml_table walks it
  const toml::table table = toml_table(study, {});
  std::ostringstream text;
  text << table;
  return study::parse_study_table(table, text.str(), kDictSource, std::filesystem::current_path());
}

/// The dict as TOML text, checked as a study file is.
std::string checked_study_text(const py::dict& study) { return parsed_study(study).text; }

/// The one MPI session of this process (a singleton rank), made by the first study and
/// finalized when the interpreter exits (finalize_mpi): MPI cannot start twice in a process.
std::unique_ptr<parallel::MpiSession>& mpi_session() {
  static std::unique_ptr<parallel::MpiSession> session;
  return session;
}

/// Ctrl-C during a study run in process: the interpreter's own SIGINT handler only marks the
/// signal, and Python code runs its handler (raising KeyboardInterrupt) when it next holds the
/// GIL. The study's master thread, which released it, looks every kPollInterval_s: with the
/// GIL held briefly, PyErr_CheckSignals() runs the handler; an exception it raises stops the
/// run as a signal stops `pcrf study` (StudyRunOptions::stop_signal) and is raised once the
/// cube is saved.
struct Interrupt {
  static constexpr double kPollInterval_s = 0.05;
  std::atomic<int> stop{0};
  std::optional<py::error_already_set> exception;
  std::chrono::steady_clock::time_point last = std::chrono::steady_clock::now();

  void poll() {
    const auto now = std::chrono::steady_clock::now();
    if (stop.load() != 0 || std::chrono::duration<double>(now - last).count() < kPollInterval_s) return;
    last = now;
    py::gil_scoped_acquire held;
    if (PyErr_CheckSignals() != 0) {
      exception.emplace();  // takes the raised exception out of the interpreter
      stop.store(SIGINT);
    }
  }
};

py::dict study(const py::object& source, const py::kwargs& kwargs) {
  run::StudyRunOptions options;
  if (py::isinstance<py::dict>(source)) {
    options.study = parsed_study(source.cast<py::dict>());
    options.study_file = kDictSource;
  } else if (py::isinstance<py::str>(source) || py::hasattr(source, "__fspath__")) {
    options.study_file = py::str(py::hasattr(source, "__fspath__") ? source.attr("__fspath__")() : source).cast<std::string>();
  } else {
    throw UserError("source", "expected a dict of the study's tables or a study file's path (got a " +
                                  py::str(source.get_type().attr("__name__")).cast<std::string>() + ")");
  }
  Keywords keywords(kwargs);
  if (const auto output = keywords.take_text("output")) options.output = *output;
  if (const auto flag = keywords.take("overwrite")) options.overwrite = py::bool_(*flag);
  if (const auto flag = keywords.take("resume")) options.resume = py::bool_(*flag);
  if (const auto flag = keywords.take("check")) options.check_only = py::bool_(*flag);
  if (options.resume && options.overwrite) throw UserError(Where{}, "give either {} or {}, not both", {"resume", "overwrite"});
  const auto progress = keywords.take("progress");
  if (progress && py::bool_(*progress)) options.progress = &std::cerr;
  options.run_overrides = keywords.take_settings(study::run_settings());
  keywords.finish();
  if (options.study && options.output.empty() && !options.check_only)
    throw UserError(Where{}, "a study given as a dict needs {} (the cube's path)", {"output"});

  std::vector<std::string> notes;  // warned by pcrf.study (as the command line prints them)
  options.notes = &notes;
  std::optional<run::StudySummary> summary;
  Interrupt interrupt;  // outside the released block: its exception is let go with the GIL held
  options.stop_signal = &interrupt.stop;
  options.poll = [&interrupt] { interrupt.poll(); };
  {
    py::gil_scoped_release released;
    if (!mpi_session()) {
      if (const auto problem = parallel::MpiSession::startup_problem(); !problem.empty()) throw UserError(problem);
      mpi_session() = std::make_unique<parallel::MpiSession>();
    }
    summary = run::run_study(options, *mpi_session());
  }
  if (interrupt.exception) {
    // The cube is left as `pcrf study` leaves it on SIGINT: checkpointed, resumable.
    const std::string note = "pcrf.study: " + run::stop_report(*summary) + "; continue with pcrf.study(..., resume=True)";
    if (py::hasattr(interrupt.exception->value(), "add_note")) interrupt.exception->value().attr("add_note")(note);
    throw std::move(*interrupt.exception);
  }
  py::dict d;
  d["total"] = summary->total;
  d["already_done"] = summary->already_done;
  d["computed"] = summary->computed;
  d["failed"] = summary->failed;
  d["output"] = summary->output.string();
  d["fingerprint"] = summary->fingerprint;
  d["cost_estimate"] = summary->cost_estimate;  // --check: measured on a sample of cases
  d["warnings"] = summary->warnings;
  d["notes"] = notes;
  d["verdict_notes"] = summary->verdict_notes;
  d["invalid_cases"] = summary->invalid_cases;
  d["invalid_frames"] = summary->invalid_frames;
  d["first_invalid"] = summary->first_invalid;
  d["error"] = summary->error;
  return d;
}

/// The [run] keywords as the flags of `pcrf study` (pcrf.study with ranks > 1 hands them to
/// mpirun), checked here as ranks=1 checks them (InputError naming the keyword).
std::vector<std::string> run_flags(const py::kwargs& kwargs) {
  Keywords keywords(kwargs);
  const auto given = keywords.take_settings(study::run_settings());
  keywords.finish();
  std::vector<std::string> flags;
  for (const auto& [setting, value] : given) {
    const std::string flag = flag_name(setting->key);
    if (const bool* on = std::get_if<bool>(&value)) {
      flags.push_back(*on ? flag : "--no-" + flag.substr(2));
      continue;
    }
    flags.push_back(flag);
    flags.push_back(setting_display(value));
  }
  return flags;
}

}  // namespace

void bind_study(py::module_& m) {
  m.def("run_flags", &run_flags, "The [run] keywords as `pcrf study` flags, checked (InputError naming the keyword).");
  m.def("study", &study, py::arg("source"), "A study in process on one rank; see pcrf.study.");
  m.def("study_text", &checked_study_text, py::arg("study"),
        "A dict study as TOML text, checked as a study file is (UserError naming the key path).");
  m.def("finalize_mpi", [] { mpi_session().reset(); }, "Ends this process's MPI session (at exit).");
}

}  // namespace pcrf::python

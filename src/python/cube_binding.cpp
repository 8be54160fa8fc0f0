// pcrf._pcrf.cube_report: what `pcrf cube stats|fragility|sensitivity|p695 --json` writes,
// from the same reports (post/cube_reports.hpp) and the same JSON writer (full precision).
#include <pybind11/stl.h>

#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "keywords.hpp"
#include "pcrf/user_error.hpp"
#include "pcrf/cube/cube_query.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/post/cube_notes.hpp"
#include "pcrf/post/cube_reports.hpp"
#include "pcrf/post/cube_risk.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"

namespace pcrf::python {
namespace {

/// A word or a list of words, the keyword `key`'s. \throws UserError naming it.
std::vector<std::string> words(const std::string& key, const std::optional<py::object>& value) {
  if (!value) return {};
  if (py::isinstance<py::str>(*value)) return {value->cast<std::string>()};
  if (!py::isinstance<py::list>(*value) && !py::isinstance<py::tuple>(*value))
    throw UserError(key, "expected a string or a list of strings");
  std::vector<std::string> texts;
  for (const auto& word : *value) {
    if (!py::isinstance<py::str>(word)) throw UserError(key, "expected a string or a list of strings");
    texts.push_back(word.cast<std::string>());
  }
  return texts;
}

/// where=: "name=value" texts, or a dict {name: value}, as the command line's -w selectors.
std::vector<cube::Selector> selectors(const std::optional<py::object>& where) {
  std::vector<std::string> texts;
  if (where && py::isinstance<py::dict>(*where)) {
    for (const auto& [name, value] : where->cast<py::dict>())
      texts.push_back(py::str(name).cast<std::string>() + "=" + py::str(value).cast<std::string>());
  } else {
    texts = words("where", where);
  }
  std::vector<cube::Selector> result;
  for (const auto& t : texts) result.push_back(cube::parse_selector(t));
  return result;
}

/// reduce_over= and reduce= as the command line's --reduce-over and --reduce (post::reduction_of).
cube::Reduction reduction_of(Keywords& keywords, const std::string& default_how) {
  const auto over = keywords.take_text("reduce_over").value_or("");
  const auto how = keywords.take_text("reduce").value_or("");
  return post::reduction_of(over, how, default_how);
}

/// The report `kind` of the cube `file` as `pcrf cube KIND` makes it; what the command line
/// says on stderr beside it (post::report_notes) in `notes`.
post::Report report(const std::string& kind, const std::string& file, Keywords& keywords,
                    std::vector<std::string>& notes) {
  const auto where = selectors(keywords.take("where"));
  if (kind == "stats") {
    const auto metric = keywords.take_text("metric").value_or("");
    const auto by = words("by", keywords.take("by"));
    const auto reduction = reduction_of(keywords, post::kStatsReduction);
    keywords.finish();
    const cube::CubeReader reader(file);
    notes = post::report_notes(kind, file, reader);
    return post::stats_report(reader, {by, metric, where, reduction});
  }
  if (kind == "fragility") {
    const auto mce = keywords.take_number("mce");
    const auto reduction = reduction_of(keywords, post::kFragilityReduction);
    keywords.finish();
    post::check_mce(mce);
    const cube::CubeReader reader(file);
    notes = post::report_notes(kind, file, reader);
    return post::fragility_report(reader, {where, mce}, reduction);
  }
  if (kind == "sensitivity") {
    const auto metric = keywords.take_text("metric").value_or("");
    const auto by_record = keywords.take("by_record");
    keywords.finish();
    const cube::CubeReader reader(file);
    notes = post::report_notes(kind, file, reader);
    return post::sensitivity_report(reader, {metric, where, by_record && py::bool_(*by_record)});
  }
  if (kind == "p695") {
    const auto period_s = keywords.take_number("period_s");
    const auto sdc = keywords.take_text("sdc").value_or("Dmax");
    const auto mu_t = keywords.take_number("mu_t").value_or(0.0);
    const auto ratings = keywords.take_text("ratings").value_or("");
    const auto s_ct = keywords.take_text("s_ct").value_or("counted");
    keywords.finish();
    if (!period_s) throw UserError(Where{}, "p695 needs {}, the archetype's period T [s]", {"period_s"});
    const post::P695Inputs in = post::p695_inputs(sdc, *period_s, mu_t, ratings, s_ct);
    const cube::CubeReader reader(file);
    notes = post::report_notes(kind, file, reader);
    return post::p695_report(reader, where, in);
  }
  if (kind == "risk") {
    post::RiskInputs in;
    const auto hazard = keywords.take_text("hazard");
    in.years = keywords.take_number("years").value_or(in.years);
    const auto tail = keywords.take_text("tail").value_or("power-law");
    in.target.target_probability = keywords.take_number("target_probability").value_or(in.target.target_probability);
    in.target.years = keywords.take_number("target_years").value_or(in.target.years);
    in.target.beta = keywords.take_number("generic_beta").value_or(in.target.beta);
    in.target.collapse_probability = keywords.take_number("generic_probability").value_or(in.target.collapse_probability);
    const auto ratings = keywords.take_text("ratings").value_or("B,B,B");
    keywords.finish();
    if (!hazard) throw UserError(Where{}, "risk needs {}, the hazard curve's CSV file", {"hazard"});
    in.hazard = *hazard;
    in.tail = risk::parse_tail(tail);
    const auto checked = post::p695_inputs("Dmax", 1.0, 0.0, ratings);  // the ratings checked as p695 checks them
    in.design_rating = checked.design_rating, in.test_rating = checked.test_rating, in.model_rating = checked.model_rating;
    const cube::CubeReader reader(file);
    notes = post::report_notes(kind, file, reader);
    return post::risk_report(post::cube_risk(reader, where, in), in, file);
  }
  throw UserError("unknown report '" + kind + "' (expected stats, fragility, sensitivity, p695 or risk)");
}

/// (the JSON of `pcrf cube KIND FILE --json`, [the lines the command line prints on stderr
/// before it, without its prefix]); the report's own warnings are in the JSON.
py::tuple cube_report(const std::string& kind, const std::string& file, const py::kwargs& kwargs) {
  Keywords keywords(kwargs);
  std::ostringstream json;
  std::vector<std::string> notes;
  if (auto running = post::running_note(file); !running.empty()) notes.push_back(std::move(running));
  try {
    std::vector<std::string> read_notes;
    post::write_json(report(kind, file, keywords, read_notes), json);
    notes.insert(notes.end(), read_notes.begin(), read_notes.end());
  } catch (const cube::CubeError& e) {  // a cube that cannot be read is the user's input: named by its file
    throw post::unreadable_cube(file, e);
  }
  return py::make_tuple(json.str(), notes);
}

/// What `pcrf cube info` says on stderr of a cube: a run holding it, results waiting in its
/// journal, cases not run, cases unresolved.
std::vector<std::string> cube_notes(const std::string& file) {
  std::vector<std::string> notes;
  if (auto running = post::running_note(file); !running.empty()) notes.push_back(std::move(running));
  try {
    const cube::CubeReader reader(file);
    for (auto& note : post::completion_notes(file, reader)) notes.push_back(std::move(note));
    for (auto& line : post::verdict_lines("info", file, reader)) notes.push_back(std::move(line));
  } catch (const cube::CubeError& e) {
    throw post::unreadable_cube(file, e);
  }
  return notes;
}

}  // namespace

void bind_cube(py::module_& m) {
  m.def("cube_report", &cube_report, py::arg("kind"), py::arg("file"),
        "(the JSON of `pcrf cube KIND FILE --json` (stats, fragility, sensitivity, p695, risk), the notes the command "
        "line prints beside it); see pcrf.fragility.");
  m.def("cube_notes", &cube_notes, py::arg("file"),
        "The notes `pcrf cube info FILE` prints on stderr: a run holding it, results in its journal, cases not run "
        "or unresolved.");
  m.def("pulse_coordinates", &schema::pulse_coordinates,
        "The coordinates a study of pulses may have along `record`: pulse_shape and the pulse axes.");
}

}  // namespace pcrf::python

// Study file parser (see study_parser.hpp and studies/README.md for the keys).
#include "pcrf/study/study_parser.hpp"

#include <fnmatch.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <cctype>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/metrics/case_result.hpp"
#include "pcrf/hazard/hazard_file.hpp"
#include "pcrf/record/pulses.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"
#include "pcrf/study/plan.hpp"
#include "study/axis_fields.hpp"
#include "study/plans/plan_support.hpp"
#include "study/stripe_selection.hpp"
#include "study/toml_depth.hpp"
#include "study/toml_fields.hpp"

namespace pcrf::study {

namespace {

using detail::Fields;
using detail::PlanEntry;
using detail::check_axis;
using detail::number_text;
using detail::read_parameters;
using detail::read_values;
using detail::with_parameter_keys;

// ---- pulses ------------------------------------------------------------------------------

using schema::pulse_axis_keys;

std::vector<std::string_view> axes_keys() {
  std::vector<std::string_view> keys{"scale", "intensity", "incidence_deg", "incidence"};
  for (const auto& k : pulse_axis_keys()) keys.push_back(k.axis_key);
  return with_parameter_keys(keys);
}

void read_pulse_axes(const Fields& f, Study& s) {
  for (const auto& k : pulse_axis_keys()) {
    if (!f.has(k.axis_key)) continue;
    auto values = read_values(f, k.axis_key);
    if (k.axis_key != "pulse_nu_deg") check_axis(f, k.axis_key, values, nullptr);  // ν may be any phase
    s.pulse_axes.push_back({std::string(k.axis_key), std::move(values), f.where(k.axis_key)});
  }
}

/// A [[records]] pulse entry: one record per shape and combination of the [axes] pulse values,
/// each named by its synthetic text (so that `pcrf run --synthetic NAME` reruns it).
std::vector<RecordSource> read_pulse_entry(const Fields& f, const Study& s) {
  std::vector<PulseShape> shapes;
  for (const auto& name : f.texts("pulse")) {
    const auto all = pulse_shapes();
    const auto it = std::find_if(all.begin(), all.end(), [&](PulseShape p) { return pulse_kind(p) == name; });
    if (it == all.end()) {
      std::string expected;
      for (std::size_t i = 0; i < all.size(); ++i) expected += (i == 0 ? "" : ", ") + pulse_kind(all[i]);
      f.fail("pulse", "unknown pulse \"" + name + "\" (expected " + expected + ")");
    }
    shapes.push_back(*it);
  }
  const double dt_s = f.number("dt_s").value_or(PulseSpec{}.dt_s);
  if (!(dt_s > 0.0)) f.fail("dt_s", "must be positive");
  std::vector<std::string> tail;  // the entry's own keys, after the axes'
  if (f.has("dt_s")) tail.push_back("dt_s=" + number_text(dt_s));
  if (const auto duration = f.number("duration_s")) tail.push_back("duration_s=" + number_text(*duration));
  for (const auto& axis : s.pulse_axes)
    if (axis.key == "pulse_period_s")
      for (double t : axis.values)
        if (t < 4.0 * dt_s)
          throw UserError(axis.declared_at, "value " + number_text(t) + " is below 4 dt = " + number_text(4.0 * dt_s) +
                                                " s of the pulse records (" + file_line_text(f.where("pulse")) + ")");
  std::vector<RecordSource> sources;
  for (PulseShape shape : shapes) {
    std::vector<const Study::PulseAxis*> axes;
    for (const auto& axis : s.pulse_axes) {
      const auto& key = *std::find_if(pulse_axis_keys().begin(), pulse_axis_keys().end(),
                                      [&](const schema::PulseAxisKey& k) { return k.axis_key == axis.key; });
      if (key.only.empty() || std::find(key.only.begin(), key.only.end(), shape) != key.only.end()) axes.push_back(&axis);
    }
    std::vector<std::size_t> at(axes.size(), 0);
    for (bool more = true; more;) {
      RecordSource source;
      source.pulse_shape = pulse_kind(shape);
      std::vector<std::string> assignments;
      for (std::size_t a = 0; a < axes.size(); ++a) {
        const double v = axes[a]->values[at[a]];
        source.pulse_values.emplace_back(axes[a]->key, v);
        assignments.push_back(axes[a]->key.substr(6) + "=" + number_text(v));  // without "pulse_"
      }
      assignments.insert(assignments.end(), tail.begin(), tail.end());
      std::string text = pulse_kind(shape);
      for (std::size_t a = 0; a < assignments.size(); ++a) text += (a == 0 ? ":" : ",") + assignments[a];
      source.synthetic = text;
      source.name = source.synthetic;
      source.declared_at = f.where("pulse");
      sources.push_back(std::move(source));
      more = false;  // the next combination, the last axis fastest
      for (std::size_t a = axes.size(); a-- > 0;) {
        if (++at[a] < axes[a]->values.size()) {
          more = true;
          break;
        }
        at[a] = 0;
      }
    }
  }
  return sources;
}

// ---- sections ----------------------------------------------------------------------------

void read_study_section(const Fields& top, Study& s) {
  s.name = std::filesystem::path(s.file).stem().string();
  const auto* table = top.subtable("study");
  if (table == nullptr) return;
  Fields f(*table, {"study"}, s.file, {"name", "description"});
  s.name = f.text("name").value_or(s.name);
  s.description = f.text("description").value_or("");
}

/// "plan \"list\"" or "plans \"sobol\" and \"saltelli\"": the plans that take a key.
std::string plans_taking(std::string_view key, std::vector<std::string_view> PlanEntry::*keys) {
  std::vector<std::string> names;
  for (const auto& entry : detail::plan_registry())
    if (std::find((entry.*keys).begin(), (entry.*keys).end(), key) != (entry.*keys).end())
      names.push_back("\"" + std::string(entry.name) + "\"");
  std::string text = names.size() == 1 ? "plan " : "plans ";
  for (std::size_t i = 0; i < names.size(); ++i) text += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + names[i];
  return text;
}

/// The plan kind [plan] names; a [plan] key or a top-level table of another plan is an error.
const PlanEntry& read_plan_kind(const Fields& top, const Fields& plan) {
  const std::string kind = plan.text("kind").value_or(std::string(detail::plan_registry().front().name));
  const auto& registry = detail::plan_registry();
  const auto entry = std::find_if(registry.begin(), registry.end(), [&](const PlanEntry& e) { return e.name == kind; });
  if (entry == registry.end()) {
    const auto kinds = plan_kinds();
    std::string expected;
    for (std::size_t i = 0; i < kinds.size(); ++i)
      expected += (i == 0 ? "" : i + 1 == kinds.size() ? " or " : ", ") + ("\"" + std::string(kinds[i]) + "\"");
    plan.fail("kind", "expected " + expected + ", got \"" + kind + "\"");
  }
  for (const auto& other : registry)
    for (auto key : other.plan_keys)
      if (plan.has(key) && std::find(entry->plan_keys.begin(), entry->plan_keys.end(), key) == entry->plan_keys.end())
        plan.fail(key, "only applies to " + plans_taking(key, &PlanEntry::plan_keys));
  for (const auto& other : registry)
    for (auto key : other.file_keys)
      if (top.has(key) && std::find(entry->file_keys.begin(), entry->file_keys.end(), key) == entry->file_keys.end())
        top.fail(key, "only applies to " + plans_taking(key, &PlanEntry::file_keys));
  return *entry;
}

/// [plan] and what the plan reads of [axes] and the file (after [base]: frames start there).
void read_plan(const Fields& top, const Fields* axes, Study& s) {
  static const toml::table kNoTable;
  std::vector<std::string_view> keys{"kind"};
  for (const auto& entry : detail::plan_registry())
    for (auto key : entry.plan_keys)
      if (std::find(keys.begin(), keys.end(), key) == keys.end()) keys.push_back(key);
  const auto* table = top.subtable("plan");
  const Fields plan(table != nullptr ? *table : kNoTable, {"plan"}, s.file, keys);
  const PlanEntry& entry = read_plan_kind(top, plan);
  s.plan = entry.read({plan, axes, top, *s.model, s.base});
  if (plan.has("samples")) s.given_at["plan.samples"] = plan.where("samples");  // for study_size's message
}

/// [frame]: the scene (model) and its base point; [base], the older table, takes the same
/// parameters (one key in only one of them).
void read_base(const Fields& top, Study& s) {
  const auto* frame_table = top.subtable("frame");
  const auto* base_table = top.subtable("base");
  const std::vector<std::string_view> keys = detail::all_scene_keys();
  if (frame_table != nullptr) {
    const Fields f(*frame_table, {"frame"}, s.file, detail::with_scene_keys({"model"}));
    if (const auto* model = detail::read_model(f)) {
      s.model = model;
      s.base = s.model->defaults();
      if (s.model != &default_scene_model()) s.given_at["frame.model"] = f.where("model");
    }
    read_parameters(f, *s.model, s.base, false);
  }
  if (base_table != nullptr) {
    const Fields f(*base_table, {"base"}, s.file, keys);
    if (frame_table != nullptr)
      for (auto key : keys)
        if (f.has(key) && frame_table->contains(key)) f.fail(key, "is also given in [frame]: give it once");
    read_parameters(f, *s.model, s.base, false);
  }
}

/// What an IDA needs of the outputs: no histories (its cases are chosen as it runs), and
/// θ_max stored when it defines collapse.
void check_ida_outputs(const Study& s) {
  if (!s.ida) return;
  if (!s.histories.empty())
    Fields::fail_at(s.file, nullptr, {"outputs", "histories"}, "an IDA chooses its cases as it runs: histories are not available");
  const bool theta_stored = std::find(s.metrics.begin(), s.metrics.end(), metric::theta_max().name) != s.metrics.end();
  if (s.ida->theta_limit_rad > 0.0 && !theta_stored)
    throw UserError(s.where("ida.theta_limit_rad"), "needs theta_max_rad among [outputs] metrics");
}

// ---- intensity ----------------------------------------------------------------------------

/// [intensity] keys besides the measure's settings: hazard-consistent stripes.
constexpr std::string_view kHazardKey = "hazard";
constexpr std::string_view kReturnPeriodsKey = "return_periods_yr";

/// A number for a message, to four significant digits.
std::string four_digits(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

/// The hazard curve of hazard-consistent stripes, read and checked against the study's
/// measure; its refusals name the study's key and the hazard file's line.
pcrf::hazard::HazardFile read_stripe_hazard(const Fields& f, const Study::HazardStripes& h, const IntensitySpec& spec) {
  std::optional<pcrf::hazard::HazardFile> read;
  try {
    read = pcrf::hazard::read_hazard_file(h.file, risk::Tail::kCutOff);  // cut off: no return period beyond the curve
  } catch (const UserError& e) {
    f.fail(kHazardKey, e.what());
  }
  const std::string where = file_line_text(Where{{}, read->file.string(), static_cast<int>(read->header_line)}) + ": ";
  if (read->measure != to_string(spec.measure))
    f.fail(kHazardKey, where + "the curve's measure is " + read->measure + ", the study's [intensity] measure is " +
                           to_string(spec.measure));
  if (read->period_s && std::abs(*read->period_s - spec.period_s) > 1e-9 * spec.period_s)
    f.fail(kHazardKey, where + "the curve is at period_s = " + number_text(*read->period_s) + " s, the study's Sa at " +
                           number_text(spec.period_s) + " s");
  return std::move(*read);
}

/// [intensity] hazard = "FILE" and return_periods_yr = [...]: the stripes' intensities, each
/// the curve's intensity at the annual rate 1/T (Study::HazardStripes).
void read_hazard_stripes(const Fields& f, const IntensitySpec& spec, Study& s) {
  if (!f.has(kHazardKey) && !f.has(kReturnPeriodsKey)) return;
  if (!f.has(kReturnPeriodsKey))
    f.fail(kHazardKey, "a hazard curve sets the stripes' intensities: give return_periods_yr = [...] beside it");
  if (!f.has(kHazardKey))
    f.fail(kReturnPeriodsKey, "needs hazard = \"FILE\", the site's hazard curve (a CSV, docs/risk.md), to turn return periods into intensities");
  Study::HazardStripes h;
  h.hazard = *f.text(kHazardKey);
  h.file = s.base_dir / h.hazard;
  h.return_periods_yr = read_values(f, kReturnPeriodsKey);
  check_axis(f, kReturnPeriodsKey, h.return_periods_yr, nullptr);
  const pcrf::hazard::HazardFile hazard = read_stripe_hazard(f, h, spec);
  const auto& rates = hazard.curve.rates_per_yr();
  std::vector<double> intensities;
  for (double period_yr : h.return_periods_yr) {
    const double x = hazard.curve.intensity_at_rate(1.0 / period_yr);
    if (!std::isfinite(x))
      f.fail(kReturnPeriodsKey, "return period " + number_text(period_yr) + " yr is outside the hazard curve " + h.hazard +
                                    ", whose rates span return periods from " + four_digits(1.0 / rates.front()) + " to " +
                                    four_digits(1.0 / rates.back()) + " yr");
    intensities.push_back(x);
  }
  h.warnings = hazard.warnings;
  s.levels = std::move(intensities);
  s.given_at["intensity.return_periods_yr"] = f.where(kReturnPeriodsKey);
  s.hazard_stripes = std::move(h);
}

void read_intensity(const Fields& top, Study& s) {
  const toml::table* table = top.subtable(intensity_settings().name);
  if (table == nullptr) return;
  IntensitySpec spec;
  detail::read_setting_table(top, intensity_settings(), spec, s.given_at, {kHazardKey, kReturnPeriodsKey});
  if (const auto problem = intensity_spec_problem(spec); !problem.empty())
    throw UserError(s.where("intensity.period_s"), problem);
  s.intensity = spec;
  std::vector<std::string_view> keys{kHazardKey, kReturnPeriodsKey};
  for (const auto& setting : intensity_settings().settings) keys.push_back(setting.key);
  read_hazard_stripes(Fields(*table, {"intensity"}, s.file, keys), spec, s);
}

void read_ida(const Fields& top, Study& s) {
  const toml::table* table = top.subtable(ida_settings().name);
  if (table == nullptr) return;
  IdaOptions ida;
  detail::read_setting_table(top, ida_settings(), ida, s.given_at);
  const Fields f(*table, {"ida"}, s.file, {"start", "step", "step_factor", "resolution", "max_intensity", "max_runs", "collapse", "theta_limit_rad"});
  if (!s.intensity)
    top.fail("ida", "an IDA needs an intensity measure: add an [intensity] table (measure = \"pga_g\", \"pgv_m_s\" or \"sa_g\")");
  if (s.hazard_stripes)
    throw UserError(s.where("intensity.return_periods_yr"),
                    "with [ida] the search chooses the intensities: give no return periods");
  if (!f.has("start")) f.fail("start", "required: the first intensity of every curve");
  if (!f.has("max_intensity")) f.fail("max_intensity", "required: the largest intensity the search may run");
  if (ida.max_intensity < ida.start)
    f.fail("max_intensity", "must be at least start (" + number_text(ida.start) + ")");
  s.ida = ida;
}

/// [axes] incidence_deg and incidence: the frames' orientation (Study::incidence_deg).
void read_incidence(const Fields& f, Study& s) {
  if (f.has("incidence")) {
    const std::string reference = *f.text("incidence");
    if (reference != "north" && reference != "fault-normal" && reference != "fault-parallel")
      f.fail("incidence", "expected \"north\", \"fault-normal\" or \"fault-parallel\", got \"" + reference + "\"");
    s.incidence_reference = reference;
    s.incidence_deg = {0.0};  // the reference direction itself, unless incidence_deg adds offsets
  }
  if (!f.has("incidence_deg")) return;
  s.incidence_deg = read_values(f, "incidence_deg");
  s.given_at["axes.incidence_deg"] = f.where("incidence_deg");  // for the radians warning (study_check)
  std::vector<double> sorted = s.incidence_deg;
  std::sort(sorted.begin(), sorted.end());
  if (auto dup = std::adjacent_find(sorted.begin(), sorted.end()); dup != sorted.end())
    f.fail("incidence_deg", "value " + number_text(*dup) + " appears twice");
  for (double v : s.incidence_deg)
    if (!(std::fabs(v) <= 360.0)) f.fail("incidence_deg", "value " + number_text(v) + " is not an angle in [-360, 360] degrees");
  if (s.intensity && rotd_percentile(s.intensity->measure) == 0)
    f.fail("incidence_deg", "the records are scaled by their " + to_string(s.intensity->measure) +
                                ", which depends on the frame's orientation: scale pairs by a RotD measure (" +
                                to_string(IntensityMeasure::kPgaRotD50) + ", " + to_string(IntensityMeasure::kSaRotD50) + ", …)");
}

/// [axes]: the level axis (scale or intensity) here, the parameter keys by the plan.
void read_axes(const Fields& top, Study& s) {
  const auto* table = top.subtable("axes");
  if (table != nullptr) s.given_at["axes"] = top.where("axes");
  const bool has_intensity_axis = table != nullptr && table->contains("intensity");
  if (s.ida && table != nullptr && (table->contains("intensity") || table->contains("scale")))
    Fields(*table, {"axes"}, s.file, axes_keys())
        .fail(table->contains("intensity") ? "intensity" : "scale",
              "with [ida] the search chooses the intensities: give no intensity or scale axis");
  if (s.hazard_stripes && table != nullptr && (table->contains("intensity") || table->contains("scale")))
    Fields(*table, {"axes"}, s.file, axes_keys())
        .fail(table->contains("intensity") ? "intensity" : "scale",
              "[intensity] return_periods_yr (" + file_line_text(s.where("intensity.return_periods_yr")) +
                  ") sets the stripes' intensities: give either it or this axis, not both");
  if (s.intensity && !s.ida && !has_intensity_axis && !s.hazard_stripes)
    top.fail("intensity", "an [intensity] table needs [axes] intensity = [...] (values in " +
                              std::string(intensity_units(s.intensity->measure)) + "), or return_periods_yr with a hazard curve");
  std::optional<Fields> axes;
  if (table != nullptr) {
    axes.emplace(*table, std::vector<std::string>{"axes"}, s.file, axes_keys());
    const Fields& f = *axes;
    read_incidence(f, s);
    read_pulse_axes(f, s);
    if (f.has("scale") && f.has("intensity"))
      f.fail("intensity", "give either scale (one factor for every record) or intensity (each record scaled to it), not both");
    if (f.has("intensity") && !s.intensity)
      f.fail("intensity", "an intensity axis needs an [intensity] table naming the measure (pga_g, pgv_m_s or sa_g)");
    for (const char* key : {"scale", "intensity"}) {
      if (!f.has(key)) continue;
      s.levels = read_values(f, key);
      check_axis(f, key, s.levels, nullptr);
    }
  }
  read_plan(top, axes ? &*axes : nullptr, s);
}

// ---- records -----------------------------------------------------------------------------

bool has_glob(const std::string& text) { return text.find_first_of("*?[") != std::string::npos; }

/// Natural order of file names: digit runs compare as numbers, so ER2 sorts before ER10.
bool natural_less(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    const bool digit_a = std::isdigit(static_cast<unsigned char>(a[i])) != 0;
    const bool digit_b = std::isdigit(static_cast<unsigned char>(b[j])) != 0;
    if (digit_a && digit_b) {
      std::size_t ei = i, ej = j;
      while (ei < a.size() && std::isdigit(static_cast<unsigned char>(a[ei]))) ++ei;
      while (ej < b.size() && std::isdigit(static_cast<unsigned char>(b[ej]))) ++ej;
      std::size_t zi = i, zj = j;  // skip leading zeros, then the longer number is larger
      while (zi + 1 < ei && a[zi] == '0') ++zi;
      while (zj + 1 < ej && b[zj] == '0') ++zj;
      if (ei - zi != ej - zj) return ei - zi < ej - zj;
      if (const int c = a.compare(zi, ei - zi, b, zj, ej - zj); c != 0) return c < 0;
      i = ei;
      j = ej;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

/// Files named by one entry: a path, or a glob in its last component (sorted matches).
std::vector<std::filesystem::path> resolve_files(const Fields& f, std::string_view key,
                                                 const std::string& entry, const std::filesystem::path& base_dir) {
  std::filesystem::path path(entry);
  if (path.is_relative()) path = base_dir / path;
  path = path.lexically_normal();
  if (!has_glob(path.filename().string())) {
    if (has_glob(path.parent_path().string())) f.fail(key, "wildcards are allowed in the file name only: " + entry);
    std::error_code error;
    const auto status = std::filesystem::status(path, error);
    if (error && status.type() != std::filesystem::file_type::not_found)
      f.fail(key, "cannot open " + path.string() + ": " + error.message());
    if (!std::filesystem::exists(status)) f.fail(key, "file not found: " + path.string());
    if (!std::filesystem::is_regular_file(status)) f.fail(key, "not a regular file: " + path.string());
    return {path};
  }
  if (has_glob(path.parent_path().string())) f.fail(key, "wildcards are allowed in the file name only: " + entry);
  std::vector<std::filesystem::path> matches;
  // Error codes, not exceptions: an entry that is a link loop (or dangling) is no regular
  // file; a folder that cannot be opened has no match.
  std::error_code open_error, step_error;
  std::filesystem::directory_iterator item(path.parent_path(), open_error), end;
  for (; !open_error && !step_error && item != end; item.increment(step_error)) {
    std::error_code type_error;
    if (item->is_regular_file(type_error) && ::fnmatch(path.filename().c_str(), item->path().filename().c_str(), 0) == 0)
      matches.push_back(item->path());
  }
  if (step_error) f.fail(key, "cannot list " + path.parent_path().string() + ": " + step_error.message());
  if (matches.empty()) f.fail(key, "no file matches " + path.string());
  std::sort(matches.begin(), matches.end(), [](const auto& a, const auto& b) {
    return natural_less(a.filename().string(), b.filename().string());
  });
  return matches;
}

/// The file specs an entry's `key` names (a path, a glob or a list), each read as `spec` says.
std::vector<RecordFileSpec> read_file_specs(const Fields& f, std::string_view key, const RecordFileSpec& spec,
                                            const std::optional<RecordFormat>& format, const Study& s) {
  if (key == "file" && !f.node("file")->is_string()) f.fail("file", "expected a string (use `files` for a list)");
  std::vector<RecordFileSpec> specs;
  for (const auto& entry : f.texts(key)) {
    for (const auto& path : resolve_files(f, key, entry, s.base_dir)) {
      RecordFileSpec file_spec = spec;
      file_spec.path = path;
      file_spec.format = format.value_or(guess_record_format(path));
      if (file_spec.format == RecordFormat::kAt2 && file_spec.skip_rows > 0)
        f.fail("skip_rows", "applies to text records only (.AT2 files have their own header)");
      if (file_spec.column > 0 && file_spec.format != RecordFormat::kOneColumn)
        f.fail("column", "applies to one-column records only");
      if (file_spec.format == RecordFormat::kOneColumn) {
        if (!f.has("dt_s")) f.fail("dt_s", "one-column records need dt_s (the sample interval)");
        file_spec.dt_s = *f.number("dt_s");
        if (file_spec.dt_s <= 0.0) f.fail("dt_s", "must be positive");
      } else if (f.has("dt_s")) {
        f.fail("dt_s", "only applies to one-column records (the others carry their time step)");
      }
      specs.push_back(std::move(file_spec));
    }
  }
  return specs;
}

/// A component's azimuth key (az1_deg, az2_deg, strike_deg): an angle in degrees.
std::optional<double> read_angle(const Fields& f, std::string_view key) {
  const auto value = f.number(key);
  if (value && !(std::fabs(*value) <= 360.0))
    f.fail(key, "expected an angle in [-360, 360] degrees, got " + number_text(*value));
  return value;
}

/// [[records]] scale: the record's own factor (pcrf record select's fragment gives one per
/// record). It multiplies a scale axis' values; beside [intensity] it would cancel (every
/// record is scaled to each intensity by its own measure), so it is refused there.
std::optional<double> read_record_scale(const Fields& f, const Study& s) {
  const auto scale = f.number("scale");
  if (!scale) return std::nullopt;
  if (!(*scale > 0.0) || !std::isfinite(*scale)) f.fail("scale", "must be a positive number (a factor on the accelerations), got " + number_text(*scale));
  if (s.intensity)
    f.fail("scale", "[intensity] scales every record to each of its intensities, which would cancel a record's own "
                    "factor: drop [intensity] to run the records with these factors (times [axes] scale), or let "
                    "[selection] choose records and factors per stripe");
  return scale;
}

std::vector<RecordSource> read_record_entry(const Fields& f, const Study& s) {
  const int given =
      int(f.has("file")) + int(f.has("files")) + int(f.has("synthetic")) + int(f.has("h1")) + int(f.has("pulse"));
  if (given != 1) f.fail(f.has("h1") ? "h1" : "file", "give exactly one of file, files, h1, synthetic or pulse");
  std::vector<std::string> components{"h1 (the first horizontal)"};
  for (const auto& c : kStationComponents) components.emplace_back(c.key);
  std::vector<std::string> need_h1(components.begin() + 1, components.end());
  need_h1.insert(need_h1.end(), {"az1_deg", "az2_deg"});
  for (const auto& key : need_h1)
    if (f.has(key) && !f.has("h1")) f.fail(key, "a station's components are " + and_list(components) + ": give h1");
  if (f.has("pulse")) {
    for (const auto key : {"format", "units", "skip_rows", "column", "name", "strike_deg", "scale"})
      if (f.has(key)) f.fail(key, "does not apply to pulse records (each is named by its text)");
    return read_pulse_entry(f, s);
  }
  if (f.has("duration_s")) f.fail("duration_s", "only applies to pulse records");
  std::vector<RecordSource> sources;
  if (f.has("synthetic")) {
    for (const auto key : {"format", "units", "dt_s", "skip_rows", "column"})
      if (f.has(key)) f.fail(key, "only applies to record files");
    for (const auto& text : f.texts("synthetic")) {
      RecordSource source;
      source.name = source.synthetic = text;
      source.declared_at = f.where("synthetic");
      sources.push_back(std::move(source));
    }
  } else {
    const std::string_view key = f.has("file") ? "file" : f.has("h1") ? "h1" : "files";
    RecordFileSpec spec;
    try {
      if (f.has("units")) spec.unit = parse_accel_unit(*f.text("units"));
    } catch (const std::exception& e) {
      f.fail("units", e.what());
    }
    if (const auto skip = f.integer("skip_rows")) {
      if (*skip < 0) f.fail("skip_rows", "must not be negative (got " + std::to_string(*skip) + ")");
      spec.skip_rows = static_cast<std::size_t>(*skip);
    }
    if (const auto column = f.integer("column")) {
      if (*column < 1) f.fail("column", "must be 1 or more (got " + std::to_string(*column) + ")");
      spec.column = static_cast<std::size_t>(*column);
    }
    std::optional<RecordFormat> format;
    try {
      if (f.has("format")) format = parse_record_format(*f.text("format"));
    } catch (const std::exception& e) {
      f.fail("format", e.what());
    }
    const auto firsts = read_file_specs(f, key, spec, format, s);
    // The other components pair with the first ones in the order their names sort.
    PerComponent<std::vector<RecordFileSpec>> others;
    for (std::size_t c = 0; c < kComponentCount; ++c) {
      const std::string_view other = kStationComponents[c].key;
      if (!f.has(other)) continue;
      others[c] = read_file_specs(f, other, spec, format, s);
      if (others[c].size() != firsts.size())
        f.fail(other, std::to_string(others[c].size()) + " files for " + std::to_string(firsts.size()) +
                          " first components (h1): each station needs one of each");
    }
    for (std::size_t i = 0; i < firsts.size(); ++i) {
      RecordSource source;
      source.name = record_name(firsts[i]);
      source.file = firsts[i];
      source.declared_at = f.where(key);
      for (std::size_t c = 0; c < kComponentCount; ++c)
        if (!others[c].empty()) source.*component_members<RecordSource>()[c] = others[c][i];
      source.az1_deg = read_angle(f, "az1_deg");
      source.az2_deg = read_angle(f, "az2_deg");
      source.strike_deg = read_angle(f, "strike_deg");
      sources.push_back(std::move(source));
    }
  }
  if (f.has("strike_deg") && f.has("synthetic")) f.fail("strike_deg", "only applies to record files");
  if (const auto scale = read_record_scale(f, s))
    for (auto& source : sources) source.scale = *scale;
  if (f.has("name")) {
    if (sources.size() != 1) f.fail("name", "only an entry that gives exactly one record can name it");
    sources.front().name = *f.text("name");
    if (sources.front().name.empty()) f.fail("name", "must not be empty");
  }
  return sources;
}

/// What the study's incidence axis and measure ask of a record entry's stations.
void check_station_needs(const Fields& f, const Study& s, const RecordSource& source) {
  const char* first = f.has("h1") ? "h1" : f.has("file") ? "file" : f.has("files") ? "files" : "synthetic";
  if (!s.incidence_deg.empty() && !source.h2)
    f.fail(f.has("h1") ? "h2" : first, "the study has an incidence axis: record \"" + source.name +
                                           "\" needs its second horizontal component (h1 and h2)");
  if (s.incidence_reference != "north" && !source.strike_deg)
    f.fail(f.has("h1") ? "h1" : first, "incidence = \"" + s.incidence_reference + "\" needs the fault's strike: record \"" +
                                           source.name + "\" has no strike_deg");
  if (s.intensity && rotd_percentile(s.intensity->measure) > 0 && !source.h2)
    f.fail(f.has("h1") ? "h1" : first, "intensity measure " + to_string(s.intensity->measure) + " is a measure of a pair: record \"" +
                                           source.name + "\" needs its second horizontal component (h1 and h2)");
}

void check_pulse_axes_used(const Study& s) {
  const bool pulses = std::any_of(s.records.begin(), s.records.end(), [](const RecordSource& r) { return !r.pulse_shape.empty(); });
  if (!pulses && !s.pulse_axes.empty())
    throw UserError(s.pulse_axes.front().declared_at, "needs a [[records]] pulse entry (pulse = \"ricker\", …) to vary");
}

void read_records(const Fields& top, Study& s) {
  if (s.selection) {
    if (top.has("records"))
      top.fail("records", "[selection] chooses each stripe's records from its library: give no [[records]]");
    return;
  }
  const auto* array = top.array("records");
  if (array == nullptr || array->empty())
    top.fail("records", "a study needs at least one [[records]] table (file, files, h1 or synthetic)");
  std::set<std::string> names;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const std::vector<std::string> path{"records", key_index(i)};
    const auto* table = (*array)[i].as_table();
    if (table == nullptr) Fields::fail_at(s.file, &(*array)[i], path, "expected a table ([[records]])");
    std::vector<std::string_view> keys{"file", "files", "synthetic", "pulse", "format", "units", "dt_s", "duration_s",
                                       "skip_rows", "column", "name", "h1", "scale"};
    for (const auto& c : kStationComponents) keys.push_back(c.key);
    keys.insert(keys.end(), {"az1_deg", "az2_deg", "strike_deg"});
    Fields f(*table, path, s.file, keys);
    for (auto& source : read_record_entry(f, s)) {
      if (!names.insert(source.name).second)
        f.fail(f.has("synthetic") ? "synthetic" : (f.has("file") ? "file" : f.has("h1") ? "h1" : "files"),
               "two records are named \"" + source.name + "\" (give one a `name`)");
      check_station_needs(f, s, source);
      s.records.push_back(std::move(source));
    }
  }
}

// ---- physics, solver, outputs, run -------------------------------------------------------

/// The default metrics: every one, the verdict check's only when it runs.
std::vector<std::string> metric_names(bool verdict_check) {
  std::vector<std::string> names;
  for (const auto& m : all_metrics())
    if (verdict_check || !m.needs_verdict_check) names.emplace_back(m.name);
  return names;
}

void read_metrics(const Fields& f, Study& s) {
  if (!f.has("metrics")) return;
  const auto names = f.texts("metrics");
  std::vector<std::string_view> known;
  for (const auto& m : all_metrics()) known.push_back(m.name);
  s.metrics.clear();
  for (const auto& name : names) {
    if (find_metric(name) == nullptr) {
      for (const auto& m : all_metrics())
        if (!m.former_name.empty() && m.former_name == name)
          f.fail("metrics", "metric \"" + name + "\" is now \"" + std::string(m.name) + "\": " + std::string(m.description));
      const auto hint = detail::closest_word(name, known);
      f.fail("metrics", "unknown metric \"" + name + "\"" + (hint.empty() ? "" : " (did you mean \"" + hint + "\"?)"));
    }
    if (std::find(s.metrics.begin(), s.metrics.end(), name) != s.metrics.end())
      f.fail("metrics", "metric \"" + name + "\" is listed twice");
    if (find_metric(name)->needs_verdict_check && !s.solver.verdict_check)
      f.fail("metrics", "metric \"" + name + "\" needs [solver] verdict_check = true");
    s.metrics.push_back(name);
  }
}

/// The cube's rule for a history group's name (one rule: journals are checked by it too).
bool valid_group_name(const std::string& name) { return cube::valid_group_name(name); }

void read_histories(const Fields& outputs, Study& s) {
  const auto* array = outputs.array("histories");
  if (array == nullptr) return;
  std::set<std::string> labels;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const std::vector<std::string> path{"outputs", "histories", key_index(i)};
    const auto* table = (*array)[i].as_table();
    if (table == nullptr) Fields::fail_at(s.file, &(*array)[i], path, "expected a table ([[outputs.histories]])");
    Fields f(*table, path, s.file, with_parameter_keys({"label", "record", "scale", "intensity", "case", "dt_s", "incidence_deg"}));
    HistoryRequest request;
    request.declared_at = f.where("label");
    if (!f.has("label")) f.fail("label", "a history needs a label (its group name)");
    request.label = *f.text("label");
    if (!valid_group_name(request.label)) f.fail("label", "use letters, digits, '_', '-' and '.' only (not . or ..), at most 255");
    if (!labels.insert(request.label).second) f.fail("label", "\"" + request.label + "\" is used twice");
    request.record = f.text("record");
    const char* level_key = s.intensity ? "intensity" : "scale";
    for (const char* key : {"scale", "intensity"})
      if (f.has(key) && std::string_view(key) != level_key)
        f.fail(key, std::string("this study's second axis is `") + level_key + "`");
    request.scale = f.number(level_key);
    request.incidence_deg = f.number("incidence_deg");
    if (const auto dt = f.number("dt_s")) {
      if (!(*dt > 0.0)) f.fail("dt_s", "the output interval must be a positive number of seconds");
      request.dt_s = *dt;
    }
    for (auto key : with_parameter_keys({"case"}))
      if (f.has(key))
        if (const auto problem = s.plan->history_key_problem(key); !problem.empty()) f.fail(key, problem);
    request.case_label = f.text("case");
    detail::refuse_other_scenes(f, *s.model);
    for (const auto& parameter : s.model->parameters) request.parameters.push_back(f.number(parameter.name));
    s.histories.push_back(std::move(request));
  }
}

void read_outputs(const Fields& top, Study& s) {
  s.metrics = metric_names(s.solver.verdict_check);
  const auto* table = top.subtable("outputs");
  if (table == nullptr) return;
  Fields f(*table, {"outputs"}, s.file, {"metrics", "histories", "record_pulses"});
  read_metrics(f, s);
  read_histories(f, s);
  s.record_pulses = f.flag("record_pulses").value_or(false);
}

}  // namespace

Where Study::where(const std::string& table_key) const {
  if (const auto given = given_at.find(table_key); given != given_at.end()) return given->second;
  Where where{{}, file, 0};
  for (std::size_t from = 0, dot; from <= table_key.size(); from = dot + 1) {
    dot = std::min(table_key.find('.', from), table_key.size());
    where.keys.push_back(table_key.substr(from, dot - from));
  }
  // A key not given: its table's line, when the table is.
  if (const auto table = given_at.find(where.keys.front()); table != given_at.end() && where.keys.size() > 1)
    where.line = table->second.line;
  return where;
}

Study parse_study(const std::string& text, const std::string& file, const std::filesystem::path& base_dir) {
  toml::table root;
  detail::refuse_deep_keys(text, file);  // before toml++, whose parser would overflow the stack
  try {
    root = toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    throw UserError(Where{{}, file, static_cast<int>(e.source().begin.line)}, "not valid TOML: " + std::string(e.description()));
  }
  return parse_study_table(root, text, file, base_dir);
}

Study parse_study_table(const toml::table& root, const std::string& text, const std::string& file,
                        const std::filesystem::path& base_dir) {
  Study s;
  s.file = file;
  s.base_dir = base_dir;
  s.text = text;
  Fields top(root, {}, file,
             {"study", "plan", "records", "axes", "frame", "base", "cases", intensity_settings().name, ida_settings().name,
              kSelectionTable, physics_settings().name, solver_settings().name, "outputs", run_settings().name});
  read_study_section(top, s);
  read_base(top, s);  // before the plan: its frames start from the base point
  read_intensity(top, s);  // before axes: it decides what the second axis is
  read_ida(top, s);
  read_axes(top, s);  // and the plan
  read_selection(top, s);  // after the stripes and the incidence axis: it makes the records
  read_records(top, s);
  check_pulse_axes_used(s);
  detail::read_setting_table(top, physics_settings(), s.physics, s.given_at);
  detail::read_setting_table(top, solver_settings(), s.solver, s.given_at);
  read_outputs(top, s);
  check_ida_outputs(s);
  detail::read_setting_table(top, run_settings(), s.run, s.given_at);
  return s;
}

std::string read_text_file(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw UserError(Where{{}, file.string(), 0}, std::string("cannot read the file: ") + std::strerror(errno));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

Study load_study(const std::filesystem::path& file) {
  std::error_code error;
  const auto status = std::filesystem::status(file, error);
  if (error && status.type() != std::filesystem::file_type::not_found)
    throw UserError(Where{{}, file.string(), 0}, "cannot open: " + error.message());
  if (!std::filesystem::exists(status)) throw UserError(Where{{}, file.string(), 0}, "no such study file");
  if (!std::filesystem::is_regular_file(status)) throw UserError(Where{{}, file.string(), 0}, "not a regular file");
  auto base_dir = std::filesystem::absolute(file).parent_path();
  return parse_study(read_text_file(file), file.string(), base_dir);
}

}  // namespace pcrf::study

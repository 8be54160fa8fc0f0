// Mapping of a study onto its result cube (see study_cube.hpp).
#include "pcrf/run/study_cube.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <ctime>
#include <type_traits>
#include <variant>

#include "pcrf/cube/chunk_grid.hpp"
#include "pcrf/excitation/station_pulse.hpp"
#include "pcrf/metrics/case_result.hpp"
#include "pcrf/model/frame_properties.hpp"
#include "pcrf/record/pulses.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"
#include "pcrf/run/result_row.hpp"
#include "pcrf/version.hpp"

namespace pcrf::run {
// A run runs a study: its values (pcrf::study) are this library's vocabulary.
using namespace pcrf::study;
namespace {

using cube::Attribute;
namespace names = schema;

std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return buffer;
}

void add_components(const Study& study, RecordCache& records, cube::CubeLayout& layout);

/// Records given their own factor ([[records]] scale): `record_scale` along `record` (the
/// factor before the scale axis' value). Nothing when every record has none.
void add_record_scales(const Study& study, cube::CubeLayout& layout) {
  if (std::all_of(study.records.begin(), study.records.end(), [](const RecordSource& r) { return r.scale == 1.0; })) return;
  std::vector<double> scales;
  for (const auto& r : study.records) scales.push_back(r.scale);
  layout.coordinates.push_back(number_coordinate("record_scale", names::kRecord, "1",
                                                 "the record's own factor on its accelerations ([[records]] scale), "
                                                 "before the scale axis' value",
                                                 scales));
}

/// The record axis (names, sources, titles), then the level axis' coordinates along it and
/// along its own dimensions (level_axis.hpp).
void add_record_and_level(const Study& study, const CaseSpace& space, RecordCache& records,
                          cube::CubeLayout& layout) {
  auto& coords = layout.coordinates;
  if (study.selection) {  // `record` holds a stripe's slots; the level axis names each stripe's records
    coords.push_back(text_coordinate(names::kRecord, names::kRecord,
                                     "slot of a stripe's selected set (selected_record_<stripe> names its record)",
                                     space.record_names()));
    space.level_axis().add_leading(layout, records);
    return;
  }
  coords.push_back(text_coordinate(names::kRecord, names::kRecord, "ground motion record", space.record_names()));
  add_record_scales(study, layout);
  std::vector<std::string> sources, titles;
  for (std::size_t r = 0; r < study.records.size(); ++r) {
    sources.push_back(study.records[r].describe());
    titles.push_back(records.title(r));
  }
  coords.push_back(text_coordinate(names::kRecordSource, names::kRecord, "where the record comes from", sources));
  coords.push_back(text_coordinate(names::kRecordTitle, names::kRecord, "the record's own title (AT2 header)", titles));
  add_components(study, records, layout);
  space.level_axis().add_leading(layout, records);
}

/// Records with components: the azimuths each horizontal was recorded along (from its
/// header or given) and the fault's strike, NaN where there is none; the component files are
/// in record_source. Nothing for studies of single records (their cubes as they were).
void add_components(const Study& study, RecordCache& records, cube::CubeLayout& layout) {
  const bool components = std::any_of(study.records.begin(), study.records.end(),
                                      [](const RecordSource& r) { return r.has_components() || r.strike_deg; });
  if (!components) return;
  const double none = std::nan("");
  std::vector<double> az1, az2, strike;
  for (std::size_t r = 0; r < study.records.size(); ++r) {
    const StationRecord& station = records.station(r);
    az1.push_back(station.az1_deg.value_or(none));
    az2.push_back(station.az2_deg.value_or(none));
    strike.push_back(study.records[r].strike_deg.value_or(none));
  }
  auto& coords = layout.coordinates;
  coords.push_back(number_coordinate("record_azimuth_h1_deg", names::kRecord, "degree",
                                     "azimuth of the first horizontal component, clockwise from north", az1));
  coords.push_back(number_coordinate("record_azimuth_h2_deg", names::kRecord, "degree",
                                     "azimuth of the second horizontal component, clockwise from north", az2));
  coords.push_back(number_coordinate("record_strike_deg", names::kRecord, "degree", "strike of the fault, clockwise from north", strike));
}

/// The incidence axis: its values as the study gives them, and where they count from
/// another direction than north, each record's frame azimuth.
void add_incidence(const Study& study, const CaseSpace& space, cube::CubeLayout& layout) {
  if (space.incidences().empty()) return;
  const bool north = study.incidence_reference == "north";
  layout.coordinates.push_back(number_coordinate(
      names::kIncidenceDeg, names::kIncidenceDeg, "degree",
      north ? "azimuth of the frame's plane, clockwise from north"
            : "angle of the frame's plane from the record's " + study.incidence_reference + " direction, clockwise",
      space.incidences()));
  if (north) return;
  cube::SideVariable azimuth{names::kFrameAzimuthDeg, "degree", "azimuth of the frame's plane, clockwise from north",
                             {names::kRecord, names::kIncidenceDeg}, {}};
  for (std::size_t r = 0; r < space.record_names().size(); ++r)
    for (double incidence : space.incidences()) azimuth.values.push_back(space.frame_azimuth_deg(r, incidence));
  layout.side_variables.push_back(std::move(azimuth));
}

/// Each record's velocity pulse ([outputs] record_pulses): identified in recorded and
/// synthetic motions (excitation/station_pulse.hpp), given for [[records]] pulse entries
/// (pulse-like by construction, T_p their period).
struct RecordPulse {
  bool pulse_like = false;
  std::string method;                 ///< "baker-2007", "shahi-baker-2014", or "synthetic-pulse"
  double period_s = std::nan("");     ///< T_p; NaN when not pulse-like, so that ω_p/p is NaN too
  double azimuth_deg = std::nan("");  ///< the pulse's azimuth (pairs); NaN else
};

/// The T_p of a [[records]] pulse entry: its [axes] pulse_period_s value, else the default.
double synthetic_pulse_period_s(const RecordSource& r) {
  const auto it = std::find_if(r.pulse_values.begin(), r.pulse_values.end(),
                               [](const auto& kv) { return kv.first == names::kPulsePeriod; });
  return it == r.pulse_values.end() ? PulseSpec{}.period_s : it->second;
}

/// Identifies every record's pulse. \throws UserError at the record's [[records]] entry when
/// its motion cannot be classified (a pair without azimuths, a record too short).
std::vector<RecordPulse> identify_record_pulses(const Study& study, RecordCache& records) {
  std::vector<RecordPulse> pulses;
  for (std::size_t r = 0; r < study.records.size(); ++r) {
    const RecordSource& source = study.records[r];
    RecordPulse p;
    if (!source.pulse_shape.empty()) {
      p = {true, "synthetic-pulse", synthetic_pulse_period_s(source), std::nan("")};
    } else {
      const std::string context = "[outputs] record_pulses: record \"" + source.name + "\": ";
      const StationRecord& station = records.station(r);
      if (station.h2 && !(station.az1_deg && station.az2_deg))
        throw UserError(source.declared_at, context + "the azimuths of its two horizontals are not known (their files state "
                                                      "none): give az1_deg and az2_deg");
      PulseClassification c;
      try {
        c = classify_station_pulse(station);
      } catch (const UserError& e) {
        throw UserError(source.declared_at, context + e.problem(Dialect::kStudy));
      }
      p.pulse_like = c.pulse_like;
      p.method = to_string(c.method);
      if (c.pulse_like) {
        p.period_s = c.period_s;
        if (c.method == PulseMethod::kShahiBaker2014) p.azimuth_deg = c.candidates[c.decided_by].azimuth_deg;
      }
    }
    pulses.push_back(std::move(p));
  }
  return pulses;
}

/// Pulse records ([[records]] pulse): their shape and [axes] pulse values along `record` (""
/// and NaN for other records); each frame's frequency parameter p and uplift threshold over
/// the frame dimensions, and ω_p/p = 2π/(T_p p) over record and frame, so that spectra of
/// different frames share axes (a_p over the uplift threshold: the intensity over
/// uplift_threshold_g). With [outputs] record_pulses, every record's identified pulse as well
/// (record_pulse_like, record_pulse_method, pulse_period_s, record_pulse_azimuth_deg): ω_p/p for real records, NaN
/// where a record is not pulse-like.
void add_pulse_coordinates(const Study& study, const CaseSpace& space, RecordCache& records, cube::CubeLayout& layout) {
  if (!study.record_pulses && study.pulse_axes.empty() &&
      std::none_of(study.records.begin(), study.records.end(), [](const RecordSource& r) { return !r.pulse_shape.empty(); }))
    return;
  std::vector<std::string> shapes;
  for (const auto& r : study.records) shapes.push_back(r.pulse_shape);
  layout.coordinates.push_back(text_coordinate(names::kPulseShape, names::kRecord, "pulse of the record (empty: not a pulse)", shapes));
  std::vector<double> periods;
  for (const auto& axis : study.pulse_axes) {
    if (study.record_pulses && axis.key == names::kPulsePeriod) continue;  // written below, with every record's
    std::vector<double> values;
    for (const auto& r : study.records) {
      const auto it = std::find_if(r.pulse_values.begin(), r.pulse_values.end(), [&](const auto& kv) { return kv.first == axis.key; });
      values.push_back(it == r.pulse_values.end() ? std::nan("") : it->second);
    }
    const auto units = axis.key.substr(axis.key.rfind('_') + 1);
    layout.coordinates.push_back(number_coordinate(axis.key, names::kRecord,
                                                   units == "s" ? "s" : units == "g" ? "g" : units == "deg" ? "degree" : "1",
                                                   "pulse parameter " + axis.key.substr(6) + " (record/pulses.hpp)", values));
    if (axis.key == names::kPulsePeriod) periods = values;
  }
  if (study.record_pulses) {
    const auto pulses = identify_record_pulses(study, records);
    std::vector<double> like, azimuths;
    std::vector<std::string> methods;
    periods.clear();
    for (const auto& p : pulses) {
      like.push_back(p.pulse_like ? 1.0 : 0.0);
      methods.push_back(p.method);
      periods.push_back(p.period_s);
      azimuths.push_back(p.azimuth_deg);
    }
    auto& coords = layout.coordinates;
    coords.push_back(number_coordinate(names::kPulseLike, names::kRecord, "",
                                       "1: the record carries a strong velocity pulse (by pulse_method), 0: not", like));
    coords.back().is_index = true;  // 0 or 1, stored as an integer
    coords.push_back(text_coordinate(names::kPulseMethod, names::kRecord,
                                     "how the pulse was found: baker-2007 (one component), shahi-baker-2014 (a pair), "
                                     "synthetic-pulse ([[records]] pulse)",
                                     methods));
    coords.push_back(number_coordinate(names::kPulsePeriod, names::kRecord, "s",
                                       "pulse period T_p (NaN: not pulse-like; record/pulse_identification.hpp)", periods));
    coords.push_back(number_coordinate(names::kPulseAzimuth, names::kRecord, "degree",
                                       "azimuth of the identified pulse, clockwise from north (pairs; NaN else)", azimuths));
  }
  std::vector<std::string> frame_dimensions;
  for (const auto& d : space.plan().dimensions()) frame_dimensions.push_back(d.name);
  cube::SideVariable p{names::kFrequencyParameter, "rad/s", "frequency parameter p of the frame (docs/frequency_parameter.md)",
                       frame_dimensions, {}};
  cube::SideVariable threshold{names::kUpliftThreshold, "g", "ground acceleration that uplifts the frame at rest",
                               frame_dimensions, {}};
  p.values.reserve(static_cast<std::size_t>(space.distinct_frames()));
  threshold.values.reserve(static_cast<std::size_t>(space.distinct_frames()));
  space.for_each_frame([&](const SceneSpec& point) {
    double p_rad_s = std::nan(""), threshold_g = std::nan("");
    try {
      const auto scene = point.make();
      const auto properties = frame_properties(*scene, study.physics.fracture_strain, 2);
      p_rad_s = properties.frequency_parameter_rad_s;
      threshold_g = properties.uplift_threshold_g;
    } catch (const std::invalid_argument&) {  // an invalid frame: its cases say so
    }
    p.values.push_back(p_rad_s);
    threshold.values.push_back(threshold_g);
  });
  if (!periods.empty()) {
    std::vector<std::string> dimensions{names::kRecord};
    dimensions.insert(dimensions.end(), frame_dimensions.begin(), frame_dimensions.end());
    cube::SideVariable ratio{names::kOmegaOverP, "1", "pulse frequency over the frame's frequency parameter, 2 pi / (T_p p)",
                             dimensions, {}};
    for (double t : periods)
      for (double frame_p : p.values) ratio.values.push_back(2.0 * std::numbers::pi / (t * frame_p));
    layout.side_variables.push_back(std::move(ratio));
  }
  layout.side_variables.push_back(std::move(p));
  layout.side_variables.push_back(std::move(threshold));
}

/// One attribute "<table>_<key>" per setting: numbers as float64, integers and flags as
/// int64 (flags 0/1), choices as text.
template <class Target>
void add_settings(std::vector<Attribute>& attributes, const SettingTable<Target>& table, const Target& values) {
  for (const auto& setting : table.settings) {
    const std::string name = names::setting_attribute(table.name, setting.key);
    std::visit(
        [&](const auto& v) {
          using V = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<V, bool>)
            attributes.push_back({name, static_cast<std::int64_t>(v ? 1 : 0)});
          else
            attributes.push_back({name, v});
        },
        setting.get(values));
  }
}

/// `mixed_scenes`: the frames are of several models (a `scene_model` coordinate says which).
std::vector<Attribute> global_attributes(const Study& study, const std::string& fingerprint, bool mixed_scenes) {
  std::vector<Attribute> a{
      {"Conventions", std::string("CF-1.8")},
      {"title", "pcrf study " + study.name},
      {"source", std::string("pcrf ") + kVersion},
      {names::kPcrfVersion, std::string(kVersion)},
      {"date_created", utc_now()},
      {names::kStudyName, study.name},
      {"study_description", study.description},
      {"study_file", study.file},
      {"study_text", study.text},
      {cube::kFingerprintName, fingerprint},
      {names::kPlan, std::string(study.plan->name())},
  };
  if (study.intensity) add_settings(a, intensity_settings(), *study.intensity);
  if (study.hazard_stripes) a.push_back({names::kIntensityHazard, study.hazard_stripes->hazard});
  if (const auto& sel = study.selection) {  // Jayaram, Lin & Baker (2011); Baker & Lee (2018)
    a.push_back({"selection_library", sel->library});
    a.push_back({"selection_kind", sel->settings.kind});
    a.push_back({"selection_count", static_cast<std::int64_t>(sel->settings.count)});
    a.push_back({"selection_scale_min", sel->settings.scale_min});
    a.push_back({"selection_scale_max", sel->settings.scale_max});
    a.push_back({"selection_seed", static_cast<std::int64_t>(sel->settings.seed)});
    a.push_back({"selection_trials", static_cast<std::int64_t>(sel->settings.trials)});
    a.push_back({"selection_loops", static_cast<std::int64_t>(sel->settings.loops)});
  }
  if (study.ida) add_settings(a, ida_settings(), *study.ida);
  add_settings(a, physics_settings(), study.physics);
  add_settings(a, solver_settings(), study.solver);
  const auto& parameters = study.model->parameters;
  if (study.model != &default_scene_model() && !mixed_scenes) a.push_back({names::kSceneModel, std::string(study.model->name)});
  for (std::size_t k = 0; k < parameters.size(); ++k)  // set once for every case: h_m, m_c_kg
    if (!parameters[k].axis) a.push_back({names::frame_attribute(parameters[k].name), study.base[k]});
  a.push_back({"gravity_m_s2", kGravity_m_s2});
  for (std::size_t k = 0; k < parameters.size(); ++k)
    if (parameters[k].axis) a.push_back({names::base_attribute(parameters[k].name), study.base[k]});
  return a;
}

}  // namespace

cube::CubeLayout make_cube_layout(const Study& study, const CaseSpace& space, RecordCache& records,
                                  const std::string& fingerprint) {
  cube::CubeLayout layout;
  for (std::size_t d = 0; d < space.shape().size(); ++d)
    layout.dimensions.push_back({space.dimension_names()[d], space.shape()[d]});
  add_record_and_level(study, space, records, layout);
  add_incidence(study, space, layout);
  add_pulse_coordinates(study, space, records, layout);
  for (auto& c : space.plan().coordinates()) layout.coordinates.push_back(std::move(c));
  layout.metrics = ResultColumns(study).variables();
  const auto& names = space.dimension_names();
  const auto trailing = static_cast<std::ptrdiff_t>(space.level_axis().trailing_dimensions().size());
  space.level_axis().add_trailing(layout, {names.begin(), names.end() - trailing});
  for (CaseStatus status : all_final_statuses())
    layout.status_flags.push_back({static_cast<std::int8_t>(status), std::string(status_name(status))});
  layout.attributes = global_attributes(study, fingerprint, layout.find_coordinate(names::kSceneModel) != nullptr);
  // Chunks hold whole groups of frames (a Saltelli base sample) where they cut the frame axis.
  layout.chunk_shape = cube::ChunkGrid(space.shape(), cube::kChunkCases, space.chunk_multiples()).chunk_shape();
  return layout;
}

cube::HistoryTable make_history_table(const std::string& label, std::int64_t case_index, const Study& study,
                                      const CaseSpace& space, const std::vector<HistorySample>& samples) {
  cube::HistoryTable table;
  table.name = label;
  for (const auto& c : history_columns()) {
    table.columns.push_back({std::string(c.name), std::string(c.units), std::string(c.long_name)});
    std::vector<double> values;
    values.reserve(samples.size());
    for (const auto& s : samples) values.push_back(s.*c.member);
    table.values.push_back(std::move(values));
  }
  const CaseSpec spec = space.case_at(case_index);
  table.attributes = {{"case_index", static_cast<std::int64_t>(case_index)},
                      {names::kRecord, study.records[spec.record].name},
                      {space.dimension_names()[1], spec.level}};
  if (spec.factor) table.attributes.push_back({names::kScaleFactor, *spec.factor});  // [selection]: the record's own factor
  const auto& parameters = spec.frame.model->parameters;
  if (spec.frame.model != study.model) table.attributes.push_back({names::kSceneModel, std::string(spec.frame.model->name)});
  for (std::size_t k = 0; k < parameters.size(); ++k)
    if (parameters[k].axis) table.attributes.push_back({std::string(parameters[k].name), spec.frame.values[k]});
  return table;
}

}  // namespace pcrf::run

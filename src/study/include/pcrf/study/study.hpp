/// \file study.hpp
/// \brief A parametric study as a study file defines it: the record and scale axes, the
/// scene and the plan over its parameters, physics and solver settings, and what to keep.
///
/// A Study is plain data; study_parser.hpp makes one from TOML and checks every value that
/// can be checked alone. studies/README.md documents every key.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <cstddef>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pcrf/model/frame.hpp"
#include "pcrf/model/parameters.hpp"
#include "pcrf/model/scene_catalog.hpp"
#include "pcrf/ida/ida_search.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/record/selection.hpp"
#include "pcrf/setting.hpp"
#include "pcrf/solver/settings.hpp"
#include "pcrf/study/record_source.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf::study {

class Plan;  // plan.hpp: how the frames are laid out

/// A case whose time history is wanted. Each given selector must match an axis value;
/// every axis with more than one value must be given, so that exactly one case matches.
struct HistoryRequest {
  std::string label;                      ///< group name under /histories
  std::optional<std::string> record;      ///< record axis value (its name)
  std::optional<double> scale;
  std::optional<double> incidence_deg;    ///< incidence axis value (as the study gives it)
  std::optional<std::string> case_label;  ///< plans with a `case` dimension
  std::vector<std::optional<double>> parameters;  ///< plans with parameter dimensions (grid), by the scene's table
  double dt_s = 0.0;                      ///< output interval [s]; 0: the record's dt
  Where declared_at;                      ///< its `label`: the entry, file and line, for messages
};

/// Where a run's cases are solved: the CPU engine, or the case kernel on a CUDA device
/// (docs/gpu.md). The answers are the same; only the speed differs.
enum class Device : std::int8_t { kCpu, kGpu };
inline constexpr std::array<EnumName<Device>, 2> kDeviceNames{{{Device::kCpu, "cpu"}, {Device::kGpu, "gpu"}}};
inline std::string device_name(Device device) { return name_of(kDeviceNames, device); }
inline Device parse_device(const std::string& text) { return parse_name(kDeviceNames, text, "device"); }

/// How a run behaves; not part of what the study computes (not in its fingerprint).
/// Described in run_settings().
struct RunOptions {
  double flush_interval_s = 30.0;
  double progress_interval_s = 5.0;
  std::size_t batch_size = 0;
  std::size_t lanes = 8;  ///< cases of one excitation integrated together (docs/batches.md)
  bool warnings_as_errors = false;  ///< a record warning (implausible PGA, units, PGV/PGA) stops the study
  Device device = Device::kCpu;     ///< where the cases are solved (docs/gpu.md)
};

/// The [run] table; `pcrf study` also takes each key as a flag (`--flush-interval-s`). Here,
/// beside the members it describes: a new [run] setting is its member, its row and its use.
inline const SettingTable<RunOptions>& run_settings() {
  using R = RunOptions;
  static const SettingTable<RunOptions> table = [] {
    SettingTable<RunOptions> t{"run", RunOptions{}, {}};
    auto& s = t.settings;
    s.push_back(number_setting("flush_interval_s", &R::flush_interval_s, "s", Bound::kPositive,
                               "the cube is written to disk at least this often; a killed run loses at most that much work"));
    s.back().aliases = {"--flush-interval"};
    s.push_back(number_setting("progress_interval_s", &R::progress_interval_s, "s", Bound::kNonNegative,
                               "progress line period on stderr; 0: only the closing line"));
    s.back().aliases = {"--progress-interval"};
    s.push_back(integer_setting("batch_size", &R::batch_size, Bound::kNonNegative, "cases per hand-out; 0: guided"));
    s.push_back(integer_setting("lanes", &R::lanes, Bound::kAtLeastOne,
                                "cases under one record a worker integrates together in lockstep vector lanes "
                                "(dopri5 without verdict check; docs/batches.md); 1: one case at a time"));
    s.push_back(flag_setting("warnings_as_errors", &R::warnings_as_errors,
                             "a record whose PGA, PGV/PGA or units look wrong stops the study (exit code 2) "
                             "instead of a warning"));
    s.push_back(choice_setting("device", &R::device, values_of(kDeviceNames), &device_name, &parse_device,
                               "where the cases are solved: the CPU engine, or the case kernel on a CUDA device "
                               "(a build with PCRF_CUDA and a usable device; each rank takes large groups of one "
                               "record; docs/gpu.md)"));
    for (auto& setting : s) setting.in_fingerprint = false;  // how, not what
    return t;
  }();
  return table;
}

/// The [ida] table: an adaptive search of each record's collapse intensity, per frame.
/// Described in ida_settings(); the search itself is ida::IdaSearch.
struct IdaOptions {
  double start = 0.0;
  double step = 0.0;
  double step_factor = ida::kDefaultStepFactor;
  double resolution = 0.02;
  double max_intensity = 0.0;
  long max_runs = 16;
  std::string collapse = "tendon_fracture,overturned";
  double theta_limit_rad = 0.0;

  ida::IdaSearchSettings search() const {
    return {start, step, step_factor, resolution, max_intensity, static_cast<int>(max_runs)};
  }
};
const SettingTable<IdaOptions>& ida_settings();

struct Study {
  std::string name;
  std::string description;
  std::string file;                 ///< the study file as given (messages, attributes)
  std::filesystem::path base_dir;   ///< relative record paths resolve against this
  std::string text;                 ///< the study file's text (stored in the cube)

  /// The frames and how they are laid out ([plan], the parameter keys of [axes], [[cases]]);
  /// parse_study always sets it.
  std::shared_ptr<const Plan> plan;

  std::vector<RecordSource> records;
  /// [axes] pulse_period_s, pulse_amplitude_g, …: each [[records]] pulse entry becomes one
  /// record per combination of these values (in this order, the last varying fastest).
  struct PulseAxis {
    std::string key;             ///< "pulse_period_s"
    std::vector<double> values;
    Where declared_at;           ///< the [axes] key, file and line
  };
  std::vector<PulseAxis> pulse_axes;
  /// The values of the second axis: scale factors of the records (`scale`), or, when
  /// `intensity` is set, intensities in the measure's units (each record gets its own factor
  /// intensity / IM(record)).
  std::vector<double> levels{1.0};
  std::optional<IntensitySpec> intensity;  ///< the [intensity] table, when given
  /// [intensity] hazard and return_periods_yr: hazard-consistent stripes (multiple-stripe
  /// analysis). `levels` are then the intensities whose mean annual rate of exceedance on the
  /// site's hazard curve is 1/T for each return period T, interpolated log-log
  /// (risk::HazardCurve::intensity_at_rate), in the order the return periods are given.
  struct HazardStripes {
    std::string hazard;                     ///< the hazard file as the study gives it
    std::filesystem::path file;             ///< resolved against base_dir
    std::vector<double> return_periods_yr;  ///< T [yr], one per level
    std::vector<UserError> warnings;        ///< the curve's post::hazard_warnings, for the study's check
  };
  std::optional<HazardStripes> hazard_stripes;
  /// [selection]: records selected per stripe of hazard-consistent stripes, each stripe's set
  /// from a library (pcrf record spectra's table) to its own target spectrum (one per return
  /// period), by select_records (Jayaram, Lin & Baker 2011; Baker & Lee 2018). `records` then
  /// holds every record some stripe uses (each once, in the order first selected), and the
  /// cube's `record` dimension is the `count` slots of a stripe's set: the case (slot k,
  /// stripe j) runs record stripes[j].records[k] scaled by stripes[j].scales[k].
  struct StripeSelection {
    std::string library;                 ///< the library table as the study gives it
    std::filesystem::path library_file;  ///< resolved against base_dir
    SelectionSettings settings;
    struct Stripe {
      std::string target;                ///< its target file as the study gives it
      std::vector<std::size_t> records;  ///< per slot: index into Study::records
      std::vector<double> scales;        ///< per slot: the selection's scale factor
      SelectionResult fit;               ///< the set's fit to the target
      double conditioning_sa_g = 0.0;    ///< the target's exp(mean_ln_sa) at the measure's period [g]
      int conditioning_line = 0;         ///< the target file's line of that period
    };
    std::vector<Stripe> stripes;  ///< one per return period, in return_periods_yr's order
    Where declared_at;            ///< the [selection] library key
  };
  std::optional<StripeSelection> selection;
  /// The [ida] table, when given: the intensity axis becomes a search, `levels` is unused.
  std::optional<IdaOptions> ida;
  /// The scene ([frame] model; the prestressed frame by default) and its base point (the
  /// [frame] or [base] values, every other parameter at its default): every frame starts there.
  const SceneModel* model = &default_scene_model();
  ScenePoint base = default_scene_model().defaults();
  /// [axes] incidence_deg: the azimuths of the frames' plane [deg], a dimension of its own
  /// after the level axis; empty: no such axis, every frame lies along its record's first
  /// component (and feels it bit for bit as if the others did not exist).
  std::vector<double> incidence_deg;
  /// What incidence_deg counts from ([axes] incidence): north (the values are azimuths),
  /// or each record's fault-normal (strike + 90°) or fault-parallel (strike) direction.
  std::string incidence_reference = "north";

  PhysicsOptions physics;
  SolverSettings solver = preset_settings("balanced");
  /// Where each setting the file gives is (its key path, file and line), by "table.key", for
  /// later checks' messages.
  std::map<std::string, Where> given_at;
  /// Where the setting "table.key" is: where the file gives it, else the file alone.
  Where where(const std::string& table_key) const;
  std::vector<std::string> metrics;  ///< metric names to store, in all_metrics() order
  std::vector<HistoryRequest> histories;
  /// [outputs] record_pulses: each record's velocity pulse is identified (Baker 2007 on one
  /// component, Shahi & Baker 2014 on a station's pair; excitation/station_pulse.hpp) and the
  /// cube gets record_pulse_like, record_pulse_method, pulse_period_s (NaN when not pulse-like) and
  /// record_pulse_azimuth_deg along `record`, and ω_p/p over record and frame. Part of the fingerprint.
  bool record_pulses = false;
  RunOptions run;
};

}  // namespace pcrf::study

/// \file study.hpp
/// \brief A parametric study as a study file defines it: the record and scale axes, the
/// plan over the eight frame parameters, physics and solver settings, and what to keep.
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
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pcrf/model/frame.hpp"
#include "pcrf/model/parameters.hpp"
#include "pcrf/plan/ida_search.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/setting.hpp"
#include "pcrf/solver/settings.hpp"
#include "pcrf/study/record_source.hpp"

namespace pcrf::study {

/// How the frame parameters are combined.
enum class PlanKind {
  kGrid,        ///< every combination of the parameter axes (the full cube)
  kOneAtATime,  ///< each swept parameter alone, the others at the base point
  kList,        ///< explicitly listed cases
  kLhs,         ///< a Latin hypercube over the [axes] ranges
  kSobol,       ///< Sobol' low-discrepancy points over the [axes] ranges
  kSaltelli,    ///< the A, B, A_B^(i) design for Sobol' sensitivity indices
};
/// True for the plans that sample the [axes] ranges (lhs, sobol, saltelli).
inline bool is_sampled(PlanKind plan) {
  return plan == PlanKind::kLhs || plan == PlanKind::kSobol || plan == PlanKind::kSaltelli;
}

/// The interval a sampled plan draws a parameter from: uniformly, or log-uniformly.
struct SampledRange {
  double from = 0.0;
  double to = 0.0;
  bool log = false;
  /// The value at unit coordinate u ∈ [0, 1).
  double at(double u) const { return log ? from * std::pow(to / from, u) : from + u * (to - from); }
};
std::string_view plan_name(PlanKind plan);  ///< "grid", "one-at-a-time", "list", "lhs", "sobol", "saltelli"

/// A frame of the list plan.
struct ListedCase {
  std::string label;
  FrameParameters parameters;
};

/// A case whose time history is wanted. Each given selector must match an axis value;
/// every axis with more than one value must be given, so that exactly one case matches.
struct HistoryRequest {
  std::string label;                      ///< group name under /histories
  std::optional<std::string> record;      ///< record axis value (its name)
  std::optional<double> scale;
  std::optional<std::string> case_label;  ///< one-at-a-time and list plans
  std::array<std::optional<double>, kParameterCount> parameters;  ///< grid plan
  double dt_s = 0.0;                      ///< output interval [s]; 0: the record's dt
  std::string declared_at;                ///< "study.toml:40", for messages
};

/// How a run behaves; not part of what the study computes (not in its fingerprint).
/// Described in run_settings().
struct RunOptions {
  double flush_interval_s = 30.0;
  double progress_interval_s = 5.0;
  std::size_t batch_size = 0;
};

/// The [run] table; `pcrf study` also takes each key as a flag (`--flush-interval-s`).
const SettingTable<RunOptions>& run_settings();

/// The [ida] table: an adaptive search of each record's collapse intensity, per frame.
/// Described in ida_settings(); the search itself is plan::IdaSearch.
struct IdaOptions {
  double start = 0.0;
  double step = 0.0;
  double resolution = 0.02;
  double max_intensity = 0.0;
  long max_runs = 16;
  std::string collapse = "tendon_fracture,overturned";
  double theta_limit_rad = 0.0;

  plan::IdaSearchSettings search() const {
    return {start, step, resolution, max_intensity, static_cast<int>(max_runs)};
  }
};
const SettingTable<IdaOptions>& ida_settings();

struct Study {
  std::string name;
  std::string description;
  std::string file;                 ///< the study file as given (messages, attributes)
  std::filesystem::path base_dir;   ///< relative record paths resolve against this
  std::string text;                 ///< the study file's text (stored in the cube)

  PlanKind plan = PlanKind::kGrid;
  bool include_base = true;         ///< one-at-a-time: the base point is a case of its own

  std::vector<RecordSource> records;
  /// The values of the second axis: scale factors of the records (`scale`), or, when
  /// `intensity` is set, intensities in the measure's units (each record gets its own factor
  /// intensity / IM(record)).
  std::vector<double> levels{1.0};
  std::optional<IntensitySpec> intensity;  ///< the [intensity] table, when given
  /// The [ida] table, when given: the intensity axis becomes a search, `levels` is unused.
  std::optional<IdaOptions> ida;
  FrameParameters base;             ///< the base point; h_m and m_c_kg of every case
  /// Grid: the values of each parameter axis (empty: the base value only).
  /// One-at-a-time: the values each parameter is swept over (empty: not swept).
  std::array<std::vector<double>, kParameterCount> axes;
  std::vector<ListedCase> cases;    ///< list plan
  /// Sampled plans: each varied parameter's range (unset: the parameter stays at `base`),
  /// the number of samples (saltelli: base samples N, N(d + 2) frames), the seed, and
  /// whether Sobol' points are Owen-scrambled.
  std::array<std::optional<SampledRange>, kParameterCount> ranges;
  std::size_t samples = 0;
  std::uint64_t seed = 0;
  bool scramble = false;

  PhysicsOptions physics;
  SolverSettings solver = preset_settings("balanced");
  /// "FILE:LINE" of each setting the file gives, by "table.key" (for later checks' messages).
  std::map<std::string, std::string> setting_lines;
  std::vector<std::string> metrics;  ///< metric names to store, in all_metrics() order
  std::vector<HistoryRequest> histories;
  RunOptions run;
};

}  // namespace pcrf::study

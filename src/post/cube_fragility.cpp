// Collapse fragility of a cube's frames (see cube_fragility.hpp).
#include "pcrf/post/cube_fragility.hpp"

#include <cmath>
#include <functional>
#include <map>

#include "pcrf/metrics/case_result.hpp"
#include "pcrf/metrics/curve_state.hpp"
#include "pcrf/row_major.hpp"
#include "pcrf/user_error.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"

namespace pcrf::post {

namespace vocabulary = schema;
namespace {


std::size_t dimension_index(const cube::CubeLayout& layout, const std::string& name) {
  if (const auto d = layout.find_dimension(name)) return *d;
  throw cube::CubeError("has no '" + name + "' axis: fragility needs records scaled to a common intensity "
                        "([intensity] table and [axes] intensity)");
}

/// The dimensions that tell frames apart: those with several values but the record, the
/// level and `reduced_dim` (the axis a reduction takes away; the level again when none).
std::vector<std::size_t> frame_dimensions(const cube::CubeLayout& layout, std::size_t record_dim, std::size_t level_dim,
                                          std::size_t reduced_dim) {
  std::vector<std::size_t> dims;
  for (std::size_t d = 0; d < layout.dimensions.size(); ++d)
    if (d != record_dim && d != level_dim && d != reduced_dim && layout.dimensions[d].size > 1) dims.push_back(d);
  return dims;
}

/// The frame of a case on `frame_dims`: "name=value,…" ("all" when none; a `case` by its case_label where the cube has one).
std::string frame_label(const cube::CubeLayout& layout, const std::vector<std::size_t>& frame_dims,
                        const std::vector<std::size_t>& coords) {
  std::string label;
  for (std::size_t d : frame_dims) {
    const auto& name = layout.dimensions[d].name;
    // A cube without case labels (a sampled plan's, whose label the case number says): case=<i>.
    const cube::Coordinate* labelled = name == vocabulary::kCase ? layout.find_coordinate(vocabulary::kCaseLabel) : nullptr;
    const cube::Coordinate* c = labelled != nullptr ? labelled : layout.find_coordinate(name);
    label += (label.empty() ? "" : ",") + (labelled != nullptr ? c->label(coords[d]) : name + "=" + c->label(coords[d]));
  }
  return label.empty() ? "all" : label;
}

/// The frame of a case as -w selectors (see FrameFragility::selection).
std::string frame_selection(const cube::CubeLayout& layout, const std::vector<std::size_t>& frame_dims,
                            const std::vector<std::size_t>& coords) {
  std::string selection;
  for (std::size_t d : frame_dims) {
    const auto& name = layout.dimensions[d].name;
    selection += (selection.empty() ? "" : ",") + name + "=" + layout.find_coordinate(name)->label(coords[d]);
  }
  return selection;
}

/// Per frame: per record, per intensity, the case's status (or not-run).
struct FrameCases {
  std::string label, selection;
  std::vector<std::vector<std::int8_t>> status;  // [record][level]
  std::vector<std::vector<double>> fraction;     // [record][level]: collapse_fraction, NaN if not checked
  std::int64_t first_case = -1;
};

}  // namespace

std::string intensity_units(const cube::CubeReader& cube) {
  if (const auto* c = cube.layout().find_coordinate(vocabulary::kIntensity)) return c->units;
  if (const auto* v = cube.layout().find_side_variable(vocabulary::kCollapseIntensity)) return v->units;
  return "";
}

namespace {

/// What an IDA fits per record (or, reduced, per combination of the other coordinates): its
/// collapse intensity, or an intensity it is known to exceed (censored), or nothing (failed).
struct CurveValue {
  double intensity = std::nan("");
  bool censored = false;
  bool unresolved = false;  ///< censored at the last safe run of an unresolved curve: a bound, never safe beyond
  bool has_value() const { return std::isfinite(intensity); }
};

/// The interval columns of a frame without a bootstrap: missing.
analysis::BootstrapResult no_interval() {
  const double none = std::nan("");
  return {{none, none}, {none, none}, 0};
}

/// IDA cube: each curve's collapse intensity, or (none found) a right-censored value at its
/// last safe intensity; one fit per frame, the bootstrap resampling records. With a reduction
/// over a dimension (incidence_deg), the curves that differ only along it are reduced to one
/// value first (cube::reduce_censored: min gives the worst orientation), and frames no longer
/// differ along it.
std::vector<FrameFragility> ida_fragility(const cube::CubeReader& cube, const std::vector<cube::Selector>& selectors,
                                          const cube::Reduction& reduction) {
  const auto& layout = cube.layout();
  const std::size_t record_dim = dimension_index(layout, vocabulary::kRecord);
  const std::size_t point_dim = dimension_index(layout, vocabulary::kIdaPoint);
  const std::size_t records = layout.dimensions[record_dim].size;
  const std::size_t runs = layout.dimensions[point_dim].size;
  const bool reduced = !reduction.dimension.empty();
  std::size_t reduced_dim = point_dim;  // "none": the point axis is never a frame axis anyway
  if (reduced) {
    cube::check_reduction(reduction.how);
    const auto d = layout.find_dimension(reduction.dimension);
    if (!d) throw cube::CubeError("no dimension '" + reduction.dimension + "' to reduce over");
    if (*d == record_dim || *d == point_dim)
      throw cube::CubeError("cannot reduce the fragility over '" + reduction.dimension + "': it fits over records and runs");
    reduced_dim = *d;
  }
  const auto collapse = cube.read_side(vocabulary::kCollapseIntensity);
  const auto safe = cube.read_side(vocabulary::kLastSafeIntensity);
  const auto runs_of = cube.read_side(vocabulary::kIdaRuns);
  // Cubes from before curve_state have none: every curve is then taken as it was.
  const bool has_states = layout.find_side_variable(vocabulary::kCurveState) != nullptr;
  const auto state = has_states ? cube.read_side(vocabulary::kCurveState) : std::vector<double>(collapse.size(), std::nan(""));
  const auto unbracketed = [&state](std::size_t curve) {
    return state[curve] == static_cast<double>(CurveState::kUnbracketed);
  };
  const auto unresolved = [&state](std::size_t curve) {
    return state[curve] == static_cast<double>(CurveState::kUnresolved);
  };
  // An unresolved curve has no collapse intensity: it is censored at its last safe run (a
  // lower bound), never at max_intensity; with no safe run it has no value.
  const auto value_of = [&](std::size_t curve) {
    if (std::isfinite(collapse[curve]) && !unbracketed(curve) && !unresolved(curve)) return CurveValue{collapse[curve], false};
    if (std::isfinite(safe[curve])) return CurveValue{safe[curve], true, unresolved(curve)};
    return CurveValue{};
  };
  const auto selected = cube::select_cases(layout, selectors);
  std::vector<std::size_t> curve_shape(layout.shape());
  curve_shape.pop_back();  // ida_point is the last axis

  // A frame's units: curves, or (reduced) the curves that differ only along the reduced axis.
  struct Unit {
    std::vector<std::size_t> curves;
  };
  struct Frame {
    std::vector<Unit> units;
    std::map<std::int64_t, std::size_t> unit_of;  // curve coordinates with the reduced one at 0 → unit
    std::size_t not_run = 0, unbracketed = 0, unresolved = 0;
    std::string selection;
    std::int64_t first_case = -1;
  };
  std::map<std::string, Frame> frames;
  std::vector<std::string> order;
  const auto frame_dims = frame_dimensions(layout, record_dim, point_dim, reduced_dim);
  for (std::size_t curve = 0; curve < collapse.size(); ++curve) {
    if (!selected[curve * runs]) continue;
    auto coords = unravel(static_cast<std::int64_t>(curve), curve_shape);
    coords.push_back(0);
    const std::string label = frame_label(layout, frame_dims, coords);
    auto [it, inserted] = frames.try_emplace(label);
    Frame& frame = it->second;
    if (inserted) {
      order.push_back(label);
      frame.selection = frame_selection(layout, frame_dims, coords);
      frame.first_case = static_cast<std::int64_t>(curve * runs);
    }
    if (!(runs_of[curve] > 0.0)) {  // NaN: no part ran it (a partial merge): left out of the fit
      ++frame.not_run;
      continue;
    }
    if (unbracketed(curve)) ++frame.unbracketed;
    if (unresolved(curve)) ++frame.unresolved;
    coords.pop_back();
    if (reduced) coords[reduced_dim] = 0;
    const auto key = reduced ? ravel(coords, curve_shape) : static_cast<std::int64_t>(curve);
    const auto [unit, added] = frame.unit_of.try_emplace(key, frame.units.size());
    if (added) frame.units.emplace_back();
    frame.units[unit->second].curves.push_back(curve);
  }
  // A unit's value: its curve's, or the reduction of its curves' (none when one has none).
  const auto unit_value = [&](const Unit& unit) {
    if (!reduced) return value_of(unit.curves.front());
    std::vector<double> observed, censored;
    for (std::size_t curve : unit.curves) {
      const CurveValue v = value_of(curve);
      if (!v.has_value()) return CurveValue{};
      (v.censored ? censored : observed).push_back(v.intensity);
    }
    const auto r = cube::reduce_censored(observed, censored, reduction.how);
    return CurveValue{r.value, r.censored, false};
  };
  std::vector<FrameFragility> result;
  for (const auto& label : order) {
    const Frame& frame = frames.at(label);
    std::vector<CurveValue> values;
    for (const Unit& unit : frame.units) values.push_back(unit_value(unit));
    FrameFragility out;
    out.frame = label;
    out.selection = frame.selection;
    out.records = records;
    out.first_case = frame.first_case;
    auto fit = [&](const std::vector<std::size_t>& sample) {
      std::vector<double> observed, censored;
      for (std::size_t k : sample)
        if (values[k].has_value()) (values[k].censored ? censored : observed).push_back(values[k].intensity);
      return analysis::fit_censored(observed, censored);
    };
    out.unbracketed = frame.unbracketed;
    out.unresolved = frame.unresolved;
    for (const CurveValue& v : values)
      if (v.has_value())
        (v.unresolved ? out.unresolved_intensities : v.censored ? out.censored_intensities : out.collapse_intensities)
            .push_back(v.intensity);
    out.cases = out.collapse_intensities.size() + out.censored_intensities.size() + out.unresolved_intensities.size();
    out.collapses = static_cast<double>(out.collapse_intensities.size());
    out.not_run = frame.not_run;
    out.failed = values.size() - out.cases;
    std::vector<std::size_t> all(values.size());
    for (std::size_t k = 0; k < all.size(); ++k) all[k] = k;
    out.fit = fit(all);
    out.interval = gives_interval(out) ? analysis::bootstrap(values.size(), fit) : no_interval();
    result.push_back(std::move(out));
  }
  return result;
}

}  // namespace

std::vector<FrameFragility> cube_fragility(const cube::CubeReader& cube, const std::vector<cube::Selector>& selectors,
                                           const cube::Reduction& reduction) {
  const auto& layout = cube.layout();
  if (layout.find_side_variable(vocabulary::kCollapseIntensity) != nullptr) return ida_fragility(cube, selectors, reduction);
  if (!reduction.dimension.empty())
    throw UserError(Where{}, cube.file().string() + ": {} needs an IDA cube (its collapse intensities are reduced; a "
                             "stripe's verdicts are not)", {"reduce_over"});
  const std::size_t record_dim = dimension_index(layout, vocabulary::kRecord);
  const std::size_t level_dim = dimension_index(layout, vocabulary::kIntensity);
  const auto& levels = layout.find_coordinate(vocabulary::kIntensity)->numbers;
  const std::size_t records = layout.dimensions[record_dim].size;
  const auto shape = layout.shape();
  const auto selected = cube::select_cases(layout, selectors);
  const auto status = cube.read_status();
  // With verdict checks, a case counts by the share of its perturbed runs that collapsed.
  std::vector<double> fraction;
  for (const auto& m : layout.metrics)
    if (m.name == metric::collapse_fraction().name) fraction = cube.read_metric(m.name);

  std::map<std::string, FrameCases> frames;  // by label, in label order
  std::vector<std::string> order;
  const auto frame_dims = frame_dimensions(layout, record_dim, level_dim, level_dim);
  for (std::int64_t i = 0; i < layout.case_count(); ++i) {
    if (!selected[static_cast<std::size_t>(i)]) continue;
    const auto coords = unravel(i, shape);
    const std::string label = frame_label(layout, frame_dims, coords);
    auto [it, inserted] = frames.try_emplace(label);
    if (inserted) {
      order.push_back(label);
      it->second.label = label;
      it->second.selection = frame_selection(layout, frame_dims, coords);
      it->second.first_case = i;
      it->second.status.assign(records, std::vector<std::int8_t>(levels.size(), cube::kStatusNotRun));
      it->second.fraction.assign(records, std::vector<double>(levels.size(), std::nan("")));
    }
    it->second.status[coords[record_dim]][coords[level_dim]] = status[static_cast<std::size_t>(i)];
    if (!fraction.empty()) it->second.fraction[coords[record_dim]][coords[level_dim]] = fraction[static_cast<std::size_t>(i)];
  }

  std::vector<FrameFragility> result;
  for (const auto& label : order) {
    const FrameCases& f = frames.at(label);
    FrameFragility out;
    out.frame = label;
    out.selection = f.selection;
    out.records = records;
    out.first_case = f.first_case;
    auto stripes_of = [&](const std::vector<std::size_t>& sample) {
      std::vector<analysis::Stripe> stripes(levels.size());
      for (std::size_t l = 0; l < levels.size(); ++l) {
        stripes[l].intensity = levels[l];
        for (std::size_t r : sample) {
          const auto s = static_cast<CaseStatus>(f.status[r][l]);
          if (!has_verdict(s)) continue;
          stripes[l].trials += 1.0;
          const double share = f.fraction[r][l];
          stripes[l].collapses += std::isfinite(share) ? share : (is_collapse(s) ? 1.0 : 0.0);
        }
      }
      return stripes;
    };
    std::vector<std::size_t> all(records);
    for (std::size_t r = 0; r < records; ++r) all[r] = r;
    out.stripes = stripes_of(all);
    for (const auto& s : out.stripes) {
      out.cases += static_cast<std::size_t>(s.trials);
      out.collapses += s.collapses;
    }
    for (const auto& by_level : f.status)
      for (std::int8_t s : by_level) {
        out.not_run += s == cube::kStatusNotRun ? 1 : 0;
        out.unresolved += s != cube::kStatusNotRun && is_unresolved(static_cast<CaseStatus>(s)) ? 1 : 0;
      }
    out.failed = records * levels.size() - out.cases - out.not_run - out.unresolved;
    out.fit = analysis::fit_stripes(out.stripes);
    out.interval = gives_interval(out) ? analysis::bootstrap(records, [&](const std::vector<std::size_t>& sample) {
                                           return analysis::fit_stripes(stripes_of(sample));
                                         })
                                       : no_interval();
    result.push_back(std::move(out));
  }
  return result;
}

std::vector<std::string> unbracketed_warnings(const std::vector<FrameFragility>& frames) {
  std::vector<std::string> lines;
  for (const auto& f : frames) {
    if (f.unbracketed && *f.unbracketed > 0)
      lines.push_back("frame " + f.frame + ": " + std::to_string(*f.unbracketed) +
                      " unbracketed curves (max_runs ran out before the resolution or max_intensity) censored at "
                      "their last safe intensity; raise [ida] max_runs or step_factor");
    if (f.unbracketed && f.unresolved > 0)
      lines.push_back("frame " + f.frame + ": " + std::to_string(f.unresolved) +
                      " unresolved curves (a run without a verdict ended them: still rocking, ground in free fall or "
                      "invalid frame) bounded at their last safe intensity, never censored at max_intensity" +
                      (f.unresolved > f.unresolved_intensities.size()
                           ? "; " + std::to_string(f.unresolved - f.unresolved_intensities.size()) + " without a safe run left out"
                           : std::string()));
    if (auto line = few_records_warning(f); !line.empty()) lines.push_back(std::move(line));
  }
  return lines;
}

std::size_t interval_units(const FrameFragility& f) { return f.unbracketed ? f.cases : f.records; }

bool gives_interval(const FrameFragility& f) { return f.fit && interval_units(f) >= kFewestForInterval; }

std::string few_records_warning(const FrameFragility& f) {
  if (!f.fit || gives_interval(f)) return {};
  return "frame " + f.frame + ": a fit from " + std::to_string(interval_units(f)) + (f.unbracketed ? " curves" : " records") +
         ", fewer than " + std::to_string(kFewestForInterval) +
         ": its median and beta are rough, and no bootstrap interval is given";
}

}  // namespace pcrf::post

// Collapse fragility of a cube's frames (see cube_fragility.hpp).
#include "pcrf/post/cube_fragility.hpp"

#include <cmath>
#include <map>

#include "pcrf/metrics/case_result.hpp"
#include "pcrf/row_major.hpp"
#include "pcrf/study/cube_vocabulary.hpp"

namespace pcrf::post {

namespace vocabulary = study::vocabulary;
namespace {


std::size_t dimension_index(const cube::CubeLayout& layout, const std::string& name) {
  if (const auto d = layout.find_dimension(name)) return *d;
  throw cube::CubeError("has no '" + name + "' axis: fragility needs records scaled to a common intensity "
                        "([intensity] table and [axes] intensity)");
}

std::string frame_label(const cube::CubeLayout& layout, const std::vector<std::size_t>& coords, std::size_t record_dim,
                        std::size_t level_dim) {
  std::string label;
  for (std::size_t d = 0; d < coords.size(); ++d) {
    if (d == record_dim || d == level_dim || layout.dimensions[d].size < 2) continue;
    const auto& name = layout.dimensions[d].name;
    const cube::Coordinate* c = layout.find_coordinate(name == vocabulary::kCase ? vocabulary::kCaseLabel : name);
    label += (label.empty() ? "" : ",") + (name == vocabulary::kCase ? c->label(coords[d]) : name + "=" + c->label(coords[d]));
  }
  return label.empty() ? "all" : label;
}

/// The frame of a case as -w selectors (see FrameFragility::selection).
std::string frame_selection(const cube::CubeLayout& layout, const std::vector<std::size_t>& coords, std::size_t record_dim,
                            std::size_t level_dim) {
  std::string selection;
  for (std::size_t d = 0; d < coords.size(); ++d) {
    if (d == record_dim || d == level_dim || layout.dimensions[d].size < 2) continue;
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
};

}  // namespace

std::string intensity_units(const cube::CubeReader& cube) {
  if (const auto* c = cube.layout().find_coordinate(vocabulary::kIntensity)) return c->units;
  if (const auto* v = cube.layout().find_side_variable(vocabulary::kCollapseIntensity)) return v->units;
  return "";
}

namespace {

/// IDA cube: each curve's collapse intensity, or (none found) a right-censored value at its
/// last safe intensity; one fit per frame, the bootstrap resampling records.
std::vector<FrameFragility> ida_fragility(const cube::CubeReader& cube, const std::vector<cube::Selector>& selectors) {
  const auto& layout = cube.layout();
  const std::size_t record_dim = dimension_index(layout, vocabulary::kRecord);
  const std::size_t point_dim = dimension_index(layout, vocabulary::kIdaPoint);
  const std::size_t records = layout.dimensions[record_dim].size;
  const std::size_t runs = layout.dimensions[point_dim].size;
  const auto collapse = cube.read_side(vocabulary::kCollapseIntensity);
  const auto safe = cube.read_side(vocabulary::kLastSafeIntensity);
  const auto runs_of = cube.read_side(vocabulary::kIdaRuns);
  const auto selected = cube::select_cases(layout, selectors);
  std::vector<std::size_t> curve_shape(layout.shape());
  curve_shape.pop_back();  // ida_point is the last axis

  std::map<std::string, std::vector<std::size_t>> curves_of;  // frame label → its curves run, by record
  std::map<std::string, std::size_t> not_run_of;
  std::map<std::string, std::string> selection_of;
  std::vector<std::string> order;
  for (std::size_t curve = 0; curve < collapse.size(); ++curve) {
    if (!selected[curve * runs]) continue;
    auto coords = unravel(static_cast<std::int64_t>(curve), curve_shape);
    coords.push_back(0);
    const std::string label = frame_label(layout, coords, record_dim, point_dim);
    auto [it, inserted] = curves_of.try_emplace(label);
    if (inserted) {
      order.push_back(label);
      selection_of[label] = frame_selection(layout, coords, record_dim, point_dim);
    }
    if (runs_of[curve] > 0.0) it->second.push_back(curve);
    else ++not_run_of[label];  // NaN: no part ran it (a partial merge): left out of the fit
  }
  std::vector<FrameFragility> result;
  for (const auto& label : order) {
    const auto& curves = curves_of.at(label);
    FrameFragility out;
    out.frame = label;
    out.selection = selection_of[label];
    out.records = records;
    auto fit = [&](const std::vector<std::size_t>& sample) {
      std::vector<double> observed, censored;
      for (std::size_t k : sample) {
        const std::size_t curve = curves[k];
        if (std::isfinite(collapse[curve])) observed.push_back(collapse[curve]);
        else if (std::isfinite(safe[curve])) censored.push_back(safe[curve]);
      }
      return analysis::fit_censored(observed, censored);
    };
    for (std::size_t curve : curves) {
      if (std::isfinite(collapse[curve])) out.collapse_intensities.push_back(collapse[curve]);
      else if (std::isfinite(safe[curve])) out.censored_intensities.push_back(safe[curve]);
    }
    out.cases = out.collapse_intensities.size() + out.censored_intensities.size();
    out.collapses = static_cast<double>(out.collapse_intensities.size());
    out.not_run = not_run_of[label];
    out.failed = curves.size() - out.cases;
    std::vector<std::size_t> all(curves.size());
    for (std::size_t k = 0; k < all.size(); ++k) all[k] = k;
    out.fit = fit(all);
    if (out.fit) out.interval = analysis::bootstrap(curves.size(), fit);
    result.push_back(std::move(out));
  }
  return result;
}

}  // namespace

std::vector<FrameFragility> cube_fragility(const cube::CubeReader& cube, const std::vector<cube::Selector>& selectors) {
  const auto& layout = cube.layout();
  if (layout.find_side_variable(vocabulary::kCollapseIntensity) != nullptr) return ida_fragility(cube, selectors);
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
  for (std::int64_t i = 0; i < layout.case_count(); ++i) {
    if (!selected[static_cast<std::size_t>(i)]) continue;
    const auto coords = unravel(i, shape);
    const std::string label = frame_label(layout, coords, record_dim, level_dim);
    auto [it, inserted] = frames.try_emplace(label);
    if (inserted) {
      order.push_back(label);
      it->second.label = label;
      it->second.selection = frame_selection(layout, coords, record_dim, level_dim);
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
      for (std::int8_t s : by_level) out.not_run += s == cube::kStatusNotRun ? 1 : 0;
    out.failed = records * levels.size() - out.cases - out.not_run;
    out.fit = analysis::fit_stripes(out.stripes);
    if (out.fit)
      out.interval = analysis::bootstrap(records, [&](const std::vector<std::size_t>& sample) {
        return analysis::fit_stripes(stripes_of(sample));
      });
    result.push_back(std::move(out));
  }
  return result;
}

}  // namespace pcrf::post

// Enumeration of a study's cases (see case_space.hpp).
#include "pcrf/study/case_space.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "pcrf/plan/sampling.hpp"
#include "pcrf/row_major.hpp"
#include "pcrf/study/cube_vocabulary.hpp"
#include "pcrf/study/study_error.hpp"

namespace pcrf::study {
namespace {

std::string shortest(double value) {
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

bool same_value(double a, double b) { return std::fabs(a - b) <= 1e-12 * std::max(std::fabs(a), std::fabs(b)); }

/// Position of `value` on an axis, or npos.
std::size_t find_value(const std::vector<double>& axis, double value) {
  for (std::size_t i = 0; i < axis.size(); ++i)
    if (same_value(axis[i], value)) return i;
  return std::string::npos;
}

/// The frames of a sampled plan: unit points mapped onto each varied parameter's range.
std::vector<CasePoint> sampled_points(const Study& study) {
  std::vector<std::size_t> varied;
  for (std::size_t p = 0; p < kParameterCount; ++p)
    if (study.ranges[p]) varied.push_back(p);
  const std::size_t d = varied.size();
  plan::UnitPoints unit;
  if (study.plan == PlanKind::kLhs) unit = plan::latin_hypercube(study.samples, d, study.seed);
  else if (study.plan == PlanKind::kSobol) unit = plan::sobol_points(study.samples, d, study.scramble, study.seed);
  else unit = plan::saltelli_design(study.samples, d, study.scramble, study.seed).points;
  std::vector<CasePoint> points(unit.size() / d);
  for (std::size_t row = 0; row < points.size(); ++row) {
    CasePoint& point = points[row];
    point.parameters = study.base;
    for (std::size_t k = 0; k < d; ++k) {
      const auto& info = all_parameters()[varied[k]];
      point.parameters.*info.member = study.ranges[varied[k]]->at(unit[row * d + k]);
    }
    if (study.plan != PlanKind::kSaltelli) {
      point.label = "s" + std::to_string(row);
      continue;
    }
    const std::size_t block = plan::SaltelliDesign::block(row, d);
    point.sample = static_cast<long>(plan::SaltelliDesign::sample(row, d));
    point.block = block == 0 ? "A" : block == 1 ? "B" : "AB_" + std::string(all_parameters()[varied[block - 2]].name);
    point.label = "s" + std::to_string(point.sample) + ":" + point.block;
  }
  return points;
}

}  // namespace

CaseSpace::CaseSpace(const Study& study) : plan_(study.plan), base_(study.base), levels_(study.levels) {
  for (const auto& r : study.records) record_names_.push_back(r.name);
  names_ = {vocabulary::kRecord};
  shape_ = {record_names_.size()};
  if (study.ida) {
    ida_runs_ = static_cast<std::size_t>(study.ida->max_runs);
    levels_.clear();  // each run's intensity comes with it (WorkItem::argument)
  } else {
    names_.emplace_back(study.intensity ? vocabulary::kIntensity : vocabulary::kScale);
    shape_.push_back(levels_.size());
  }
  frame_dim_ = shape_.size();
  if (plan_ == PlanKind::kGrid) {
    for (std::size_t p = 0; p < kParameterCount; ++p) {
      const auto& info = all_parameters()[p];
      grid_values_[p] = study.axes[p].empty() ? std::vector<double>{base_.*info.member} : study.axes[p];
      names_.emplace_back(info.name);
      shape_.push_back(grid_values_[p].size());
    }
  } else if (plan_ == PlanKind::kOneAtATime) {
    if (study.include_base) points_.push_back({"base", "none", base_, "", -1});
    for (std::size_t p = 0; p < kParameterCount; ++p) {
      const auto& info = all_parameters()[p];
      for (double v : study.axes[p]) {
        CasePoint point{std::string(info.name) + "=" + shortest(v), std::string(info.name), base_, "", -1};
        point.parameters.*info.member = v;
        points_.push_back(std::move(point));
      }
    }
  } else if (is_sampled(plan_)) {
    points_ = sampled_points(study);
  } else {
    for (const auto& c : study.cases) points_.push_back({c.label, "", c.parameters, "", -1});
  }
  if (plan_ != PlanKind::kGrid) {
    names_.emplace_back(vocabulary::kCase);
    shape_.push_back(points_.size());
  }
  if (ida_runs_ > 0) {
    names_.emplace_back(vocabulary::kIdaPoint);
    shape_.push_back(ida_runs_);
  }
  for (auto n : shape_) size_ *= static_cast<std::int64_t>(n);
}

std::vector<std::size_t> CaseSpace::coordinates(std::int64_t index) const { return unravel(index, shape_); }

std::int64_t CaseSpace::index(const std::vector<std::size_t>& coordinates) const {
  return ravel(coordinates, shape_);
}

CaseSpec CaseSpace::case_at(std::int64_t index) const {
  const auto c = coordinates(index);
  CaseSpec spec{c[0], levels_.empty() ? std::nan("") : levels_[c[1]], base_};
  if (plan_ == PlanKind::kGrid) {
    for (std::size_t p = 0; p < kParameterCount; ++p)
      spec.parameters.*all_parameters()[p].member = grid_values_[p][c[frame_dim_ + p]];
  } else {
    spec.parameters = points_[c[frame_dim_]].parameters;
  }
  return spec;
}

std::vector<std::int64_t> CaseSpace::frame_major(std::vector<std::int64_t> indices) const {
  // Key: the frame's position among the frame axes, then the record and level axes.
  std::int64_t frames = 1;
  for (std::size_t d = frame_dim_; d < shape_.size(); ++d) frames *= static_cast<std::int64_t>(shape_[d]);
  const std::int64_t per_frame = size_ / frames;
  auto key = [&](std::int64_t index) { return (index % frames) * per_frame + index / frames; };
  std::stable_sort(indices.begin(), indices.end(), [&](std::int64_t a, std::int64_t b) { return key(a) < key(b); });
  return indices;
}

std::vector<FrameParameters> CaseSpace::frames() const {
  if (plan_ != PlanKind::kGrid) {
    std::vector<FrameParameters> frames;
    for (const auto& p : points_) frames.push_back(p.parameters);
    return frames;
  }
  std::vector<FrameParameters> frames{base_};
  for (std::size_t p = 0; p < kParameterCount; ++p) {
    std::vector<FrameParameters> next;
    next.reserve(frames.size() * grid_values_[p].size());
    for (const auto& f : frames)
      for (double v : grid_values_[p]) {
        next.push_back(f);
        next.back().*all_parameters()[p].member = v;
      }
    frames = std::move(next);
  }
  return frames;
}

std::int64_t CaseSpace::resolve(const HistoryRequest& request) const {
  auto fail = [&](const std::string& problem) -> std::size_t {
    throw StudyError(request.declared_at + ": outputs.histories \"" + request.label + "\": " + problem);
  };
  auto pick_single = [&](std::size_t size, const std::string& key) -> std::size_t {
    if (size == 1) return 0;
    return fail("the " + key + " axis has " + std::to_string(size) + " values: give `" + key + "`");
  };
  std::vector<std::size_t> coords(shape_.size());
  if (request.record) {
    auto it = std::find(record_names_.begin(), record_names_.end(), *request.record);
    coords[0] = it != record_names_.end() ? static_cast<std::size_t>(it - record_names_.begin())
                                          : fail("no record is named \"" + *request.record + "\"");
  } else {
    coords[0] = pick_single(record_names_.size(), "record");
  }
  if (request.scale) {
    coords[1] = find_value(levels_, *request.scale);
    if (coords[1] == std::string::npos)
      fail(names_[1] + " " + shortest(*request.scale) + " is not on the " + names_[1] + " axis");
  } else {
    coords[1] = pick_single(levels_.size(), names_[1]);
  }
  if (plan_ == PlanKind::kGrid) {
    for (std::size_t p = 0; p < kParameterCount; ++p) {
      const std::string key(all_parameters()[p].name);
      if (!request.parameters[p]) {
        coords[2 + p] = pick_single(grid_values_[p].size(), key);
        continue;
      }
      coords[2 + p] = find_value(grid_values_[p], *request.parameters[p]);
      if (coords[2 + p] == std::string::npos)
        fail(key + " " + shortest(*request.parameters[p]) + " is not on the " + key + " axis");
    }
  } else if (request.case_label) {
    auto it = std::find_if(points_.begin(), points_.end(), [&](const CasePoint& p) { return p.label == *request.case_label; });
    coords[2] = it != points_.end() ? static_cast<std::size_t>(it - points_.begin())
                                    : fail("no case is labelled \"" + *request.case_label + "\"");
  } else {
    coords[2] = pick_single(points_.size(), "case");
  }
  return index(coords);
}

}  // namespace pcrf::study

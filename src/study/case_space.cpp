// Enumeration of a study's cases (see case_space.hpp).
#include "pcrf/study/case_space.hpp"

#include <algorithm>
#include <cmath>

#include "pcrf/row_major.hpp"
#include "pcrf/study/cube_vocabulary.hpp"
#include "pcrf/study/study_error.hpp"

namespace pcrf::study {

CaseSpace::CaseSpace(const Study& study)
    : plan_(study.plan), level_axis_(make_level_axis(study)), levels_(level_axis_->levels()) {
  for (const auto& r : study.records) record_names_.push_back(r.name);
  names_ = {vocabulary::kRecord};
  shape_ = {record_names_.size()};
  auto add = [&](const std::vector<cube::Dimension>& dimensions) {
    for (const auto& d : dimensions) {
      names_.push_back(d.name);
      shape_.push_back(d.size);
    }
  };
  add(level_axis_->leading_dimensions());
  frame_dim_ = shape_.size();
  add(plan_->dimensions());
  const auto trailing = level_axis_->trailing_dimensions();
  add(trailing);
  if (!trailing.empty()) ida_runs_ = trailing.back().size;
  for (auto n : shape_) size_ *= static_cast<std::int64_t>(n);
}

std::vector<std::size_t> CaseSpace::coordinates(std::int64_t index) const { return unravel(index, shape_); }

std::int64_t CaseSpace::index(const std::vector<std::size_t>& coordinates) const {
  return ravel(coordinates, shape_);
}

CaseSpec CaseSpace::case_at(std::int64_t index) const {
  const auto c = coordinates(index);
  const std::span<const std::size_t> frame(c.data() + frame_dim_, plan_->dimensions().size());
  return {c[0], levels_.empty() ? std::nan("") : levels_[c[1]], plan_->frame_at(frame)};
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

std::vector<ScenePoint> CaseSpace::frames() const { return plan_->frames(); }

std::int64_t CaseSpace::resolve(const HistoryRequest& request) const {
  std::vector<std::size_t> coords(shape_.size());
  if (request.record) {
    auto it = std::find(record_names_.begin(), record_names_.end(), *request.record);
    if (it == record_names_.end()) fail_history(request, "no record is named \"" + *request.record + "\"");
    coords[0] = static_cast<std::size_t>(it - record_names_.begin());
  } else {
    coords[0] = pick_single(request, record_names_.size(), vocabulary::kRecord);
  }
  if (request.scale) {
    coords[1] = find_value(levels_, *request.scale);
    if (coords[1] == std::string::npos)
      fail_history(request, names_[1] + " " + number_text(*request.scale) + " is not on the " + names_[1] + " axis");
  } else {
    coords[1] = pick_single(request, levels_.size(), names_[1]);
  }
  const auto frame = plan_->locate(request);
  std::copy(frame.begin(), frame.end(), coords.begin() + static_cast<std::ptrdiff_t>(frame_dim_));
  return index(coords);
}

}  // namespace pcrf::study

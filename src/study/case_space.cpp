// Enumeration of a study's cases (see case_space.hpp).
#include "pcrf/study/case_space.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "pcrf/row_major.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf::study {

CaseSpace::CaseSpace(const Study& study)
    : plan_(study.plan), level_axis_(make_level_axis(study)), levels_(level_axis_->levels()),
      incidences_(study.incidence_deg) {
  selection_ = study.selection;
  if (selection_)
    for (std::size_t k = 0; k < selection_->settings.count; ++k) record_names_.push_back("slot_" + std::to_string(k + 1));
  for (const auto& r : study.records) {
    if (!selection_) record_names_.push_back(r.name);
    const double strike = r.strike_deg.value_or(0.0);  // the parser requires it where it is used
    incidence_origin_deg_.push_back(study.incidence_reference == "fault-normal"     ? strike + 90.0
                                    : study.incidence_reference == "fault-parallel" ? strike
                                                                                    : 0.0);
  }
  names_ = {schema::kRecord};
  shape_ = {record_names_.size()};
  auto add = [&](const std::vector<cube::Dimension>& dimensions) {
    for (const auto& d : dimensions) {
      names_.push_back(d.name);
      shape_.push_back(d.size);
    }
  };
  add(level_axis_->leading_dimensions());
  if (!incidences_.empty()) {
    incidence_dim_ = shape_.size();
    add({{schema::kIncidenceDeg, incidences_.size()}});
  }
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
  // unravel's coordinates on the stack (a vector a case cost 250 instructions of the ~3 000
  // case_at took for an LHS frame, issue 38); a space of more axes than that is unravelled as before.
  std::array<std::size_t, 16> on_stack;
  std::vector<std::size_t> on_heap;
  if (shape_.size() > on_stack.size()) on_heap.resize(shape_.size());
  const std::span<std::size_t> c = on_heap.empty() ? std::span(on_stack).first(shape_.size()) : std::span(on_heap);
  unravel_into(index, shape_, c);
  const std::span<const std::size_t> frame(c.data() + frame_dim_, plan_->dimensions().size());
  const auto [record, factor] = record_at(c[0], levels_.empty() ? 0 : c[1]);
  CaseSpec spec{record, levels_.empty() ? std::nan("") : levels_[c[1]], plan_->frame_at(frame), std::nullopt, factor};
  if (incidence_dim_ > 0) spec.incidence_deg = frame_azimuth_deg(record, incidences_[c[incidence_dim_]]);
  return spec;
}

std::pair<std::size_t, std::optional<double>> CaseSpace::record_at(std::size_t slot, std::size_t stripe) const {
  if (!selection_) return {slot, std::nullopt};
  const auto& s = selection_->stripes.at(stripe);
  return {s.records.at(slot), s.scales.at(slot)};
}

std::vector<std::int64_t> CaseSpace::frame_major(std::vector<std::int64_t> indices, std::int64_t frames_together) const {
  // Key: the frame's tile among the frame axes, then the record and level axes, then the
  // frame within its tile (storage order: the frame axes vary fastest).
  const std::int64_t frames = frame_count();
  const std::int64_t per_frame = size_ / frames, tile = std::max<std::int64_t>(frames_together, 1);
  auto key = [&](std::int64_t index) {
    const std::int64_t frame = index % frames;
    return ((frame / tile) * per_frame + index / frames) * tile + frame % tile;
  };
  std::stable_sort(indices.begin(), indices.end(), [&](std::int64_t a, std::int64_t b) { return key(a) < key(b); });
  return indices;
}

std::int64_t CaseSpace::frame_count() const {
  std::int64_t frames = 1;
  for (std::size_t d = frame_dim_; d < shape_.size(); ++d) frames *= static_cast<std::int64_t>(shape_[d]);
  return frames;
}

std::int64_t CaseSpace::excitation_of(std::int64_t index) const {
  const std::int64_t frames = frame_count();
  return index / frames;
}

std::int64_t CaseSpace::handout_index(std::int64_t position) const {
  if (!plan_->hands_out_by_frame() || ida_runs_ > 0) return position;
  const std::int64_t frames = frame_count();
  const std::int64_t per_frame = size_ / frames;
  return (position % per_frame) * frames + position / per_frame;
}

std::int64_t CaseSpace::handout_position(std::int64_t index) const {
  if (!plan_->hands_out_by_frame() || ida_runs_ > 0) return index;
  const std::int64_t frames = frame_count();
  const std::int64_t per_frame = size_ / frames;
  return (index % frames) * per_frame + index / frames;
}

std::vector<std::size_t> CaseSpace::chunk_multiples() const {
  std::vector<std::size_t> multiples(shape_.size(), 1);
  const std::size_t frame_axes = plan_->dimensions().size();
  if (frame_axes > 0) multiples[frame_dim_ + frame_axes - 1] = std::max<std::size_t>(plan_->frames_per_group(), 1);
  return multiples;
}

std::vector<SceneSpec> CaseSpace::frames() const { return plan_->frames(); }

std::int64_t CaseSpace::distinct_frames() const {
  std::int64_t n = 1;
  for (const auto& d : plan_->dimensions()) n *= static_cast<std::int64_t>(d.size);
  return n;
}

void CaseSpace::for_each_frame(const std::function<void(const SceneSpec&)>& visit) const {
  std::vector<std::size_t> shape;
  for (const auto& d : plan_->dimensions()) shape.push_back(d.size);
  const std::int64_t n = distinct_frames();
  for (std::int64_t f = 0; f < n; ++f) visit(plan_->frame_at(unravel(f, shape)));  // row-major, as frames()
}

std::int64_t CaseSpace::resolve(const HistoryRequest& request) const {
  std::vector<std::size_t> coords(shape_.size());
  if (request.record) {
    auto it = std::find(record_names_.begin(), record_names_.end(), *request.record);
    if (it == record_names_.end()) fail_history(request, "no record is named \"" + *request.record + "\"");
    coords[0] = static_cast<std::size_t>(it - record_names_.begin());
  } else {
    coords[0] = pick_single(request, record_names_.size(), schema::kRecord);
  }
  if (request.scale) {
    coords[1] = find_value(levels_, *request.scale);
    if (coords[1] == std::string::npos)
      fail_history(request, names_[1] + " " + number_text(*request.scale) + " is not on the " + names_[1] + " axis");
  } else {
    coords[1] = pick_single(request, levels_.size(), names_[1]);
  }
  if (incidence_dim_ > 0) {
    if (request.incidence_deg) {
      coords[incidence_dim_] = find_value(incidences_, *request.incidence_deg);
      if (coords[incidence_dim_] == std::string::npos)
        fail_history(request, "incidence_deg " + number_text(*request.incidence_deg) + " is not on the incidence_deg axis");
    } else {
      coords[incidence_dim_] = pick_single(request, incidences_.size(), schema::kIncidenceDeg);
    }
  } else if (request.incidence_deg) {
    fail_history(request, "the study has no incidence axis");
  }
  const auto frame = plan_->locate(request);
  std::copy(frame.begin(), frame.end(), coords.begin() + static_cast<std::ptrdiff_t>(frame_dim_));
  return index(coords);
}

}  // namespace pcrf::study

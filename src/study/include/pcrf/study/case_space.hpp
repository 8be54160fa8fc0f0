/// \file case_space.hpp
/// \brief The cases of a study as a row-major cube: linear index ↔ coordinates ↔ the case
/// itself (record, scale factor, frame parameters).
///
/// Dimensions: record × the level axis (scale or intensity; none in an IDA) × with an
/// incidence axis `incidence_deg` × the plan's frame dimensions (plan.hpp: grid, one per parameter; the others, `case`) × in an IDA
/// `ida_point`, the runs of each curve.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pcrf/study/level_axis.hpp"
#include "pcrf/study/plan.hpp"
#include "pcrf/study/study.hpp"

namespace pcrf::study {

/// One case, ready to build a frame and scale a record.
struct CaseSpec {
  std::size_t record = 0;  ///< index into Study::records
  double level = 1.0;  ///< the record's scale factor, or (intensity axis) its target intensity
  SceneSpec frame;     ///< the scene: its model and values
  /// The azimuth of the frame's plane [deg from north] (its incidence resolved for this
  /// record); none without an incidence axis (the frame lies along the first component).
  std::optional<double> incidence_deg;
  /// The factor on the record's accelerations when the study fixes it per case ([selection]:
  /// the selection's scale factor of the record in its stripe); none: RecordCache::scale_factor.
  std::optional<double> factor = std::nullopt;
};

class CaseSpace {
 public:
  explicit CaseSpace(const Study& study);

  const Plan& plan() const { return *plan_; }
  const LevelAxis& level_axis() const { return *level_axis_; }
  std::int64_t size() const { return size_; }
  const std::vector<std::string>& dimension_names() const { return names_; }
  const std::vector<std::size_t>& shape() const { return shape_; }

  std::vector<std::size_t> coordinates(std::int64_t index) const;
  std::int64_t index(const std::vector<std::size_t>& coordinates) const;
  CaseSpec case_at(std::int64_t index) const;

  /// The values of the `record` dimension: the records' names, or with [selection] the slots
  /// of a stripe's set ("slot_1", …), each stripe's record in a slot being its own.
  const std::vector<std::string>& record_names() const { return record_names_; }
  /// [selection]: the record (index into Study::records) and its scale factor in slot `slot`
  /// of stripe `stripe`; without one, the record `slot` itself and no factor.
  std::pair<std::size_t, std::optional<double>> record_at(std::size_t slot, std::size_t stripe) const;
  /// Values of the second axis (`scale` or `intensity`, see Study::levels).
  const std::vector<double>& levels() const { return levels_; }
  /// `indices` reordered so that the cases of one frame (every record and level) are
  /// adjacent, frames in storage order: a worker then prepares each frame once. With
  /// `frames_together` > 1, the same for tiles of that many frames: in a tile, the cases of
  /// one excitation (excitation_of) are adjacent, for a worker to compute them in lockstep.
  std::vector<std::int64_t> frame_major(std::vector<std::int64_t> indices, std::int64_t frames_together = 1) const;
  /// The excitation of a case — its record, level and incidence — as a number: equal for two
  /// cases exactly when their frames feel the same ground motion.
  std::int64_t excitation_of(std::int64_t index) const;
  /// The case handed out `position`-th: `position` itself (storage order), or when the plan
  /// hands out by frame (Plan::hands_out_by_frame) frame-major over the whole cube: every
  /// record, level and incidence of frame 0, then of frame 1, … A bijection of [0, size()).
  std::int64_t handout_index(std::int64_t position) const;
  /// The position at which case `index` is handed out: the inverse of handout_index.
  std::int64_t handout_position(std::int64_t index) const;
  /// Per dimension, the multiple a chunk of the cube holds along it where it cuts it
  /// (cube::ChunkGrid): the plan's frames_per_group along its last frame axis, 1 elsewhere.
  std::vector<std::size_t> chunk_multiples() const;
  /// The first of the plan's frame axes (after record, the level axis and the incidence
  /// axis); they run to the end of the shape but in an IDA, whose runs (ida_point) follow.
  std::size_t frame_dimension() const { return frame_dim_; }
  /// Distinct frames of the study (every parameter combination), for up-front checks.
  std::vector<SceneSpec> frames() const;
  /// Number of distinct frames (frames().size()).
  std::int64_t distinct_frames() const;
  /// Calls `visit` with each of frames() in turn, in its order, made one at a time: memory
  /// for one frame, not for every frame of the study.
  void for_each_frame(const std::function<void(const SceneSpec&)>& visit) const;

  /// The incidence axis' values as the study gives them (empty: no such axis).
  const std::vector<double>& incidences() const { return incidences_; }
  /// The frame's azimuth [deg from north] for record `record` at incidence value `incidence`.
  double frame_azimuth_deg(std::size_t record, double incidence) const { return incidence_origin_deg_[record] + incidence; }

  /// IDA: runs per curve (the last axis, ida_point); 0 otherwise. Curve c's k-th run is case
  /// c · ida_runs() + k, the curves being the records × frames in row-major order.
  std::size_t ida_runs() const { return ida_runs_; }
  /// Number of curves of an IDA (records × frames).
  std::int64_t curves() const { return ida_runs_ > 0 ? size_ / static_cast<std::int64_t>(ida_runs_) : 0; }

  /// The single case a history request names. \throws UserError naming the request.
  std::int64_t resolve(const HistoryRequest& request) const;

 private:
  /// Cases a record, level and incidence have: the product of the frame axes.
  std::int64_t frame_count() const;
  std::shared_ptr<const Plan> plan_;
  std::shared_ptr<const LevelAxis> level_axis_;
  std::vector<std::string> names_;
  std::vector<std::size_t> shape_;
  std::int64_t size_ = 1;
  std::vector<std::string> record_names_;
  std::optional<Study::StripeSelection> selection_;
  std::vector<double> levels_;
  std::size_t frame_dim_ = 2;  ///< first frame axis (after record and the level axis, if any)
  std::vector<double> incidences_;
  std::vector<double> incidence_origin_deg_;  ///< per record: what the incidence counts from
  std::size_t incidence_dim_ = 0;             ///< 0: no incidence axis
  std::size_t ida_runs_ = 0;
};

}  // namespace pcrf::study

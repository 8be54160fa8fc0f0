/// \file case_space.hpp
/// \brief The cases of a study as a row-major cube: linear index ↔ coordinates ↔ the case
/// itself (record, scale factor, frame parameters).
///
/// Dimensions by plan:
///   grid           record × scale × kappa × lambda × tan_alpha × lambda_h × pi_sigma_b ×
///                  pi_sigma_c × pi_e_b × pi_e_c (a parameter not swept has one value)
///   one-at-a-time  record × scale × case; `case` enumerates the base point (if included)
///   and list       and each sweep value, or the listed cases; every case carries its label,
///                  its eight parameter values and (one-at-a-time) the varied parameter.
///   lhs, sobol,    record × scale × case; `case` enumerates the sampled frames ("s0", …);
///   saltelli       saltelli's are grouped by base sample j: A_j, B_j, A_B^(i)_j for each
///                  varied parameter i, labelled "s<j>:A", "s<j>:B", "s<j>:AB_<parameter>".
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "pcrf/study/study.hpp"

namespace pcrf::study {

/// One case, ready to build a frame and scale a record.
struct CaseSpec {
  std::size_t record = 0;  ///< index into Study::records
  double level = 1.0;  ///< the record's scale factor, or (intensity axis) its target intensity
  FrameParameters parameters;
};

/// A frame of the one-at-a-time or list plan (a value of the `case` dimension).
struct CasePoint {
  std::string label;   ///< "base", "kappa=1.2", the list case's label, or "s12" (sampled)
  std::string varied;  ///< parameter swept ("none" for the base point); list: empty
  FrameParameters parameters;
  std::string block;   ///< saltelli: "A", "B" or "AB_<parameter>"
  long sample = -1;    ///< saltelli: the base sample j this frame belongs to
};

class CaseSpace {
 public:
  explicit CaseSpace(const Study& study);

  PlanKind plan() const { return plan_; }
  std::int64_t size() const { return size_; }
  const std::vector<std::string>& dimension_names() const { return names_; }
  const std::vector<std::size_t>& shape() const { return shape_; }

  std::vector<std::size_t> coordinates(std::int64_t index) const;
  std::int64_t index(const std::vector<std::size_t>& coordinates) const;
  CaseSpec case_at(std::int64_t index) const;

  const std::vector<std::string>& record_names() const { return record_names_; }
  /// Values of the second axis (`scale` or `intensity`, see Study::levels).
  const std::vector<double>& levels() const { return levels_; }
  /// Grid plan: values of each parameter axis.
  const std::vector<double>& grid_values(std::size_t parameter) const { return grid_values_[parameter]; }
  /// One-at-a-time and list plans: the frames along `case`.
  const std::vector<CasePoint>& points() const { return points_; }
  /// `indices` reordered so that the cases of one frame (every record and level) are
  /// adjacent, frames in storage order: a worker then prepares each frame once.
  std::vector<std::int64_t> frame_major(std::vector<std::int64_t> indices) const;
  /// Distinct frames of the study (every parameter combination), for up-front checks.
  std::vector<FrameParameters> frames() const;

  /// IDA: runs per curve (the last axis, ida_point); 0 otherwise. Curve c's k-th run is case
  /// c · ida_runs() + k, the curves being the records × frames in row-major order.
  std::size_t ida_runs() const { return ida_runs_; }
  /// Number of curves of an IDA (records × frames).
  std::int64_t curves() const { return ida_runs_ > 0 ? size_ / static_cast<std::int64_t>(ida_runs_) : 0; }

  /// The single case a history request names. \throws StudyError naming the request.
  std::int64_t resolve(const HistoryRequest& request) const;

 private:
  PlanKind plan_;
  FrameParameters base_;
  std::vector<std::string> names_;
  std::vector<std::size_t> shape_;
  std::int64_t size_ = 1;
  std::vector<std::string> record_names_;
  std::vector<double> levels_;
  std::size_t frame_dim_ = 2;  ///< first frame axis (after record and the level axis, if any)
  std::size_t ida_runs_ = 0;
  std::array<std::vector<double>, kParameterCount> grid_values_;
  std::vector<CasePoint> points_;
};

}  // namespace pcrf::study

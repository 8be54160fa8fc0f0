/// \file plan.hpp
/// \brief A study's plan: how the frames of a study (the scene of each case: its model and
/// the values of the model's parameters) are laid out along the frame dimensions of its cube.
///
/// A plan owns its dimensions, the frame at each of their points, the cube's coordinate
/// variables along them, how a history request names one of its frames, and its part of the
/// study's canonical text (fingerprint.hpp). CaseSpace, the cube layout and the fingerprint
/// ask the plan; none of them knows which plan it is. The plans and their [plan] keys are
/// listed in src/study/plans/plan_registry.cpp, each plan in a file of its own there.
#pragma once

#include <cstddef>
#include <ostream>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pcrf/cube/cube_layout.hpp"
#include "pcrf/model/parameters.hpp"
#include "pcrf/number_text.hpp"
#include "pcrf/study/study.hpp"

namespace pcrf::study {

class Plan {
 public:
  virtual ~Plan() = default;

  /// The plan's name: its [plan] kind, and the cube's `plan` attribute.
  virtual std::string_view name() const = 0;

  /// The frame dimensions (they follow record and the level axis in the cube), outermost
  /// first; their sizes multiply to the number of frames.
  virtual const std::vector<cube::Dimension>& dimensions() const = 0;

  /// The frame at `coordinates` (one per dimension, each below its size): its scene.
  virtual SceneSpec frame_at(std::span<const std::size_t> coordinates) const = 0;

  /// Every frame, in storage order (row-major over dimensions()).
  virtual std::vector<SceneSpec> frames() const = 0;

  /// The cube's coordinate variables along dimensions(), with their auxiliary coordinates.
  virtual std::vector<cube::Coordinate> coordinates() const = 0;

  /// The coordinates of the frame a history request names (every frame dimension of more
  /// than one value must be given). \throws UserError naming the request (fail_history).
  virtual std::vector<std::size_t> locate(const HistoryRequest& request) const = 0;

  /// Why a history's key `key` (`case`, or a parameter's name) cannot select a frame of this
  /// plan; empty when it can. The parser asks, so that the message names the key's line.
  virtual std::string history_key_problem(std::string_view key) const = 0;

  /// The plan's part of the study's canonical text: the rest of its `plan <name>` line...
  virtual std::string canonical_heading() const;
  /// ...and whole lines (each ending in '\n') that follow the base point's line. Numbers are
  /// written at the stream's precision. Two studies with the same text compute the same frames.
  virtual void describe(std::ostream& out) const = 0;

  /// True when the plan's results are read frame by frame across every record (a Saltelli
  /// design's base sample is whole once its frames ran for all records): the study hands
  /// its cases out frame by frame over the whole cube (CaseSpace::handout_index), so that a
  /// partial cube holds whole base samples. False: in storage order.
  virtual bool hands_out_by_frame() const { return false; }

  /// Frames that belong together along the plan's last frame dimension (a Saltelli base
  /// sample: its d + 2 frames A, B, AB_1 … AB_d, one after another): a chunk of the cube that
  /// cuts that dimension holds whole groups of them (cube::ChunkGrid's multiples). 1: none.
  virtual std::size_t frames_per_group() const { return 1; }

  /// Memory the plan holds per frame [bytes] (an upper estimate), which the study's size
  /// check counts: a plan that computes its frames from their numbers (grid, the sampled
  /// plans) holds none, one that lists them (list, one-at-a-time) holds each.
  virtual double bytes_per_frame() const { return 0.0; }
};

/// The names of every plan kind a study file can give ([plan] kind), the default first.
std::vector<std::string_view> plan_kinds();

/// \throws UserError at the request's label: "history \"<label>\": <problem>".
[[noreturn]] void fail_history(const HistoryRequest& request, const std::string& problem);

/// 0 when an axis has a single value; otherwise fail_history asking for `key`.
std::size_t pick_single(const HistoryRequest& request, std::size_t size, const std::string& key);

/// Position of `value` on an axis (relative tolerance 1e-12), or std::string::npos.
std::size_t find_value(const std::vector<double>& axis, double value);


/// A numeric coordinate variable along `dimension`.
cube::Coordinate number_coordinate(std::string name, std::string dimension, std::string units, std::string long_name,
                                   std::vector<double> values);
/// A text coordinate variable along `dimension`.
cube::Coordinate text_coordinate(std::string name, std::string dimension, std::string long_name,
                                 std::vector<std::string> values);

}  // namespace pcrf::study

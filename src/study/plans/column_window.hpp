// A thread's window of a computed plan's values, filled a column at a time (issue 38). A
// worker handed a unit of consecutive cases asks for each case's point (frame_values, the
// case's set-up), then, sealing the unit, for the unit's piece of each coordinate
// (point_values): computing each point's coordinates together (the design's row) and then
// each coordinate's piece again (its column) did the work twice, the first time by the
// slower path. A window computes the values once by columns, where the frames asked come in
// runs, and hands them to both.
//
// Which frames it fills. Only frames asked in a run (frame i after frame i - 1) are filled,
// each fill as long as the run so far (at least kFirstFillFrames), and never past the end of
// the aligned window of kWindowFrames frames that holds the frame asked: frames asked one by
// one in any other order (the last cases handed out one by one, a history, a test's
// strides) fill nothing and are computed by the caller, and a run's fills hold at most the
// run's frames plus as many again (plus kFirstFillFrames), never more than one window. The
// frames a run already had before its fill are filled with it, so that the unit's pieces are
// whole in the window when the unit is sealed.
//
// Memory: kWindowFrames values per column, allocated at the first fill (1 MiB a thread for
// 8 varied parameters); a thread keeps one window, of the plan it last filled for.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace pcrf::study::detail {

class ColumnWindow {
 public:
  /// Frames a window holds, aligned to multiples of it [frames]: the cube's unit of an LHS
  /// along `case` (16 384 cases a chunk), so that a unit's pieces lie in one window.
  static constexpr std::size_t kWindowFrames = 16384;
  /// The shortest fill [frames]: two frames in a run fill this many.
  static constexpr std::size_t kFirstFillFrames = 32;

  /// Frame i's `out.size()` column values (column s into out[s]) of the plan `owner` (an id
  /// no other plan has) of `frames` frames, when the window has them or the frames asked run
  /// into i (then it fills them first, by fill(s, first, values): column s of frames first,
  /// first + 1, …). False: not held; the caller computes them.
  template <class Fill>
  bool frame(std::uint64_t owner, std::size_t frames, std::size_t i, std::span<double> out, Fill&& fill) {
    if (owner != owner_) take(owner, out.size());
    run_ = i == last_ + 1 ? run_ + 1 : i == last_ ? run_ : 1;
    last_ = i;
    if (!holds(i)) {
      if (run_ < 2 || i >= frames) return false;  // a frame past the plan's: the caller's, as before
      extend_to(i, frames, fill);
    }
    for (std::size_t s = 0; s < out.size(); ++s) out[s] = values_[s * kWindowFrames + (i - start_)];
    return true;
  }

  /// Copies the values the window holds of column s of frames [first, first + out.size()) of
  /// plan `owner` into out, and says which frames they are: [from, to), empty (from == to)
  /// when none. The caller computes the others.
  std::pair<std::size_t, std::size_t> piece(std::uint64_t owner, std::size_t s, std::size_t first, std::span<double> out) const {
    if (owner != owner_ || s >= columns_) return {first, first};
    const std::size_t from = std::max(first, lo_), to = std::min(first + out.size(), hi_);
    if (from >= to) return {first, first};
    std::copy_n(values_.data() + s * kWindowFrames + (from - start_), to - from, out.begin() + static_cast<std::ptrdiff_t>(from - first));
    return {from, to};
  }

  /// Values computed by fills since the window was made [values]: what the tests weigh.
  std::size_t filled_values() const { return filled_; }

 private:
  static constexpr std::size_t kNone = static_cast<std::size_t>(-1);

  std::uint64_t owner_ = 0;
  std::size_t columns_ = 0;
  std::size_t start_ = 0;        ///< the window's first frame, a multiple of kWindowFrames
  std::size_t lo_ = 0, hi_ = 0;  ///< frames held: [lo_, hi_) within the window
  std::size_t last_ = kNone;     ///< the frame asked last
  std::size_t run_ = 0;          ///< frames asked in a run ending at last_
  std::size_t filled_ = 0;
  std::vector<double> values_;   ///< column s of frame start_ + m at [s * kWindowFrames + m]

  bool holds(std::size_t i) const { return i >= lo_ && i < hi_; }

  /// Another plan's window: nothing held, no run.
  void take(std::uint64_t owner, std::size_t columns) {
    owner_ = owner;
    columns_ = columns;
    lo_ = hi_ = 0;
    last_ = kNone;
    run_ = 0;
  }

  /// Fills frames up to at least i + 1: on from what is held when i follows it in the same
  /// window, else anew from the run's first frame in i's window. A fill that throws leaves
  /// held only frames it did not touch.
  template <class Fill>
  void extend_to(std::size_t i, std::size_t frames, Fill& fill) {
    if (values_.size() < columns_ * kWindowFrames) values_.resize(columns_ * kWindowFrames);
    const std::size_t start = i / kWindowFrames * kWindowFrames;
    std::size_t from = hi_;
    if (!(start == start_ && lo_ < hi_ && i == hi_)) {
      start_ = start;
      from = std::max(i + 1 - run_, start);
      lo_ = hi_ = from;
    }
    const std::size_t to = std::min({i + std::max(run_, kFirstFillFrames), start + kWindowFrames, frames});
    for (std::size_t s = 0; s < columns_; ++s)
      fill(s, from, std::span(values_.data() + s * kWindowFrames + (from - start), to - from));
    filled_ += (to - from) * columns_;
    hi_ = to;
  }
};

}  // namespace pcrf::study::detail

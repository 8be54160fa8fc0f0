// ColumnWindow (src/study/plans/column_window.hpp): which frames it fills and what it hands
// back, with a fill whose values say their column and frame, so that any value out of place
// shows; the plans' values through it are compared bit for bit in plan_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <stdexcept>
#include <span>
#include <vector>

#include "study/plans/column_window.hpp"

namespace pcrf::study::detail {
namespace {

constexpr std::size_t kWindow = ColumnWindow::kWindowFrames;

/// Column s of frame i.
double value_of(std::size_t s, std::size_t i) { return static_cast<double>(s) * 1e9 + static_cast<double>(i); }

/// A plan's columns as the window fills them: checks each fill lies within the plan's frames.
struct Columns {
  std::size_t frames = 0;
  std::size_t fills = 0;
  std::size_t throw_at = static_cast<std::size_t>(-1);  ///< the fill (counted from 0) that throws, half written
  void operator()(std::size_t s, std::size_t first, std::span<double> out) {
    ASSERT_LE(first + out.size(), frames) << "a fill past the plan's last frame";
    ASSERT_FALSE(out.empty()) << "an empty fill";
    if (fills++ == throw_at) {
      std::fill(out.begin(), out.end(), -2.0);
      throw std::runtime_error("fill failed");
    }
    for (std::size_t m = 0; m < out.size(); ++m) out[m] = value_of(s, first + m);
  }
};

/// Asks frame i of `owner`: true when the window answered, its values then checked.
bool ask(ColumnWindow& window, Columns& columns, std::uint64_t owner, std::size_t i, std::size_t width = 3) {
  std::vector<double> out(width, -1.0);
  if (!window.frame(owner, columns.frames, i, std::span(out), columns)) return false;
  for (std::size_t s = 0; s < width; ++s) EXPECT_EQ(out[s], value_of(s, i)) << "column " << s << " of frame " << i;
  return true;
}

/// The frames [from, to) of column s the window holds are those it hands back, each right.
std::pair<std::size_t, std::size_t> held(const ColumnWindow& window, std::uint64_t owner, std::size_t s, std::size_t first,
                                         std::size_t count) {
  std::vector<double> out(count, -1.0);
  const auto [from, to] = window.piece(owner, s, first, out);
  EXPECT_LE(first, from);
  EXPECT_LE(to, first + count);
  for (std::size_t i = from; i < to; ++i) EXPECT_EQ(out[i - first], value_of(s, i)) << "frame " << i;
  for (std::size_t i = first; i < first + count; ++i)
    if (i < from || i >= to) {
      EXPECT_EQ(out[i - first], -1.0) << "frame " << i << " written though not held";
    }
  return {from, to};
}

TEST(ColumnWindow, FramesAskedOutOfOrderFillNothing) {
  ColumnWindow window;
  Columns columns{100000};
  std::vector<std::size_t> order(5000);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), std::mt19937(7));
  for (std::size_t i : order) EXPECT_FALSE(ask(window, columns, 1, i * 17));  // never one frame after the other
  for (std::size_t i = 0; i < 2000; i += 2) EXPECT_FALSE(ask(window, columns, 1, i));
  EXPECT_EQ(window.filled_values(), 0u) << "frames asked one by one are the caller's to compute";
  EXPECT_EQ(held(window, 1, 0, 0, 100), (std::pair<std::size_t, std::size_t>{0, 0}));
}

TEST(ColumnWindow, AUnitAskedInOrderIsFilledOnceAndSealedFromTheWindow) {
  ColumnWindow window;
  Columns columns{5 * kWindow};
  const std::size_t unit = 2 * kWindow;
  EXPECT_FALSE(ask(window, columns, 1, unit)) << "the unit's first frame: no run yet";
  for (std::size_t i = unit + 1; i < unit + kWindow; ++i) ASSERT_TRUE(ask(window, columns, 1, i));
  EXPECT_EQ(window.filled_values(), 3 * kWindow) << "every frame of the unit once, the first included, nothing past it";
  for (std::size_t s = 0; s < 3; ++s)
    EXPECT_EQ(held(window, 1, s, unit, kWindow), (std::pair{unit, unit + kWindow})) << "column " << s;
  EXPECT_EQ(held(window, 1, 3, unit, kWindow), (std::pair{unit, unit})) << "no column 3";
  EXPECT_EQ(held(window, 2, 0, unit, kWindow), (std::pair{unit, unit})) << "another plan's";
  // A piece that starts before the window and ends after it: only the held frames come back.
  EXPECT_EQ(held(window, 1, 1, unit - 100, kWindow + 200), (std::pair{unit, unit + kWindow}));
  // The next unit, on the same worker: its first frame continues the run and fills the window whole.
  ASSERT_TRUE(ask(window, columns, 1, unit + kWindow));
  EXPECT_EQ(window.filled_values(), 6 * kWindow);
  EXPECT_EQ(held(window, 1, 2, unit + kWindow, kWindow), (std::pair{unit + kWindow, unit + 2 * kWindow}));
}

TEST(ColumnWindow, AShortRunFillsAtMostTwiceItsFramesAndNoneOfTheNextWindow) {
  for (std::size_t length : {2u, 3u, 31u, 33u, 100u, 1000u, 5000u}) {
    SCOPED_TRACE(length);
    ColumnWindow window;
    Columns columns{10 * kWindow};
    const std::size_t first = kWindow + 7;
    for (std::size_t i = first; i < first + length; ++i) ASSERT_EQ(ask(window, columns, 1, i, 2), i > first);
    EXPECT_LE(window.filled_values(), 2 * (2 * length + ColumnWindow::kFirstFillFrames));
    EXPECT_GE(window.filled_values(), 2 * length);
  }
  // A run that crosses a window's end: each fill stops at it, the next window starts anew.
  ColumnWindow window;
  Columns columns{3 * kWindow};
  for (std::size_t i = kWindow - 40; i < kWindow + 40; ++i) ASSERT_EQ(ask(window, columns, 1, i), i > kWindow - 40);
  EXPECT_EQ(held(window, 1, 0, kWindow - 40, 80).first, kWindow);
}

TEST(ColumnWindow, TheLastWindowStopsAtThePlansLastFrame) {
  ColumnWindow window;
  Columns columns{kWindow + 500};  // the last window holds 500 frames
  for (std::size_t i = kWindow; i < kWindow + 500; ++i) ASSERT_EQ(ask(window, columns, 1, i), i > kWindow);
  EXPECT_EQ(held(window, 1, 2, kWindow, kWindow), (std::pair{kWindow, kWindow + 500}));
  EXPECT_EQ(window.filled_values(), 3 * 500u);
  EXPECT_FALSE(ask(window, columns, 1, kWindow + 500)) << "a frame past the plan's is not the window's";
  EXPECT_EQ(window.filled_values(), 3 * 500u);
}

TEST(ColumnWindow, RepeatedAndRevisitedFramesKeepTheirValues) {
  ColumnWindow window;
  Columns columns{3 * kWindow};
  // An IDA's cases: each frame several times (its runs), frame after frame.
  for (std::size_t i = 100; i < 400; ++i)
    for (int run = 0; run < 5; ++run) (void)ask(window, columns, 1, i);
  // Frames revisited (lanes: a tile of frames, every record in turn) and asked backwards.
  for (int record = 0; record < 3; ++record)
    for (std::size_t i = 200; i < 264; ++i) EXPECT_TRUE(ask(window, columns, 1, i));
  for (std::size_t i = 399; i > 150; --i) EXPECT_TRUE(ask(window, columns, 1, i));
  EXPECT_LE(window.filled_values(), 3 * (2 * 300 + ColumnWindow::kFirstFillFrames));
  // Runs here and there, in random order: what comes back is always right (ask checks it).
  std::mt19937 random(3);
  for (int k = 0; k < 200; ++k) {
    const std::size_t start = std::uniform_int_distribution<std::size_t>(0, 3 * kWindow - 1)(random);
    const std::size_t length = std::uniform_int_distribution<std::size_t>(1, 300)(random);
    for (std::size_t i = start; i < std::min(start + length, 3 * kWindow); ++i) (void)ask(window, columns, 1 + k % 2, i);
    const std::size_t first = std::uniform_int_distribution<std::size_t>(0, 3 * kWindow - 1000)(random);
    (void)held(window, 1 + k % 2, k % 3, first, 1000);
  }
}

TEST(ColumnWindow, AFillThatThrowsLeavesNothingWrongHeld) {
  // A fill that throws half way (its column half written): the frames it was filling are not
  // held, whether it extended the window or started it anew; the frames asked later are right.
  for (std::size_t throw_at : {1u, 2u, 4u, 5u}) {
    SCOPED_TRACE(throw_at);
    ColumnWindow window;
    Columns columns{3 * kWindow};
    columns.throw_at = throw_at;  // 3 columns a fill: 1, 2 the first fill; 4, 5 the second
    std::size_t thrown = 0;
    for (std::size_t i = 10; i < 200; ++i) {
      try {
        (void)ask(window, columns, 1, i);
      } catch (const std::runtime_error&) {
        ++thrown;
      }
    }
    EXPECT_EQ(thrown, 1u);
    for (std::size_t s = 0; s < 3; ++s) (void)held(window, 1, s, 0, 300);  // checks every value held
    for (std::size_t i = 10; i < 200; ++i) (void)ask(window, columns, 1, i);
    // A run that starts anew below what the window holds, its fill failing.
    columns.throw_at = columns.fills + 1;
    EXPECT_THROW(for (std::size_t i = 0; i < 10; ++i) (void)ask(window, columns, 1, i), std::runtime_error);
    for (std::size_t s = 0; s < 3; ++s) (void)held(window, 1, s, 0, 300);
  }
}

}  // namespace
}  // namespace pcrf::study::detail

// Every plan kind keeps the Plan contract: its dimensions count its frames, frame_at and
// frames() agree in storage order, each dimension has its coordinate variable and every
// coordinate spans its dimension, and its canonical text tells two plans apart.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <map>
#include <numeric>
#include <random>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "pcrf/row_major.hpp"
#include "pcrf/study/plan.hpp"
#include "pcrf/study/study_parser.hpp"
#include "study/study_test_support.hpp"

namespace pcrf::study {
namespace {

const std::string kRecords = "[[records]]\nsynthetic = \"sine:amplitude_g=1.5\"\n";

/// Two studies of each kind that differ in one value of the plan.
const std::map<std::string, std::pair<std::string, std::string>> kStudies = {
    {"grid", {"[axes]\nkappa = [1.5, 2]\npi_e_c = [2000, 3000, 4000]\n", "[axes]\nkappa = [1.5, 2.5]\npi_e_c = [2000, 3000, 4000]\n"}},
    {"one-at-a-time",
     {"[plan]\nkind = \"one-at-a-time\"\n[axes]\nkappa = [1.5, 2]\ntan_alpha = [0.2]\n",
      "[plan]\nkind = \"one-at-a-time\"\ninclude_base = false\n[axes]\nkappa = [1.5, 2]\ntan_alpha = [0.2]\n"}},
    {"list", {"[plan]\nkind = \"list\"\n[[cases]]\nkappa = 1.5\n[[cases]]\nlabel = \"b\"\ntan_alpha = 0.2\n",
              "[plan]\nkind = \"list\"\n[[cases]]\nkappa = 1.5\n[[cases]]\nlabel = \"b\"\ntan_alpha = 0.25\n"}},
    {"lhs", {"[plan]\nkind = \"lhs\"\nsamples = 5\n[axes]\nkappa = {from = 1.2, to = 2.4}\n",
             "[plan]\nkind = \"lhs\"\nsamples = 5\nseed = 1\n[axes]\nkappa = {from = 1.2, to = 2.4}\n"}},
    {"sobol", {"[plan]\nkind = \"sobol\"\nsamples = 4\n[axes]\nkappa = {from = 1.2, to = 2.4}\nlambda = {from = 1, to = 3}\n",
               "[plan]\nkind = \"sobol\"\nsamples = 4\nscramble = true\n[axes]\nkappa = {from = 1.2, to = 2.4}\nlambda = {from = 1, to = 3}\n"}},
    {"saltelli",
     {"[plan]\nkind = \"saltelli\"\nsamples = 2\n[axes]\nkappa = {from = 1.2, to = 2.4}\nlambda = {from = 1, to = 3}\n",
      "[plan]\nkind = \"saltelli\"\nsamples = 2\n[axes]\nkappa = {from = 1.2, to = 2.4}\nlambda = {from = 1, to = 3, spacing = \"log\"}\n"}},
};

Study parse(const std::string& text) { return parse_study(kRecords + text, "t.toml", test::source_dir()); }

std::string canonical(const Plan& plan) {
  std::ostringstream out;
  out.precision(17);
  out << plan.canonical_heading() << '\n';
  plan.describe(out);
  return out.str();
}

bool same_frame(const SceneSpec& a, const SceneSpec& b) { return same_scene(a, b); }

TEST(Plan, EveryKindIsTestedHere) {
  for (auto kind : plan_kinds()) EXPECT_EQ(kStudies.count(std::string(kind)), 1u) << kind;
  EXPECT_EQ(plan_kinds().front(), "grid");  // the default
}

/// A numeric coordinate's values asked a run at a time (as the cube's creation does, piece by
/// piece) are its values one by one, bit for bit, from any first value; past its end, an error.
void expect_runs_are_values(const cube::Coordinate& c) {
  if (c.is_text) return;
  SCOPED_TRACE(c.name);
  const std::size_t n = c.size();
  for (std::size_t first : {std::size_t{0}, std::size_t{1}, n / 2, n - 1}) {
    std::vector<double> run(n - first);
    c.numbers_into(first, run);
    for (std::size_t k = 0; k < run.size(); ++k)  // bits, as a NaN (a parameter another model lacks) is no value
      ASSERT_EQ(std::bit_cast<std::uint64_t>(run[k]), std::bit_cast<std::uint64_t>(c.number(first + k))) << "value " << first + k;
  }
  std::vector<double> past(2);
  EXPECT_THROW(c.numbers_into(n - 1, past), std::out_of_range);
}

/// The contract of the plan `texts.first` makes, of kind `kind`; `texts.second` is another plan.
void expect_contract(const std::string& kind, const std::pair<std::string, std::string>& texts) {
  SCOPED_TRACE(kind);
  const Study study = parse(texts.first);
  const Plan& plan = *study.plan;
  EXPECT_EQ(plan.name(), kind);
  std::vector<std::size_t> shape;
  for (const auto& d : plan.dimensions()) shape.push_back(d.size);
  const auto frames = plan.frames();
  std::size_t count = 1;
  for (auto n : shape) count *= n;
  ASSERT_EQ(frames.size(), count);
  ASSERT_GT(count, 1u);
  for (std::size_t i = 0; i < count; ++i) {
    const auto coordinates = unravel(static_cast<std::int64_t>(i), shape);
    EXPECT_TRUE(same_frame(plan.frame_at(coordinates), frames[i])) << "frame " << i;
  }
  const auto coordinates = plan.coordinates();
  for (const auto& d : plan.dimensions())
    EXPECT_TRUE(std::any_of(coordinates.begin(), coordinates.end(), [&](const auto& c) { return c.name == d.name; }))
        << "no coordinate variable for dimension " << d.name;
  for (const auto& c : coordinates) {
    const auto d = std::find_if(plan.dimensions().begin(), plan.dimensions().end(), [&](const auto& dim) { return dim.name == c.dimension; });
    ASSERT_NE(d, plan.dimensions().end()) << c.name << " is along " << c.dimension << ", not a dimension of the plan";
    EXPECT_EQ(c.size(), d->size) << c.name;
  }
  for (const auto& c : coordinates) expect_runs_are_values(c);
  const std::string text = canonical(plan);
  EXPECT_EQ(text, canonical(*parse(texts.first).plan)) << "the same study, the same text";
  EXPECT_NE(text, canonical(*parse(texts.second).plan)) << "another plan, another text";
  EXPECT_EQ(text.back(), '\n');
}

TEST(Plan, EveryKindKeepsTheContract) {
  for (const auto& [kind, texts] : kStudies) expect_contract(kind, texts);
}

TEST(Plan, AListOfScenesKeepsTheContractAndItsTextNamesTheirModels) {
  // The block and the rocking frame share their parameters' names: only the model tells
  // these two plans apart.
  const std::string frame = "[plan]\nkind = \"list\"\n[[cases]]\nkappa = 1.5\n[[cases]]\nlabel = \"b\"\nslenderness_rad = 0.2\n";
  expect_contract("list", {frame + "model = \"block\"\n", frame + "model = \"rocking-frame\"\n"});
  EXPECT_EQ(canonical(*parse(kStudies.at("list").first).plan).find("model="), std::string::npos)
      << "a list of one scene keeps the text (and fingerprint) it had";
}

// Issue 38 changed which points an LHS draws (a Feistel permutation by index instead of an
// mt19937 shuffle): its canonical text names the construction, so the fingerprint of an LHS
// study differs from an older cube's and --resume refuses it; Sobol' and Saltelli points did
// not change, nor did their text.
TEST(Plan, TheLatinHypercubesTextNamesItsConstruction) {
  const std::string sampled = "samples = 8\nseed = 3\n[axes]\nkappa = {from = 1, to = 2}\ntan_alpha = {from = 0.1, to = 0.2}\n";
  EXPECT_NE(canonical(*parse("[plan]\nkind = \"lhs\"\n" + sampled).plan).find(" design=lhs-feistel-1 "), std::string::npos);
  for (const char* kind : {"sobol", "saltelli"})
    EXPECT_EQ(canonical(*parse(std::string("[plan]\nkind = \"") + kind + "\"\n" + sampled).plan).find("design="),
              std::string::npos) << kind;
}

TEST(Plan, SampledPlansFillTheirParametersARunAtATimeWithTheSameBits) {
  // Sizes that walk the Latin hypercube's Feistel cycles (just above a power of 4) and cross
  // a piece of the cube (65 536 values); a linear and a log range; Sobol' scrambled or not.
  const std::string ranges = "[axes]\nkappa = {from = 1.2, to = 2.4}\nlambda = {from = 1, to = 3, spacing = \"log\"}\n";
  const std::vector<std::string> plans = {
      "kind = \"lhs\"\nsamples = 4097\nseed = 5\n", "kind = \"lhs\"\nsamples = 65537\n",
      "kind = \"sobol\"\nsamples = 70000\n", "kind = \"sobol\"\nsamples = 4097\nscramble = true\nseed = 2\n",
      "kind = \"saltelli\"\nsamples = 16385\n", "kind = \"saltelli\"\nsamples = 1000\nscramble = true\n"};
  for (const std::string& plan : plans) {
    SCOPED_TRACE(plan);
    const Study study = parse("[plan]\n" + plan + ranges);
    std::size_t parameters = 0;
    const auto coordinates = study.plan->coordinates();
    for (const auto& c : coordinates) {
      expect_runs_are_values(c);
      if (c.is_text || c.is_index) continue;
      ++parameters;  // varied (the design's columns) or at the base point
      EXPECT_TRUE(c.numbers_from) << c.name << " has no fast path";
    }
    EXPECT_GE(parameters, 2u);
    // A case's frame (its point computed at once, the design's row) has the cube's values.
    const std::size_t frames = coordinates.front().size();
    for (std::size_t i = 0; i < frames; i += 1 + frames / 3000) {
      const SceneSpec frame = study.plan->frame_at(std::span<const std::size_t>(&i, 1));
      for (const auto& c : coordinates) {
        if (c.is_text || c.is_index) continue;
        ASSERT_EQ(std::bit_cast<std::uint64_t>(frame.value(c.name)), std::bit_cast<std::uint64_t>(c.number(i)))
            << c.name << " of frame " << i;
      }
    }
  }
}

/// Every varied parameter of every frame of `study`'s plan by the design's row: frames asked
/// never one after the other (evens, then odds), so that no thread's window fills (column_window.hpp).
std::vector<std::vector<double>> row_values(const Study& study, const std::vector<std::string_view>& names) {
  const std::size_t frames = study.plan->dimensions().front().size;
  std::vector<std::vector<double>> values(frames);
  for (std::size_t parity : {0u, 1u})
    for (std::size_t i = parity; i < frames; i += 2) {
      const SceneSpec frame = study.plan->frame_at(std::span<const std::size_t>(&i, 1));
      for (std::string_view name : names) values[i].push_back(frame.value(name));
    }
  return values;
}

TEST(Plan, SampledFramesAskedInRunsAreTheRowsValuesForEveryOrderAndPiece) {
  // A case's point from the thread's window of columns (filled where the frames asked run) and
  // a unit's pieces read from it are the row's bits: runs within a window of 16 384 frames,
  // across two, into the last (short) one, a unit then its pieces, and runs in random order.
  // Each pattern on a plan of its own (a window is the last plan's it filled for).
  const std::string ranges = "[axes]\nkappa = {from = 1.2, to = 2.4}\nlambda = {from = 1, to = 3, spacing = \"log\"}\n";
  const std::vector<std::string> plans = {"kind = \"lhs\"\nsamples = 40000\nseed = 9\n", "kind = \"sobol\"\nsamples = 40000\nscramble = true\n",
                                          "kind = \"saltelli\"\nsamples = 10001\n"};
  const std::vector<std::string_view> names = {"kappa", "lambda"};
  for (const std::string& plan : plans) {
    SCOPED_TRACE(plan);
    const std::string text = "[plan]\n" + plan + ranges;
    const auto reference = row_values(parse(text), names);
    const std::size_t frames = reference.size(), window = 16384;
    auto expect_frames = [&](const Study& study, const std::vector<std::size_t>& order) {
      for (std::size_t i : order) {
        const SceneSpec frame = study.plan->frame_at(std::span<const std::size_t>(&i, 1));
        for (std::size_t k = 0; k < names.size(); ++k)
          ASSERT_EQ(std::bit_cast<std::uint64_t>(frame.value(names[k])), std::bit_cast<std::uint64_t>(reference[i][k]))
              << names[k] << " of frame " << i;
      }
    };
    auto expect_piece = [&](const Study& study, std::size_t first, std::size_t count) {
      for (const auto& c : study.plan->coordinates()) {
        const auto k = std::find(names.begin(), names.end(), c.name);
        if (k == names.end()) continue;
        std::vector<double> piece(count);
        c.numbers_into(first, piece);
        for (std::size_t m = 0; m < count; ++m)
          ASSERT_EQ(std::bit_cast<std::uint64_t>(piece[m]), std::bit_cast<std::uint64_t>(reference[first + m][k - names.begin()]))
              << c.name << " of frame " << first + m << " in the piece from " << first;
      }
    };
    auto run = [](std::size_t from, std::size_t to) {
      std::vector<std::size_t> order(to - from);
      std::iota(order.begin(), order.end(), from);
      return order;
    };
    {  // every frame in order: runs in each window, across their ends, into the last one
      const Study study = parse(text);
      expect_frames(study, run(0, frames));
      expect_piece(study, 2 * window, frames - 2 * window);  // the last window, held
      expect_piece(study, window - 500, 1000);               // across two windows, partly held
    }
    {  // a unit, then its pieces (held) and pieces around it (partly held)
      const Study study = parse(text);
      expect_frames(study, run(window, 2 * window));
      expect_piece(study, window, window);
      expect_piece(study, window - 3, window + 6);
      expect_piece(study, window + 100, 200);
    }
    {  // a run across a window's end, then frames asked again, backwards
      const Study study = parse(text);
      expect_frames(study, run(window - 40, window + 40));
      auto back = run(window - 100, window + 100);
      std::reverse(back.begin(), back.end());
      expect_frames(study, back);
    }
    {  // runs of random length from random frames, and single frames, in random order
      const Study study = parse(text);
      std::mt19937 random(5);
      std::vector<std::size_t> order;
      for (int r = 0; r < 60; ++r) {
        const std::size_t from = std::uniform_int_distribution<std::size_t>(0, frames - 1)(random);
        const std::size_t length = std::uniform_int_distribution<std::size_t>(1, 400)(random);
        for (std::size_t i : run(from, std::min(from + length, frames))) order.push_back(i);
      }
      expect_frames(study, order);
      expect_piece(study, order.back() - std::min<std::size_t>(order.back(), 300), 300);
    }
  }
}

TEST(Plan, AKeyOfAnotherPlanNamesThePlansThatTakeIt) {
  try {
    parse("[plan]\nkind = \"lhs\"\nsamples = 4\nscramble = true\n[axes]\nkappa = {from = 1, to = 2}\n");
    FAIL() << "scramble accepted by lhs";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("t.toml:6: [plan] scramble: only applies to plans \"sobol\" and \"saltelli\""), std::string::npos)
        << e.what();
  }
  try {
    parse("[[cases]]\nkappa = 2\n");
    FAIL() << "[[cases]] accepted by grid";
  } catch (const UserError& e) {
    EXPECT_NE(std::string(e.what()).find("cases: only applies to plan \"list\""), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pcrf::study

// The sampled plans: points of the unit hypercube (plan/sampling.hpp) mapped onto the
// [axes] ranges of the varied parameters, the others at the base point, frame by frame when
// asked: the plan computes frame i's unit point from i (LatinHypercube, SobolSequence,
// SaltelliRows) and holds nothing per frame, whatever the number of frames (issue 38). lhs
// and sobol label their frames "s0", "s1", …; saltelli groups them by base sample j ("s<j>:A",
// "s<j>:B", "s<j>:AB_<parameter>") and stores each frame's block and sample.
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <span>

#include "pcrf/study/sampling.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"
#include "study/axis_fields.hpp"
#include "study/plans/column_window.hpp"
#include "study/plans/plan_support.hpp"

namespace pcrf::study::detail {
namespace {

/// The interval a parameter is drawn from: uniformly, or log-uniformly.
struct SampledRange {
  double from = 0.0;
  double to = 0.0;
  bool log = false;
  /// The value at unit coordinate u ∈ [0, 1).
  double at(double u) const { return log ? from * std::pow(to / from, u) : from + u * (to - from); }
};

/// What every sampled plan reads: the number of samples (saltelli: base samples N, N(d + 2)
/// frames), the seed, whether Sobol' points are Owen-scrambled, and each varied parameter's range.
struct Sampling {
  std::size_t samples = 0;
  std::uint64_t seed = 0;
  bool scramble = false;
  std::vector<std::optional<SampledRange>> ranges;  ///< per parameter of the scene's table
  std::vector<std::size_t> varied() const {
    std::vector<std::size_t> v;
    for (std::size_t p = 0; p < ranges.size(); ++p)
      if (ranges[p]) v.push_back(p);
    return v;
  }
};

/// A sampled plan's range: {from, to} (and spacing), every value inside the parameter's
/// domain; a list, a single number or a count is an error.
SampledRange read_sampled_range(const Fields& fields, const SceneParameter& info) {
  const toml::node& node = *fields.node(info.name);
  const auto* table = node.as_table();
  if (table == nullptr)
    fields.fail(info.name, "a sampled plan draws from a range: give {from = A, to = B}, not " + Fields::type_name(node));
  const auto path = fields.path(info.name);
  Fields range(*table, path, fields.file(), {"from", "to", "spacing", "count"});
  if (range.has("count")) range.fail("count", "a sampled plan draws `samples` values: no count");
  for (auto key : {"from", "to"})
    if (!range.has(key)) range.fail(key, "a range needs from and to");
  SampledRange r{*range.number("from"), *range.number("to"), false};
  const std::string spacing = range.text("spacing").value_or("linear");
  if (spacing != "linear" && spacing != "log") range.fail("spacing", "expected \"linear\" or \"log\", got \"" + spacing + "\"");
  r.log = spacing == "log";
  if (!(r.to > r.from)) range.fail("to", "must be above from (" + number_text(r.from) + ")");
  if (r.log && !(r.from > 0.0)) range.fail("from", "a log range must start above 0");
  for (auto [key, value] : {std::pair{"from", r.from}, std::pair{"to", r.to}})
    if (const auto problem = info.problem(value); !problem.empty())
      range.fail(key, "value " + number_text(value) + " " + problem);
  return r;
}

/// Refuses more Sobol' points than the 32-bit sequence has (2^32).
void check_sobol_length(const PlanInput& input, std::size_t samples) {
  if (static_cast<double>(samples) > 4294967296.0)
    input.plan.fail("samples", "the Sobol' sequence has 2^32 points: at most 4294967296 samples");
}

Sampling read_sampling(const PlanInput& input) {
  Sampling s;
  if (!input.plan.has("samples")) input.plan.fail("samples", "required: how many points to draw");
  const auto n = *input.plan.integer("samples");
  if (n < 2) input.plan.fail("samples", "must be at least 2 (got " + std::to_string(n) + ")");
  s.samples = static_cast<std::size_t>(n);
  const auto seed = input.plan.integer("seed").value_or(0);
  if (seed < 0) input.plan.fail("seed", "must not be negative");
  s.seed = static_cast<std::uint64_t>(seed);
  s.scramble = input.plan.flag("scramble").value_or(false);
  s.ranges.resize(input.model.parameters.size());
  if (input.axes != nullptr) refuse_other_scenes(*input.axes, input.model);
  for (std::size_t p : axis_parameters(input.model))
    if (input.axes != nullptr && input.axes->has(input.model.parameters[p].name))
      s.ranges[p] = read_sampled_range(*input.axes, input.model.parameters[p]);
  if (s.varied().empty()) input.top.fail("axes", "a sampled plan needs at least one parameter range {from, to} in [axes]");
  return s;
}

/// A design's unit coordinates, in [0, 1), computed from the frame number: coordinate k of
/// frame i (`at`), of a run of frames at once (`column`), or coordinates first, first + 1, …
/// of frame i (`row`), the same bits.
struct UnitDesign {
  std::function<double(std::uint64_t, std::size_t)> at;
  std::function<void(std::size_t k, std::uint64_t first, std::span<double> out)> column;
  std::function<void(std::uint64_t i, std::size_t first, std::span<double> out)> row;
};

/// The UnitDesign of a design that has at(i, k) and column(k, first, out), and row(i, first,
/// out) where it computes a point's coordinates together (sampling.hpp).
template <class Design>
UnitDesign unit_design(std::shared_ptr<const Design> design) {
  return {[design](std::uint64_t i, std::size_t k) { return design->at(i, k); },
          [design](std::size_t k, std::uint64_t first, std::span<double> out) { design->column(k, first, out); },
          [design](std::uint64_t i, std::size_t first, std::span<double> out) {
            if constexpr (requires { design->row(i, first, out); }) design->row(i, first, out);
            else
              for (std::size_t s = 0; s < out.size(); ++s) out[s] = design->at(i, first + s);
          }};
}

/// A sampled plan computes frame i's unit point from i (UnitDesign) and maps it onto the
/// ranges when asked: no frame, label, parameter vector or unit point is held per case.
/// lhs and sobol label frame i "s<i>".
class SampledPlan : public PointPlan {
 public:
  /// `construction`: a word for the fingerprint naming how the design draws its points
  /// (empty: the construction the plan has had since its first fingerprints).
  SampledPlan(const SceneModel& model, std::string_view name, std::size_t count, UnitDesign unit, Sampling sampling,
              ScenePoint base, std::string construction = {})
      : PointPlan(model, count), name_(name), sampling_(std::move(sampling)), base_(std::move(base)),
        unit_(std::move(unit)), construction_(std::move(construction)), varied_(sampling_.varied()),
        slot_(base_.size(), kNotVaried) {
    for (std::size_t k = 0; k < varied_.size(); ++k) slot_[varied_[k]] = k;
  }

  std::string_view name() const override { return name_; }
  bool stores_labels() const override { return false; }  // "s<case>" (saltelli: its sample and block)
  void describe(std::ostream& out) const override {
    describe_axes(out, model(), {});
    out << "sampled samples=" << sampling_.samples << " seed=" << sampling_.seed << " scramble=" << sampling_.scramble;
    if (!construction_.empty()) out << " design=" << construction_;
    for (std::size_t p = 0; p < sampling_.ranges.size(); ++p)
      if (const auto& r = sampling_.ranges[p])
        out << ' ' << model().parameters[p].name << '=' << r->from << ':' << r->to << (r->log ? ":log" : "");
    out << '\n';
  }

 protected:
  const SceneModel& point_model(std::size_t) const override { return model(); }
  /// The base point's value, or the unit coordinate mapped onto the parameter's range.
  double point_value(std::size_t i, std::size_t k) const override {
    if (slot_[k] == kNotVaried) return base_[k];
    return sampling_.ranges[k]->at(unit_.at(i, slot_[k]));
  }
  /// point_value of every parameter of frame i: the varied ones from this thread's window
  /// where the frames asked run (column_window.hpp: the design's columns, once for the case
  /// and its unit's seal), else from the design's row.
  void frame_values(std::size_t i, std::span<double> values) const override {
    std::copy(base_.begin(), base_.end(), values.begin());
    std::array<double, 32> unit;  // a row's piece on the stack [unit coordinates]; mapped ones from the window
    if (varied_.size() <= unit.size()) {
      const auto mapped = std::span(unit.data(), varied_.size());
      const auto fill = [this](std::size_t s, std::size_t first, std::span<double> out) { mapped_column(s, first, out); };
      if (window().frame(id_, point_count(), i, mapped, fill)) {
        for (std::size_t s = 0; s < mapped.size(); ++s) values[varied_[s]] = mapped[s];
        return;
      }
    }
    for (std::size_t first = 0; first < varied_.size(); first += unit.size()) {
      const std::size_t count = std::min(unit.size(), varied_.size() - first);
      unit_.row(i, first, std::span(unit.data(), count));
      for (std::size_t s = 0; s < count; ++s) {
        const std::size_t k = varied_[first + s];
        values[k] = sampling_.ranges[k]->at(unit[s]);
      }
    }
  }
  /// point_value of frames first, first + 1, …: what this thread's window holds of them (a
  /// unit's cases just set up), the others from the design's column and the range's map.
  void point_values(std::size_t first, std::size_t k, std::span<double> out) const override {
    if (slot_[k] == kNotVaried) return std::fill(out.begin(), out.end(), base_[k]);
    const auto [from, to] = window().piece(id_, slot_[k], first, out);
    if (from == to) return mapped_column(slot_[k], first, out);
    mapped_column(slot_[k], first, out.first(from - first));
    mapped_column(slot_[k], to, out.subspan(to - first));
  }
  std::string point_label(std::size_t i) const override { return "s" + std::to_string(i); }
  /// The varied parameters (positions in the model's table), d of them.
  const std::vector<std::size_t>& varied() const { return varied_; }

 private:
  static constexpr std::size_t kNotVaried = static_cast<std::size_t>(-1);
  std::string_view name_;
  Sampling sampling_;
  ScenePoint base_;
  UnitDesign unit_;
  std::string construction_;
  std::vector<std::size_t> varied_;
  std::vector<std::size_t> slot_;  ///< per parameter: its column of the design, or kNotVaried
  /// This plan among those made in the process (ColumnWindow's owner; never 0, never reused).
  std::uint64_t id_ = next_id();

  static std::uint64_t next_id() {
    static std::atomic<std::uint64_t> last{0};
    return ++last;
  }
  /// The calling thread's window (one a thread, for the plan it last filled for).
  static ColumnWindow& window() {
    thread_local ColumnWindow w;
    return w;
  }
  /// Design column s of frames first, first + 1, … mapped onto its parameter's range.
  void mapped_column(std::size_t s, std::size_t first, std::span<double> out) const {
    if (out.empty()) return;
    unit_.column(s, first, out);
    const SampledRange& range = *sampling_.ranges[varied_[s]];
    for (double& value : out) value = range.at(value);
  }
};

/// Saltelli: frame i is row i of the design, base sample i / (d + 2), block i % (d + 2).
class SaltelliPlan final : public SampledPlan {
 public:
  SaltelliPlan(const SceneModel& model, std::size_t count, UnitDesign unit, Sampling sampling, ScenePoint base)
      : SampledPlan(model, "saltelli", count, std::move(unit), std::move(sampling), std::move(base)) {}

 protected:
  bool hands_out_by_frame() const override { return true; }  // frames are base sample by base sample
  std::size_t frames_per_group() const override { return varied().size() + 2; }  // a base sample

  std::string point_label(std::size_t i) const override {
    return "s" + std::to_string(study::SaltelliDesign::sample(i, varied().size())) + ":" + block_name(i);
  }

  /// Computed from the frame number, as the parameters (PointPlan::coordinates).
  std::vector<cube::Coordinate> extra_coordinates() const override {
    const std::size_t d = varied().size();
    auto block = text_coordinate(schema::kSaltelliBlock, schema::kCase, "Saltelli design block: A, B or AB_<parameter>", {});
    block.text_at = [this](std::size_t i) { return block_name(i); };
    block.computed_size = point_count();
    auto sample = number_coordinate(schema::kSaltelliSample, schema::kCase, "1",
                                    "Saltelli base sample the frame belongs to", {});
    sample.number_at = [d](std::size_t i) { return static_cast<double>(study::SaltelliDesign::sample(i, d)); };
    sample.computed_size = point_count();
    sample.is_index = true;  // whole numbers: stored as integers
    return {std::move(block), std::move(sample)};
  }

 private:
  /// "A", "B" or "AB_<parameter>".
  std::string block_name(std::size_t i) const {
    const std::size_t block = study::SaltelliDesign::block(i, varied().size());
    if (block < 2) return block == 0 ? "A" : "B";
    return "AB_" + std::string(model().parameters[varied()[block - 2]].name);
  }
};

}  // namespace

/// The word the fingerprint gives the LHS construction of issue 38 (a keyed Feistel
/// permutation per dimension, evaluable by index): a cube or journal of the earlier
/// construction (an mt19937_64 shuffle, other points) is another study, never resumed.
constexpr const char* kLatinHypercubeConstruction = "lhs-feistel-1";

std::shared_ptr<const Plan> read_lhs_plan(const PlanInput& input) {
  const Sampling s = read_sampling(input);
  auto design = std::make_shared<const study::LatinHypercube>(s.samples, s.varied().size(), s.seed);
  return std::make_shared<SampledPlan>(
      input.model, "lhs", s.samples, unit_design(design), s, input.base, kLatinHypercubeConstruction);
}

std::shared_ptr<const Plan> read_sobol_plan(const PlanInput& input) {
  const Sampling s = read_sampling(input);
  check_sobol_length(input, s.samples);
  auto design = std::make_shared<const study::SobolSequence>(s.varied().size(), s.scramble, s.seed);
  return std::make_shared<SampledPlan>(
      input.model, "sobol", s.samples, unit_design(design), s, input.base);
}

std::shared_ptr<const Plan> read_saltelli_plan(const PlanInput& input) {
  const Sampling s = read_sampling(input);
  const std::size_t d = s.varied().size();
  if (d < 2) input.top.fail("axes", "plan \"saltelli\" needs at least two varied parameters (sensitivity apportions variance among them)");
  check_sobol_length(input, s.samples);
  auto design = std::make_shared<const study::SaltelliRows>(d, s.scramble, s.seed);
  return std::make_shared<SaltelliPlan>(
      input.model, s.samples * (d + 2), unit_design(design), s, input.base);
}

}  // namespace pcrf::study::detail

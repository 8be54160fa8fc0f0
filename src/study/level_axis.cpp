// The three second axes of a study (see level_axis.hpp).
#include "pcrf/study/level_axis.hpp"

#include <iterator>
#include <optional>

#include "pcrf/number_text.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"
#include "pcrf/ida/ida_search.hpp"
#include "pcrf/study/plan.hpp"

namespace pcrf::study {
namespace {

namespace names = schema;

/// "how the curve ended: 0 bracketed (…), 1 censored (…), 2 unbracketed (…), 3 unresolved (…);
/// NaN: not finished".
std::string curve_state_long_name() {
  static const char* const kMeaning[] = {"bracketed to the resolution", "safe at max_intensity: right-censored",
                                         "max_runs ran out before either",
                                         "a run without a verdict ended the hunt: no collapse intensity, never safe beyond "
                                         "the last safe run"};
  static_assert(std::size(kMeaning) == ida::kCurveStateNames.size());
  std::string text = "how the curve ended:";
  for (const auto& n : ida::kCurveStateNames)
    text += " " + std::to_string(static_cast<int>(n.value)) + " " + n.name + " (" + kMeaning[static_cast<int>(n.value)] + "),";
  return text + " NaN not finished";
}

class ScaleAxis final : public LevelAxis {
 public:
  explicit ScaleAxis(std::vector<double> factors) : factors_(std::move(factors)) {}

  std::vector<cube::Dimension> leading_dimensions() const override { return {{names::kScale, factors_.size()}}; }
  const std::vector<double>& levels() const override { return factors_; }
  void add_leading(cube::CubeLayout& layout, RecordCache& /*records*/) const override {
    layout.coordinates.push_back(
        number_coordinate(names::kScale, names::kScale, "1", "factor applied to the record's accelerations", factors_));
  }
  void describe(std::ostream& out) const override {
    out << "scale";
    for (double s : factors_) out << ' ' << s;
  }

 private:
  std::vector<double> factors_;
};

/// What both intensity axes share: the measure, and each record's unscaled intensity along `record`.
class MeasuredAxis : public LevelAxis {
 public:
  explicit MeasuredAxis(const IntensitySpec& measure)
      : measure_(measure), units_(intensity_units(measure.measure)),
        long_name_(intensity_long_name(measure.measure, measure.period_s, measure.damping)) {}

 protected:
  void add_unscaled(cube::CubeLayout& layout, RecordCache& records) const {
    std::vector<double> unscaled;
    for (std::size_t r = 0; r < records.size(); ++r) unscaled.push_back(records.intensity(r, measure_));
    layout.coordinates.push_back(number_coordinate("record_" + to_string(measure_.measure), names::kRecord, units_,
                                                   "unscaled record's " + long_name_, unscaled));
  }

  IntensitySpec measure_;
  std::string units_;
  std::string long_name_;
};

/// Stripes at given intensities, or (hazard-consistent) at the intensities of given return
/// periods on a site's hazard curve, recorded beside them as `return_period_yr`.
class IntensityStripes final : public MeasuredAxis {
 public:
  IntensityStripes(const IntensitySpec& measure, std::vector<double> intensities,
                   const std::optional<Study::HazardStripes>& hazard, const std::optional<Study::StripeSelection>& selection)
      : MeasuredAxis(measure), intensities_(std::move(intensities)), hazard_(hazard), selection_(selection) {}

  std::vector<cube::Dimension> leading_dimensions() const override { return {{names::kIntensity, intensities_.size()}}; }
  const std::vector<double>& levels() const override { return intensities_; }
  void add_leading(cube::CubeLayout& layout, RecordCache& records) const override {
    if (!selection_) add_unscaled(layout, records);  // with a selection, each stripe's records are their own
    layout.coordinates.push_back(number_coordinate(names::kIntensity, names::kIntensity, units_, long_name_, intensities_));
    if (hazard_)
      layout.coordinates.push_back(number_coordinate(
          names::kReturnPeriod, names::kIntensity, "yr",
          "return period of the stripe's intensity on the hazard curve " + hazard_->hazard +
              " (1 / its mean annual rate of exceedance, the curve interpolated log-log)",
          hazard_->return_periods_yr));
    if (selection_) return add_selection(layout, records);
    cube::SideVariable factor{names::kScaleFactor, "1", "factor applied to the record's accelerations to reach the intensity",
                              {names::kRecord, names::kIntensity}, {}};
    for (std::size_t r = 0; r < records.size(); ++r)
      for (double level : intensities_) factor.values.push_back(records.scale_factor(r, level, measure_));
    layout.side_variables.push_back(std::move(factor));
  }

  /// [selection]: per stripe, the record in each slot (a text coordinate along `record` per
  /// stripe, `selected_record_<k>` for the k-th stripe from 0) and its target file (along
  /// `intensity`); over (record, intensity) the selection's scale factor (`scale_factor`, as
  /// every stripe cube has it) and the record's unscaled intensity; per stripe the set's fit.
  void add_selection(cube::CubeLayout& layout, RecordCache& records) const {
    const auto& stripes = selection_->stripes;
    const std::size_t slots = selection_->settings.count;
    const std::string library = " from the library " + selection_->library;
    std::vector<std::string> targets;
    for (std::size_t k = 0; k < stripes.size(); ++k) {
      std::vector<std::string> chosen;
      for (std::size_t r : stripes[k].records) chosen.push_back(records_name(records, r));
      layout.coordinates.push_back(text_coordinate(
          selected_record_name(k), names::kRecord,
          "record selected for slot of stripe " + std::to_string(k) + " (intensity " + number_text(intensities_[k]) + " " + units_ +
              (hazard_ ? ", return period " + number_text(hazard_->return_periods_yr[k]) + " yr" : std::string()) + ")" + library,
          chosen));
      targets.push_back(stripes[k].target);
    }
    layout.coordinates.push_back(text_coordinate("selection_target", names::kIntensity,
                                                 "target spectrum the stripe's records were selected to", targets));
    const std::vector<std::string> over{names::kRecord, names::kIntensity};
    cube::SideVariable factor{names::kScaleFactor, "1",
                              "factor applied to the record's accelerations: the selection's scale factor of the stripe's record in the slot",
                              over, {}};
    cube::SideVariable unscaled{"selected_record_" + to_string(measure_.measure), units_,
                                "unscaled " + long_name_ + " of the stripe's record in the slot", over, {}};
    for (std::size_t slot = 0; slot < slots; ++slot)
      for (const auto& stripe : stripes) {
        factor.values.push_back(stripe.scales.at(slot));
        unscaled.values.push_back(records.intensity(stripe.records.at(slot), measure_));
      }
    layout.side_variables.push_back(std::move(factor));
    layout.side_variables.push_back(std::move(unscaled));
    auto per_stripe = [&](const std::string& name, const std::string& unit, const std::string& long_name, auto member) {
      cube::SideVariable v{name, unit, long_name, {names::kIntensity}, {}};
      for (const auto& stripe : stripes) v.values.push_back(stripe.fit.*member);
      layout.side_variables.push_back(std::move(v));
    };
    per_stripe("selection_median_error_percent", "percent",
               "largest error of the selected set's median Sa against the target's, over the target's periods",
               &SelectionResult::median_error_percent);
    per_stripe("selection_sigma_error_percent", "percent",
               "largest error of the selected set's sigma ln Sa against the target's, over periods where it is not 0",
               &SelectionResult::sigma_error_percent);
    per_stripe("selection_sum_of_squares", "1",
               "Baker & Lee (2018) figure of merit: w_mean sum (m - mu)^2 + w_sigma sum (s - sigma)^2 of ln Sa",
               &SelectionResult::sum_of_squares);
  }
  void describe(std::ostream& out) const override {
    out << "intensity";
    for (double s : intensities_) out << ' ' << s;
    if (!hazard_) return;
    out << " return_periods_yr";
    for (double t : hazard_->return_periods_yr) out << ' ' << t;
  }

 private:
  static std::string records_name(RecordCache& records, std::size_t r) { return records.source(r).name; }

  std::vector<double> intensities_;
  std::optional<Study::HazardStripes> hazard_;
  std::optional<Study::StripeSelection> selection_;
};

class IdaAxis final : public MeasuredAxis {
 public:
  IdaAxis(const IntensitySpec& measure, std::size_t runs, bool verdict_check, std::vector<double> unused_levels)
      : MeasuredAxis(measure), runs_(runs), verdict_check_(verdict_check), unused_levels_(std::move(unused_levels)) {}

  std::vector<cube::Dimension> leading_dimensions() const override { return {}; }
  std::vector<cube::Dimension> trailing_dimensions() const override { return {{names::kIdaPoint, runs_}}; }
  const std::vector<double>& levels() const override { return none_; }
  /// The intensities are the runs' own (row_variables): only the records' own here.
  void add_leading(cube::CubeLayout& layout, RecordCache& records) const override { add_unscaled(layout, records); }

  /// `ida_point` (the runs of a curve, in the order run) and per curve the collapse
  /// intensity, the last safe intensity, the number of runs, how the curve ended, how many of
  /// its runs were unresolved, and with verdict checks the band
  /// of intensities whose verdicts were unstable.
  void add_trailing(cube::CubeLayout& layout, const std::vector<std::string>& curves) const override {
    std::vector<double> points(runs_);
    for (std::size_t k = 0; k < points.size(); ++k) points[k] = static_cast<double>(k);
    cube::Coordinate axis = number_coordinate(names::kIdaPoint, names::kIdaPoint, "", "run of the IDA curve, in the order run", points);
    axis.is_index = true;
    layout.coordinates.push_back(std::move(axis));
    auto& side = layout.side_variables;
    side.push_back({names::kCollapseIntensity, units_,
                    "lowest intensity found to collapse (NaN: none up to max_intensity, right-censored)", curves, {}});
    side.push_back({names::kLastSafeIntensity, units_, "highest safe intensity below the collapse", curves, {}});
    side.push_back({names::kIdaRuns, "1", "runs of the curve so far", curves, {}});
    side.push_back({names::kCurveState, "1", curve_state_long_name(), curves, {}});
    side.push_back({names::kUnresolvedRuns, "1",
                    "runs of the curve whose frame was still rocking when its tail ended (rocking_at_end): no verdict, "
                    "each stops its curve's hunt without counting as a collapse",
                    curves, {}});
    if (!verdict_check_) return;
    side.push_back({names::kUnstableFrom, units_,
                    "lowest intensity of the curve whose verdict failed the perturbation test (NaN: none)", curves, {}});
    side.push_back({names::kUnstableTo, units_,
                    "highest intensity of the curve whose verdict failed the perturbation test (NaN: none)", curves, {}});
  }

  std::vector<cube::MetricVariable> row_variables() const override {
    return {{names::kIdaIntensity, units_, "intensity of the run: " + long_name_},
            {names::kScaleFactor, "1", "factor applied to the record's accelerations for the run"}};
  }
  void describe(std::ostream& out) const override {
    out << "intensity";  // and Study::levels, unused (the default 1), as every IDA fingerprint has it
    for (double s : unused_levels_) out << ' ' << s;
  }

 private:
  std::size_t runs_;
  bool verdict_check_;
  std::vector<double> unused_levels_;
  std::vector<double> none_;
};

}  // namespace

std::string selected_record_name(std::size_t stripe) { return "selected_record_" + std::to_string(stripe); }

std::shared_ptr<const LevelAxis> make_level_axis(const Study& study) {
  if (study.ida)
    return std::make_shared<IdaAxis>(*study.intensity, static_cast<std::size_t>(study.ida->max_runs), study.solver.verdict_check,
                                     study.levels);
  if (study.intensity)
    return std::make_shared<IntensityStripes>(*study.intensity, study.levels, study.hazard_stripes, study.selection);
  return std::make_shared<ScaleAxis>(study.levels);
}

}  // namespace pcrf::study

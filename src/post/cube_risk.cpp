// The annual collapse rate of a cube's frames at a site (see cube_risk.hpp).
#include "pcrf/post/cube_risk.hpp"

#include "pcrf/user_error.hpp"

#include <algorithm>
#include <functional>
#include <random>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "pcrf/analysis/p695.hpp"
#include "pcrf/number_text.hpp"
#include "pcrf/post/cube_fragility.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"

namespace pcrf::post {
namespace {

namespace names = schema;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kBinsPerDecade = 10.0;
constexpr double kLowerTailShare = 0.5;     // the "more than half of λ_c"
constexpr double kBeyondLastShare = 0.1;    // a tenth of λ_c from an extrapolation is worth a line
constexpr double kFragilityAtLowest = 1e-3; // P(C) at the curve's start above which λ_c is a lower bound

/// The hazard's measure (and Sa period) against the cube's; the refusal names the hazard
/// file's header line.
std::string check_measure(const cube::CubeReader& cube, const pcrf::hazard::HazardFile& hazard) {
  const auto& layout = cube.layout();
  const std::string measure = layout.text_attribute(names::setting_attribute(intensity_settings().name, "measure"));
  const Where where{{}, hazard.file.string(), static_cast<int>(hazard.header_line)};
  if (measure.empty())
    throw UserError(where, "the cube " + cube.file().string() + " records no intensity measure to match " +
                          hazard.measure + " against");
  if (measure != hazard.measure)
    throw UserError(where, "the curve's measure is " + hazard.measure + ", the cube's (" + cube.file().string() +
                          ") is " + measure);
  if (!hazard.period_s) return measure;
  for (const auto& a : layout.attributes)
    if (a.name == names::setting_attribute(intensity_settings().name, "period_s"))
      if (const double* stored = std::get_if<double>(&a.value); stored && std::abs(*stored - *hazard.period_s) > 1e-9 * *stored)
        throw UserError(where, "the curve is at period_s = " + number_text(*hazard.period_s) + " s, the cube's Sa at " +
                              number_text(*stored) + " s");
  return measure;
}

/// The units of a measure as a study spells it ("pga_g": "g", "pgv_m_s": "m/s"); "" when none.
std::string units_of(const std::string& measure) {
  try {
    return measure.empty() ? "" : std::string(pcrf::intensity_units(parse_intensity_measure(measure)));
  } catch (const std::invalid_argument&) {
    return "";
  }
}

/// Deaggregation bin edges, 10 per decade on round values, covering the curve and (power
/// law) the frames' fragilities up to θ exp(3 β).
std::vector<double> bin_edges(const risk::HazardCurve& hazard, const std::vector<FrameFragility>& frames) {
  double low = hazard.intensities().front(), high = hazard.intensities().back();
  if (hazard.tail() == risk::Tail::kPowerLaw)
    for (const auto& f : frames) {
      if (f.fit) high = std::max(high, f.fit->median * std::exp(3.0 * f.fit->beta));
      for (double x : f.collapse_intensities) high = std::max(high, x);
    }
  const double a = std::floor(std::log10(low) * kBinsPerDecade), b = std::ceil(std::log10(high) * kBinsPerDecade);
  std::vector<double> edges;
  for (double e = a; e <= std::max(b, a + 1.0); e += 1.0) edges.push_back(std::pow(10.0, e / kBinsPerDecade));
  return edges;
}

/// The step fragility of a frame: the fraction collapsed at each stripe, or the IDA curves'
/// empirical CDF.
void empirical_steps(const FrameFragility& f, std::vector<double>& x, std::vector<double>& p) {
  x.clear();
  p.clear();
  if (f.stripes.empty()) {
    risk::empirical_ida_steps(f.collapse_intensities, f.cases, x, p);
    return;
  }
  auto stripes = f.stripes;
  std::sort(stripes.begin(), stripes.end(), [](const auto& a, const auto& b) { return a.intensity < b.intensity; });
  for (const auto& s : stripes)
    if (s.trials > 0.0) {
      x.push_back(s.intensity);
      p.push_back(s.collapses / s.trials);
    }
}

double lowest_collapse(const FrameFragility& f) {
  double lowest = kNaN;
  for (double x : f.collapse_intensities) lowest = std::isnan(lowest) ? x : std::min(lowest, x);
  for (const auto& s : f.stripes)
    if (s.collapses > 0.0) lowest = std::isnan(lowest) ? s.intensity : std::min(lowest, s.intensity);
  return lowest;
}

std::size_t bracketing(const FrameFragility& f) {
  if (f.stripes.empty()) return f.collapse_intensities.size();
  double most = 0.0;
  for (const auto& s : f.stripes) most = std::max(most, s.collapses);
  return static_cast<std::size_t>(std::floor(most));
}

/// The refit of a resample: an IDA's curves drawn with replacement (censored ones stay
/// censored); a stripe cube's collapses drawn per stripe from a binomial at its fraction.
std::function<std::optional<analysis::Lognormal>(std::mt19937_64&)> refit_of(const FrameFragility& f) {
  if (f.stripes.empty())
    return [&f](std::mt19937_64& g) {
      const std::size_t n = f.collapse_intensities.size() + f.censored_intensities.size();
      std::uniform_int_distribution<std::size_t> pick(0, n - 1);
      std::vector<double> observed, censored;
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t k = pick(g);
        if (k < f.collapse_intensities.size()) observed.push_back(f.collapse_intensities[k]);
        else censored.push_back(f.censored_intensities[k - f.collapse_intensities.size()]);
      }
      return analysis::fit_censored(observed, censored);
    };
  return [&f](std::mt19937_64& g) {
    auto stripes = f.stripes;
    for (auto& s : stripes) {
      const auto n = static_cast<int>(std::lround(s.trials));
      if (n <= 0) continue;
      std::binomial_distribution<int> draw(n, std::clamp(s.collapses / s.trials, 0.0, 1.0));
      s.trials = n;
      s.collapses = draw(g);
    }
    return analysis::fit_stripes(stripes);
  };
}

std::size_t sample_size(const FrameFragility& f) {
  if (f.stripes.empty()) return f.collapse_intensities.size() + f.censored_intensities.size();
  double most = 0.0;
  for (const auto& s : f.stripes) most = std::max(most, s.trials);
  return static_cast<std::size_t>(std::lround(most));
}

std::string percent(double share) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f %%", 100.0 * share);
  return text;
}

void warn(const FrameRisk& r, const RiskReport& report, const std::string& units, std::vector<std::string>& warnings) {
  const std::string frame = "frame " + r.frame + ": ";
  if (!r.fit) warnings.push_back(frame + "no lognormal fit (the data cannot fix a median and a beta): the empirical rate only");
  if (r.lognormal && r.lower_tail_share > kLowerTailShare)
    warnings.push_back(frame + percent(r.lower_tail_share) + " of the lognormal lambda_c comes from intensities below the "
                       "lowest collapse seen (" + number_text(r.lowest_collapse) + " " + units +
                       "): the fitted lower tail, not the data, decides it");
  if (r.bracketing < kFewBracketing)
    warnings.push_back(frame + "only " + std::to_string(r.bracketing) + " curves bracket a collapse (fewer than " +
                       std::to_string(kFewBracketing) + "): lambda_c rests on few collapses");
  const risk::RateResult& main = r.lognormal ? *r.lognormal : r.empirical;
  if (main.fragility_at_lowest > kFragilityAtLowest)
    warnings.push_back(frame + "P(collapse) is " + number_text(main.fragility_at_lowest) + " at the hazard curve's lowest "
                       "intensity (" + number_text(report.hazard.curve.intensities().front()) + " " + units +
                       "): rates below it are not counted, lambda_c is a lower bound");
  if (main.lambda_per_yr > 0.0 && main.beyond_last_per_yr > kBeyondLastShare * main.lambda_per_yr)
    warnings.push_back(frame + percent(main.beyond_last_per_yr / main.lambda_per_yr) + " of lambda_c comes from beyond "
                       "the hazard curve's last point (" + number_text(report.hazard.curve.intensities().back()) + " " +
                       units + ", " + risk::to_string(report.hazard.curve.tail()) + " tail)");
}

/// The measured modelling scatter of sampled frames and the λ_c each total implies.
void add_model_scatter(const cube::CubeReader& cube, const std::vector<FrameFragility>& frames, const RiskInputs& in,
                       RiskReport& report) {
  report.model = model_scatter(cube, frames, in.design_rating, in.test_rating, in.model_rating);
  if (!report.model) return;
  const auto& hazard = report.hazard.curve;
  const double median = report.model->dispersion.pooled.median;
  report.model_pooled = risk::collapse_rate(hazard, report.model->dispersion.pooled);
  report.model_measured = risk::collapse_rate(hazard, {median, report.model->beta_total_measured});
  report.model_rated = risk::collapse_rate(hazard, {median, report.model->beta_total_rated});
  if (const auto warning = model_scatter_warning(report.model); !warning.empty()) report.warnings.push_back(warning);
}

}  // namespace

double RiskInputs::ratings_beta() const {
  const double d = p695::rating_beta(design_rating), t = p695::rating_beta(test_rating), m = p695::rating_beta(model_rating);
  return std::sqrt(d * d + t * t + m * m);
}

RiskReport cube_risk(const cube::CubeReader& cube, const std::vector<cube::Selector>& selectors, const RiskInputs& in) {
  if (!(in.years > 0.0) || !std::isfinite(in.years)) throw UserError("years", "must be positive");
  risk::check(in.target);
  (void)in.ratings_beta();  // an unknown rating throws before anything is read
  RiskReport report{pcrf::hazard::read_hazard_file(in.hazard, in.tail), "", {}, {}, kNaN, kNaN, {}, {}, {}, {}, {}};
  report.cube_measure = check_measure(cube, report.hazard);
  for (const UserError& w : report.hazard.warnings) report.warnings.push_back(w.message(Dialect::kFlag));
  const auto& hazard = report.hazard.curve;
  const std::string units = intensity_units(cube);
  const auto frames = cube_fragility(cube, selectors);
  report.bin_edges = bin_edges(hazard, frames);
  for (const FrameFragility& f : frames) {
    FrameRisk r;
    r.frame = f.frame;
    r.selection = f.selection;
    r.cases = f.cases;
    r.collapses = f.collapses;
    r.fit = f.fit;
    r.lowest_collapse = lowest_collapse(f);
    r.bracketing = bracketing(f);
    empirical_steps(f, r.empirical_intensity, r.empirical_probability);
    r.empirical = risk::collapse_rate_steps(hazard, r.empirical_intensity, r.empirical_probability, report.bin_edges);
    r.lower_tail_share = kNaN;
    r.hazard_factor = kNaN;
    if (f.fit) {
      auto breakpoints = report.bin_edges;
      if (std::isfinite(r.lowest_collapse)) breakpoints.push_back(r.lowest_collapse);
      r.lognormal = risk::collapse_rate(hazard, *f.fit, breakpoints);
      if (std::isfinite(r.lowest_collapse) && r.lognormal->lambda_per_yr > 0.0)
        r.lower_tail_share = r.lognormal->rate_below(r.lowest_collapse) / r.lognormal->lambda_per_yr;
      r.hazard_factor = risk::hazard_factor_at_target(hazard, *f.fit, in.target);
      const double added = in.ratings_beta();
      r.with_ratings = risk::collapse_rate(hazard, {f.fit->median, std::sqrt(f.fit->beta * f.fit->beta + added * added)});
      r.sample_size = sample_size(f);
      // The one rule of cube fragility (kFewestForInterval): no interval from few records.
      r.interval = gives_interval(f) ? risk::rate_interval(hazard, refit_of(f)) : risk::RateInterval{kNaN, kNaN, 0};
    }
    warn(r, report, units, report.warnings);
    if (auto line = few_records_warning(f); !line.empty()) report.warnings.push_back(std::move(line));
    report.frames.push_back(std::move(r));
  }
  add_model_scatter(cube, frames, in, report);
  report.risk_targeted_intensity = risk::risk_targeted_intensity(hazard, in.target);
  report.uniform_hazard_intensity = hazard.intensity_at_rate(risk::rate_for_probability(0.02, 50.0));
  if (!std::isfinite(report.risk_targeted_intensity))
    report.warnings.push_back("no risk-targeted intensity: the hazard curve never reaches the target rate of " +
                              number_text(in.target.rate_per_yr()) + " /yr with the generic fragility");
  return report;
}

namespace {


struct RiskRow {
  const FrameRisk* frame;
  double years;
  double ratings_beta;
};

std::vector<ColumnOf<RiskRow>> risk_spec(const std::string& units) {
  using R = RiskRow;
  auto lognormal = [](double (*get)(const risk::RateResult&)) {
    return [get](const R& r) { return r.frame->lognormal ? number_or_missing(get(*r.frame->lognormal)) : Cell{}; };
  };
  const std::string rate = "%.3g";
  return {
      {{"frame", "", "the frame, as in cube fragility", "%s"}, [](const R& r) { return Cell{r.frame->frame}; }},
      {{"cases", "", "curves (IDA) or cases with a verdict (stripes) fitted"}, [](const R& r) { return count(r.frame->cases); }},
      {{"collapses", "", "of which collapsed"}, [](const R& r) { return Cell{r.frame->collapses}; }},
      {{"median", units, "median collapse intensity of the fitted lognormal"},
       [](const R& r) { return r.frame->fit ? Cell{r.frame->fit->median} : Cell{}; }},
      {{"beta", "", "its lognormal standard deviation"}, [](const R& r) { return r.frame->fit ? Cell{r.frame->fit->beta} : Cell{}; }},
      {{"lambda_collapse_per_yr", "1/yr", "annual collapse rate of the fitted lognormal: integral of P(C|im) |d lambda(im)|", rate},
       lognormal([](const risk::RateResult& x) { return x.lambda_per_yr; })},
      {{"p_collapse_in_years", "", "1 - exp(-lambda_c t), t = years", rate},
       [](const R& r) {
         return r.frame->lognormal ? number_or_missing(risk::probability_in_years(r.frame->lognormal->lambda_per_yr, r.years)) : Cell{};
       }},
      {{"lambda_collapse_empirical_per_yr", "1/yr", "annual collapse rate of the empirical fragility (fraction collapsed at each intensity)", rate},
       [](const R& r) { return number_or_missing(r.frame->empirical.lambda_per_yr); }},
      {{"p_collapse_empirical_in_years", "", "1 - exp(-lambda_c t) of the empirical rate", rate},
       [](const R& r) { return number_or_missing(risk::probability_in_years(r.frame->empirical.lambda_per_yr, r.years)); }},
      {{"empirical_vs_lognormal", "", "empirical rate / lognormal rate - 1: the difference the lognormal's shape makes", "%.3f"},
       [](const R& r) {
         return r.frame->lognormal && r.frame->lognormal->lambda_per_yr > 0.0
                    ? number_or_missing(r.frame->empirical.lambda_per_yr / r.frame->lognormal->lambda_per_yr - 1.0)
                    : Cell{};
       }},
      {{"lambda_collapse_5%", "1/yr", "5 % end of lambda_c's 90 % bootstrap interval (IDA: curves resampled; stripes: binomial redraws)", "%.3g"},
       [](const R& r) { return r.frame->lognormal ? number_or_missing(r.frame->interval.low) : Cell{}; }},
      {{"lambda_collapse_95%", "1/yr", "95 % end of lambda_c's 90 % bootstrap interval", "%.3g"},
       [](const R& r) { return r.frame->lognormal ? number_or_missing(r.frame->interval.high) : Cell{}; }},
      {{"records_for_10pct", "", "records (IDA: curves) for a 90 % interval of +-10 % of lambda_c, the width shrinking as 1/sqrt(n)", "%.0f"},
       [](const R& r) {
         return r.frame->lognormal ? number_or_missing(r.frame->interval.size_for(r.frame->lognormal->lambda_per_yr, r.frame->sample_size, 0.1))
                                   : Cell{};
       }},
      {{"beta_with_ratings", "", "the fitted beta with the P-695 ratings' dispersion added in quadrature (--ratings)", "%.3f"},
       [](const R& r) {
         return r.frame->fit ? number_or_missing(std::sqrt(r.frame->fit->beta * r.frame->fit->beta + r.ratings_beta * r.ratings_beta)) : Cell{};
       }},
      {{"lambda_collapse_with_ratings_per_yr", "1/yr", "lambda_c of the fitted median with beta_with_ratings", "%.3g"},
       [](const R& r) { return r.frame->with_ratings ? number_or_missing(r.frame->with_ratings->lambda_per_yr) : Cell{}; }},
      {{"lowest_collapse", units, "the lowest intensity at which a collapse was seen"},
       [](const R& r) { return number_or_missing(r.frame->lowest_collapse); }},
      {{"lower_tail_share", "", "share of the lognormal lambda_c from intensities below the lowest collapse seen", "%.3f"},
       [](const R& r) { return number_or_missing(r.frame->lower_tail_share); }},
      {{"beyond_last_share", "", "share of the lognormal lambda_c from beyond the hazard curve's last point", "%.3f"},
       [](const R& r) {
         const auto& l = r.frame->lognormal;
         return l && l->lambda_per_yr > 0.0 ? number_or_missing(l->beyond_last_per_yr / l->lambda_per_yr) : Cell{};
       }},
      {{"bracketing", "", "curves that bracket a collapse (stripes: the most records collapsed at one intensity)"},
       [](const R& r) { return count(r.frame->bracketing); }},
      {{"hazard_factor_at_target", "", "factor on the hazard's intensities at which this fragility meets the risk target", "%.3f"},
       [](const R& r) { return number_or_missing(r.frame->hazard_factor); }},
      {{"selection", "", "the frame as -w selectors, comma-separated (empty: all)", "%s", true},
       [](const R& r) { return Cell{r.frame->selection}; }},
  };
}

struct BinRow {
  std::string frame;
  double low, high, lognormal, lognormal_share, empirical, empirical_share;
};

std::vector<ColumnOf<BinRow>> bin_spec(const std::string& units) {
  using B = BinRow;
  return {
      {{"frame", "", "the frame", "%s"}, [](const B& b) { return Cell{b.frame}; }},
      {{"im_low", units, "the bin's lower intensity"}, [](const B& b) { return Cell{b.low}; }},
      {{"im_high", units, "the bin's upper intensity (the last bin also holds what lies beyond)"}, [](const B& b) { return Cell{b.high}; }},
      {{"lambda_lognormal_per_yr", "1/yr", "the part of the lognormal lambda_c from this bin", "%.3g"},
       [](const B& b) { return number_or_missing(b.lognormal); }},
      {{"share_lognormal", "", "its share of lambda_c", "%.3f"}, [](const B& b) { return number_or_missing(b.lognormal_share); }},
      {{"lambda_empirical_per_yr", "1/yr", "the part of the empirical lambda_c from this bin", "%.3g"},
       [](const B& b) { return number_or_missing(b.empirical); }},
      {{"share_empirical", "", "its share of the empirical lambda_c", "%.3f"}, [](const B& b) { return number_or_missing(b.empirical_share); }},
  };
}

std::vector<BinRow> bin_rows(const RiskReport& result) {
  std::vector<BinRow> rows;
  for (const auto& f : result.frames) {
    const auto empirical = risk::deaggregate(f.empirical.pieces, result.bin_edges);
    const auto lognormal = f.lognormal ? risk::deaggregate(f.lognormal->pieces, result.bin_edges)
                                       : std::vector<double>(empirical.size(), kNaN);
    const double lt = f.lognormal ? f.lognormal->lambda_per_yr : kNaN, et = f.empirical.lambda_per_yr;
    for (std::size_t b = 0; b < empirical.size(); ++b)
      rows.push_back({f.frame, result.bin_edges[b], result.bin_edges[b + 1], lognormal[b], lt > 0.0 ? lognormal[b] / lt : kNaN,
                      empirical[b], et > 0.0 ? empirical[b] / et : kNaN});
  }
  return rows;
}

struct Point {
  std::string frame;
  double x, y;
};

}  // namespace

Report risk_report(const RiskReport& result, const RiskInputs& in, const std::string& file) {
  Report report;
  report.command = "risk";
  double sum = 0.0, most = 0.0;
  std::size_t fitted = 0;
  for (const auto& f : result.frames)
    if (f.lognormal) {
      sum += f.lognormal->lambda_per_yr;
      most = std::max(most, f.lognormal->lambda_per_yr);
      ++fitted;
    }
  const double mean = fitted > 0 ? sum / static_cast<double>(fitted) : kNaN;
  const double rt = result.risk_targeted_intensity, uh = result.uniform_hazard_intensity;
  report.fields = {
      {"file", file},
      {"hazard_file", result.hazard.file.string()},
      {"measure", result.hazard.measure},
      {"period_s", result.hazard.period_s ? Cell{*result.hazard.period_s} : Cell{}},
      {"tail", risk::to_string(result.hazard.curve.tail())},
      {"years", in.years},
      {"target_probability", in.target.target_probability},
      {"target_years", in.target.years},
      {"target_rate_per_yr", in.target.rate_per_yr()},
      {"generic_beta", in.target.beta},
      {"generic_collapse_probability", in.target.collapse_probability},
      {"risk_targeted_intensity", number_or_missing(rt)},
      {"uniform_hazard_intensity_2pct_50yr", number_or_missing(uh)},
      {"risk_coefficient", number_or_missing(rt / uh)},
      {"ratings", std::string{in.design_rating, in.test_rating, in.model_rating}},
      {"ratings_beta", in.ratings_beta()},
      {"group_frames", static_cast<std::int64_t>(fitted)},
      {"group_lambda_collapse_per_yr", number_or_missing(mean)},
      {"group_p_collapse_in_years", number_or_missing(risk::probability_in_years(mean, in.years))},
      {"group_lambda_collapse_max_per_yr", fitted > 0 ? Cell{most} : Cell{}},
  };
  auto rate = [](const std::optional<risk::RateResult>& r) { return r ? number_or_missing(r->lambda_per_yr) : Cell{}; };
  for (auto& field : model_fields(result.model, {{"model_lambda_pooled_per_yr", rate(result.model_pooled)},
                                                 {"model_lambda_measured_per_yr", rate(result.model_measured)},
                                                 {"model_lambda_rated_per_yr", rate(result.model_rated)}}))
    report.fields.push_back(std::move(field));
  report.warnings = result.warnings;
  std::vector<RiskRow> rows;
  for (const auto& f : result.frames) rows.push_back({&f, in.years, in.ratings_beta()});
  const std::string im_units = units_of(result.hazard.measure);
  report.tables.emplace_back("frames", make_table(risk_spec(im_units), rows));
  report.tables.emplace_back("deaggregation", make_table(bin_spec(im_units), bin_rows(result)));
  std::vector<Point> curve, steps;
  const auto& h = result.hazard.curve;
  for (std::size_t i = 0; i < h.intensities().size(); ++i) curve.push_back({"", h.intensities()[i], h.rates_per_yr()[i]});
  for (const auto& f : result.frames)
    for (std::size_t i = 0; i < f.empirical_intensity.size(); ++i)
      steps.push_back({f.frame, f.empirical_intensity[i], f.empirical_probability[i]});
  report.tables.emplace_back(
      "hazard", make_table(std::vector<ColumnOf<Point>>{
                               {{names::kIntensity, im_units, "the hazard curve's intensity, as read"}, [](const Point& p) { return Cell{p.x}; }},
                               {{"annual_rate_per_yr", "1/yr", "its mean annual rate of exceedance"}, [](const Point& p) { return Cell{p.y}; }}},
                           curve));
  report.tables.emplace_back(
      "empirical", make_table(std::vector<ColumnOf<Point>>{
                                  {{"frame", "", "the frame", "%s"}, [](const Point& p) { return Cell{p.frame}; }},
                                  {{names::kIntensity, im_units, "from this intensity on"}, [](const Point& p) { return Cell{p.x}; }},
                                  {{"probability", "", "the fraction collapsed"}, [](const Point& p) { return Cell{p.y}; }}},
                              steps));
  return report;
}

void print_risk(const Report& report, std::ostream& out) {
  auto text = [&](const std::string& name) {
    const Cell c = report.field(name);
    if (const auto* s = std::get_if<std::string>(&c)) return *s;
    if (const auto* d = std::get_if<double>(&c)) {
      char number[32];
      std::snprintf(number, sizeof number, "%.4g", *d);
      return std::string(number);
    }
    if (const auto* i = std::get_if<std::int64_t>(&c)) return std::to_string(*i);
    return std::string("none");
  };
  out << "hazard " << text("hazard_file") << " (" << text("measure")
      << (text("period_s") == "none" ? "" : ", T = " + text("period_s") + " s") << "), beyond its last point: "
      << text("tail") << "; lambda_c exact per segment of the curve\n";
  out << "risk target " << text("target_probability") << " in " << text("target_years") << " years ("
      << text("target_rate_per_yr") << " /yr), generic fragility beta " << text("generic_beta") << " with "
      << text("generic_collapse_probability") << " at the intensity: risk-targeted intensity " << text("risk_targeted_intensity")
      << "; 2 % in 50 years: " << text("uniform_hazard_intensity_2pct_50yr") << " (risk coefficient "
      << text("risk_coefficient") << ")\n";
  out << "per frame: p_collapse_in_years for t = " << text("years") << " years; the empirical rate beside the lognormal's; "
      << "with ratings " << text("ratings") << " (beta " << text("ratings_beta") << " added in quadrature)\n";
  write_text(report.table("frames"), out);
  if (std::get<std::int64_t>(report.field("group_frames")) > 1)
    out << "group of " << text("group_frames") << " frames: mean lambda_c " << text("group_lambda_collapse_per_yr")
        << " /yr (p in " << text("years") << " years " << text("group_p_collapse_in_years") << "), largest "
        << text("group_lambda_collapse_max_per_yr") << " /yr\n";
  print_model_scatter(report, units_of(text("measure")), out);
  if (text("model_lambda_pooled_per_yr") != "none")
    out << "lambda_c of the pooled median: with beta_pooled " << text("model_lambda_pooled_per_yr")
        << " /yr; with beta_TOT measured " << text("model_lambda_measured_per_yr") << " /yr, rated "
        << text("model_lambda_rated_per_yr") << " /yr\n";
}

std::vector<Column> risk_columns() { return columns_of(risk_spec("")); }
std::vector<Column> risk_deaggregation_columns() { return columns_of(bin_spec("")); }

}  // namespace pcrf::post

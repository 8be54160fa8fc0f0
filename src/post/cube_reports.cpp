// One report per cube command (see cube_reports.hpp). Each table is a list of columns over
// a result struct: a new field needs one line here to reach text, CSV, JSON and Python.
#include "pcrf/post/cube_reports.hpp"

#include "pcrf/user_error.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "pcrf/post/cube_fragility.hpp"
#include "pcrf/post/cube_sensitivity.hpp"
#include "pcrf/metrics/curve_state.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"

namespace pcrf::post {

namespace vocabulary = schema;
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();


/// `numeric[b]`: the b-th coordinate grouped by holds numbers (its values are written as
/// numbers, which their labels are the shortest round-trip text of), else texts.
std::vector<ColumnOf<cube::GroupStats>> stats_spec(const std::vector<std::string>& by, const std::vector<bool>& numeric) {
  using G = cube::GroupStats;
  std::vector<ColumnOf<G>> spec;
  for (std::size_t b = 0; b < by.size(); ++b)
    spec.push_back({{by[b], "", "the group's value of " + by[b], "%.17g"}, [b, number = numeric[b]](const G& g) {
                      return number ? Cell{std::stod(g.key[b])} : Cell{g.key[b]};
                    }});
  spec.push_back({{"cases", "", "selected cases in the group"}, [](const G& g) { return count(g.cases); }});
  spec.push_back({{vocabulary::kCollapses, "", "cases that collapsed (tendon fracture, overturned): not in the percentiles"},
                  [](const G& g) { return count(g.set_apart); }});
  spec.push_back({{"values", "", "finite values of the metric among the other cases"},
                  [](const G& g) { return count(g.values); }});
  spec.push_back({{"median", "", "median of the metric (in metric_units)"},
                  [](const G& g) { return number_or_missing(g.median); }});
  spec.push_back({{"p16", "", "16th percentile of the metric (in metric_units)"},
                  [](const G& g) { return number_or_missing(g.p16); }});
  spec.push_back({{"p84", "", "84th percentile of the metric (in metric_units)"},
                  [](const G& g) { return number_or_missing(g.p84); }});
  spec.push_back({{"unresolved", "", "cases without a verdict (still rocking at the end, ground in free fall, invalid frame): not in the percentiles"},
                  [](const G& g) { return count(g.unresolved); }});
  return spec;
}

std::vector<ColumnOf<FrameFragility>> fragility_spec(const std::string& units, std::optional<double> mce,
                                                     bool unbracketed = false) {
  using F = FrameFragility;
  auto fitted = [](double (*get)(const F&)) {
    return [get](const F& f) { return f.fit ? number_or_missing(get(f)) : Cell{}; };
  };
  std::vector<ColumnOf<F>> spec{
      {{"frame", "", "the frame: the frame axes with several values (kappa=1.8,lambda=2), a case label, or all", "%s"},
       [](const F& f) { return Cell{f.frame}; }},
      {{"records", "", "records on the cube's record axis"}, [](const F& f) { return count(f.records); }},
      {{"cases", "", "cases that ended with a verdict (IDA: curves)"}, [](const F& f) { return count(f.cases); }},
      {{"collapses", "", "of which collapsed (a sum of collapse fractions with verdict checks)"},
       [](const F& f) { return Cell{f.collapses}; }},
      {{"failed", "", "cases with no verdict (solver failure, time limit; IDA: curves with no value)"},
       [](const F& f) { return count(f.failed); }},
      {{"median", units, "median collapse intensity of the fitted lognormal"}, fitted([](const F& f) { return f.fit->median; })},
      {{"median_5%", units, "5 % end of the median's 90 % bootstrap interval"},
       fitted([](const F& f) { return f.interval.median.low; })},
      {{"median_95%", units, "95 % end of the median's 90 % bootstrap interval"},
       fitted([](const F& f) { return f.interval.median.high; })},
      {{"beta", "", "lognormal standard deviation of the collapse intensity"}, fitted([](const F& f) { return f.fit->beta; })},
      {{"beta_5%", "", "5 % end of beta's 90 % bootstrap interval"}, fitted([](const F& f) { return f.interval.beta.low; })},
      {{"beta_95%", "", "95 % end of beta's 90 % bootstrap interval"},
       fitted([](const F& f) { return f.interval.beta.high; })},
  };
  if (mce)
    spec.push_back({{"CMR", "", "collapse margin ratio: median / MCE intensity (--mce)"},
                    [m = *mce](const F& f) { return f.fit ? number_or_missing(f.fit->median / m) : Cell{}; }});
  if (unbracketed)
    spec.push_back({{"unresolved", "", "IDA curves ended by a run without a verdict (censored at their last safe intensity, a bound)"},
                    [](const F& f) { return count(f.unresolved); }});
  if (unbracketed)
    spec.push_back({{"unbracketed", "", "IDA curves whose max_runs ran out before a bracket (censored at their last safe intensity)"},
                    [](const F& f) { return f.unbracketed ? count(*f.unbracketed) : Cell{}; }});
  spec.push_back({{"selection", "", "the frame as -w selectors, comma-separated (empty: all)", "%s", true},
                  [](const F& f) { return Cell{f.selection}; }});
  return spec;
}

struct FragilityPoint {
  std::string frame, kind;
  double intensity, trials, collapses;
};

std::vector<ColumnOf<FragilityPoint>> fragility_point_spec() {
  using P = FragilityPoint;
  return {
      {{"frame", "", "the frame, as in the frames table", "%s"}, [](const P& p) { return Cell{p.frame}; }},
      {{"kind", "", "stripe (a grid cube's intensity), collapse (an IDA curve's collapse intensity), censored "
                    "(an IDA curve safe up to this intensity) or unresolved (an IDA curve safe up to this intensity, "
                    "then without a verdict)", "%s"},
       [](const P& p) { return Cell{p.kind}; }},
      {{vocabulary::kIntensity, "", "the intensity (in intensity_units)"}, [](const P& p) { return Cell{p.intensity}; }},
      {{"trials", "", "cases with a verdict at this intensity (1 for an IDA curve)"}, [](const P& p) { return Cell{p.trials}; }},
      {{"collapses", "", "of which collapsed"}, [](const P& p) { return Cell{p.collapses}; }},
  };
}

std::vector<FragilityPoint> fragility_points(const std::vector<FrameFragility>& frames) {
  std::vector<FragilityPoint> points;
  for (const auto& f : frames) {
    for (const auto& s : f.stripes) points.push_back({f.frame, "stripe", s.intensity, s.trials, s.collapses});
    for (double x : f.collapse_intensities) points.push_back({f.frame, "collapse", x, 1.0, 1.0});
    for (double x : f.censored_intensities) points.push_back({f.frame, "censored", x, 1.0, 0.0});
    for (double x : f.unresolved_intensities) points.push_back({f.frame, "unresolved", x, 1.0, 0.0});
  }
  return points;
}

struct IndexRow {
  std::string record, parameter;
  analysis::SobolIndex index;
  std::size_t samples;
};

std::vector<ColumnOf<IndexRow>> sensitivity_spec() {
  using R = IndexRow;
  auto number = [](double analysis::SobolIndex::*member) {
    return [member](const R& r) { return number_or_missing(r.index.*member); };
  };
  const std::string f = "%.3f";
  return {
      {{vocabulary::kRecord, "", "all (across records: the mean output), or the record", "%s"}, [](const R& r) { return Cell{r.record}; }},
      {{"parameter", "", "the varied parameter", "%s"}, [](const R& r) { return Cell{r.parameter}; }},
      {{"S1", "", "first-order Sobol' index", f}, number(&analysis::SobolIndex::s1)},
      {{"S1_5%", "", "5 % end of S1's 90 % bootstrap interval", f}, number(&analysis::SobolIndex::s1_low)},
      {{"S1_95%", "", "95 % end of S1's 90 % bootstrap interval", f}, number(&analysis::SobolIndex::s1_high)},
      {{"ST", "", "total Sobol' index", f}, number(&analysis::SobolIndex::st)},
      {{"ST_5%", "", "5 % end of ST's 90 % bootstrap interval", f}, number(&analysis::SobolIndex::st_low)},
      {{"ST_95%", "", "95 % end of ST's 90 % bootstrap interval", f}, number(&analysis::SobolIndex::st_high)},
      {{"samples", "", "base samples used (those with a value for every frame)"}, [](const R& r) { return count(r.samples); }},
  };
}

std::vector<ColumnOf<FrameP695>> p695_spec() {
  using P = FrameP695;
  auto number = [](double p695::Assessment::*member) {
    return [member](const P& p) { return number_or_missing(p.assessment.*member); };
  };
  using A = p695::Assessment;
  return {
      {{"frame", "", "the frame, as in cube fragility", "%s"}, [](const P& p) { return Cell{p.frame}; }},
      {{"mu_t", "", "period-based ductility used (given, or the frame's own: docs/p695_rocking_frame.md)"},
       [](const P& p) { return number_or_missing(p.mu_t); }},
      {{"ssf_beta1", "", "beta1 of the spectral shape factor at that mu_T (Appendix B)"},
       [](const P& p) { return number_or_missing(p695::ssf_beta1(p.mu_t)); }},
      {{"s_ct_g", "g", "median collapse intensity S_CT used for CMR and ACMR (the field s_ct says which)"}, number(&A::s_ct_g)},
      {{"s_ct_counted_g", "g", "S_CT counted: the lowest intensity at which half the records collapse (P-695 6.3, 6.4)"},
       [](const P& p) { return number_or_missing(p.s_ct_counted_g); }},
      {{"s_ct_lognormal_g", "g", "median of the fitted lognormal fragility"},
       [](const P& p) { return number_or_missing(p.s_ct_lognormal_g); }},
      {{"s_ct_bounded", "", "curves without a collapse shown above a bound below the counted S_CT, counted as collapsing there"},
       [](const P& p) { return count(p.bounded); }},
      {{"s_mt_g", "g", "MCE intensity S_MT at T (Table 5-1)"}, number(&A::s_mt_g)},
      {{"cmr", "", "collapse margin ratio S_CT / S_MT"}, number(&A::cmr)},
      {{"ssf", "", "spectral shape factor (Appendix B)"}, number(&A::ssf)},
      {{"acmr", "", "adjusted collapse margin ratio SSF x CMR"}, number(&A::acmr)},
      {{"beta_rtr", "", "record-to-record uncertainty"}, number(&A::beta_rtr)},
      {{"beta_total", "", "total uncertainty beta_TOT, rounded to 0.025"}, number(&A::beta_total)},
      {{"acmr10", "", "acceptable ACMR at 10 % collapse probability (Table 7-3)"}, number(&A::acmr10)},
      {{"acmr20", "", "acceptable ACMR at 20 % collapse probability (Table 7-3)"}, number(&A::acmr20)},
      {{"p_collapse_mce", "", "collapse probability at the MCE"}, number(&A::p_collapse_mce)},
      {{"individual", "", "pass when ACMR >= ACMR20%, else fail", "%s"},
       [](const P& p) { return Cell{std::string(p.assessment.passes_individual ? "pass" : "fail")}; }},
  };
}

/// A reduction of an IDA's collapse_intensity in cube stats reduces the values the cube holds:
/// a curve that found no collapse (NaN: censored, or unbracketed before one) is left out of it,
/// and an unbracketed curve that found one enters at that collapse, not refined to the
/// resolution (an upper bound), where cube fragility --reduce-over keeps both censored at
/// their last safe intensity. Says so when the cube has such curves.
std::string censored_reduction_note(const cube::CubeReader& cube, const StatsRequest& request) {
  if (request.reduction.dimension.empty() || request.metric != vocabulary::kCollapseIntensity) return "";
  const auto collapse = cube.read_side(vocabulary::kCollapseIntensity);
  const auto runs = cube.read_side(vocabulary::kIdaRuns);
  const bool has_states = cube.layout().find_side_variable(vocabulary::kCurveState) != nullptr;
  const auto state = has_states ? cube.read_side(vocabulary::kCurveState) : std::vector<double>(collapse.size(), kNaN);
  std::size_t left_out = 0, unrefined = 0, unresolved = 0;
  for (std::size_t c = 0; c < collapse.size(); ++c) {
    if (!(runs[c] > 0.0)) continue;
    if (state[c] == static_cast<double>(CurveState::kUnresolved)) ++unresolved;
    else if (!std::isfinite(collapse[c])) ++left_out;
    else if (state[c] == static_cast<double>(CurveState::kUnbracketed)) ++unrefined;
  }
  std::string note;
  if (left_out > 0)
    note = std::to_string(left_out) + " curves without a collapse (censored, or unbracketed before one) are left out of the reduction";
  if (unresolved > 0)
    note += (note.empty() ? "" : "; ") + std::to_string(unresolved) +
            " unresolved curves (a run without a verdict ended them: no collapse intensity) are left out of the reduction";
  if (unrefined > 0)
    note += (note.empty() ? "" : "; ") + std::to_string(unrefined) +
            " unbracketed curves enter the reduction at a collapse not refined to the resolution (an upper bound)";
  return note.empty() ? "" : note + "; cube fragility --reduce-over keeps them censored at their last safe intensity";
}

/// The fields reduced_over and reduction of a report whose values were reduced first (none when not).
void add_reduction_fields(const cube::Reduction& reduction, Report& report) {
  if (reduction.dimension.empty()) return;
  report.fields.emplace_back("reduced_over", reduction.dimension);
  report.fields.emplace_back("reduction", reduction.how);
}

}  // namespace

Report stats_report(const cube::CubeReader& cube, const StatsRequest& request) {
  const auto& layout = cube.layout();
  if (request.by.empty()) throw UserError(Where{}, "give at least one coordinate to group by ({})", {"by"});
  // In a one-at-a-time cube, the first swept parameter grouped by picks its sweep.
  auto where = request.where;
  for (const auto& by : request.by) where = vocabulary::stats_selectors(layout, by, where);
  std::vector<std::string> pooled;
  const cube::PoolReport pool{vocabulary::expected_pooling(), &pooled, vocabulary::collapse_statuses(),
                              vocabulary::unresolved_statuses()};
  const auto groups = request.reduction.dimension.empty()
                          ? cube::group_stats(cube, request.by, request.metric, where, pool)
                          : cube::group_stats_reduced(cube, request.by, request.metric, where, request.reduction, pool);
  Report report;
  report.command = "stats";
  std::string by_text, units;
  for (const auto& b : request.by) by_text += (by_text.empty() ? "" : ",") + b;
  for (const auto& m : layout.metrics)
    if (m.name == request.metric) units = m.units;
  report.fields = {{"file", cube.file().string()}, {"metric", request.metric}, {"metric_units", units}, {"by", by_text}};
  add_reduction_fields(request.reduction, report);
  for (const auto& p : pooled) report.warnings.push_back("also pooled over " + p);
  if (const auto note = censored_reduction_note(cube, request); !note.empty()) report.warnings.push_back(note);
  std::vector<bool> numeric;
  for (const auto& b : request.by) numeric.push_back(!layout.find_coordinate(b)->is_text);
  report.tables.emplace_back("groups", make_table(stats_spec(request.by, numeric), groups));
  return report;
}

Report fragility_report(const cube::CubeReader& cube, const FragilityRequest& request, const cube::Reduction& reduction) {
  const auto frames = cube_fragility(cube, request.where, reduction);
  const std::string units = intensity_units(cube);
  Report report;
  report.command = "fragility";
  report.fields = {{"file", cube.file().string()}, {"intensity_units", units},
                   {"mce", request.mce ? Cell{*request.mce} : Cell{}}};
  add_reduction_fields(reduction, report);
  report.warnings = unbracketed_warnings(frames);
  const bool ida = !frames.empty() && frames.front().unbracketed.has_value();
  report.tables.emplace_back("frames", make_table(fragility_spec(units, request.mce, ida), frames));
  report.tables.emplace_back("points", make_table(fragility_point_spec(), fragility_points(frames)));
  return report;
}

Report sensitivity_report(const cube::CubeReader& cube, const SensitivityRequest& request) {
  const auto groups = cube_sensitivity(cube, request.metric, request.where, request.by_record);
  std::vector<IndexRow> rows;
  Report report;
  report.command = "sensitivity";
  report.fields = {{"file", cube.file().string()}, {"metric", request.metric},
                   {"by_record", Cell{std::int64_t{request.by_record ? 1 : 0}}}};
  for (const auto& g : groups) {
    if (g.dropped > 0)
      report.warnings.push_back(g.record + ": interim indices from " + std::to_string(g.samples) + " of " +
                                std::to_string(g.samples + g.dropped) + " base samples; " + std::to_string(g.dropped) +
                                " left out (a frame without a value: not run yet, or no verdict)");
    for (std::size_t i = 0; i < g.parameters.size(); ++i) {
      rows.push_back({g.record, g.parameters[i],
                      i < g.indices.size() ? g.indices[i] : analysis::SobolIndex{kNaN, kNaN, kNaN, kNaN, kNaN, kNaN},
                      g.samples});
      if (const auto caution = analysis::sobol_caution(rows.back().index, g.samples); !caution.empty())
        report.warnings.push_back(g.record + ": " + g.parameters[i] + ": " + caution);
    }
  }
  report.tables.emplace_back("indices", make_table(sensitivity_spec(), rows));
  return report;
}

Report p695_report(const cube::CubeReader& cube, const std::vector<cube::Selector>& where, const P695Inputs& in) {
  return p695_report(cube_p695(cube, where, in), in, cube.file().string());
}

Report p695_report(const P695Report& result, const P695Inputs& in, const std::string& file) {
  Report report;
  report.command = "p695";
  report.fields = {{"file", file},
                   {"sdc", p695::to_string(in.sdc)},
                   {"period_s", in.period_s},
                   {"mu_t", in.mu_t > 0.0 ? Cell{in.mu_t} : Cell{}},
                   {"mu_t_source", std::string(in.mu_t > 0.0 ? "given" : "frame (pushover peak, docs/p695_rocking_frame.md)")},
                   {"s_ms_g", p695::mce_spectrum(in.sdc).s_ms_g},
                   {"s_m1_g", p695::mce_spectrum(in.sdc).s_m1_g},
                   {"far_field_epsilon", p695::far_field_epsilon(in.period_s)},
                   {"target_epsilon", p695::target_epsilon(in.sdc)},
                   {"ratings", std::string{in.design_rating, in.test_rating, in.model_rating}},
                   {"ratings_source", std::string(in.default_ratings ? "default" : "given")},
                   {"s_ct", to_string(in.s_ct)},
                   {"group_mean_acmr", result.group.mean_acmr},
                   {"group_acmr10", result.group.acmr10},
                   {"group", std::string(result.group.passes ? "pass" : "fail")},
                   {"measure_problem", result.measure_problem}};
  const bool model = result.model.has_value();
  for (auto& field : model_fields(result.model, {{"model_p_collapse_mce_measured", model ? Cell{result.model_p_collapse_mce_measured} : Cell{}},
                                                 {"model_p_collapse_mce_rated", model ? Cell{result.model_p_collapse_mce_rated} : Cell{}}}))
    report.fields.push_back(std::move(field));
  if (!result.measure_problem.empty()) report.warnings.push_back(result.measure_problem);
  for (const auto& note : result.notes) report.warnings.push_back(note);
  report.tables.emplace_back("frames", make_table(p695_spec(), result.frames));
  return report;
}

std::vector<Column> stats_columns(const std::vector<std::string>& by) {
  return columns_of(stats_spec(by, std::vector<bool>(by.size(), false)));
}
std::vector<Column> fragility_columns(bool with_mce) {
  return columns_of(fragility_spec("", with_mce ? std::optional<double>(1.0) : std::nullopt));
}
std::vector<Column> fragility_point_columns() { return columns_of(fragility_point_spec()); }
std::vector<Column> sensitivity_columns() { return columns_of(sensitivity_spec()); }
std::vector<Column> p695_columns() { return columns_of(p695_spec()); }

UserError unreadable_cube(const std::string& file, const cube::CubeError& error) {
  std::string problem = error.what();
  if (problem.rfind(file + ": ", 0) == 0) problem.erase(0, file.size() + 2);  // said once, as the file
  return UserError(Where{{}, file, 0}, problem);
}

void check_mce(const std::optional<double>& mce) {
  if (mce && !(*mce > 0.0)) throw UserError("mce", "must be positive");
}

cube::Reduction reduction_of(const std::string& over, const std::string& how, const std::string& default_how) {
  if (over.empty() && !how.empty()) throw UserError("reduce", "goes with {} DIMENSION", {"reduce_over"});
  if (over.empty()) return {};
  cube::Reduction reduction{over, how.empty() ? default_how : how};
  try {
    cube::check_reduction(reduction.how);
  } catch (const cube::CubeError& e) {
    throw UserError("reduce", e.what());
  }
  return reduction;
}

P695Inputs p695_inputs(const std::string& sdc, double period_s, double mu_t, const std::string& ratings,
                       const std::string& s_ct) {
  P695Inputs in;
  in.default_ratings = ratings.empty();
  in.s_ct = parse_s_ct(s_ct);
  std::string r = ratings.empty() ? std::string("BBB") : ratings;
  std::erase(r, ',');
  if (r.size() != 3) throw UserError("ratings", "give three letters A-D, e.g. B,B,C (got '" + ratings + "')");
  in.sdc = p695::parse_sdc(sdc);
  for (const char c : r) (void)p695::rating_beta(c);
  if (!(mu_t >= 1.0 || mu_t == 0.0)) throw UserError("mu_t", "must be at least 1 (0: each frame's own)");
  in.period_s = p695::archetype_period_s(period_s);
  in.mu_t = mu_t;
  in.design_rating = r[0], in.test_rating = r[1], in.model_rating = r[2];
  return in;
}

}  // namespace pcrf::post

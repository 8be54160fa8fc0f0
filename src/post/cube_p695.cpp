// FEMA P-695 from a cube (see cube_p695.hpp).
#include "pcrf/post/cube_p695.hpp"

#include "pcrf/user_error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/frame.hpp"
#include "pcrf/model/frame_properties.hpp"
#include "pcrf/model/parameters.hpp"
#include "pcrf/number_text.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/row_major.hpp"
#include "pcrf/solver/settings.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"

namespace pcrf::post {
namespace {

namespace names = schema;

/// The cube's attribute of [intensity] `key` (the measure the records were scaled by).
std::string intensity_attribute(std::string_view key) { return names::setting_attribute(intensity_settings().name, key); }

/// Why the cube's intensity is not the methodology's Sa(T); empty when it is.
std::string measure_problem(const cube::CubeReader& cube, double period_s) {
  const auto& layout = cube.layout();
  const std::string measure = layout.text_attribute(intensity_attribute("measure"));
  if (measure != to_string(IntensityMeasure::kSa))
    return "the cube's intensity measure is " + (measure.empty() ? std::string("none") : measure) +
           ", not Sa(T): P-695 scales the records to Sa at the archetype's period, so these numbers are not P-695's";
  for (const auto& a : layout.attributes) {
    if (a.name != intensity_attribute("period_s")) continue;
    const double* stored = std::get_if<double>(&a.value);
    if (stored != nullptr && std::abs(*stored - period_s) > 1e-9 * period_s)
      return "the cube's Sa is at T = " + number_text(*stored) + " s, not at the --period-s " + number_text(period_s) +
             " s: these numbers are not P-695's";
  }
  if (layout.text_attribute(intensity_attribute("normalise")) != to_string(SetNormalisation::kP695))
    return "the cube's records were each scaled to their own Sa(T), not normalised and scaled as one set "
           "([intensity] normalise = \"p695\", Appendix A): its median collapse intensity is not P-695's S_CT";
  return {};
}

/// The scene model of case `index`: its `scene_model` coordinate (a study of several scenes),
/// else the cube's attribute, else the prestressed frame.
std::string scene_of_case(const cube::CubeLayout& layout, std::int64_t index) {
  if (const cube::Coordinate* c = layout.find_coordinate(names::kSceneModel))
    if (const auto dim = layout.find_dimension(c->dimension)) return c->label(unravel(index, layout.shape())[*dim]);
  const std::string attribute = layout.text_attribute(names::kSceneModel);
  return attribute.empty() ? "pcrf" : attribute;
}

/// The frame parameters of case `index`: the study's base point, overridden by every
/// parameter coordinate the cube has (a grid's axes, a list's or sample's per-case values).
/// \throws UserError for a case of another scene than the prestressed frame.
FrameParameters parameters_of_case(const cube::CubeLayout& layout, std::int64_t index) {
  if (const auto scene = scene_of_case(layout, index); scene != "pcrf")
    throw UserError(Where{}, "a " + scene + " scene has no engine convention for mu_T (docs/p695_rocking_frame.md is the prestressed frame's): give {}", {"mu_t"});
  auto attribute = [&](const std::string& name) {
    for (const auto& a : layout.attributes)
      if (a.name == name)
        if (const double* v = std::get_if<double>(&a.value)) return *v;
    throw UserError(Where{}, "the cube has no attribute " + name + ": give {}", {"mu_t"});
  };
  FrameParameters p;
  for (const auto& info : all_parameters()) p.*info.member = attribute(names::base_attribute(info.name));
  p.h_m = attribute(names::frame_attribute("h_m"));
  p.m_c_kg = attribute(names::frame_attribute("m_c_kg"));
  const auto coords = unravel(index, layout.shape());
  for (const auto& info : all_parameters()) {
    const cube::Coordinate* c = layout.find_coordinate(std::string(info.name));
    if (c == nullptr || c->is_text) continue;
    const auto dim = layout.find_dimension(c->dimension);
    if (dim) p.*info.member = c->numbers[coords[*dim]];
  }
  return p;
}

/// μ_T of the frame of case `index` by the engine's convention (docs/p695_rocking_frame.md).
double own_mu_t(const cube::CubeLayout& layout, std::int64_t index, double period_s) {
  double fracture_strain = PhysicsOptions{}.fracture_strain;
  for (const auto& a : layout.attributes)
    if (a.name == names::setting_attribute(physics_settings().name, "fracture_strain"))
      if (const double* v = std::get_if<double>(&a.value)) fracture_strain = *v;
  const FrameParameters parameters = parameters_of_case(layout, index);
  const EquationOfMotion eom(make_frame(parameters));
  const auto properties = frame_properties(eom, fracture_strain, 2001);
  return std::max(1.0, p695_ductility(properties, parameters.h_m, period_s).mu_t_capacity);
}

/// A value for a note: four significant digits.
std::string short_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

/// Ŝ_CT counted from a frame's fragility data: its IDA curves (collapse intensities, and the
/// censored, unbracketed and unresolved curves' bounds), or its stripes (the lowest stripe at
/// which at least half the records with a verdict collapsed).
p695::CountedMedian counted_of(const FrameFragility& f) {
  if (f.stripes.empty()) {
    std::vector<double> bounds = f.censored_intensities;
    bounds.insert(bounds.end(), f.unresolved_intensities.begin(), f.unresolved_intensities.end());
    return p695::counted_median(f.collapse_intensities, bounds);
  }
  p695::CountedMedian m;
  m.s_ct_g = m.low_g = m.high_g = std::nan("");
  for (const auto& s : f.stripes)  // in intensity order
    if (s.trials > 0.0 && 2.0 * s.collapses >= s.trials) {
      m.s_ct_g = m.low_g = m.high_g = s.intensity;
      m.curves = static_cast<std::size_t>(s.trials);
      break;
    }
  return m;
}

/// The measured modelling scatter of sampled frames and the P(collapse | MCE) each total implies.
void add_model_scatter(const cube::CubeReader& cube, const std::vector<FrameFragility>& frames, const P695Inputs& in,
                       P695Report& report) {
  report.model = model_scatter(cube, frames, in.design_rating, in.test_rating, in.model_rating);
  if (!report.model) return;
  const double s_mt = p695::mce_spectrum(in.sdc).at(in.period_s), median = report.model->dispersion.pooled.median;
  report.model_p_collapse_mce_measured = analysis::normal_cdf(std::log(s_mt / median) / report.model->beta_total_measured);
  report.model_p_collapse_mce_rated = analysis::normal_cdf(std::log(s_mt / median) / report.model->beta_total_rated);
  if (const auto warning = model_scatter_warning(report.model); !warning.empty()) report.notes.push_back(warning);
}

}  // namespace

SctFrom parse_s_ct(const std::string& text) {
  if (text == "counted") return SctFrom::kCounted;
  if (text == "lognormal") return SctFrom::kLognormal;
  throw UserError("s_ct", "unknown value '" + text + "' (expected counted or lognormal)");
}

std::string to_string(SctFrom from) { return from == SctFrom::kCounted ? "counted" : "lognormal"; }

P695Report cube_p695(const cube::CubeReader& cube, const std::vector<cube::Selector>& selectors, const P695Inputs& in) {
  if (!(in.period_s > 0.0)) throw UserError("period_s", "must be positive");
  P695Report report;
  report.measure_problem = measure_problem(cube, in.period_s);
  const auto frames = cube_fragility(cube, selectors);
  for (const FrameFragility& f : frames) {
    const auto counted = counted_of(f);
    const double lognormal = f.fit ? f.fit->median : std::nan("");
    const double s_ct = in.s_ct == SctFrom::kCounted ? counted.s_ct_g : lognormal;
    if (!std::isfinite(s_ct))
      throw UserError("frame " + f.frame + (in.s_ct == SctFrom::kCounted
                                                            ? ": fewer than half its records collapse, so no counted median collapse intensity to assess"
                                                            : ": no collapse, so no median collapse intensity to assess"));
    double mu_t = in.mu_t;
    try {
      if (!(mu_t > 0.0)) mu_t = own_mu_t(cube.layout(), f.first_case, in.period_s);
    } catch (const UserError& e) {  // which frame
      throw e.preceded_by("frame " + f.frame + ": ");
    }
    report.frames.push_back({f.frame, mu_t, counted.s_ct_g, counted.high_g, counted.bounded, lognormal,
                             p695::assess(s_ct, in.period_s, mu_t, in.sdc, in.design_rating, in.test_rating, in.model_rating)});
    if (counted.bounded > 0)
      report.notes.push_back("frame " + f.frame + ": " + std::to_string(counted.bounded) +
                             " curves without a collapse shown above their last safe intensity (censored, unbracketed or "
                             "unresolved) count as collapsing there: the counted S_CT " + short_number(counted.low_g) +
                             " g is conservative (" + (std::isnan(counted.high_g) ? std::string("fewer than half collapse otherwise")
                                                                                    : short_number(counted.high_g) + " g were they never to collapse") + ")");
  }
  add_model_scatter(cube, frames, in, report);
  std::vector<p695::Assessment> all;
  for (const auto& f : report.frames) all.push_back(f.assessment);
  report.group = p695::assess_group(all);
  if (report.frames.size() == 1)
    report.notes.push_back("a performance group of one archetype: P-695's group test (mean ACMR against ACMR10%, Section 7.6) "
                           "is then that archetype's own; select several frames for a group");
  if (in.default_ratings)
    report.notes.push_back("quality ratings not given: B,B,B (good) by default; give --ratings for design, test data and model "
                           "(Sections 3 and 5)");
  return report;
}

void print_p695(const P695Report& report, const P695Inputs& in, std::ostream& out) {
  char line[320];
  const auto spectrum = p695::mce_spectrum(in.sdc);
  std::snprintf(line, sizeof line,
                "FEMA P-695, SDC %s (S_MS %g g, S_M1 %g g), T = %g s, mu_T %s, ratings %c/%c/%c (design, tests, model)\n",
                p695::to_string(in.sdc).c_str(), spectrum.s_ms_g, spectrum.s_m1_g, in.period_s,
                in.mu_t > 0.0 ? number_text(in.mu_t).c_str() : "of each frame (pushover peak, docs/p695_rocking_frame.md)",
                in.design_rating, in.test_rating, in.model_rating);
  out << line;
  std::snprintf(line, sizeof line,
                "SSF = exp(beta1 (eps0 - eps(T))), beta1 = 0.14 (mu_T - 1)^0.42, far-field eps(T) = %.3f, eps0 = %.1f\n",
                p695::far_field_epsilon(in.period_s), p695::target_epsilon(in.sdc));
  out << line;
  std::snprintf(line, sizeof line,
                "S_CT: %s (%s); the other median beside it. Counted: the lowest intensity at which half the records "
                "collapse (Sections 6.3, 6.4)\n",
                to_string(in.s_ct).c_str(), in.s_ct == SctFrom::kCounted ? "P-695's own" : "the lognormal fit's median, on request");
  out << line;
  std::snprintf(line, sizeof line, "%-24s %8s %9s %9s %8s %6s %6s %6s %6s %6s %8s %8s %8s %8s %10s\n", "frame", "S_CT [g]",
                "cnt. [g]", "logn. [g]", "S_MT [g]", "CMR", "mu_T", "SSF", "ACMR", "b_RTR", "beta_TOT", "ACMR10%", "ACMR20%",
                "P(c|MCE)", "ACMR20%?");
  out << line;
  for (const auto& f : report.frames) {
    const auto& a = f.assessment;
    std::snprintf(line, sizeof line,
                  "%-24s %8.3f %9.3f %9.3f %8.3f %6.2f %6.2f %6.2f %6.2f %6.2f %8.3f %8.2f %8.2f %8.3f %10s\n",
                  f.frame.c_str(), a.s_ct_g, f.s_ct_counted_g, f.s_ct_lognormal_g, a.s_mt_g, a.cmr, f.mu_t, a.ssf, a.acmr,
                  a.beta_rtr, a.beta_total, a.acmr10, a.acmr20, a.p_collapse_mce, a.passes_individual ? "pass" : "fail");
    out << line;
  }
  std::snprintf(line, sizeof line, "group: mean ACMR %.2f against ACMR10%% %.2f, every frame against ACMR20%%: %s\n",
                report.group.mean_acmr, report.group.acmr10, report.group.passes ? "PASS" : "FAIL");
  out << line;
  if (!report.model) return;
  const auto& m = *report.model;
  std::snprintf(line, sizeof line,
                "modelling uncertainty measured over %zu sampled frames: pooled median %.3g g, beta %.3g = sqrt(beta_rtr "
                "%.3g^2 + beta_model %.3g^2); the rating's beta_MDL %.3g\n",
                m.dispersion.frames, m.dispersion.pooled.median, m.dispersion.pooled.beta, m.dispersion.beta_rtr,
                m.dispersion.beta_model, m.beta_mdl_rated);
  out << line;
  std::snprintf(line, sizeof line,
                "beta_TOT with the modelling term measured %.3f (P(c|MCE) %.3f at the pooled median), rated %.3f (%.3f)\n",
                m.beta_total_measured, report.model_p_collapse_mce_measured, m.beta_total_rated,
                report.model_p_collapse_mce_rated);
  out << line;
}

}  // namespace pcrf::post

// FEMA P-695 from a cube (see cube_p695.hpp).
#include "pcrf/post/cube_p695.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <utility>

#include "pcrf/number_text.hpp"
#include "pcrf/record/intensity.hpp"

namespace pcrf::post {
namespace {

/// Why the cube's intensity is not the methodology's Sa(T); empty when it is.
std::string measure_problem(const cube::CubeReader& cube, double period_s) {
  const auto& layout = cube.layout();
  const std::string measure = layout.text_attribute("intensity_measure");
  if (measure != to_string(IntensityMeasure::kSa))
    return "the cube's intensity measure is " + (measure.empty() ? std::string("none") : measure) +
           ", not Sa(T): P-695 scales the records to Sa at the archetype's period, so these numbers are not P-695's";
  for (const auto& a : layout.attributes) {
    if (a.name != "intensity_period_s") continue;
    const double* stored = std::get_if<double>(&a.value);
    if (stored != nullptr && std::abs(*stored - period_s) > 1e-9 * period_s)
      return "the cube's Sa is at T = " + number_text(*stored) + " s, not at the --period-s " + number_text(period_s) +
             " s: these numbers are not P-695's";
  }
  return {};
}

}  // namespace

P695Report cube_p695(const cube::CubeReader& cube, const std::vector<cube::Selector>& selectors, const P695Inputs& in) {
  if (!(in.period_s > 0.0)) throw std::invalid_argument("--period-s must be positive");
  P695Report report;
  report.measure_problem = measure_problem(cube, in.period_s);
  for (const FrameFragility& f : cube_fragility(cube, selectors)) {
    if (!f.fit) throw std::invalid_argument("frame " + f.frame + ": no collapse, so no median collapse intensity to assess");
    report.frames.push_back({f.frame, p695::assess(f.fit->median, in.period_s, in.mu_t, in.sdc, in.design_rating,
                                                   in.test_rating, in.model_rating)});
  }
  std::vector<p695::Assessment> all;
  for (const auto& f : report.frames) all.push_back(f.assessment);
  report.group = p695::assess_group(all);
  return report;
}

void print_p695(const P695Report& report, const P695Inputs& in, std::ostream& out) {
  char line[256];
  std::snprintf(line, sizeof line, "FEMA P-695, SDC %s, T = %g s, mu_T = %g, ratings %c/%c/%c\n",
                p695::to_string(in.sdc).c_str(), in.period_s, in.mu_t, in.design_rating, in.test_rating, in.model_rating);
  out << line;
  std::snprintf(line, sizeof line, "%-24s %8s %8s %6s %6s %6s %8s %8s %8s %8s %10s\n", "frame", "S_CT [g]", "S_MT [g]",
                "CMR", "SSF", "ACMR", "beta_TOT", "ACMR10%", "ACMR20%", "P(c|MCE)", "ACMR20%?");
  out << line;
  for (const auto& f : report.frames) {
    const auto& a = f.assessment;
    std::snprintf(line, sizeof line, "%-24s %8.3f %8.3f %6.2f %6.2f %6.2f %8.3f %8.2f %8.2f %8.3f %10s\n",
                  f.frame.c_str(), a.s_ct_g, a.s_mt_g, a.cmr, a.ssf, a.acmr, a.beta_total, a.acmr10, a.acmr20,
                  a.p_collapse_mce, a.passes_individual ? "pass" : "fail");
    out << line;
  }
  std::snprintf(line, sizeof line, "group: mean ACMR %.2f against ACMR10%% %.2f, every frame against ACMR20%%: %s\n",
                report.group.mean_acmr, report.group.acmr10, report.group.passes ? "PASS" : "FAIL");
  out << line;
}

}  // namespace pcrf::post

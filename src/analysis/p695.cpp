// FEMA P-695 from the median collapse intensity to the verdict (see p695.hpp).
#include "pcrf/analysis/p695.hpp"

#include "pcrf/user_error.hpp"

#include <boost/math/distributions/normal.hpp>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "pcrf/analysis/fragility.hpp"

namespace pcrf::p695 {
namespace {

struct SdcRow {
  Sdc sdc;
  const char* name;
  double s_ms_g, s_m1_g;  // Table 5-1
};
constexpr std::array<SdcRow, 6> kSdcs{{{Sdc::kDmax, "Dmax", 1.5, 0.9},
                                       {Sdc::kDmin, "Dmin", 0.75, 0.30},
                                       {Sdc::kCmax, "Cmax", 0.75, 0.30},
                                       {Sdc::kCmin, "Cmin", 0.50, 0.20},
                                       {Sdc::kBmax, "Bmax", 0.50, 0.20},
                                       {Sdc::kBmin, "Bmin", 0.25, 0.10}}};

const SdcRow& row_of(Sdc sdc) {
  return *std::find_if(kSdcs.begin(), kSdcs.end(), [sdc](const SdcRow& r) { return r.sdc == sdc; });
}

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

Sdc parse_sdc(const std::string& text) {
  for (const SdcRow& r : kSdcs)
    if (lower(text) == lower(r.name)) return r.sdc;
  throw UserError("unknown seismic design category '" + text + "' (expected Dmax, Dmin, Cmax, Cmin, Bmax or Bmin)");
}

std::string to_string(Sdc sdc) { return row_of(sdc).name; }

double MceSpectrum::at(double period_s) const {
  const double t_s = s_m1_g / s_ms_g;
  return period_s <= t_s ? s_ms_g : s_m1_g / period_s;
}

MceSpectrum mce_spectrum(Sdc sdc) { return {row_of(sdc).s_ms_g, row_of(sdc).s_m1_g}; }

double rating_beta(char rating) {
  switch (std::toupper(static_cast<unsigned char>(rating))) {
    case 'A': return 0.10;
    case 'B': return 0.20;
    case 'C': return 0.35;
    case 'D': return 0.50;
    default: throw UserError(std::string("unknown quality rating '") + rating + "' (expected A, B, C or D)");
  }
}

double beta_record_to_record(double mu_t) { return std::min(0.1 + 0.1 * mu_t, 0.4); }

double beta_total(double mu_t, char design_rating, char test_rating, char model_rating) {
  const double b_rtr = beta_record_to_record(mu_t), b_dr = rating_beta(design_rating),
               b_td = rating_beta(test_rating), b_mdl = rating_beta(model_rating);
  const double b = std::sqrt(b_rtr * b_rtr + b_dr * b_dr + b_td * b_td + b_mdl * b_mdl);
  return std::round(b * 40.0) / 40.0;
}

double spectral_shape_factor(double period_s, double mu_t, Sdc sdc) {
  if (!(mu_t >= 1.0)) throw UserError("the period-based ductility mu_T must be at least 1");
  if (!(period_s > 0.0)) throw UserError("the period must be positive");
  return std::exp(ssf_beta1(mu_t) * (target_epsilon(sdc) - far_field_epsilon(period_s)));
}

double ssf_beta1(double mu_t) { return 0.14 * std::pow(std::min(mu_t, 8.0) - 1.0, 0.42); }

double far_field_epsilon(double period_s) { return 0.6 * (1.5 - std::clamp(period_s, 0.5, 1.5)); }

double target_epsilon(Sdc sdc) { return sdc == Sdc::kDmax ? 1.5 : 1.0; }

double acceptable_cmr(double beta_total, double probability) {
  const boost::math::normal standard;
  return std::exp(-boost::math::quantile(standard, probability) * beta_total);
}

CountedMedian counted_median(std::vector<double> collapse_g, std::vector<double> censored_g) {
  CountedMedian m;
  m.curves = collapse_g.size() + censored_g.size();
  if (m.curves == 0) throw UserError("no IDA curve to count a median collapse intensity from");
  const std::size_t k = (m.curves + 1) / 2;  // ⌈N/2⌉
  const double none = std::nan("");
  std::sort(collapse_g.begin(), collapse_g.end());
  m.high_g = collapse_g.size() >= k ? collapse_g[k - 1] : none;
  std::vector<double> all = collapse_g;
  for (double bound : censored_g) {
    // A curve safe up to at least high_g cannot move the count below it.
    if (!std::isnan(m.high_g) && bound >= m.high_g) continue;
    all.push_back(bound);
    ++m.bounded;
  }
  std::sort(all.begin(), all.end());
  m.low_g = all.size() >= k ? all[k - 1] : none;
  m.s_ct_g = m.low_g;
  return m;
}

double archetype_period_s(double cu_ta_s) { return std::max(cu_ta_s, 0.25); }

Assessment assess(double s_ct_g, double period_s, double mu_t, Sdc sdc, char design_rating, char test_rating,
                  char model_rating) {
  Assessment a{};
  a.s_ct_g = s_ct_g;
  a.s_mt_g = mce_spectrum(sdc).at(period_s);
  a.cmr = s_ct_g / a.s_mt_g;
  a.ssf = spectral_shape_factor(period_s, mu_t, sdc);
  a.acmr = a.ssf * a.cmr;
  a.beta_rtr = beta_record_to_record(mu_t);
  a.beta_total = beta_total(mu_t, design_rating, test_rating, model_rating);
  a.acmr10 = acceptable_cmr(a.beta_total, 0.10);
  a.acmr20 = acceptable_cmr(a.beta_total, 0.20);
  a.p_collapse_mce = analysis::normal_cdf(std::log(a.s_mt_g / s_ct_g) / a.beta_total);
  a.passes_individual = a.acmr >= a.acmr20;
  return a;
}

GroupVerdict assess_group(const std::vector<Assessment>& archetypes) {
  if (archetypes.empty()) throw UserError("a performance group needs at least one archetype");
  GroupVerdict v{};
  for (const Assessment& a : archetypes) v.mean_acmr += a.acmr / static_cast<double>(archetypes.size());
  // One β_TOT per performance group (Section 7.6): the largest of its archetypes'.
  double beta = 0.0;
  for (const Assessment& a : archetypes) beta = std::max(beta, a.beta_total);
  v.acmr10 = acceptable_cmr(beta, 0.10);
  v.passes = v.mean_acmr >= v.acmr10 &&
             std::all_of(archetypes.begin(), archetypes.end(), [](const Assessment& a) { return a.passes_individual; });
  return v;
}

}  // namespace pcrf::p695

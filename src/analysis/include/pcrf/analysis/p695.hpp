/// \file p695.hpp
/// \brief The FEMA P-695 collapse assessment (FEMA P-695, "Quantification of Building Seismic
/// Performance Factors", 2009), from a median collapse intensity to its verdict.
///
/// Numbers only: the caller gives the archetype's median collapse intensity Ŝ_CT [g] at the
/// period T, its period-based ductility μ_T and the quality ratings; every function here is
/// the methodology's own formula or table, with its section named.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace pcrf::p695 {

/// Seismic design categories of the methodology's Table 5-1 (maximum and minimum of each).
enum class Sdc { kDmax, kDmin, kCmax, kCmin, kBmax, kBmin };
/// "Dmax", "Dmin", … (case ignored). \throws UserError listing the names.
Sdc parse_sdc(const std::string& text);
std::string to_string(Sdc sdc);

/// Mapped MCE spectral accelerations of Table 5-1 [g]: S_MS (short period) and S_M1 (1 s).
struct MceSpectrum {
  double s_ms_g;
  double s_m1_g;
  /// S_MT at period T [s]: S_MS up to T_S = S_M1/S_MS, then S_M1/T (Section 5.2.4). [g]
  double at(double period_s) const;
};
MceSpectrum mce_spectrum(Sdc sdc);

/// Quality ratings of Section 3 (design requirements, test data) and 5 (modelling):
/// A superior 0.10, B good 0.20, C fair 0.35, D poor 0.50 (Section 7.3.4).
double rating_beta(char rating);

/// β_RTR = 0.1 + 0.1 μ_T, at most 0.4 (Eq. 7-2).
double beta_record_to_record(double mu_t);

/// β_TOT = √(β_RTR² + β_DR² + β_TD² + β_MDL²) (Eq. 7-5), rounded to the nearest 0.025 as the
/// methodology's Table 7-2 does.
double beta_total(double mu_t, char design_rating, char test_rating, char model_rating);

/// Spectral shape factor (Section 7.2.2, Appendix B): SSF = exp(β₁ (ε̄₀ − ε̄(T))) with
/// β₁ = 0.14 (μ_T − 1)^0.42, the far-field set's ε̄(T) = 0.6 (1.5 − T) for 0.5 ≤ T ≤ 1.5 s
/// (T clamped to that range, as Table 7-1 does) and the target ε̄₀ = 1.5 for SDC Dmax,
/// 1.0 for the others; μ_T above 8 counts as 8. Equals Tables 7-1a/7-1b to their two decimals.
/// \throws UserError for μ_T < 1 or T ≤ 0.
double spectral_shape_factor(double period_s, double mu_t, Sdc sdc);
/// The three pieces of the SSF: β₁(μ_T) (Eq. B-3, μ_T above 8 as 8), the far-field set's
/// ε̄(T) (Eq. B-1, Figure B-3) and the target ε̄₀ of the SDC (Section B.3.2).
double ssf_beta1(double mu_t);
double far_field_epsilon(double period_s);
double target_epsilon(Sdc sdc);

/// Acceptable collapse margin ratio at a collapse probability `p` under the MCE:
/// exp(−Φ⁻¹(p) β_TOT) (Section 7.4, Table 7-3 lists it for ACMR10% and ACMR20%).
double acceptable_cmr(double beta_total, double probability);

/// Ŝ_CT as the methodology defines it (Sections 6.3 and 6.4): the intensity at which one
/// half of the records cause collapse, counted from the records' IDA collapse intensities.
/// With N curves, it is the lowest intensity at which at least N/2 of them have collapsed:
/// the k-th smallest collapse intensity, k = ⌈N/2⌉ (N = 44: the 22nd; an even N takes the
/// lower of the two middle values, not their mean; an odd N the middle one).
/// A censored curve (no collapse shown above `censored_g`: safe at the cap, or unbracketed or
/// unresolved and bounded at its last safe run) counts as not collapsed at every intensity up
/// to its bound and unknown above. When such a bound lies below the k-th collapse, that curve
/// could have collapsed before it: Ŝ_CT then lies in [low_g, high_g], where low_g counts those
/// curves as collapsing at their bounds (conservative) and high_g as never collapsing; `s_ct_g`
/// is low_g, and `bounded` says how many curves moved it. With fewer than k collapses even
/// counting every bound, Ŝ_CT is above every intensity run: NaN.
struct CountedMedian {
  double s_ct_g = 0.0;        ///< the counted Ŝ_CT used (low_g) [g]; NaN when not reached
  double low_g = 0.0;         ///< bounded curves counted as collapsing at their bounds [g]
  double high_g = 0.0;        ///< bounded curves counted as never collapsing [g]; NaN when not reached
  std::size_t curves = 0;     ///< N
  std::size_t bounded = 0;    ///< curves whose bound lies below high_g (or every censored one when high_g is NaN)
};
/// \throws UserError for no curve at all.
CountedMedian counted_median(std::vector<double> collapse_g, std::vector<double> censored_g);

/// The methodology's numbers for one archetype.
struct Assessment {
  double s_ct_g;          ///< median collapse intensity Ŝ_CT [g]
  double s_mt_g;          ///< MCE intensity at T [g]
  double cmr;             ///< Ŝ_CT / S_MT
  double ssf;             ///< spectral shape factor
  double acmr;            ///< SSF × CMR
  double beta_rtr;        ///< record-to-record uncertainty
  double beta_total;      ///< β_TOT, rounded to 0.025
  double acmr10;          ///< acceptable ACMR at 10 % collapse probability
  double acmr20;          ///< acceptable ACMR at 20 % collapse probability
  double p_collapse_mce;  ///< Φ(ln(S_MT / Ŝ_CT) / β_TOT), the collapse probability at the MCE
  bool passes_individual; ///< ACMR ≥ ACMR20% (Section 7.6: each archetype)
};

/// Everything for an archetype of period `period_s` [s] with median collapse intensity
/// `s_ct_g` (Sa(T) in g) and period-based ductility `mu_t`.
Assessment assess(double s_ct_g, double period_s, double mu_t, Sdc sdc, char design_rating, char test_rating,
                  char model_rating);

/// A performance group passes when its mean ACMR reaches ACMR10% and every archetype's ACMR
/// reaches ACMR20% (Section 7.6). (Issue 21 of this project states the two the other way
/// round; the methodology's text is followed here.) The group's β_TOT is its largest.
struct GroupVerdict {
  double mean_acmr;
  double acmr10;
  bool passes;
};
/// \throws UserError for an empty group.
GroupVerdict assess_group(const std::vector<Assessment>& archetypes);

/// The fundamental period the methodology uses: max(C_u T_a, 0.25 s) (Section 5.2.5) [s].
double archetype_period_s(double cu_ta_s);

}  // namespace pcrf::p695

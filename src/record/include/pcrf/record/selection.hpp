/// \file selection.hpp
/// \brief Records selected from a library (record_library.hpp) so that their scaled spectra
/// match a target distribution of ln Sa: greedy optimisation after simulated spectra.
///
/// Jayaram, N., Lin, T. & Baker, J. W. (2011), "A computationally efficient ground-motion
/// selection algorithm for matching a target response spectrum mean and variance",
/// Earthquake Spectra 27(3), 797–815; improved by Baker, J. W. & Lee, C. (2018), "An improved
/// algorithm for selecting ground motions to match a conditional spectrum", J. Earthquake
/// Eng. 22(sup1), 708–723.
///
///  1. `trials` sets of N spectra are drawn from the multivariate normal distribution of ln Sa
///     (mean μ, standard deviations σ, correlation ρ: the target's, or Baker & Jayaram 2008's
///     model when it gives none) and ranked by how close their sample mean, standard deviation
///     and skewness are to μ, σ and 0 (weights w_mean, w_sigma, w_skew on the sums of squares).
///     Baker & Lee keep the best; here steps 2 and 3 start from each of the best `starts` sets
///     and the best final fit is kept (starts = 1 is their algorithm).
///  2. For each simulated spectrum, the library entry with the smallest Σ (ln(s·Sa) − ln Sa_sim)²
///     is chosen (each entry once), s its scale factor.
///  3. Greedy optimisation: each chosen entry in turn is replaced by the entry (and scale) that
///     minimises the set's w_mean Σ (m̂ − μ)² + w_sigma Σ (ŝ − σ)² (m̂, ŝ the set's mean and
///     standard deviation of ln Sa, ŝ with 1/N), pass after pass until a pass replaces no entry
///     (at most `loops` passes; Baker & Lee run two).
///
/// Scale factors: when the target has a conditioning period (σ = 0 there, as a conditional
/// spectrum has), every entry is scaled to Sa(T*) = exp(μ(T*)) and entries whose factor falls
/// outside [scale_min, scale_max] are not used. Otherwise each entry's s minimises the error it
/// is judged by, within the limits: step 2, least squares on Sa (Jayaram et al.), clamped to
/// the limits; step 3, the set's fit, searched over ln s in 64 steps and refined by
/// golden-section search to 1e-9 in ln s (Baker & Lee's code searches s in steps of 0.1).
///
/// The library's Sa are interpolated at the target's periods linearly in (ln T, ln Sa); a
/// target period outside the library's grid is refused.
#pragma once

#include <cstdint>
#include <istream>
#include <string>
#include <vector>

#include "pcrf/record/record_library.hpp"

namespace pcrf {

/// The distribution of ln Sa [ln g] to match, per period. pcrf computes no ground-motion
/// model: a target comes from OpenQuake's conditional-spectrum output or EzGM's
/// conditional_spectrum (its T, mu_ln, sigma_ln), written as CSV (read_selection_target).
struct SelectionTarget {
  std::vector<double> periods_s;
  std::vector<double> mean_ln_sa;   ///< μ = E[ln Sa/g]
  std::vector<double> sigma_ln_sa;  ///< σ ≥ 0
  std::vector<std::vector<double>> correlation;  ///< ρ between periods; empty: Baker & Jayaram (2008)
  std::string file;             ///< where it was read (messages)
  std::vector<int> row_lines;   ///< the file's line of each period
};

/// Reads a target: CSV, '#' comments, a header with `period_s`, `mean_ln_sa` and
/// `sigma_ln_sa` (in any order) and optionally `rho_<T>s` columns (one per period, in the rows'
/// order: the correlation matrix). \throws UserError naming the file, line and key: a missing
/// column, a value that is not a finite number, periods not increasing, σ < 0, ρ not in
/// [−1, 1] or not 1 on the diagonal or not symmetric.
SelectionTarget read_selection_target(std::istream& in, const std::string& file);

/// Baker & Jayaram (2008), Earthquake Spectra 24(1): correlation of ε between periods.
double baker_jayaram_correlation(double t1_s, double t2_s);

struct SelectionSettings {
  std::size_t count = 10;           ///< N
  std::string kind = "rotd50";      ///< library entries used: "rotd50" or "component"
  double scale_min = 0.25;
  double scale_max = 4.0;
  std::uint64_t seed = 1;
  int trials = 20;                  ///< simulated sets (step 1)
  int starts = 20;                  ///< steps 2 and 3 from each of the best `starts` simulated sets (at most `trials`)
  int loops = 100;                  ///< greedy passes at most (step 3 stops after a pass that replaces no entry)
  double w_mean = 1.0, w_sigma = 2.0, w_skew = 0.3;  ///< Baker & Lee's defaults
  /// The σ term of the objective on relative errors, w_sigma Σ ((ŝ − σ)/σ)² over the periods
  /// with σ > 0, instead of Baker & Lee's w_sigma Σ (ŝ − σ)²: a target whose σ is small near
  /// T* (a conditional spectrum's) is then matched there in proportion, as a tolerance on
  /// σ in percent asks. The figure of merit reported stays Baker & Lee's.
  bool relative_sigma = false;
};

struct SelectedRecord {
  std::size_t entry = 0;  ///< index in the table
  double scale = 1.0;
};

struct SelectionResult {
  std::vector<SelectedRecord> records;
  std::vector<double> mean_ln_sa;     ///< of the selected, scaled set, at the target's periods
  std::vector<double> sigma_ln_sa;    ///< (1/N)
  double sum_of_squares = 0.0;        ///< Σ (m̂ − μ)² + 2 Σ (ŝ − σ)²: Baker & Lee's figure of merit, whatever was optimised
  double median_error_percent = 0.0;  ///< max over periods of |exp m̂ − exp μ| / exp μ
  double sigma_error_percent = 0.0;   ///< max over periods (σ > 0) of |ŝ − σ| / σ
  std::vector<std::vector<double>> ln_sa;  ///< the selected scaled spectra, per record, at the target's periods
};

/// \throws UserError naming the target's file, line and `period_s` for a period outside the
/// library's grid; UserError when fewer usable entries than N remain, or for bad settings.
SelectionResult select_records(const SelectionTarget& target, const SpectraTable& table, const SelectionSettings& settings);

}  // namespace pcrf

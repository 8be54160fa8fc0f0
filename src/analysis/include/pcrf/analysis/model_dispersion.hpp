/// \file model_dispersion.hpp
/// \brief Modelling uncertainty measured: the dispersion a collapse fragility gains when the
/// frame's parameters are sampled (a study's lhs, sobol or saltelli plan) besides the records,
/// set against the record-to-record dispersion of the frames themselves, and the totals that
/// FEMA P-695 (Section 7.3.4) would form with it or with its quality ratings instead. Numbers
/// only: no cube, no file (docs/risk.md gives every formula).
///
/// With n frames i, each fitted alone (θ_i, β_i), and all their data pooled and fitted as one
/// fragility (θ, β_pooled):
///   β_RTR     = √(Σ β_i² / n)                  record-to-record, at a typical frame
///   β_model   = √(max(0, β_pooled² − β_RTR²))  what the parameters' scatter adds
///   β_medians = √(Σ (ln θ_i − m)² / n), m = Σ ln θ_i / n   the frames' medians' own scatter
/// For complete collapse intensities (no censoring) fitted by maximum likelihood,
/// β_pooled² = β_medians² + β_RTR² exactly (the law of total variance, divisor n), so
/// β_model = β_medians; censoring, stripes or data far from lognormal make the two differ,
/// which shows how far the decomposition holds.
#pragma once

#include <cstddef>
#include <vector>

#include "pcrf/analysis/fragility.hpp"

namespace pcrf::analysis {

struct MeasuredDispersion {
  Lognormal pooled;          ///< the fit of every frame's data together: β_pooled = pooled.beta
  double beta_rtr = 0.0;     ///< β_RTR
  double beta_model = 0.0;   ///< β_model
  double beta_medians = 0.0; ///< β_medians
  std::size_t frames = 0;    ///< n

  /// β_TOT with the modelling term measured, design requirements and test data rated:
  /// √(β_pooled² + β_DR² + β_TD²) = √(β_RTR² + β_model² + β_DR² + β_TD²) (β_model > 0).
  double total_measured(double beta_design, double beta_test) const;
  /// β_TOT with the modelling term rated (P-695 Eq. 7-5, β_RTR as measured):
  /// √(β_RTR² + β_DR² + β_TD² + β_MDL²).
  double total_rated(double beta_design, double beta_test, double beta_model_rated) const;
};

/// \throws std::invalid_argument for fewer than two frames, or a β or θ not positive.
MeasuredDispersion measured_dispersion(const Lognormal& pooled, const std::vector<Lognormal>& frames);

}  // namespace pcrf::analysis

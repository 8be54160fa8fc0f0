// Modelling uncertainty measured over sampled frames (see model_dispersion.hpp).
#include "pcrf/analysis/model_dispersion.hpp"

#include <cmath>
#include <stdexcept>

namespace pcrf::analysis {
namespace {

void check(const Lognormal& f) {
  if (!(f.median > 0.0) || !(f.beta > 0.0) || !std::isfinite(f.median) || !std::isfinite(f.beta))
    throw std::invalid_argument("measured_dispersion: a fragility needs a positive median and beta");
}

}  // namespace

double MeasuredDispersion::total_measured(double beta_design, double beta_test) const {
  return std::sqrt(pooled.beta * pooled.beta + beta_design * beta_design + beta_test * beta_test);
}

double MeasuredDispersion::total_rated(double beta_design, double beta_test, double beta_model_rated) const {
  return std::sqrt(beta_rtr * beta_rtr + beta_design * beta_design + beta_test * beta_test +
                   beta_model_rated * beta_model_rated);
}

MeasuredDispersion measured_dispersion(const Lognormal& pooled, const std::vector<Lognormal>& frames) {
  if (frames.size() < 2) throw std::invalid_argument("measured_dispersion: needs at least two frames");
  check(pooled);
  const double n = static_cast<double>(frames.size());
  double sum_beta2 = 0.0, sum_log = 0.0;
  for (const auto& f : frames) {
    check(f);
    sum_beta2 += f.beta * f.beta;
    sum_log += std::log(f.median);
  }
  const double mean_log = sum_log / n;
  double sum_dev2 = 0.0;
  for (const auto& f : frames) sum_dev2 += (std::log(f.median) - mean_log) * (std::log(f.median) - mean_log);
  MeasuredDispersion d;
  d.pooled = pooled;
  d.frames = frames.size();
  d.beta_rtr = std::sqrt(sum_beta2 / n);
  d.beta_model = std::sqrt(std::max(0.0, pooled.beta * pooled.beta - sum_beta2 / n));
  d.beta_medians = std::sqrt(sum_dev2 / n);
  return d;
}

}  // namespace pcrf::analysis

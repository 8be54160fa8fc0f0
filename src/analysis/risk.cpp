// Annual collapse rate from a hazard curve and a fragility (see risk.hpp).
#include "pcrf/analysis/risk.hpp"

#include "pcrf/user_error.hpp"

#include <boost/math/distributions/normal.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace pcrf::risk {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kTailSigmas = 8.5;       // a lognormal is 1 to 1e-17 beyond θ exp(8.5 β)

double quantile(double p) { return boost::math::quantile(boost::math::normal(), p); }

double lognormal_cdf(const analysis::Lognormal& f, double x) {
  return x > 0.0 ? analysis::normal_cdf(std::log(x / f.median) / f.beta) : 0.0;
}

void check_fragility(const analysis::Lognormal& f) {
  if (!(f.median > 0.0) || !std::isfinite(f.median)) throw UserError("fragility median must be positive");
  if (!(f.beta > 0.0) || !std::isfinite(f.beta)) throw UserError("fragility beta must be positive");
}

/// The standard normal density φ(z).
double normal_pdf(double z) { return std::exp(-0.5 * z * z) / std::sqrt(2.0 * std::numbers::pi); }

/// Mills's ratio Q(t)/φ(t) = (1 − Φ(t))/φ(t) for t ≥ 0: directly where both are far from
/// underflow, beyond by its continued fraction 1/(t + 1/(t + 2/(t + 3/(t + …)))) (Abramowitz &
/// Stegun 26.2.14), which at t ≥ 20 is exact to rounding within 60 terms.
double mills_ratio(double t) {
  if (t < 20.0) return 0.5 * std::erfc(t / std::numbers::sqrt2) / normal_pdf(t);
  if (std::isinf(t)) return 0.0;
  double f = t;
  for (int k = 60; k >= 1; --k) f = t + k / f;
  return 1.0 / f;
}

/// ∫ P(C | x) |dλ(x)| over [a, b] inside one hazard segment, where λ(x) = λ_a (x/a)^−k, in
/// closed form. In z = ln(x/θ)/β and s = kβ, integration by parts gives
///   Φ(z_a) λ_a − Φ(z_b) λ_b + λ_a φ(z_a)/φ(z_a + s) [Φ(z_b + s) − Φ(z_a + s)],
/// the last term written with Mills's ratio where z_a + s > 0 so that no factor overflows
/// however steep the segment (k of 10⁶ and more). The result is held within its exact bounds
/// P(a) (λ_a − λ_b) and P(b) (λ_a − λ_b) (P grows with x), which only rounding can leave.
double segment_rate(const analysis::Lognormal& f, double a, double b, double rate_a, double k) {
  if (!(k > 0.0) || !(b > a)) return 0.0;
  const double za = std::log(a / f.median) / f.beta, zb = std::log(b / f.median) / f.beta, s = k * f.beta;
  const double pa = analysis::normal_cdf(za), pb = analysis::normal_cdf(zb);
  const double fall = -rate_a * std::expm1(-k * std::log(b / a));  // λ_a − λ_b
  const double rate_b = rate_a - fall;
  const double t1 = za + s, t2 = zb + s;
  double jump;  // ∫ λ dP
  if (t1 > 0.0) {
    const double ratio = std::isinf(t2) ? 0.0 : mills_ratio(t2) * std::exp(-0.5 * (t2 - t1) * (t2 + t1));
    jump = rate_a * normal_pdf(za) * (mills_ratio(t1) - ratio);
  } else {
    jump = rate_a * std::exp(s * (za + 0.5 * s)) * (analysis::normal_cdf(t2) - analysis::normal_cdf(t1));
  }
  const double rate = pa * rate_a - pb * rate_b + jump;
  return std::clamp(rate, pa * fall, pb * fall);
}

/// Finds the root of a decreasing `f` of ln x between `low` and `high` (bisection); NaN
/// when f does not change sign there.
template <class F>
double bisect_log(F f, double low, double high) {
  double a = std::log(low), b = std::log(high);
  const double fa = f(a), fb = f(b);
  if (!(fa >= 0.0) || !(fb <= 0.0)) return kNaN;
  for (int i = 0; i < 200 && b - a > 1e-12; ++i) {
    const double m = 0.5 * (a + b);
    (f(m) > 0.0 ? a : b) = m;
  }
  return std::exp(0.5 * (a + b));
}

}  // namespace

std::string to_string(Tail tail) { return tail == Tail::kCutOff ? "cut-off" : "power-law"; }

Tail parse_tail(const std::string& text) {
  if (text == "cut-off" || text == "cutoff") return Tail::kCutOff;
  if (text == "power-law") return Tail::kPowerLaw;
  throw UserError("unknown hazard tail '" + text + "' (expected cut-off or power-law)");
}

HazardCurve::HazardCurve(std::vector<double> intensity, std::vector<double> rate_per_yr, Tail tail)
    : x_(std::move(intensity)), rate_(std::move(rate_per_yr)), tail_(tail) {
  if (x_.size() != rate_.size()) throw UserError("a hazard curve needs as many rates as intensities");
  if (x_.size() < 2) throw UserError("a hazard curve needs at least two points");
  for (std::size_t i = 0; i < x_.size(); ++i) {
    const std::string point = "point " + std::to_string(i) + ": ";
    if (!(x_[i] > 0.0) || !std::isfinite(x_[i])) throw UserError(point + "intensity must be positive");
    if (!(rate_[i] > 0.0) || !std::isfinite(rate_[i])) throw UserError(point + "rate must be positive");
    if (i > 0 && !(x_[i] > x_[i - 1])) throw UserError(point + "intensities must increase");
    if (i > 0 && !(rate_[i] < rate_[i - 1])) throw UserError(point + "the rate must decrease");
  }
}

namespace {
/// The segment [x_i, x_{i+1}] holding x (x_0 ≤ x ≤ x_n); the last one at x_n.
std::size_t segment(const std::vector<double>& xs, double x) {
  const auto it = std::upper_bound(xs.begin(), xs.end(), x);
  const auto i = static_cast<std::size_t>(it - xs.begin());
  return std::min(i == 0 ? 0 : i - 1, xs.size() - 2);
}
double exponent(const std::vector<double>& xs, const std::vector<double>& rs, std::size_t i) {
  return -std::log(rs[i + 1] / rs[i]) / std::log(xs[i + 1] / xs[i]);
}
}  // namespace

double HazardCurve::rate_per_yr(double x) const {
  if (x <= x_.front()) return rate_.front();
  if (x > x_.back() && tail_ == Tail::kCutOff) return 0.0;
  const std::size_t i = segment(x_, x);
  return rate_[i] * std::pow(x / x_[i], -exponent(x_, rate_, i));
}

double HazardCurve::slope(double x) const {
  if (x < x_.front()) return 0.0;
  if (x > x_.back() && tail_ == Tail::kCutOff) return 0.0;
  return exponent(x_, rate_, segment(x_, x));
}

double HazardCurve::intensity_at_rate(double r) const {
  if (!(r > 0.0) || r > rate_.front()) return kNaN;
  if (r < rate_.back() && tail_ == Tail::kCutOff) return kNaN;
  std::size_t i = x_.size() - 2;
  for (std::size_t j = 0; j + 1 < x_.size(); ++j)
    if (r >= rate_[j + 1]) {
      i = j;
      break;
    }
  return x_[i] * std::pow(r / rate_[i], -1.0 / exponent(x_, rate_, i));
}

HazardCurve power_law_curve(double k0_per_yr, double k, double low, double high, std::size_t points, Tail tail) {
  if (points < 2 || !(low > 0.0) || !(high > low)) throw UserError("power_law_curve: bad range");
  std::vector<double> x(points), r(points);
  for (std::size_t i = 0; i < points; ++i) {
    x[i] = low * std::pow(high / low, static_cast<double>(i) / static_cast<double>(points - 1));
    r[i] = k0_per_yr * std::pow(x[i], -k);
  }
  return HazardCurve(std::move(x), std::move(r), tail);
}

double RateResult::rate_below(double x) const {
  double sum = 0.0;
  for (const auto& p : pieces) {
    if (p.high < x || (p.high == p.low && p.low < x) || (p.high == x && p.high > p.low)) sum += p.rate_per_yr;
    else if (p.low < x && x < p.high) sum += p.rate_per_yr * std::log(x / p.low) / std::log(p.high / p.low);
  }
  return sum;
}

RateResult collapse_rate(const HazardCurve& h, const analysis::Lognormal& f, const std::vector<double>& breakpoints) {
  check_fragility(f);
  const auto& xs = h.intensities();
  const double low = xs.front(), last = xs.back();
  const double upper = h.tail() == Tail::kCutOff ? last : std::max(last, f.median * std::exp(kTailSigmas * f.beta));
  std::vector<double> edges(xs.begin(), xs.end());
  edges.push_back(upper);
  for (double b : breakpoints)
    if (b > low && b < upper) edges.push_back(b);
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());

  RateResult out;
  for (std::size_t p = 0; p + 1 < edges.size(); ++p) {
    // Each piece lies within one segment of the curve (its points are edges): λ is one power
    // law on it, with the exponent found at the piece's middle.
    const double a = edges[p], b = edges[p + 1];
    const double rate = segment_rate(f, a, b, h.rate_per_yr(a), h.slope(std::exp(0.5 * (std::log(a) + std::log(b)))));
    out.pieces.push_back({a, b, rate});
    if (a >= last) out.beyond_last_per_yr += rate;
  }
  out.evaluations = out.pieces.size();
  // What lies above `upper`: the cut-off's rate of exceeding the last point, counted there;
  // or the power law's rate beyond θ exp(8.5 β), where P(C | x) is 1 to 1e-17.
  const double mass = h.rate_per_yr(upper) * lognormal_cdf(f, upper);
  out.pieces.push_back({upper, upper, mass});
  out.beyond_last_per_yr += mass;
  for (const auto& p : out.pieces) out.lambda_per_yr += p.rate_per_yr;
  out.fragility_at_lowest = lognormal_cdf(f, low);
  return out;
}

RateResult collapse_rate_steps(const HazardCurve& h, const std::vector<double>& intensity,
                               const std::vector<double>& probability, const std::vector<double>& breakpoints) {
  if (intensity.size() != probability.size()) throw UserError("a step fragility needs a probability per intensity");
  for (std::size_t j = 0; j < intensity.size(); ++j) {
    if (!(intensity[j] > 0.0) || (j > 0 && !(intensity[j] > intensity[j - 1])))
      throw UserError("a step fragility's intensities must be positive and increase");
    if (!(probability[j] >= 0.0 && probability[j] <= 1.0))
      throw UserError("a step fragility's probabilities must lie in [0, 1]");
  }
  RateResult out;
  if (intensity.empty()) return out;
  const auto& xs = h.intensities();
  const double last = xs.back();
  // P is constant between consecutive edges: each piece is P(a) (λ(a) − λ(b)), and the
  // rate of exceeding the last edge is counted at it with the last P.
  std::vector<double> edges(intensity.begin(), intensity.end());
  edges.insert(edges.end(), xs.begin(), xs.end());
  for (double b : breakpoints)
    if (b > 0.0 && std::isfinite(b)) edges.push_back(b);
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  auto p_at = [&](double x) {
    const auto it = std::upper_bound(intensity.begin(), intensity.end(), x);
    return it == intensity.begin() ? 0.0 : probability[static_cast<std::size_t>(it - intensity.begin()) - 1];
  };
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const double a = edges[e], p = p_at(a);
    const bool final = e + 1 == edges.size();
    const double rate = p * (h.rate_per_yr(a) - (final ? 0.0 : h.rate_per_yr(edges[e + 1])));
    out.pieces.push_back({a, final ? a : edges[e + 1], rate});
    out.lambda_per_yr += rate;
    if (a >= last) out.beyond_last_per_yr += rate;
  }
  out.fragility_at_lowest = p_at(xs.front());
  return out;
}

void empirical_ida_steps(std::vector<double> collapses, std::size_t curves, std::vector<double>& intensity,
                         std::vector<double>& probability) {
  intensity.clear();
  probability.clear();
  if (curves == 0) return;
  std::sort(collapses.begin(), collapses.end());
  for (std::size_t i = 0; i < collapses.size(); ++i) {
    if (i + 1 < collapses.size() && collapses[i + 1] == collapses[i]) continue;
    intensity.push_back(collapses[i]);
    probability.push_back(static_cast<double>(i + 1) / static_cast<double>(curves));
  }
}

std::vector<double> deaggregate(const std::vector<RatePiece>& pieces, const std::vector<double>& edges) {
  if (edges.size() < 2) throw UserError("deaggregate needs at least two bin edges");
  std::vector<double> bins(edges.size() - 1, 0.0);
  for (const auto& p : pieces) {
    const double at = p.high > p.low ? std::sqrt(p.low * p.high) : p.low;
    const auto it = std::upper_bound(edges.begin(), edges.end(), at);
    const auto i = it == edges.begin() ? std::size_t{0} : static_cast<std::size_t>(it - edges.begin()) - 1;
    bins[std::min(i, bins.size() - 1)] += p.rate_per_yr;
  }
  return bins;
}

RateInterval rate_interval(const HazardCurve& h, const std::function<std::optional<analysis::Lognormal>(std::mt19937_64&)>& refit,
                           std::size_t resamples, double confidence, std::uint64_t seed) {
  std::mt19937_64 generator(seed);
  std::vector<double> rates;
  rates.reserve(resamples);
  for (std::size_t i = 0; i < resamples; ++i)
    if (const auto f = refit(generator); f && f->median > 0.0 && f->beta > 0.0 && std::isfinite(f->median) && std::isfinite(f->beta))
      rates.push_back(collapse_rate(h, *f).lambda_per_yr);
  RateInterval out{kNaN, kNaN, rates.size()};
  if (rates.size() < 2) return out;
  std::sort(rates.begin(), rates.end());
  auto at = [&](double q) {  // linear between order statistics
    const double position = q * static_cast<double>(rates.size() - 1);
    const auto k = static_cast<std::size_t>(position);
    const double w = position - static_cast<double>(k);
    return k + 1 < rates.size() ? rates[k] * (1.0 - w) + rates[k + 1] * w : rates[k];
  };
  out.low = at(0.5 * (1.0 - confidence));
  out.high = at(0.5 * (1.0 + confidence));
  return out;
}

double RateInterval::size_for(double lambda_per_yr, std::size_t size, double fraction) const {
  if (!(lambda_per_yr > 0.0) || !std::isfinite(low) || !std::isfinite(high) || size == 0) return kNaN;
  const double half = 0.5 * (high - low) / lambda_per_yr;
  return std::ceil(static_cast<double>(size) * (half / fraction) * (half / fraction));
}

double probability_in_years(double lambda_per_yr, double years) { return -std::expm1(-lambda_per_yr * years); }

double rate_for_probability(double probability, double years) { return -std::log1p(-probability) / years; }

analysis::Lognormal RiskTarget::fragility_at(double intensity) const {
  return {intensity * std::exp(-quantile(collapse_probability) * beta), beta};
}

void check(const RiskTarget& t) {
  if (!(t.target_probability > 0.0 && t.target_probability < 1.0))
    throw UserError("the target collapse probability must lie in (0, 1)");
  if (!(t.collapse_probability > 0.0 && t.collapse_probability < 1.0))
    throw UserError("the collapse probability at the risk-targeted intensity must lie in (0, 1)");
  if (!(t.years > 0.0) || !std::isfinite(t.years)) throw UserError("the target's years must be positive");
  if (!(t.beta > 0.0) || !std::isfinite(t.beta)) throw UserError("the generic fragility's beta must be positive");
}

double risk_targeted_intensity(const HazardCurve& h, const RiskTarget& t) {
  check(t);
  const double target = t.rate_per_yr();
  return bisect_log([&](double u) { return collapse_rate(h, t.fragility_at(std::exp(u))).lambda_per_yr - target; },
                    h.intensities().front() * 1e-6, h.intensities().back() * 1e6);
}

double hazard_factor_at_target(const HazardCurve& h, const analysis::Lognormal& f, const RiskTarget& t) {
  check(t);
  check_fragility(f);
  const double target = t.rate_per_yr();
  // λ_c grows with s: bisect on −ln s so that the function decreases.
  const double r = bisect_log(
      [&](double u) { return collapse_rate(h, {f.median * std::exp(u), f.beta}).lambda_per_yr - target; }, 1e-6, 1e6);
  return std::isfinite(r) ? 1.0 / r : r;
}

double cornell_collapse_rate(double k0, double k, const analysis::Lognormal& f) {
  return k0 * std::pow(f.median, -k) * std::exp(0.5 * k * k * f.beta * f.beta);
}

double cornell_risk_targeted_intensity(double k0, double k, const RiskTarget& t) {
  check(t);
  const double theta = std::pow(k0 * std::exp(0.5 * k * k * t.beta * t.beta) / t.rate_per_yr(), 1.0 / k);
  return theta * std::exp(quantile(t.collapse_probability) * t.beta);
}

}  // namespace pcrf::risk

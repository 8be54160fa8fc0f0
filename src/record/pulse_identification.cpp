// Velocity pulses of recorded ground motions (see pulse_identification.hpp).
#include "pcrf/record/pulse_identification.hpp"

#include <Eigen/Dense>
#include <unsupported/Eigen/FFT>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

#include "pcrf/units.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf {
namespace {

constexpr int kLevels = 10;               // the dyadic table of ψ: 2^-10 apart
constexpr int kPerUnit = 1 << kLevels;
constexpr int kSupport = 7;               // db4: φ and ψ vanish outside [0, 7]
constexpr int kTableSize = kSupport * kPerUnit + 1;

// Shahi & Baker (2014)'s scales: pseudo-periods 0.25 s to 15 s in 50 steps.
constexpr double kShortestPeriod_s = 0.25;
constexpr double kLongestPeriod_s = 15.0;
constexpr int kScaleSteps = 50;
constexpr int kWaveletsPerPulse = 10;     // wavelets summed into one pulse
constexpr double kSearchHalfWidth = 0.4;  // of the scale: where the later wavelets are centred
constexpr int kCandidates = 5;            // pulses tried in the two-component method
/// Largest record analysed [samples]: the transforms hold a few arrays of this length
/// (and FFTs of twice it); the longest PEER records have about 10⁵.
constexpr std::size_t kMaxSamples = std::size_t{1} << 22;

const std::vector<double>& db4_lowpass() {
  // Daubechies (1992), Table 6.1, N = 4 (normalised to Σ h = √2).
  static const std::vector<double> h{0.2303778133088964,  0.7148465705529154,  0.6308807679298587,
                                     -0.0279837694168599, -0.1870348117190931, 0.0308413818355607,
                                     0.0328830116668852,  -0.0105974017850690};
  return h;
}

/// φ at the integers 0…7: the eigenvector of the two-scale relation φ(k) = √2 Σ h_j φ(2k − j)
/// with eigenvalue 1, normalised to Σ φ(k) = 1 (the partition of unity).
std::vector<double> scaling_at_integers() {
  const auto& h = db4_lowpass();
  Eigen::Matrix<double, 7, 6> system = Eigen::Matrix<double, 7, 6>::Zero();
  for (int k = 1; k <= 6; ++k)
    for (int l = 1; l <= 6; ++l) {
      const int j = 2 * k - l;
      if (j >= 0 && j <= kSupport) system(k - 1, l - 1) = std::numbers::sqrt2 * h[static_cast<std::size_t>(j)];
    }
  system.topRows<6>() -= Eigen::Matrix<double, 6, 6>::Identity();
  system.row(6).setOnes();
  Eigen::Matrix<double, 7, 1> rhs = Eigen::Matrix<double, 7, 1>::Zero();
  rhs(6) = 1.0;
  const Eigen::Matrix<double, 6, 1> inner = system.colPivHouseholderQr().solve(rhs);
  std::vector<double> phi(kSupport + 1, 0.0);
  for (int k = 1; k <= 6; ++k) phi[static_cast<std::size_t>(k)] = inner(k - 1);
  return phi;
}

/// φ on the dyadic table, level by level from the integers (cascade algorithm).
std::vector<double> scaling_table() {
  const auto& h = db4_lowpass();
  std::vector<double> phi(kTableSize, 0.0);
  const std::vector<double> at_integers = scaling_at_integers();
  for (int k = 0; k <= kSupport; ++k) phi[static_cast<std::size_t>(k * kPerUnit)] = at_integers[static_cast<std::size_t>(k)];
  for (int level = 1; level <= kLevels; ++level) {
    const int step = kPerUnit >> level;
    for (int i = step; i < kTableSize - 1; i += 2 * step) {
      double value = 0.0;
      for (int j = 0; j <= kSupport; ++j) {
        const int at = 2 * i - j * kPerUnit;  // 2x − j, on the previous level's points
        if (at >= 0 && at < kTableSize) value += h[static_cast<std::size_t>(j)] * phi[static_cast<std::size_t>(at)];
      }
      phi[static_cast<std::size_t>(i)] = std::numbers::sqrt2 * value;
    }
  }
  return phi;
}

/// ψ(x) = √2 Σ g_k φ(2x − k), g_k = (−1)^k h_{7−k}, on the same table.
std::vector<double> wavelet_table() {
  const auto& h = db4_lowpass();
  const std::vector<double> phi = scaling_table();
  std::vector<double> psi(kTableSize, 0.0);
  for (int i = 0; i < kTableSize; ++i) {
    double value = 0.0;
    for (int k = 0; k <= kSupport; ++k) {
      const int at = 2 * i - k * kPerUnit;
      const double g = (k % 2 == 0 ? 1.0 : -1.0) * h[static_cast<std::size_t>(kSupport - k)];
      if (at >= 0 && at < kTableSize) value += g * phi[static_cast<std::size_t>(at)];
    }
    psi[static_cast<std::size_t>(i)] = std::numbers::sqrt2 * value;
  }
  return psi;
}

const std::vector<double>& psi_table() {
  static const std::vector<double> table = wavelet_table();
  return table;
}

/// |Ψ(f)|² of the tabulated ψ (trapezoidal Fourier integral).
double wavelet_power(double f_per_unit) {
  const auto& psi = psi_table();
  double re = 0.0, im = 0.0;
  for (int i = 0; i < kTableSize; ++i) {
    const double x = static_cast<double>(i) / kPerUnit, w = (i == 0 || i == kTableSize - 1) ? 0.5 : 1.0;
    re += w * psi[static_cast<std::size_t>(i)] * std::cos(2.0 * std::numbers::pi * f_per_unit * x);
    im += w * psi[static_cast<std::size_t>(i)] * std::sin(2.0 * std::numbers::pi * f_per_unit * x);
  }
  return re * re + im * im;
}

/// The centre frequency as MATLAB's centfrq defines it, which Baker (2007) and Shahi & Baker
/// (2014) use for T_p: the largest |Ψ(f)| among the frequencies k/7 of the Fourier series of ψ
/// over its support [0, 7] (5/7 Hz for db4; the continuous peak of |Ψ| lies at 0.698 Hz).
double peak_frequency() {
  int best = 1;
  for (int k = 2; k <= 4 * kSupport; ++k)
    if (wavelet_power(static_cast<double>(k) / kSupport) > wavelet_power(static_cast<double>(best) / kSupport)) best = k;
  return static_cast<double>(best) / kSupport;
}

// ---- the transform --------------------------------------------------------------------

/// ψ(k/a) for k = 0 … 7a: one wavelet of scale a sampled at the record's samples.
std::vector<double> wavelet_taps(int scale) {
  std::vector<double> taps(static_cast<std::size_t>(kSupport * scale + 1));
  for (std::size_t k = 0; k < taps.size(); ++k) taps[k] = Db4Wavelet::psi(static_cast<double>(k) / scale);
  return taps;
}
/// The sample where a wavelet of scale a starts, relative to its centre b.
int centre_offset(int scale) { return static_cast<int>(std::lround(0.5 * kSupport * scale)); }

std::size_t fft_length(std::size_t n) {
  std::size_t length = 1;
  while (length < n) length <<= 1;
  return length;
}

/// C(a, b) for every centre b of a record (zero outside it), by FFT convolution.
class Transform {
 public:
  Transform(const std::vector<double>& v, int largest_scale)
      : n_(v.size()), length_(fft_length(v.size() + static_cast<std::size_t>(kSupport * largest_scale) + 1)) {
    std::vector<double> padded(length_, 0.0);
    std::copy(v.begin(), v.end(), padded.begin());
    fft_.fwd(spectrum_, padded);
  }

  std::vector<double> row(int scale) {
    const std::vector<double> taps = wavelet_taps(scale);
    const std::size_t last = taps.size() - 1;
    std::vector<double> reversed(length_, 0.0);
    for (std::size_t k = 0; k <= last; ++k) reversed[k] = taps[last - k];
    std::vector<std::complex<double>> product;
    fft_.fwd(product, reversed);
    for (std::size_t i = 0; i < length_; ++i) product[i] *= spectrum_[i];
    std::vector<double> convolved;
    fft_.inv(convolved, product);
    // C(b) = Σ_k w_k v[b − c + k] = (v * reversed)[b + K − c].
    std::vector<double> coefs(n_);
    const double norm = 1.0 / std::sqrt(static_cast<double>(scale));
    const std::size_t shift = last - static_cast<std::size_t>(centre_offset(scale));
    for (std::size_t b = 0; b < n_; ++b) coefs[b] = norm * convolved[b + shift];
    return coefs;
  }

 private:
  std::size_t n_, length_;
  Eigen::FFT<double> fft_;
  std::vector<std::complex<double>> spectrum_;
};

/// C(a, b) at one centre, directly.
double coefficient(const std::vector<double>& v, int scale, std::size_t centre) {
  const long start = static_cast<long>(centre) - centre_offset(scale);
  double sum = 0.0;
  for (int k = 0; k <= kSupport * scale; ++k) {
    const long m = start + k;
    if (m >= 0 && m < static_cast<long>(v.size()))
      sum += v[static_cast<std::size_t>(m)] * Db4Wavelet::psi(static_cast<double>(k) / scale);
  }
  return sum / std::sqrt(static_cast<double>(scale));
}

/// Adds `coef` times the unit wavelet (a, b) to `series`.
void add_wavelet(std::vector<double>& series, int scale, std::size_t centre, double coef) {
  const long start = static_cast<long>(centre) - centre_offset(scale);
  const double amplitude = coef / std::sqrt(static_cast<double>(scale));
  for (int k = 0; k <= kSupport * scale; ++k) {
    const long m = start + k;
    if (m >= 0 && m < static_cast<long>(series.size()))
      series[static_cast<std::size_t>(m)] += amplitude * Db4Wavelet::psi(static_cast<double>(k) / scale);
  }
}

std::vector<int> analysis_scales(double dt_s) {
  const double per_second = Db4Wavelet::centre_frequency() / dt_s;  // scale per second of period
  const int smallest = std::max(1, static_cast<int>(std::floor(kShortestPeriod_s * per_second)));
  const int step = std::max(1, static_cast<int>(std::ceil((kLongestPeriod_s * per_second - smallest) / kScaleSteps)));
  std::vector<int> scales;
  for (int i = 0; i <= kScaleSteps; ++i) scales.push_back(smallest + i * step);
  return scales;
}

double period_of_scale_s(double scale, double dt_s) { return scale * dt_s / Db4Wavelet::centre_frequency(); }

// ---- a pulse and its measures --------------------------------------------------------

double peak_abs(const std::vector<double>& v) {
  double peak = 0.0;
  for (double x : v) peak = std::max(peak, std::fabs(x));
  return peak;
}
double sum_of_squares(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x * x;
  return sum;
}
/// Cumulative squared series as a fraction of its total, sample by sample.
std::vector<double> cumulative_fraction(const std::vector<double>& v) {
  std::vector<double> out(v.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = (sum += v[i] * v[i]);
  for (double& x : out) x = sum > 0.0 ? x / sum : 0.0;
  return out;
}
std::size_t first_reaching(const std::vector<double>& fraction, double level) {
  return static_cast<std::size_t>(std::find_if(fraction.begin(), fraction.end(), [&](double x) { return x >= level; }) -
                                  fraction.begin());
}

/// Baker (2007): the pulse's CSV reaches 10 % after the record's reaches 20 %.
bool late_baker(const std::vector<double>& v, const std::vector<double>& pulse) {
  return first_reaching(cumulative_fraction(pulse), 0.10) > first_reaching(cumulative_fraction(v), 0.20);
}
/// Shahi & Baker (2014): the record's CSV at the last sample where the pulse's is ≤ 5 %.
bool late_shahi(const std::vector<double>& v, const std::vector<double>& pulse) {
  const std::vector<double> p = cumulative_fraction(pulse), s = cumulative_fraction(v);
  std::size_t last = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (p[i] <= 0.05) last = i;
  return s[last] >= 0.17;
}

void classify(PulseCandidate& c, PulseMethod method) {
  if (method == PulseMethod::kBaker2007) {
    c.pulse_indicator = 10.0 / (1.0 + std::exp(-23.3 + 14.6 * c.pgv_ratio + 20.5 * c.energy_ratio));
    c.late = late_baker(c.velocity_cm_s, c.pulse_cm_s);
    c.pulse_like = c.pulse_indicator > 0.85 && !c.late && c.pgv_cm_s >= 30.0;
    return;
  }
  const double pc = 0.63 * c.pgv_ratio + 0.777 * c.energy_ratio;
  const double p = (pc - 1.208421) / 0.2462717, v = (c.pgv_cm_s - 11.58861) / 18.88015;
  c.pulse_indicator = -7.817 - 0.5679 * p * p - 0.1516 * v * v - 3.0253 * p - 1.7396 * v - 2.7156 * p * v;
  c.late = late_shahi(c.velocity_cm_s, c.pulse_cm_s);
  c.pulse_like = c.pulse_indicator > 0.0 && !c.late;
}

/// The scale, between the grid's neighbours of `row`, with the largest |C| at `centre`.
int refined_scale(const std::vector<double>& v, const std::vector<int>& scales, std::size_t row, std::size_t centre) {
  const int lo = scales[row == 0 ? 0 : row - 1], hi = scales[std::min(row + 1, scales.size() - 1)];
  int best = scales[row];
  double best_abs = -1.0;
  for (int a = lo; a <= hi; ++a)
    if (const double c = std::fabs(coefficient(v, a, centre)); c > best_abs) best = a, best_abs = c;
  return best;
}

/// Ten wavelets of the refined scale taken from v one after the other, centred near `centre`.
PulseCandidate extract(std::vector<double> v, double dt_s, const std::vector<int>& scales, std::size_t row,
                       std::size_t centre, PulseMethod method) {
  PulseCandidate c;
  const int scale = refined_scale(v, scales, row, centre);
  const std::size_t half = static_cast<std::size_t>(std::ceil(kSearchHalfWidth * scale));
  const std::size_t from = centre > half ? centre - half : 0, to = std::min(v.size() - 1, centre + half);
  std::vector<double> pulse(v.size(), 0.0), residual = v;
  for (int w = 0; w < kWaveletsPerPulse; ++w) {
    const std::vector<double> row_coefs = Transform(residual, scale).row(scale);
    std::size_t at = from;
    for (std::size_t b = from; b <= to; ++b)
      if (std::fabs(row_coefs[b]) > std::fabs(row_coefs[at])) at = b;
    add_wavelet(pulse, scale, at, row_coefs[at]);
    add_wavelet(residual, scale, at, -row_coefs[at]);
  }
  c.scale_samples = scale;
  c.period_s = period_of_scale_s(scale, dt_s);
  c.centre_s = static_cast<double>(centre) * dt_s;
  c.pgv_cm_s = peak_abs(v);
  c.pgv_ratio = c.pgv_cm_s > 0.0 ? peak_abs(residual) / c.pgv_cm_s : 1.0;
  const double energy = sum_of_squares(v);
  c.energy_ratio = energy > 0.0 ? sum_of_squares(residual) / energy : 1.0;
  c.velocity_cm_s = std::move(v);
  c.pulse_cm_s = std::move(pulse);
  c.residual_cm_s = std::move(residual);
  classify(c, method);
  return c;
}

/// For each centre b, the scale row with the largest C_E² + C_N² (the largest coefficient
/// over all orientations), that value, and the two coefficients there.
struct CentrePeaks {
  std::vector<double> value, c_east, c_north;
  std::vector<std::size_t> row;
};
CentrePeaks strongest_per_centre(const std::vector<double>& v_east, const std::vector<double>& v_north,
                                 const std::vector<int>& scales) {
  const std::size_t n = v_east.size();
  CentrePeaks p{std::vector<double>(n, -1.0), std::vector<double>(n, 0.0), std::vector<double>(n, 0.0),
                std::vector<std::size_t>(n, 0)};
  Transform t_east(v_east, scales.back()), t_north(v_north, scales.back());
  for (std::size_t r = 0; r < scales.size(); ++r) {
    const std::vector<double> ce = t_east.row(scales[r]), cn = t_north.row(scales[r]);
    for (std::size_t b = 0; b < n; ++b)
      if (const double m = ce[b] * ce[b] + cn[b] * cn[b]; m > p.value[b])
        p.value[b] = m, p.row[b] = r, p.c_east[b] = ce[b], p.c_north[b] = cn[b];
  }
  return p;
}

void check_length(const GroundMotion& record) {
  if (record.size() > kMaxSamples)
    throw UserError("record", record.name() + " has " + std::to_string(record.size()) +
                                  " samples; pulse identification reads at most " + std::to_string(kMaxSamples));
}

void decide(PulseClassification& result) {
  for (std::size_t i = 0; i < result.candidates.size(); ++i)
    if (result.candidates[i].pulse_like) {
      result.pulse_like = true;
      result.period_s = result.candidates[i].period_s;
      result.decided_by = i;
      return;
    }
}

}  // namespace

const std::vector<double>& Db4Wavelet::lowpass() { return db4_lowpass(); }

double Db4Wavelet::psi(double x) {
  if (!(x > 0.0 && x < kSupport)) return 0.0;
  const auto& table = psi_table();
  const double at = x * kPerUnit;
  const auto i = static_cast<std::size_t>(at);
  const double frac = at - static_cast<double>(i);
  return i + 1 < table.size() ? table[i] + frac * (table[i + 1] - table[i]) : table[i];
}

double Db4Wavelet::centre_frequency() {
  static const double fc = peak_frequency();
  return fc;
}

std::string to_string(PulseMethod method) {
  return method == PulseMethod::kBaker2007 ? "baker-2007" : "shahi-baker-2014";
}

std::vector<double> velocity_cm_s(const GroundMotion& record) {
  const auto& a = record.samples_m_s2();
  std::vector<double> v(a.size(), 0.0);
  for (std::size_t i = 1; i < a.size(); ++i) v[i] = v[i - 1] + 0.5 * (a[i - 1] + a[i]) * record.dt_s() * 100.0;
  return v;
}

PulseClassification classify_pulse(const GroundMotion& record) {
  check_length(record);
  PulseClassification result;
  result.method = PulseMethod::kBaker2007;
  result.dt_s = record.dt_s();
  const std::vector<double> v = velocity_cm_s(record);
  const std::vector<int> scales = analysis_scales(record.dt_s());
  Transform transform(v, scales.back());
  std::size_t best_row = 0, best_b = 0;
  double best = -1.0;
  for (std::size_t r = 0; r < scales.size(); ++r) {
    const std::vector<double> coefs = transform.row(scales[r]);
    for (std::size_t b = 0; b < coefs.size(); ++b)
      if (std::fabs(coefs[b]) > best) best = std::fabs(coefs[b]), best_row = r, best_b = b;
  }
  result.candidates.push_back(extract(v, record.dt_s(), scales, best_row, best_b, PulseMethod::kBaker2007));
  decide(result);
  return result;
}

PulseClassification classify_pulse(const HorizontalPair& pair) {
  const GroundMotion east = project(pair, 90.0), north = project(pair, 0.0);
  check_length(east);
  PulseClassification result;
  result.method = PulseMethod::kShahiBaker2014;
  result.dt_s = east.dt_s();
  const std::vector<double> v_east = velocity_cm_s(east), v_north = velocity_cm_s(north);
  const std::vector<int> scales = analysis_scales(east.dt_s());
  const std::size_t n = v_east.size();
  CentrePeaks peaks = strongest_per_centre(v_east, v_north, scales);
  std::vector<double>& peak = peaks.value;
  for (int k = 0; k < kCandidates; ++k) {
    const auto b = static_cast<std::size_t>(std::max_element(peak.begin(), peak.end()) - peak.begin());
    if (peak[b] < 0.0) break;  // every centre blocked
    double azimuth = std::atan2(peaks.c_east[b], peaks.c_north[b]) * 180.0 / std::numbers::pi;
    if (azimuth < 0.0) azimuth += 180.0;  // an orientation: φ and φ + 180° are one line
    const double s = std::sin(azimuth * std::numbers::pi / 180.0), co = std::cos(azimuth * std::numbers::pi / 180.0);
    std::vector<double> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = s * v_east[i] + co * v_north[i];
    PulseCandidate c = extract(std::move(v), east.dt_s(), scales, peaks.row[b], b, PulseMethod::kShahiBaker2014);
    c.azimuth_deg = azimuth;
    // Block the centres near this one so that the next candidate is another pulse.
    const double half = kSearchHalfWidth * scales[peaks.row[b]];
    for (std::size_t i = 0; i < n; ++i)
      if (std::fabs(static_cast<double>(i) - static_cast<double>(b)) < half) peak[i] = -1.0;
    result.candidates.push_back(std::move(c));
  }
  decide(result);
  return result;
}

}  // namespace pcrf

// [selection]: records per stripe (see stripe_selection.hpp and studies/README.md).
#include "study/stripe_selection.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

#include "pcrf/number_text.hpp"
#include "pcrf/record/horizontal_pair.hpp"
#include "pcrf/record/record_library.hpp"

namespace pcrf::study {
namespace {


using detail::Fields;

constexpr std::string_view kLibrary = "library", kTargets = "targets", kCount = "count", kKind = "kind",
                           kScaleMin = "scale_min", kScaleMax = "scale_max", kSeed = "seed", kTrials = "trials",
                           kLoops = "loops";

/// `path` opened to read, once it is known to be a regular file (following links: not a
/// folder, nor a FIFO that would block). \throws UserError naming `as_given`.
std::ifstream open_table(const std::filesystem::path& path, const std::string& as_given) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw UserError(as_given + ": no such file");
  if (!std::filesystem::is_regular_file(status)) throw UserError(as_given + ": not a regular file");
  std::ifstream in(path);
  if (!in) throw UserError(as_given + ": cannot open the file");
  return in;
}

/// The library kind the study's measure compares with: a component's Sa (sa_g) with
/// "component" entries, a pair's Sa RotD50 with "rotd50" entries.
std::string kind_of_measure(const Fields& f, const IntensitySpec& spec) {
  if (spec.measure == IntensityMeasure::kSa) return "component";
  if (spec.measure == IntensityMeasure::kSaRotD50) return "rotd50";
  f.fail(kLibrary, "a library holds spectra: the study's [intensity] measure must be " + to_string(IntensityMeasure::kSa) +
                       " (entries of kind component) or " + to_string(IntensityMeasure::kSaRotD50) + " (kind rotd50), not " +
                       to_string(spec.measure));
}

SelectionSettings read_settings(const Fields& f, const IntensitySpec& spec) {
  SelectionSettings w;
  w.kind = kind_of_measure(f, spec);
  if (const auto kind = f.text(kKind); kind && *kind != w.kind)
    f.fail(kKind, "the study's measure " + to_string(spec.measure) + " is compared with entries of kind " + w.kind +
                      ", not " + *kind + " (leave kind out)");
  if (spec.normalise != SetNormalisation::kNone)
    f.fail(kLibrary, "a selected set is scaled by the selection, not normalised: give no [intensity] normalise");
  const auto count = f.integer(kCount);
  if (!count) f.fail(kCount, "required: the number of records each stripe runs");
  if (*count < 2 || *count > 100000) f.fail(kCount, "must be 2 to 100000, got " + std::to_string(*count));
  w.count = static_cast<std::size_t>(*count);
  w.scale_min = f.number(kScaleMin).value_or(w.scale_min);
  w.scale_max = f.number(kScaleMax).value_or(w.scale_max);
  if (!(w.scale_min > 0.0) || !std::isfinite(w.scale_min)) f.fail(kScaleMin, "must be a positive number");
  if (!(w.scale_max >= w.scale_min) || !std::isfinite(w.scale_max))
    f.fail(kScaleMax, "must be a number at least scale_min (" + number_text(w.scale_min) + ")");
  if (const auto seed = f.integer(kSeed)) {
    if (*seed < 0) f.fail(kSeed, "must not be negative");
    w.seed = static_cast<std::uint64_t>(*seed);
  }
  if (const auto trials = f.integer(kTrials)) {
    if (*trials < 1 || *trials > 100000) f.fail(kTrials, "must be 1 to 100000");
    w.trials = static_cast<int>(*trials);
  }
  if (const auto loops = f.integer(kLoops)) {
    if (*loops < 0 || *loops > 1000) f.fail(kLoops, "must be 0 to 1000");
    w.loops = static_cast<int>(*loops);
  }
  return w;
}

SpectraTable read_library(const Fields& f, const std::filesystem::path& file, const std::string& as_given,
                          const IntensitySpec& spec) {
  SpectraTable table;
  try {
    auto in = open_table(file, as_given);
    table = read_spectra_csv(in, as_given);
  } catch (const UserError& e) {
    f.fail(kLibrary, e.message(Dialect::kStudy));
  }
  for (const auto& entry : table.entries)
    if (std::abs(entry.damping - spec.damping) > 1e-12)
      f.fail(kLibrary, as_given + ": entry " + entry.name + " is at damping " + number_text(entry.damping) +
                           ", the study's [intensity] damping is " + number_text(spec.damping) + ": compute the library with --damping " +
                           number_text(spec.damping));
  return table;
}

/// A stripe's target must be conditioned on the study's measure at the stripe's intensity:
/// σ = 0 at the measure's period T* (the selection then scales every record to exp μ(T*)),
/// and exp μ(T*) the intensity the hazard curve gives the return period (so that the cube's
/// `intensity`, which cube risk integrates against the curve, is what the records feel).
void check_conditioning(const Fields& f, const SelectionTarget& t, const IntensitySpec& spec, double stripe_intensity,
                        double return_period_yr, Study::StripeSelection::Stripe& stripe) {
  const auto at = std::find_if(t.periods_s.begin(), t.periods_s.end(),
                               [&](double p) { return std::abs(p - spec.period_s) <= 1e-9 * spec.period_s; });
  const std::string period = number_text(spec.period_s);
  if (at == t.periods_s.end())
    f.fail(kTargets, t.file + ": no row at period_s = " + period + " s, the period of the study's " + to_string(spec.measure) +
                         ": a stripe's target is conditioned on the study's measure (sigma_ln_sa = 0 there)");
  const auto j = static_cast<std::size_t>(at - t.periods_s.begin());
  const int line = j < t.row_lines.size() ? t.row_lines[j] : 0;
  const std::string where = file_line_text(Where{{}, t.file, line}) + ": ";
  if (t.sigma_ln_sa[j] != 0.0)
    f.fail(kTargets, where + "sigma_ln_sa: is " + number_text(t.sigma_ln_sa[j]) + " at period_s = " + period +
                         " s: a stripe's target is conditioned on the study's measure there (sigma_ln_sa = 0), so that "
                         "every record of the stripe has its intensity");
  const double level = std::exp(t.mean_ln_sa[j]);
  if (!(std::abs(level / stripe_intensity - 1.0) <= kConditioningRelativeTolerance))
    f.fail(kTargets, where + "mean_ln_sa: the target is conditioned on Sa(" + period + " s) = " + number_text(level) +
                         " g, but the stripe of return period " + number_text(return_period_yr) + " yr is at " +
                         selection_number_text(stripe_intensity) + " g on the hazard curve: make the target for that level (within " +
                         number_text(100.0 * kConditioningRelativeTolerance) + " %)");
  stripe.conditioning_sa_g = level;
  stripe.conditioning_line = line;
}

/// The component part of a record file's name, after its last '_' ("RRS228" of
/// "RSN1063_NORTHR_RRS228.AT2"), as pcrf record spectra reads it.
std::string component_of_file(const std::string& file) {
  const std::string stem = std::filesystem::path(file).stem().string();
  const auto cut = stem.rfind('_');
  return cut == std::string::npos ? stem : stem.substr(cut + 1);
}

/// A library entry as a record of the study: its file (a pair: h1 and h2), relative paths
/// resolved against the library table's folder.
RecordSource record_of(const LibraryEntry& e, const std::filesystem::path& library_dir, const Where& where) {
  auto spec = [&](const std::string& path) {
    RecordFileSpec f;
    f.path = std::filesystem::path(path).is_absolute() ? std::filesystem::path(path) : library_dir / path;
    f.format = guess_record_format(f.path);
    return f;
  };
  RecordSource source;
  source.name = e.name;
  source.file = spec(e.file);
  source.declared_at = where;
  if (e.file_h2.empty()) return source;
  // A pair at the azimuths its RotD50 was computed with: those its file names state (pcrf
  // record spectra pairs by them), which some headers do not (Chi-Chi's CHY101-E).
  source.h2 = spec(e.file_h2);
  auto azimuth = [](const std::string& file) { return azimuth_of_component(component_of_file(file)); };
  source.az1_deg = azimuth(e.file);
  source.az2_deg = azimuth(e.file_h2);
  return source;
}

/// The targets' files: the list as given, or one file name with {return_period_yr} in it, that
/// placeholder replaced by each return period as the study gives it ("t{return_period_yr}.csv":
/// t475.csv, t2475.csv, …).
std::vector<std::string> target_files(const Fields& f, const std::vector<double>& periods_yr) {
  auto targets = f.texts(kTargets);
  static const std::string placeholder = "{return_period_yr}";
  if (targets.size() != 1 || targets.front().find(placeholder) == std::string::npos) return targets;
  const std::string pattern = targets.front();
  targets.clear();
  for (double t : periods_yr) {
    std::string name = pattern;
    for (auto at = name.find(placeholder); at != std::string::npos; at = name.find(placeholder, at))
      name.replace(at, placeholder.size(), number_text(t));
    targets.push_back(std::move(name));
  }
  return targets;
}

}  // namespace

std::string selection_number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

void read_selection(const Fields& top, Study& s) {
  const auto* table = top.subtable(kSelectionTable);
  if (table == nullptr) return;
  const Fields f(*table, {std::string(kSelectionTable)}, s.file,
                 {kLibrary, kTargets, kCount, kKind, kScaleMin, kScaleMax, kSeed, kTrials, kLoops});
  if (!s.hazard_stripes || !s.intensity)
    f.fail(kLibrary, "selects records per stripe of hazard-consistent stripes: it needs [intensity] hazard = \"FILE\" "
                     "and return_periods_yr = [...]");
  const IntensitySpec& spec = *s.intensity;
  if (!f.has(kLibrary)) f.fail(kLibrary, "required: the spectra table of the records to select from (pcrf record spectra)");
  if (!f.has(kTargets)) f.fail(kTargets, "required: one target spectrum CSV per return period, in return_periods_yr's order");
  if (s.incidence_reference != "north")
    f.fail(kLibrary, "a library's records carry no fault strike: [axes] incidence = \"" + s.incidence_reference +
                         "\" is not available with [selection]");
  Study::StripeSelection sel;
  sel.settings = read_settings(f, spec);
  sel.library = *f.text(kLibrary);
  sel.library_file = s.base_dir / sel.library;
  sel.declared_at = f.where(kLibrary);
  const SpectraTable library = read_library(f, sel.library_file, sel.library, spec);
  const auto& periods_yr = s.hazard_stripes->return_periods_yr;
  const auto targets = target_files(f, periods_yr);
  if (targets.size() != periods_yr.size())
    f.fail(kTargets, std::to_string(targets.size()) + " target(s) for " + std::to_string(periods_yr.size()) +
                         " return periods in return_periods_yr (" + file_line_text(s.where("intensity.return_periods_yr")) +
                         "): give one per return period, in its order");
  const auto library_dir = sel.library_file.parent_path();
  std::map<std::string, std::size_t> record_of_name;
  for (std::size_t k = 0; k < targets.size(); ++k) {
    Study::StripeSelection::Stripe stripe;
    stripe.target = targets[k];
    SelectionTarget target;
    try {
      auto in = open_table(s.base_dir / targets[k], targets[k]);
      target = read_selection_target(in, targets[k]);
    } catch (const UserError& e) {
      f.fail(kTargets, e.message(Dialect::kStudy));
    }
    check_conditioning(f, target, spec, s.levels.at(k), periods_yr[k], stripe);
    try {
      stripe.fit = select_records(target, library, sel.settings);
    } catch (const UserError& e) {
      const auto& keys = e.where().keys;
      const std::string stripe_text = "stripe of " + number_text(periods_yr[k]) + " yr (" + targets[k] + "): ";
      if (e.where().file.empty() && keys.size() == 1 && f.has(kCount))  // a setting the selection refuses
        f.fail(keys.front() == "count" || !f.has(keys.front()) ? kCount : std::string_view(keys.front()),
               stripe_text + e.problem(Dialect::kStudy));
      f.fail(kTargets, stripe_text + e.message(Dialect::kStudy));
    }
    for (const auto& chosen : stripe.fit.records) {
      const LibraryEntry& entry = library.entries.at(chosen.entry);
      auto [it, added] = record_of_name.try_emplace(entry.name, s.records.size());
      if (added) s.records.push_back(record_of(entry, library_dir, sel.declared_at));
      stripe.records.push_back(it->second);
      stripe.scales.push_back(chosen.scale);
    }
    sel.stripes.push_back(std::move(stripe));
  }
  s.given_at["selection.library"] = f.where(kLibrary);
  s.given_at["selection.targets"] = f.where(kTargets);
  s.selection = std::move(sel);
}

}  // namespace pcrf::study

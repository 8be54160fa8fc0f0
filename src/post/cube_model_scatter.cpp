// Modelling uncertainty measured over a cube's sampled frames (see cube_model_scatter.hpp).
#include "pcrf/post/cube_model_scatter.hpp"

#include <cmath>
#include <cstdio>
#include <ostream>

#include "pcrf/analysis/p695.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"

namespace pcrf::post {
namespace {

/// The fields every command shows, in order, with what each holds.
struct ModelField {
  const char* name;
  double (*get)(const ModelScatter&);
  bool count = false;  ///< a whole number
};
const std::vector<ModelField>& common_fields() {
  static const std::vector<ModelField> fields{
      {"model_frames", [](const ModelScatter& m) { return static_cast<double>(m.dispersion.frames); }, true},
      {"model_unfitted", [](const ModelScatter& m) { return static_cast<double>(m.unfitted); }, true},
      {"model_pooled_median", [](const ModelScatter& m) { return m.dispersion.pooled.median; }},
      {"model_beta_pooled", [](const ModelScatter& m) { return m.dispersion.pooled.beta; }},
      {"model_beta_rtr", [](const ModelScatter& m) { return m.dispersion.beta_rtr; }},
      {"model_beta_model", [](const ModelScatter& m) { return m.dispersion.beta_model; }},
      {"model_beta_medians", [](const ModelScatter& m) { return m.dispersion.beta_medians; }},
      {"model_beta_mdl_rated", [](const ModelScatter& m) { return m.beta_mdl_rated; }},
      {"model_beta_total_measured", [](const ModelScatter& m) { return m.beta_total_measured; }},
      {"model_beta_total_rated", [](const ModelScatter& m) { return m.beta_total_rated; }},
  };
  return fields;
}

}  // namespace

bool frames_are_sampled(const cube::CubeReader& cube) {
  const std::string plan = cube.layout().text_attribute(schema::kPlan);
  return plan == "lhs" || plan == "sobol" || plan == "saltelli";
}

std::optional<analysis::Lognormal> pooled_fit(const std::vector<FrameFragility>& frames) {
  if (frames.empty()) return std::nullopt;
  if (frames.front().stripes.empty()) {
    std::vector<double> observed, censored;
    for (const auto& f : frames) {
      observed.insert(observed.end(), f.collapse_intensities.begin(), f.collapse_intensities.end());
      censored.insert(censored.end(), f.censored_intensities.begin(), f.censored_intensities.end());
      censored.insert(censored.end(), f.unresolved_intensities.begin(), f.unresolved_intensities.end());
    }
    return analysis::fit_censored(observed, censored);
  }
  std::vector<analysis::Stripe> pooled = frames.front().stripes;
  for (auto& s : pooled) s.trials = s.collapses = 0.0;
  for (const auto& f : frames)
    for (std::size_t l = 0; l < pooled.size() && l < f.stripes.size(); ++l) {
      pooled[l].trials += f.stripes[l].trials;
      pooled[l].collapses += f.stripes[l].collapses;
    }
  return analysis::fit_stripes(pooled);
}

std::optional<ModelScatter> model_scatter(const cube::CubeReader& cube, const std::vector<FrameFragility>& frames,
                                          char design_rating, char test_rating, char model_rating) {
  if (!frames_are_sampled(cube)) return std::nullopt;
  std::vector<analysis::Lognormal> fits;
  for (const auto& f : frames)
    if (f.fit) fits.push_back(*f.fit);
  const auto pooled = pooled_fit(frames);
  if (fits.size() < 2 || !pooled) return std::nullopt;
  ModelScatter m;
  m.dispersion = analysis::measured_dispersion(*pooled, fits);
  m.unfitted = frames.size() - fits.size();
  const double dr = p695::rating_beta(design_rating), td = p695::rating_beta(test_rating);
  m.beta_mdl_rated = p695::rating_beta(model_rating);
  m.beta_total_measured = m.dispersion.total_measured(dr, td);
  m.beta_total_rated = m.dispersion.total_rated(dr, td, m.beta_mdl_rated);
  return m;
}

std::vector<std::pair<std::string, Cell>> model_fields(const std::optional<ModelScatter>& scatter,
                                                       std::vector<std::pair<std::string, Cell>> extra) {
  std::vector<std::pair<std::string, Cell>> fields;
  for (const auto& f : common_fields()) {
    Cell value;
    if (scatter) {
      const double v = f.get(*scatter);
      value = f.count ? Cell{static_cast<std::int64_t>(v)} : number_or_missing(v);
    }
    fields.emplace_back(f.name, value);
  }
  for (auto& e : extra) fields.push_back(std::move(e));
  return fields;
}

std::string model_field_names() {
  std::string names;
  for (const auto& f : common_fields()) names += (names.empty() ? "" : ", ") + std::string(f.name);
  return names + " (modelling uncertainty measured over sampled frames; missing otherwise, docs/risk.md)";
}

std::string model_scatter_warning(const std::optional<ModelScatter>& scatter) {
  if (!scatter || scatter->unfitted == 0) return "";
  return std::to_string(scatter->unfitted) + " sampled frames have no fit of their own (no collapse, or all collapsed): "
         "beta_rtr and beta_medians leave them out, the pooled fit keeps their data";
}

void print_model_scatter(const Report& report, const std::string& units, std::ostream& out) {
  const Cell frames = report.field("model_frames");
  if (std::holds_alternative<std::monostate>(frames)) return;
  auto number = [&](const char* name) {
    const Cell c = report.field(name);
    char text[32];
    if (const double* d = std::get_if<double>(&c)) std::snprintf(text, sizeof text, "%.3g", *d);
    else std::snprintf(text, sizeof text, "none");
    return std::string(text);
  };
  out << "modelling uncertainty measured over " << std::get<std::int64_t>(frames) << " sampled frames: pooled median "
      << number("model_pooled_median") << " " << units << ", beta " << number("model_beta_pooled") << " = sqrt(beta_rtr "
      << number("model_beta_rtr") << "^2 + beta_model " << number("model_beta_model") << "^2) (frames' medians scatter "
      << number("model_beta_medians") << "); the rating's beta_MDL " << number("model_beta_mdl_rated") << "\n"
      << "beta_TOT with the modelling term measured " << number("model_beta_total_measured") << ", rated "
      << number("model_beta_total_rated") << " (design and test-data ratings in both)\n";
}

}  // namespace pcrf::post

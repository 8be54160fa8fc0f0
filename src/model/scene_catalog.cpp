// The scenes by name and their parameter tables (see scene_catalog.hpp).
#include "pcrf/model/scene_catalog.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "pcrf/model/equation_of_motion.hpp"
#include "pcrf/model/parameters.hpp"
#include "pcrf/model/rigid_rocker.hpp"
#include "pcrf/number_text.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf {
namespace {

constexpr double kAbsent = std::numeric_limits<double>::quiet_NaN();

std::string finite_problem(double v) { return std::isfinite(v) ? "" : "must be a finite number"; }
std::string positive(double v) { return !finite_problem(v).empty() ? finite_problem(v) : v > 0.0 ? "" : "must be positive"; }
std::string non_negative(double v) {
  return !finite_problem(v).empty() ? finite_problem(v) : v >= 0.0 ? "" : "must not be negative";
}
std::string unit_open(double v) {
  return !finite_problem(v).empty() ? finite_problem(v) : v > 0.0 && v < 1.0 ? "" : "must be between 0 and 1 (exclusive)";
}
std::string slenderness(double v) {
  return !finite_problem(v).empty() ? finite_problem(v)
         : v > 0.0 && v < 0.5 * std::numbers::pi
             ? ""
             : "must lie between 0 and pi/2 (a column wider than tall is not a rocking column)";
}
std::string unit_closed(double v) {
  return !finite_problem(v).empty() ? finite_problem(v) : v >= 0.0 && v <= 1.0 ? "" : "must lie in [0, 1]";
}

std::string (*problem_of(ParameterDomain domain))(double) {
  switch (domain) {
    case ParameterDomain::kPositive: return positive;
    case ParameterDomain::kNonNegative: return non_negative;
    case ParameterDomain::kUnitOpen: return unit_open;
  }
  return finite_problem;
}

// ---- pcrf: the eight dimensionless parameters, then the size ----------------------------

std::vector<SceneParameter> pcrf_parameters() {
  std::vector<SceneParameter> table;
  const FrameParameters basic{};
  for (const auto& info : all_parameters())
    table.push_back({info.name, info.long_name, info.units, basic.*info.member, true, problem_of(info.domain)});
  for (const auto& info : size_parameters())
    table.push_back({info.name, info.long_name, info.units, basic.*info.member, false, problem_of(info.domain)});
  for (auto& p : table)
    if (p.name == "m_c_kg") p.aliases = {"--mc"};
  return table;
}

std::unique_ptr<Scene> make_pcrf(std::span<const double> values) {
  FrameParameters p;
  std::size_t k = 0;
  for (const auto& info : all_parameters()) p.*info.member = values[k++];
  for (const auto& info : size_parameters()) p.*info.member = values[k++];
  return std::make_unique<EquationOfMotion>(make_frame(p));
}

// ---- the rockers: slenderness, size or frequency parameter, restitution[, γ] -------------

enum RockerSlot : std::size_t { kAlpha, kSize, kFrequency, kRestitution, kGamma };

std::vector<SceneParameter> rocker_table(bool with_beam) {
  const RockerParameters d{};
  std::vector<SceneParameter> table{
      {"slenderness_rad", "slenderness alpha of the columns, tan alpha = b/h", "rad", d.slenderness_rad, true, slenderness},
      {"size_m", "half-diagonal R of the columns", "m", d.size_m, true, positive},
      {"frequency_parameter_rad_s", "frequency parameter p = sqrt(3g/4R) (p-hat of a rocking frame), instead of size_m",
       "rad/s", kAbsent, true, positive},
      // Not "restitution": that is the metric of the r a case used, whichever way it came.
      {"given_restitution", "coefficient of restitution given instead of the one from angular momentum", "1", kAbsent,
       true, unit_closed, {"--restitution"}},
  };
  if (with_beam)
    table.push_back({"beam_mass_ratio", "beam to columns mass ratio gamma", "1", d.beam_mass_ratio, true, non_negative});
  return table;
}

std::unique_ptr<Scene> make_rocker(std::span<const double> values) {
  RockerParameters p;
  p.slenderness_rad = values[kAlpha];
  p.beam_mass_ratio = values.size() > kGamma ? values[kGamma] : 0.0;
  p.size_m = values[kSize];
  if (!std::isnan(values[kFrequency])) {
    // p̂² = (3g/4R)(1 + 2γ)/(1 + 3γ), the block's p² = 3g/4R at γ = 0.
    const double w = values[kFrequency], gamma = p.beam_mass_ratio;
    if (!(w > 0.0)) throw UserError("frequency_parameter_rad_s", "must be positive");
    p.size_m = 3.0 * p.gravity_m_s2 * (1.0 + 2.0 * gamma) / (4.0 * w * w * (1.0 + 3.0 * gamma));
  }
  if (!std::isnan(values[kRestitution])) p.restitution = values[kRestitution];
  return std::make_unique<RigidRocker>(p);
}

}  // namespace

std::size_t SceneModel::index(std::string_view key) const {
  for (std::size_t k = 0; k < parameters.size(); ++k)
    if (parameters[k].name == key) return k;
  return std::string::npos;
}

ScenePoint SceneModel::defaults() const {
  ScenePoint point;
  for (const auto& p : parameters) point.push_back(p.default_value);
  return point;
}

std::string SceneModel::keys_text() const {
  std::string text;
  for (const auto& p : parameters) text += (text.empty() ? "" : ", ") + std::string(p.name);
  return text;
}

const std::vector<SceneModel>& scene_models() {
  static const std::vector<SceneModel> models{
      {"pcrf", "the prestressed rocking frame (Zhao & Su 2021)", pcrf_parameters(), make_pcrf, {}},
      {"block", "Housner's rigid block (1963)", rocker_table(false), make_rocker, {"size_m", "frequency_parameter_rad_s"}},
      {"rocking-frame", "columns capped by a freely supported beam (Makris & Vassiliou 2013)", rocker_table(true),
       make_rocker, {"size_m", "frequency_parameter_rad_s"}},
  };
  return models;
}

const SceneModel& scene_model(std::string_view name) {
  const auto& models = scene_models();
  for (const auto& m : models)
    if (m.name == name) return m;
  std::string expected;
  for (std::size_t i = 0; i < models.size(); ++i)
    expected += (i == 0 ? "" : i + 1 == models.size() ? " or " : ", ") + std::string(models[i].name);
  throw UserError("model", "unknown scene '" + std::string(name) + "' (expected " + expected + ")");
}

std::string models_taking(std::string_view key) {
  std::vector<std::string> names;
  for (const auto& m : scene_models())
    if (m.index(key) != std::string::npos) names.push_back("\"" + std::string(m.name) + "\"");
  if (names.empty()) return "";
  std::string text = "model ";
  for (std::size_t i = 0; i < names.size(); ++i) text += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  return text;
}

bool same_point(const ScenePoint& a, const ScenePoint& b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](double x, double y) {
           return x == y || (std::isnan(x) && std::isnan(y));
         });
}

double SceneSpec::value(std::string_view key) const {
  const std::size_t k = model->index(key);
  return k == std::string::npos ? kAbsent : values[k];
}

bool same_scene(const SceneSpec& a, const SceneSpec& b) { return a.model == b.model && same_point(a.values, b.values); }

ScenePoint scene_point(const SceneModel& model, const std::map<std::string, double, std::less<>>& values) {
  ScenePoint point = model.defaults();
  for (const auto& [key, value] : values) {
    const std::size_t k = model.index(key);
    if (k == std::string::npos) {
      const auto owners = models_taking(key);
      if (!owners.empty())
        throw UserError(key, "does not apply to model \"" + std::string(model.name) + "\" (it is a parameter of " + owners + ")");
      std::vector<std::string> keys;
      for (const auto& p : model.parameters) keys.emplace_back(p.name);
      std::string list;
      for (std::size_t i = 0; i < keys.size(); ++i) list += i == 0 ? "{}" : ", {}";
      throw UserError(key, "does not apply to model \"" + std::string(model.name) + "\" (its parameters: " + list + ")",
                      keys);
    }
    if (const auto problem = model.parameters[k].problem(value); !problem.empty())
      throw UserError(key, problem + ", got " + number_text(value));
    point[k] = value;
  }
  std::size_t given = 0;
  for (auto key : model.exclusive) given += values.count(key);
  if (given > 1) {
    std::string list;
    std::vector<std::string> keys;
    for (auto key : model.exclusive) {
      list += keys.empty() ? "{}" : " or {}";
      keys.emplace_back(key);
    }
    throw UserError(Where{}, "give either " + list + ", not both", keys);
  }
  if (given == 1)
    for (auto key : model.exclusive)
      if (values.count(key) == 0) point[model.index(key)] = kAbsent;
  return point;
}

}  // namespace pcrf

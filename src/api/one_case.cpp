// One case as the command line and the Python module solve it (see one_case.hpp).
#include "pcrf/api/one_case.hpp"

#include "pcrf/user_error.hpp"
#include "pcrf/solver/rocking_solver.hpp"

namespace pcrf::api {

double scale_factor(const Scaling& scaling, const StationRecord& station, std::optional<double> incidence_deg) {
  const GroundMotion& motion = station.h1;
  if (!scaling.intensity) {
    if (!scaling.measure.empty())
      throw UserError(Where{}, "{}, {} and {} go with {} VALUE", {"measure", "period_s", "damping", "intensity"});
    return scaling.scale;
  }
  if (scaling.scale_given) throw UserError(Where{}, "give either {} or {}, not both", {"scale", "intensity"});
  if (!(*scaling.intensity > 0.0)) throw UserError("intensity", "must be positive");
  const IntensitySpec spec = resolve_settings(intensity_settings(), scaling.measure);
  if (const auto problem = intensity_spec_problem(spec); !problem.empty()) throw UserError("period_s", problem);
  if (spec.normalise != SetNormalisation::kNone)
    throw UserError("normalise", "applies to a study's record set, not to one record: scale it with {}", {"scale"});
  if (component_measure(spec.measure) == IntensityMeasure::kSa)
    if (const auto problem = sa_period_problem(spec.period_s, motion.dt_s()); !problem.empty())
      throw UserError("period_s", problem + " (" + motion.name() + ")");
  if (const auto problem = measures_problem(motion); !problem.empty()) throw UserError(motion.name() + ": " + problem);
  const double im = station_intensity(station, incidence_deg, spec);
  if (!(im > 0.0)) throw UserError(motion.name() + ": its " + to_string(spec.measure) + " is 0: it cannot be scaled");
  return intensity_scale_factor(*scaling.intensity, im);
}

ScaledExcitation scaled_excitation(const StationRecord& station, std::optional<double> incidence_deg,
                                   const Scaling& scaling) {
  return frame_excitation(station, incidence_deg, scale_factor(scaling, station, incidence_deg));
}

CaseResult solve_one_case(std::unique_ptr<Scene> scene, const PhysicsOptions& physics, const Excitation& excitation,
                          const SolverSettings& solver, double history_dt_s, const HistorySink& sink) {
  OutputRequest request;
  request.history_dt_s = history_dt_s;
  const auto prepared = prepare_scene(std::move(scene), physics);
  return solve_case(*prepared, excitation, solver, request, sink);
}

JsonObject case_json(double scale_factor, const CaseResult& result, const PhysicsOptions& physics) {
  JsonObject json;
  json.number("scale_factor", scale_factor);
  add_to_json(json, result);
  json.number("rest_rise_rad", physics.rest_rise_rad);
  return json;
}

std::string verdict_note(const CaseResult& result, const PhysicsOptions& physics) {
  const std::string status(status_name(result.status));
  if (is_unresolved(result.status)) {
    std::string advice = tail_advice(physics.tail_s);
    advice.replace(advice.find("resolves them"), 13, "resolves it");
    return "the frame was still rocking when the case ended (" + status + "): no verdict, neither safe nor collapsed; " +
           advice;
  }
  if (is_outside_model(result.status))
    return "the case ended " + status + ": the model no longer applies, so it says nothing of the frame, safe or not";
  return {};
}

}  // namespace pcrf::api

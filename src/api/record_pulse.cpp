// Pulse identification of a station's record as JSON (see record_pulse.hpp).
#include "pcrf/api/record_pulse.hpp"

namespace pcrf::api {

namespace {

JsonObject candidate_json(const PulseCandidate& c, PulseMethod method) {
  JsonObject o;
  if (method == PulseMethod::kShahiBaker2014) o.number("azimuth_deg", c.azimuth_deg);
  o.boolean("pulse_like", c.pulse_like)
      .number("period_s", c.period_s)
      .number("scale_samples", c.scale_samples)
      .number("centre_s", c.centre_s)
      .number("pgv_cm_s", c.pgv_cm_s)
      .number("pgv_ratio", c.pgv_ratio)
      .number("energy_ratio", c.energy_ratio)
      .number("pulse_indicator", c.pulse_indicator)
      .boolean("late", c.late);
  return o;
}

}  // namespace

JsonObject pulse_json(const PulseClassification& result, bool series) {
  JsonObject o;
  o.text("method", to_string(result.method))
      .boolean("pulse_like", result.pulse_like)
      .number("period_s", result.pulse_like ? result.period_s : 0.0)
      .number("dt_s", result.dt_s)
      .integer("decided_by", static_cast<long long>(result.decided_by));
  std::vector<JsonObject> candidates;
  for (const auto& c : result.candidates) candidates.push_back(candidate_json(c, result.method));
  o.objects("candidates", candidates);
  if (series && !result.candidates.empty()) {
    const PulseCandidate& c = result.candidates[result.decided_by];
    o.numbers("velocity_cm_s", c.velocity_cm_s).numbers("pulse_cm_s", c.pulse_cm_s).numbers("residual_cm_s", c.residual_cm_s);
  }
  return o;
}

}  // namespace pcrf::api

// A station's intensity measures as one JSON object (see record_measures.hpp).
#include "pcrf/api/record_measures.hpp"

#include <string>
#include <utility>

#include "pcrf/user_error.hpp"
#include "pcrf/record/horizontal_pair.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/record/rotd.hpp"

namespace pcrf::api {
namespace {

/// The measures of one component read from `file` (empty: a synthetic motion), and what its
/// file says about itself.
/// \throws UserError naming the file (else the motion) for values that overflow the measures
/// or a period below 2·dt.
JsonObject measures(const GroundMotion& motion, const std::string& file, const RecordMetadata& meta,
                    const MeasureRequest& args) {
  if (const auto problem = measures_problem(motion); !problem.empty())
    throw file.empty() ? UserError(motion.name() + ": " + problem) : UserError(Where{{}, file, 0}, problem);
  for (double t : args.periods_s)
    if (const auto problem = sa_period_problem(t, motion.dt_s()); !problem.empty())
      throw UserError("periods_s", problem + " (" + (file.empty() ? motion.name() : file) + ")");
  const auto peak = peak_acceleration(motion);
  std::vector<double> sa_g;
  for (double t : args.periods_s) sa_g.push_back(spectral_acceleration_g(motion, t, args.damping));
  JsonObject json;
  json.text("name", motion.name())
      .integer("npts", static_cast<long long>(motion.size()))
      .number("dt_s", motion.dt_s())
      .number("duration_s", motion.duration_s())
      .number("pga_g", peak.pga_g)
      .number("t_pga_s", peak.t_pga_s)
      .number("pgv_m_s", peak_velocity_m_s(motion))
      .number("pgd_m", peak_displacement_m(motion))
      .number("arias_intensity_m_s", arias_intensity_m_s(motion))
      .number("significant_duration_s", significant_duration_s(motion))
      .number("damping", args.damping)
      .numbers("periods_s", args.periods_s)
      .numbers("sa_g", sa_g);
  for (const auto& [key, value] : {std::pair{"title", meta.title}, std::pair{"event", meta.event},
                                   std::pair{"station", meta.station}, std::pair{"component", meta.component},
                                   std::pair{"rsn", meta.rsn}})
    if (!value.empty()) json.text(key, value);
  return json;
}

/// RotD50 and RotD100 of PGA, PGV and Sa at each period, added to `json` with the
/// measure names a study uses ("pga_rotd50_g", …) and the azimuths used.
void add_rotd(JsonObject& json, const HorizontalPair& pair, const MeasureRequest& args) {
  auto both = [&](IntensityMeasure m, double period_s) { return rotd(pair, {m, period_s, args.damping}); };
  const RotD pga = both(IntensityMeasure::kPga, 0.0), pgv = both(IntensityMeasure::kPgv, 0.0);
  std::vector<double> sa50, sa100;
  for (double t : args.periods_s) {
    const RotD sa = both(IntensityMeasure::kSa, t);
    sa50.push_back(sa.rotd50);
    sa100.push_back(sa.rotd100);
  }
  json.numbers("azimuths_deg", {pair.az1_deg, pair.az2_deg})
      .number("pga_rotd50_g", pga.rotd50)
      .number("pga_rotd100_g", pga.rotd100)
      .number("pgv_rotd50_m_s", pgv.rotd50)
      .number("pgv_rotd100_m_s", pgv.rotd100)
      .numbers("sa_rotd50_g", sa50)
      .numbers("sa_rotd100_g", sa100);
}

/// The metadata of a component file (its header's title, component, …); none for a synthetic.
RecordMetadata metadata_of_file(const RecordInput& input, const std::string& file) {
  if (file.empty()) return {};
  return record_metadata(input.component(file).spec());
}

}  // namespace

void check_measure_request(const MeasureRequest& request) {
  if (!(request.damping >= 0.0 && request.damping < 1.0)) throw UserError("damping", "must be in [0, 1)");
  for (double t : request.periods_s)
    if (const auto problem = sa_period_problem(t, 0.0); !problem.empty()) throw UserError("periods_s", problem);
}

JsonObject record_measures(const StationRecord& station, const RecordInput& input, const MeasureRequest& request) {
  JsonObject json = measures(station.h1, input.file, metadata_of_file(input, input.file), request);
  if (station.h2) {
    if (!station.az1_deg || !station.az2_deg)
      throw UserError(Where{}, "the azimuth of '" + (station.az1_deg ? station.h2->name() : station.h1.name()) +
                       "' is not stated by its header: give {}", {station.az1_deg ? "h2_azimuth_deg" : "azimuth_deg"});
    add_rotd(json, HorizontalPair{station.h1, *station.az1_deg, *station.h2, *station.az2_deg}, request);
  }
  const auto members = component_members<StationRecord>();
  for (std::size_t i = 0; i < kComponentCount; ++i)
    if (const auto& motion = station.*members[i])
      json.object(kStationComponents[i].measures_key,
                  measures(*motion, input.component_files[i], metadata_of_file(input, input.component_files[i]), request));
  return json;
}

}  // namespace pcrf::api

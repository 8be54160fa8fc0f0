/// \file one_case.hpp
/// \brief One case as `pcrf run` and `pcrf.run` solve it, in the steps both take: a station's
/// record scaled by a factor or to an intensity of the motion in the frame's plane, then a
/// scene under physics and solver settings, with an optional history; the result record as
/// the command line prints it.
#pragma once

#include <memory>
#include <optional>

#include "pcrf/api/given_settings.hpp"
#include "pcrf/excitation/station_record.hpp"
#include "pcrf/json.hpp"
#include "pcrf/metrics/case_result.hpp"
#include "pcrf/model/scene.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/solver/history.hpp"
#include "pcrf/solver/settings.hpp"

namespace pcrf::api {

/// How the record is scaled: by `scale`, or to `intensity` of the measure described by the
/// given intensity settings (measure, period_s, damping).
struct Scaling {
  double scale = 1.0;
  bool scale_given = false;
  std::optional<double> intensity;  ///< in the measure's units (g or m/s)
  GivenSettings<IntensitySpec> measure;
};

/// The factor the record is scaled by: `scale`, or `intensity` over the station's measure (of
/// the in-plane motion at `incidence_deg`, or of the horizontal pair for a RotD measure).
/// \throws UserError (a measure without an intensity, both a scale and an intensity, a
/// period the record cannot resolve, a record whose measure is 0); std::invalid_argument
/// from station_intensity (a RotD measure without a pair).
double scale_factor(const Scaling& scaling, const StationRecord& station, std::optional<double> incidence_deg);

/// The station's components at the frame's incidence, scaled as `scaling` says (with the
/// factor: ScaledExcitation::factor).
/// \throws UserError (an incidence without a pair, a scale that overflows, see scale_factor).
ScaledExcitation scaled_excitation(const StationRecord& station, std::optional<double> incidence_deg,
                                   const Scaling& scaling);

/// Solves `scene` shaken by `excitation`; each history row (every `history_dt_s`, 0: the
/// record's dt, plus the events) goes to `sink` when it is not empty.
/// \throws UserError for settings the scene or the record refuse (e.g. theta0_rad).
CaseResult solve_one_case(std::unique_ptr<Scene> scene, const PhysicsOptions& physics, const Excitation& excitation,
                          const SolverSettings& solver, double history_dt_s, const HistorySink& sink);

/// What the result's status says that its numbers cannot, one line (empty when nothing):
/// a frame still rocking at its end (rocking_at_end) has no verdict, and the setting that
/// resolves it is named (tail_advice); a status outside the model (ground_free_fall,
/// invalid_frame) says nothing of the frame. `pcrf run` prints it on stderr, pcrf.run warns.
std::string verdict_note(const CaseResult& result, const PhysicsOptions& physics);

/// The result record as `pcrf run` prints it: the scale factor, then every metric, the
/// status and the message, and the return-to-rest cut-off that defines `impacts`
/// (physics.rest_rise_rad).
JsonObject case_json(double scale_factor, const CaseResult& result, const PhysicsOptions& physics);

}  // namespace pcrf::api

// The columns of a time history (see pcrf/solver/history.hpp).
#include "pcrf/solver/history.hpp"

#include <cmath>

#include "pcrf/number_text.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf {

const std::vector<HistoryEventName>& history_events() {
  static const std::vector<HistoryEventName> events = {
      {kEventUplift, "uplift", "the frame leaves rest"},
      {kEventImpact, "impact", "theta1 returns to 0: velocity before and after in the row"},
      {kEventThetaPeak, "theta_peak", "local extremum of theta1 (located exactly)"},
      {kEventOmegaPeak, "omega_peak", "local extremum of the angular velocity (located exactly)"},
      {kEventRest, "rest", "the frame is put at rest"},
      {kEventStop, "stop", "tendon fracture or overturning: the case ends"},
      {kEventEnd, "end", "the end of the computed time (record plus tail)"},
  };
  return events;
}

const std::vector<HistoryColumn>& history_columns() {
  static const std::vector<HistoryColumn> columns = {
      {"t_s", "s", "time", &HistorySample::t_s},
      {"theta1_rad", "rad", "rotation of the pivoting column", &HistorySample::theta1_rad},
      {"omega1_rad_s", "rad/s", "angular velocity of the pivoting column (arriving, at an impact)",
       &HistorySample::omega1_rad_s},
      {"omega1_after_rad_s", "rad/s", "angular velocity leaving the row's instant (differs at an impact)",
       &HistorySample::omega1_after_rad_s},
      {"theta2_rad", "rad", "rotation of the beam", &HistorySample::theta2_rad},
      {"theta3_rad", "rad", "rotation of the other column", &HistorySample::theta3_rad},
      {"strain_column_left", "1", "left column tendon strain", &HistorySample::strain_column_left},
      {"strain_column_right", "1", "right column tendon strain", &HistorySample::strain_column_right},
      {"strain_beam", "1", "beam tendon strain", &HistorySample::strain_beam},
      {"ground_accel_m_s2", "m/s2", "ground acceleration (scaled)", &HistorySample::ground_accel_m_s2},
      {"ground_accel_g", "1", "ground acceleration (scaled) in units of g = 9.81 m/s2", &HistorySample::ground_accel_g},
      {"event", "1",
       "event flags (sum): 1 uplift, 2 impact, 4 peak of theta1, 8 peak of omega1, 16 return to rest, "
       "32 fracture or overturning, 64 end",
       &HistorySample::event},
  };
  return columns;
}

void check_history_interval(double case_s, double history_dt_s, double record_dt_s) {
  const double dt_s = history_dt_s > 0.0 ? history_dt_s : record_dt_s;
  const double rows = case_s / dt_s;
  if (rows <= kMaxHistoryRows) return;  // NaN (no interval) falls through to the refusal
  const std::string why = number_text(case_s) + " s of case (record and tail) at " + number_text(dt_s) + " s give " +
                          number_text(std::floor(rows)) + " rows, more than " + number_text(kMaxHistoryRows) +
                          ": give an interval of at least " + number_text(case_s / kMaxHistoryRows) + " s";
  throw UserError("history_dt_s", history_dt_s > 0.0 ? why : "the record's sample interval: " + why);
}

}  // namespace pcrf

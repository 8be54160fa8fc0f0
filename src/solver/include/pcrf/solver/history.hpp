/// \file history.hpp
/// \brief A case's time history: what one row holds, its columns (name, unit, meaning), and
/// the sink that receives the rows.
///
/// Rows come at a regular output interval (dense output from the integrator's interpolant:
/// the state between steps is the integrator's own polynomial, not a re-integration) plus one
/// row at every event the solver locates: uplift, impacts, peaks of |θ₁| and |θ̇₁|, return
/// to rest, fracture or overturning, and the end. Time strictly increases from row to row.
/// An impact is one row: `omega1_rad_s` is the velocity arriving, `omega1_after_rad_s` the
/// velocity leaving (r times it, or 0 when the frame comes to rest); elsewhere the two are
/// equal.
#pragma once

#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

namespace pcrf {

/// Event flags of a history row (bits; a row may carry several, e.g. impact | rest).
enum HistoryEvent : std::uint32_t {
  kEventNone = 0,
  kEventUplift = 1,      ///< the frame leaves rest
  kEventImpact = 2,      ///< θ₁ returns to 0: velocity before and after in the row
  kEventThetaPeak = 4,   ///< local extremum of θ₁ (located exactly)
  kEventOmegaPeak = 8,   ///< local extremum of θ̇₁ (located exactly)
  kEventRest = 16,       ///< the frame is put at rest (README "Return to rest")
  kEventStop = 32,       ///< tendon fracture or overturning: the case ends
  kEventEnd = 64,        ///< the end of the computed time (record plus tail)
};

/// An event flag's name and meaning: the one list scripts and figures read (`pcrf settings --json`).
struct HistoryEventName {
  HistoryEvent flag;
  std::string_view name;
  std::string_view meaning;
};
/// Every flag, in bit order.
const std::vector<HistoryEventName>& history_events();

/// One row of a time history.
struct HistorySample {
  double t_s;
  double theta1_rad, omega1_rad_s, omega1_after_rad_s;
  double theta2_rad, theta3_rad;
  double strain_column_left, strain_column_right, strain_beam;
  double ground_accel_m_s2, ground_accel_g;
  double event;  ///< HistoryEvent bits, as a number (CSV and cube columns are numbers)
};

/// Receives the rows in time order. Empty function: no history.
using HistorySink = std::function<void(const HistorySample&)>;

/// The most rows at its output interval a case's history may have: 10⁷ rows are about 2 GB of
/// CSV (12 columns at full precision) or 1 GB in memory, ten hours of a record sampled at
/// 0.005 s. Rows at events (impacts, peaks) come on top.
inline constexpr double kMaxHistoryRows = 1e7;

/// Checks the history interval of a case that runs for `case_s` seconds (record and tail):
/// `history_dt_s` (0: the record's `record_dt_s`) must give at most kMaxHistoryRows rows.
/// \throws UserError at `history_dt_s`, naming the rows it would write and the interval
/// that stays within the bound, before any row is written.
void check_history_interval(double case_s, double history_dt_s, double record_dt_s);

/// One column of a history: its name (the CSV header and the cube variable), unit
/// (UDUNITS spelling, "1" for dimensionless), meaning and field.
struct HistoryColumn {
  std::string_view name;
  std::string_view units;
  std::string_view long_name;
  double HistorySample::*member;
};

/// Every column, time first; the single description that the CSV writer (`pcrf run
/// --history`) and the cube's history groups derive from.
const std::vector<HistoryColumn>& history_columns();

}  // namespace pcrf

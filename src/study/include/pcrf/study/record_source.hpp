/// \file record_source.hpp
/// \brief The record axis of a study: where each ground motion comes from, and a per-process
/// cache that loads each of them once.
#pragma once

#include <cstddef>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "pcrf/excitation/station_record.hpp"
#include "pcrf/record/ground_motion.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf::study {

/// One value of the record axis.
struct RecordSource {
  std::string name;                    ///< its coordinate value in the cube (unique)
  std::optional<RecordFileSpec> file;  ///< a file (path already resolved), or
  std::string synthetic;               ///< a synthetic motion, make_synthetic() text
  Where declared_at;                   ///< the [[records]] entry's key that makes it, file and line
  /// A station's other components (kStationComponents: [[records]] h2, up), read like `file`
  /// (the first, h1). (Initialised, so that sources written as {name, file, synthetic, where}
  /// stay complete.)
  std::optional<RecordFileSpec> h2 = std::nullopt;
  std::optional<RecordFileSpec> up = std::nullopt;
  std::optional<double> az1_deg = std::nullopt;  ///< given azimuths [deg from north]; else from the headers
  std::optional<double> az2_deg = std::nullopt;
  std::optional<double> strike_deg = std::nullopt;  ///< the fault's strike [deg from north], for fault-normal incidence
  /// [[records]] scale: the record's own factor on its accelerations, applied before a scale
  /// axis' value (the study refuses it beside [intensity], whose scaling it would cancel).
  double scale = 1.0;

  bool has_components() const;
  /// Every file it reads: the first component's, then the others'.
  std::vector<const RecordFileSpec*> files() const;
  /// A pulse of a [[records]] pulse entry: its shape ("ricker") and the values of its [axes]
  /// pulse_* keys by key ("pulse_period_s"), the cube's coordinates along `record`.
  std::string pulse_shape = {};
  std::vector<std::pair<std::string, double>> pulse_values = {};

  /// "file ER1.AT2" or "synthetic sine:...", for messages.
  std::string describe() const;
};

/// A record as loaded: its motion, and what it calls itself (the AT2 title line, else the
/// file name, or the synthetic text), both from one read of its file.
struct LoadedRecord {
  StationRecord station;  ///< station.h1 is the record itself
  std::string title;
  std::vector<std::string> notes;  ///< alignment and sign notes (make_station)
  std::vector<std::string> warnings;  ///< components whose headers name other events or stations (different_station)
};

/// Reads or generates the motion. \throws UserError.
LoadedRecord load_record(const RecordSource& source);

/// The station of a record for FEMA P-695's pairs: its name up to the last '_'
/// ("RSN1111_KOBE" for "RSN1111_KOBE_NIS000", "NGA_no_829" for "NGA_no_829_RIO270").
std::string station_of(const std::string& record_name);

/// FEMA P-695 Appendix A over a set of components, each named by its station (station_of):
/// the normalisation factor of station k, NM_k = median_j(PGV_j) / PGV_k with PGV_k the
/// geometric mean of its two components' PGV; the set's intensity S = median_i(NM_i IM_i)
/// over all components; returned per component i: S / NM_i, the set intensity at which it
/// enters unscaled (so the factor to a set intensity I is I / (S / NM_i) = NM_i I / S).
/// \throws std::invalid_argument naming a station that has not exactly two components.
std::vector<double> p695_set_intensities(const std::vector<std::string>& stations, const std::vector<double>& pgv_m_s,
                                         const std::vector<double>& measure);

/// Loads each record at most once per process (records are read by every rank that needs
/// them, then scaled per case). Thread-safe.
class RecordCache {
 public:
  explicit RecordCache(std::vector<RecordSource> sources);

  /// The unscaled motion of record `index`, loading it on first use. \throws as load_record.
  const GroundMotion& get(std::size_t index);
  /// Every component of record `index` (aligned), loading it on first use.
  const StationRecord& station(std::size_t index);
  /// The notes made when record `index` was put together (padding, a DWN vertical).
  const std::vector<std::string>& notes(std::size_t index);
  /// The warnings made when record `index` was put together (LoadedRecord::warnings).
  const std::vector<std::string>& warnings(std::size_t index);

  /// The title of record `index` (LoadedRecord::title), loading it on first use.
  const std::string& title(std::size_t index);

  /// The unscaled record's value of an intensity measure, computed once per record: of its
  /// first component, or for a RotD measure of its horizontal pair (station_intensity). With
  /// spec.normalise = p695 the intensity at which the record is used unscaled in the
  /// normalised set (p695_set_intensities). \throws std::invalid_argument when the records
  /// do not form pairs.
  double intensity(std::size_t index, const IntensitySpec& spec);

  /// The factor record `index` is multiplied by for a value of the study's second axis: the
  /// value times the record's own `scale` on a scale axis (no `intensity`), else
  /// intensity_scale_factor(level, IM).
  double scale_factor(std::size_t index, double level, const std::optional<IntensitySpec>& intensity);

  std::size_t size() const { return sources_.size(); }
  const RecordSource& source(std::size_t index) const { return sources_.at(index); }

 private:
  std::vector<RecordSource> sources_;
  const LoadedRecord& loaded(std::size_t index);

  double p695_intensity(std::size_t index, const IntensitySpec& spec);

  std::vector<std::unique_ptr<LoadedRecord>> loaded_;
  std::vector<std::optional<double>> intensities_;  // of the one measure a study uses
  std::mutex mutex_;
};

}  // namespace pcrf::study

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

#include "pcrf/record/ground_motion.hpp"
#include "pcrf/record/intensity.hpp"
#include "pcrf/record/record_readers.hpp"

namespace pcrf::study {

/// One value of the record axis.
struct RecordSource {
  std::string name;                    ///< its coordinate value in the cube (unique)
  std::optional<RecordFileSpec> file;  ///< a file (path already resolved), or
  std::string synthetic;               ///< a synthetic motion, make_synthetic() text
  std::string declared_at;             ///< "study.toml:12", for messages

  /// "file ER1.AT2" or "synthetic sine:...", for messages.
  std::string describe() const;
};

/// Reads or generates the motion. \throws RecordError or std::invalid_argument.
GroundMotion load_record(const RecordSource& source);

/// Loads each record at most once per process (records are read by every rank that needs
/// them, then scaled per case). Thread-safe.
class RecordCache {
 public:
  explicit RecordCache(std::vector<RecordSource> sources);

  /// The unscaled motion of record `index`, loading it on first use.
  const GroundMotion& get(std::size_t index);

  /// The unscaled record's value of an intensity measure, computed once per record.
  double intensity(std::size_t index, const IntensitySpec& spec);

  /// Stores a motion already loaded elsewhere (e.g. during validation).
  void put(std::size_t index, GroundMotion motion);

  std::size_t size() const { return sources_.size(); }

 private:
  std::vector<RecordSource> sources_;
  std::vector<std::unique_ptr<GroundMotion>> loaded_;
  std::vector<std::optional<double>> intensities_;  // of the one measure a study uses
  std::mutex mutex_;
};

}  // namespace pcrf::study

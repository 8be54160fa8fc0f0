/// \file cube_writer.hpp
/// \brief Writes a result cube: a netCDF-4 compatible HDF5 file that xarray, netCDF4 and
/// h5py open with no custom code.
///
/// File layout (see studies/README.md, "The result cube"):
///   /<dimension>       coordinate variables, HDF5 dimension scales (netCDF-4 dimensions)
///   /<auxiliary>       1-D coordinates over one dimension (CF `coordinates` attribute)
///   /<metric>          float64 over every dimension, _FillValue NaN, `units`
///   /status            int8 over every dimension, _FillValue -1 (not run), CF flags
///   /messages/         case index and text of every case that reported a message
///   /histories/<name>/ time histories of selected cases (each its own time dimension)
/// Variables are chunked (each chunk one contiguous range of cases) and deflated.
///
/// Memory: the status of every case (1 byte each) and the values stored since the last
/// flush, chunk by chunk; nothing else of the cube. flush() writes a checkpoint by the one
/// atomic-file rule (io::AtomicFile, as every output): the last one copied to <file>.partial,
/// the chunks stored since written into it (laid over what it holds), synced, and renamed
/// over the file. A process killed at any moment leaves the last complete checkpoint. The
/// copy makes a checkpoint's cost grow with the whole cube (docs/checkpoint.md).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "pcrf/cube/cube_layout.hpp"

namespace pcrf::cube {

enum class OpenMode {
  kCreate,     ///< the file must not exist
  kOverwrite,  ///< replace any existing file
  kResume,     ///< continue an existing cube of the same study (create it if absent)
};

/// A time history to store in its own group, /histories/<name>.
struct HistoryTable {
  std::string name;                     ///< group name (letters, digits, '_', '-', '.')
  std::vector<Attribute> attributes;    ///< e.g. the case's coordinates
  std::vector<MetricVariable> columns;  ///< the first one is the time axis
  std::vector<std::vector<double>> values;  ///< one vector per column, equal lengths
};

class CubeWriter {
 public:
  /// \throws CubeError naming the file: exists (kCreate), belongs to another study or has
  /// another layout (kResume), or cannot be written.
  CubeWriter(std::filesystem::path file, CubeLayout layout, OpenMode mode);
  ~CubeWriter();
  CubeWriter(const CubeWriter&) = delete;
  CubeWriter& operator=(const CubeWriter&) = delete;

  /// True when an existing cube was opened for --resume.
  bool resumed() const { return resumed_; }
  /// Status of every case (kStatusNotRun where not computed yet).
  const std::vector<std::int8_t>& status() const { return status_; }
  std::int64_t done_count() const;
  /// A metric of every case (NaN where not computed): the last checkpoint's values with
  /// those stored since laid over them. Reads the whole variable: meant for small cubes
  /// (an IDA's). \throws CubeError for an unknown metric.
  std::vector<double> read_values(const std::string& metric) const;
  /// Memory held by the values stored since the last checkpoint [bytes].
  std::size_t pending_bytes() const;

  /// Stores one case in memory. `values` holds one value per metric, in layout order.
  void store(std::int64_t index, std::int8_t status, const std::vector<double>& values);
  /// Stores a message for a case (written under /messages).
  void store_note(std::int64_t index, std::string note);
  /// Queues a history group (written at the next flush).
  void store_history(HistoryTable table);
  /// Replaces the values of a side variable of the layout (written at the next flush).
  /// \throws CubeError for an unknown name or a wrong number of values.
  void store_side(const std::string& name, std::vector<double> values);

  /// Writes what changed since the last flush and flushes the file to disk.
  void flush();
  /// flush() and close. Further calls are invalid.
  void close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<std::int8_t> status_;
  bool resumed_ = false;
};

}  // namespace pcrf::cube

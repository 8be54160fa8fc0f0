/// \file cube_layout.hpp
/// \brief What a result cube holds: its dimensions, coordinate variables, metric variables,
/// the status flags and the global attributes. Independent of physics and of HDF5.
///
/// Storage order is row-major: the last dimension varies fastest, and a case's linear index
/// is its position in that order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <optional>
#include <span>
#include <variant>
#include <vector>

#include "pcrf/row_major.hpp"

namespace pcrf::cube {

/// A cube file cannot be made, read or continued; what() names the file and the problem,
/// cause() what a user can do about it.
class CubeError : public std::runtime_error {
 public:
  enum class Cause {
    kOther,
    kNoSpace,   ///< a full disk or quota (ENOSPC, EDQUOT): free space, then resume
    kGone,      ///< the cube or its folder was removed while being written
    kReplaced,  ///< another file took the cube's path while it was being written
    kLostLock,  ///< the lock that keeps other runs off the cube was removed during the run
  };
  explicit CubeError(const std::string& what, Cause cause = Cause::kOther) : std::runtime_error(what), cause_(cause) {}
  /// The cause an operating-system error number stands for.
  static Cause cause_of(int os_error);
  Cause cause() const { return cause_; }

 private:
  Cause cause_;
};

/// A cube axis.
struct Dimension {
  std::string name;
  std::size_t size = 0;
};

/// A numeric coordinate of more values than this is chunked (Coordinate::chunked); a shorter
/// one, or text, stays contiguous: a chunk index would cost more than it saves. How many values
/// a chunk holds is the cube's grid's to say (coordinate_chunk_values, chunk_grid.hpp): a
/// coordinate written live along `case` is cut as the metrics are along it, so that one unit's
/// cases have one chunk of each coordinate (issue 38: written with the unit, not at the
/// creation); one written at the creation (the case number) in chunks of up to 2^20 values.
/// Measured on a 4 x 10^5-case LHS (bench/master/pcrf_cube_filters): a random parameter costs
/// 7.27, 6.88, 6.83 and 6.80 B a value in chunks of 1 Ki, 8 Ki, 64 Ki and 256 Ki values
/// (shuffle, level 1), 8 B plain; the case number 0.31, 0.07, 0.03, 0.03 B against 4 B.
/// Levels 4 and 9 gain under 1 %, without shuffle 9 % is lost: level 1 with shuffle, as the metrics.
inline constexpr std::size_t kContiguousCoordinateMax = 4096;

/// A 1-D coordinate variable. A dimension coordinate has the name of its dimension; an
/// auxiliary coordinate (e.g. `varied_parameter` over `case`) has another name.
struct Coordinate {
  std::string name;
  std::string dimension;
  std::string units;      ///< UDUNITS text; empty for text and index coordinates
  std::string long_name;
  std::vector<double> numbers;       ///< numeric values, or
  std::vector<std::string> strings;  ///< text values, or `number_at` / `text_at` below
  bool is_text = false;
  bool is_index = false;  ///< numbers are whole (an index 0, 1, 2, …, a sample number) stored as int32
  /// Values computed from their index instead of held (a plan's coordinates along `case`:
  /// nothing per case stays in memory; the writer asks for them piece by piece while it
  /// creates the cube, and never after). Set: `numbers` and `strings` stay empty, and
  /// `computed_size` is the number of values.
  std::function<double(std::size_t)> number_at{};
  std::function<std::string(std::size_t)> text_at{};
  /// Optional beside number_at: number_at(first + k) into out[k] for every k, the same bits,
  /// at once (a sampled plan's parameter: a chunk of 16 384 values in a tight loop instead of
  /// a chain of calls per value, issue 38). Empty: numbers_into asks number_at value by value.
  std::function<void(std::size_t first, std::span<double> out)> numbers_from{};
  std::size_t computed_size = 0;

  bool computed() const { return number_at || text_at; }
  std::size_t size() const { return computed() ? computed_size : is_text ? strings.size() : numbers.size(); }
  /// Value i, held or computed.
  double number(std::size_t i) const { return number_at ? number_at(i) : numbers.at(i); }
  /// Values first … first + out.size() - 1 (number of each) into out.
  /// \throws std::out_of_range past size().
  void numbers_into(std::size_t first, std::span<double> out) const;
  std::string text(std::size_t i) const { return text_at ? text_at(i) : strings.at(i); }
  /// Value i as text ("%.17g" shortest round-trip for numbers).
  std::string label(std::size_t i) const;
  /// Drops the values, held or computed (what a writer does once they are in the file).
  void release_values();

  /// Stored in chunks (coordinate_chunk_values), shuffled and deflated like the metrics: a
  /// numeric coordinate longer than kContiguousCoordinateMax.
  bool chunked() const { return !is_text && size() > kContiguousCoordinateMax; }
  /// Values written into a new cube on disk after its creation, piece by piece, not into its
  /// in-memory image: a long one (the image would hold it whole: an LHS of 10^8 frames,
  /// gigabytes) or a computed one.
  bool written_later() const { return computed() || size() > kContiguousCoordinateMax; }
  /// Written during the run, not at the creation (issue 38): a chunked auxiliary coordinate of
  /// numbers that are not an index (a sampled plan's parameters along `case`). Its variable is made
  /// with the fill NaN (netCDF `_FillValue`: a value not written yet, as a metric's); each
  /// chunk goes in with the first unit of its cases (sealed by the worker that computed them,
  /// or by the writer at a fold), and close() writes every chunk still missing. An index (the
  /// case number, whole numbers with no NaN) and a dimension's own coordinate (xarray's index
  /// of it) are written at the creation, as before.
  bool written_live() const { return chunked() && !is_index && name != dimension; }
};

/// A float64 variable over every dimension, NaN where not computed.
struct MetricVariable {
  std::string name;
  std::string units;
  std::string long_name;
};

/// A float64 variable over some of the dimensions (not all: that is a metric), e.g. a scale
/// factor per record and intensity, or a summary per curve. Written whole, at creation or
/// whenever the producer has new values; NaN where not known.
struct SideVariable {
  std::string name;
  std::string units;
  std::string long_name;
  std::vector<std::string> dimensions;  ///< a subset of the cube's, in the cube's order
  std::vector<double> values;           ///< row-major over `dimensions`; empty: all NaN
};

/// One value of the int8 `status` variable (CF flag_values / flag_meanings).
struct StatusFlag {
  std::int8_t value = 0;
  std::string meaning;  ///< one word, e.g. "at_rest"
};

/// A global attribute.
struct Attribute {
  std::string name;
  std::variant<std::string, double, std::int64_t> value;
};

/// Fill of `status`: the case has not been computed.
inline constexpr std::int8_t kStatusNotRun = -1;
inline constexpr const char* kStatusNotRunName = "not_run";  ///< its CF flag meaning
inline constexpr const char* kStatusName = "status";
/// Global attribute that identifies the study a cube belongs to (compared by --resume).
inline constexpr const char* kFingerprintName = "study_fingerprint";
/// Global attribute of a cube that holds one shard of a run ("2/8"); absent when unsharded.
inline constexpr const char* kShardName = "shard";

/// Everything that defines a cube file before any case is computed.
struct CubeLayout {
  std::vector<Dimension> dimensions;
  std::vector<Coordinate> coordinates;
  std::vector<MetricVariable> metrics;
  std::vector<SideVariable> side_variables;
  std::vector<StatusFlag> status_flags;
  std::vector<Attribute> attributes;
  /// The extent of the cube's chunks along each dimension (ChunkGrid; HDF5's chunk shape of
  /// every metric and the status): a new cube's as its maker chose it (a study's: the rule of
  /// ChunkGrid with its plan's groups of frames), an existing one's as its file stores it
  /// (CubeReader). Empty: the rule of ChunkGrid with no groups (layout_grid), the chunks of
  /// every cube made before chunks held whole groups.
  std::vector<std::size_t> chunk_shape;

  std::int64_t case_count() const;
  std::vector<std::size_t> shape() const;
  /// Names of the auxiliary coordinates (CF `coordinates` attribute of every variable).
  std::vector<std::string> auxiliary_names() const;
  const Coordinate* find_coordinate(const std::string& name) const;
  /// Position of a dimension among `dimensions`, or nullopt when the cube has none of that name.
  std::optional<std::size_t> find_dimension(const std::string& name) const;
  const SideVariable* find_side_variable(const std::string& name) const;
  /// Number of values of a side variable (the product of its dimensions' sizes).
  std::size_t side_size(const SideVariable& variable) const;
  /// Value of a global text attribute; empty if absent.
  std::string text_attribute(const std::string& name) const;
};

using pcrf::unravel;  // row-major, as every cube stores its cases

}  // namespace pcrf::cube

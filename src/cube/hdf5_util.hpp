// Thin RAII and attribute helpers over the HDF5 C API, used by the cube writer and reader.
// Every failing call throws CubeError with the caller's description of what failed.
#pragma once

#include <hdf5.h>

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "pcrf/cube/cube_layout.hpp"

namespace pcrf::cube::h5 {

/// Turns off HDF5's own error printing: failures become CubeError messages instead.
void silence_library_errors();

/// Owns one HDF5 identifier and closes it with the right function.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  Handle(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Handle(Handle&& other) noexcept { *this = std::move(other); }
  Handle& operator=(Handle&& other) noexcept {
    if (this != &other) {
      reset();
      std::swap(id_, other.id_);
      std::swap(closer_, other.closer_);
    }
    return *this;
  }
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() { reset(); }

  hid_t get() const { return id_; }
  operator hid_t() const { return id_; }  // NOLINT: handles pass straight to the C API
  bool valid() const { return id_ >= 0; }
  void reset() {
    if (id_ >= 0 && closer_ != nullptr) closer_(id_);
    id_ = -1;
  }
  /// Gives up ownership (for a close whose result the caller checks).
  hid_t release() {
    const hid_t id = id_;
    id_ = -1;
    return id;
  }

 private:
  hid_t id_ = -1;
  Closer closer_ = nullptr;
};

/// Throws CubeError(what) when an HDF5 call returned a negative value.
hid_t check(hid_t id, const std::string& what);
/// check() for a call made once a chunk or more (the fold's raw chunk writes): the description
/// is made by `what()` only when the call failed, not a string built for every success.
template <class What>
hid_t check_lazily(hid_t id, What&& what) {
  return id >= 0 ? id : check(id, what());
}
inline Handle file(hid_t id, const std::string& what) { return {check(id, what), H5Fclose}; }
inline Handle group(hid_t id, const std::string& what) { return {check(id, what), H5Gclose}; }
inline Handle dataset(hid_t id, const std::string& what) { return {check(id, what), H5Dclose}; }
inline Handle space(hid_t id, const std::string& what) { return {check(id, what), H5Sclose}; }
inline Handle type(hid_t id, const std::string& what) { return {check(id, what), H5Tclose}; }
inline Handle plist(hid_t id, const std::string& what) { return {check(id, what), H5Pclose}; }
inline Handle attribute(hid_t id, const std::string& what) { return {check(id, what), H5Aclose}; }

/// Objects created in the open `file` from now on take HDF5 1.10's format and no later one
/// (H5Fset_libver_bounds, both bounds 1.10): a chunked dataset of a fixed shape is then indexed
/// by a fixed array, one entry a chunk set in place, not by a version-1 B-tree searched and
/// split at every chunk written (the fold's raw chunk writes, issue 38). Set on the open file,
/// not on its access list, so that the superblock stays version 0: HDF5 before 2.0 leaves a
/// version 2 or 3 superblock's checksum stale in H5Fget_file_image's copy (HDFGroup/hdf5
/// #1915), and the writer saves its new cubes through that copy. Read by HDF5 1.10 and later.
void use_chunk_indices_of_1_10(hid_t file, const std::string& what);

/// A file access property list for a cube opened to be written (its long coordinates, a
/// fold): raw data is placed without HDF5's small-data aggregator (block size 0). With it
/// (2 KiB blocks), a small chunk (a constant metric's deflates to about 150 B) is carved from
/// a block at the end of the file, a large chunk written after it leaves the block's rest as
/// free space, and every later chunk's allocation first searches the free-space manager
/// (0.5 instructions a result of a non-lifting LHS's fold). Without it, each chunk goes to
/// the end of the file: no search, and the cube is no larger (a few hundred bytes smaller).
Handle writing_access(const std::string& what);

/// Dimensions of a dataset (empty for a scalar). \throws CubeError(what) when unreadable.
std::vector<hsize_t> extent(hid_t dataset, const std::string& what);

/// "2×3×4" (a scalar: "1").
std::string shape_text(const std::vector<hsize_t>& dims);

/// Refuses (CubeError "<name> declares …") to read `values` values of a dataset into memory
/// at `bytes_each` bytes each when the file cannot hold them: more than kUsableMemoryShare of
/// this machine's memory, or, for data stored whole and unfiltered (contiguous or compact),
/// more bytes than the file has. Declared sizes are untrusted: checked before allocating.
void check_readable(hid_t dataset, double values, double bytes_each, const std::string& name);

/// Whether the link `name` of `location` leads to a dataset; false when it cannot be read.
bool is_dataset(hid_t location, const std::string& name);

/// Variable-length UTF-8 string type (what netCDF-4 calls NC_STRING).
Handle vlen_string_type();

// ---- attributes (netCDF-4 style: text as fixed-length strings, numbers as scalars) ----
void write_attribute(hid_t object, const std::string& name, const std::string& text);
void write_attribute(hid_t object, const std::string& name, double value);
void write_attribute(hid_t object, const std::string& name, std::int64_t value);
void write_attribute(hid_t object, const std::string& name, const std::vector<std::int8_t>& values);
void write_int8_attribute(hid_t object, const std::string& name, std::int8_t value);

bool has_attribute(hid_t object, const std::string& name);
/// Text attribute (fixed-length or variable-length string); empty if absent.
std::string read_text_attribute(hid_t object, const std::string& name);
std::vector<std::int8_t> read_int8_attribute(hid_t object, const std::string& name);
/// Every scalar text or numeric attribute of an object, in creation (or name) order.
std::vector<Attribute> read_attributes(hid_t object);

// ---- string datasets ----
void write_strings(hid_t dataset, const std::vector<std::string>& values);
/// Every value of a 1-D (or any-rank) text dataset; checked with check_readable() first.
std::vector<std::string> read_strings(hid_t dataset, const std::string& name = "text values");

}  // namespace pcrf::cube::h5

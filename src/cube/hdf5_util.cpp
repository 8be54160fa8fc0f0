// HDF5 helpers (see hdf5_util.hpp). Attributes follow what netCDF-C writes, so that
// netCDF4-python and xarray read them as plain text and numbers.
#include "cube/hdf5_util.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <mutex>

#include "pcrf/machine_memory.hpp"

namespace pcrf::cube::h5 {

void silence_library_errors() {
  static std::once_flag once;
  std::call_once(once, [] { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); });
}

namespace {

/// The most bytes one attribute may make a reader allocate: far above any text or flag list a
/// cube holds (a study's whole text is a few kB), far below what could exhaust memory.
constexpr std::size_t kMaxAttributeBytes = std::size_t{64} << 20;

/// The largest chunk a reader reads [bytes]: 512 times the largest pcrf writes (16 384 cases
/// of float64, 128 KiB), and more than any netCDF or h5py default.
constexpr double kMaxChunkBytes = 64.0 * 1024 * 1024;

/// The innermost messages of HDF5's error stack (the library's own reason), e.g.
/// "unable to open file: ... errno = 28, error message = 'No space left on device'".
std::string library_reason() {
  std::vector<std::string> messages;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned, const H5E_error2_t* e, void* data) -> herr_t {
        auto& out = *static_cast<std::vector<std::string>*>(data);
        if (e->desc != nullptr && *e->desc != '\0' && out.size() < 2) out.emplace_back(e->desc);
        return 0;
      },
      &messages);
  H5Eclear2(H5E_DEFAULT);
  std::string reason;
  for (auto it = messages.rbegin(); it != messages.rend(); ++it) reason += (reason.empty() ? "" : ": ") + *it;
  return reason;
}

/// The operating system's error that HDF5 quotes in its reason ("errno = 28, error message =
/// 'No space left on device'"), 0 when it quotes none. HDF5 1.14 reports a full disk from its
/// file driver this way, where 1.10 failed earlier: the cause, and so the advice, is the same.
int quoted_os_error(const std::string& reason) {
  const std::string key = "errno = ";
  const auto at = reason.find(key);
  return at == std::string::npos ? 0 : std::atoi(reason.c_str() + at + key.size());
}

}  // namespace

hid_t check(hid_t id, const std::string& what) {
  if (id >= 0) return id;
  const std::string reason = library_reason();
  throw CubeError(reason.empty() ? what : what + " (" + reason + ")", CubeError::cause_of(quoted_os_error(reason)));
}

void use_chunk_indices_of_1_10(hid_t file, const std::string& what) {
  check(H5Fset_libver_bounds(file, H5F_LIBVER_V110, H5F_LIBVER_V110), what);
}

Handle writing_access(const std::string& what) {
  auto fapl = plist(H5Pcreate(H5P_FILE_ACCESS), what);
  check(H5Pset_small_data_block_size(fapl, 0), what);
  return fapl;
}

std::vector<hsize_t> extent(hid_t dataset, const std::string& what) {
  auto s = space(H5Dget_space(dataset), what);
  const int rank = H5Sget_simple_extent_ndims(s);
  if (rank < 0) check(rank, what);
  std::vector<hsize_t> dims(static_cast<std::size_t>(rank));
  if (rank > 0) check(H5Sget_simple_extent_dims(s, dims.data(), nullptr), what);
  return dims;
}

std::string shape_text(const std::vector<hsize_t>& dims) {
  if (dims.empty()) return "1";
  std::string text;
  for (auto n : dims) text += (text.empty() ? "" : "×") + std::to_string(n);
  return text;
}

namespace {

/// How a dataset's values are stored: whole and unfiltered (contiguous or compact), or not
/// (chunked: unwritten chunks hold the fill value and take no room in the file).
bool stored_whole(hid_t dataset) {
  auto dcpl = plist(H5Dget_create_plist(dataset), "cannot read a dataset's storage");
  const H5D_layout_t layout = H5Pget_layout(dcpl);
  return layout == H5D_CONTIGUOUS || layout == H5D_COMPACT;
}

double file_size_of(hid_t object) {
  Handle file(check(H5Iget_file_id(object), "cannot find a dataset's file"), H5Fclose);
  hsize_t size = 0;
  check(H5Fget_filesize(file, &size), "cannot read the file's size");
  return static_cast<double>(size);
}

}  // namespace

void check_readable(hid_t dataset, double values, double bytes_each, const std::string& name) {
  char text[320];
  const double bytes = values * bytes_each, memory = machine_memory_bytes();
  if (bytes > kUsableMemoryShare * memory) {
    std::snprintf(text, sizeof text,
                  "'%s' declares %.4g values (%.3g GB in memory), more than %.0f %% of this machine's %.3g GB: "
                  "a damaged cube, or one too large for this machine",
                  name.c_str(), values, bytes / 1e9, 100.0 * kUsableMemoryShare, memory / 1e9);
    throw CubeError(text);
  }
  auto t = type(H5Dget_type(dataset), "cannot read the type of '" + name + "'");
  if (!stored_whole(dataset)) {
    // HDF5 reads a chunk whole into a buffer of the size its layout declares, whatever the
    // variable's length: a damaged chunk size must not size that buffer.
    auto dcpl = plist(H5Dget_create_plist(dataset), "cannot read a dataset's storage");
    if (H5Pget_layout(dcpl) != H5D_CHUNKED) return;
    const int rank = H5Pget_chunk(dcpl, 0, nullptr);
    std::vector<hsize_t> chunk(static_cast<std::size_t>(std::max(rank, 0)));
    if (rank < 0 || (rank > 0 && H5Pget_chunk(dcpl, rank, chunk.data()) < 0))
      throw CubeError("'" + name + "': cannot read its chunk size");
    double chunk_bytes = static_cast<double>(H5Tget_size(t));
    for (const auto n : chunk) chunk_bytes *= static_cast<double>(n);
    if (chunk_bytes > kMaxChunkBytes) {
      std::snprintf(text, sizeof text, "'%s' declares chunks of %.4g bytes, more than the %.3g MB a reader allows: a damaged cube",
                    name.c_str(), chunk_bytes, kMaxChunkBytes / 1e6);
      throw CubeError(text);
    }
    return;
  }
  const double stored = values * static_cast<double>(H5Tget_size(t)), file_size = file_size_of(dataset);
  if (stored > file_size) {
    std::snprintf(text, sizeof text,
                  "'%s' declares %.4g values (%.4g bytes stored whole), more than the file's %.4g bytes: a damaged cube",
                  name.c_str(), values, stored, file_size);
    throw CubeError(text);
  }
}

bool is_dataset(hid_t location, const std::string& name) {
  // HDF5 1.12 changed the object-information call (H5O_info2_t, with tokens for addresses):
  // the one place that tells the releases apart.
#if H5_VERSION_GE(1, 12, 0)
  H5O_info2_t info;
  const herr_t status = H5Oget_info_by_name3(location, name.c_str(), &info, H5O_INFO_BASIC, H5P_DEFAULT);
#else
  H5O_info_t info;
  const herr_t status = H5Oget_info_by_name2(location, name.c_str(), &info, H5O_INFO_BASIC, H5P_DEFAULT);
#endif
  return status >= 0 && info.type == H5O_TYPE_DATASET;
}

Handle vlen_string_type() {
  auto t = type(H5Tcopy(H5T_C_S1), "cannot make a string type");
  check(H5Tset_size(t, H5T_VARIABLE), "cannot make a string type");
  check(H5Tset_cset(t, H5T_CSET_UTF8), "cannot make a string type");
  return t;
}

namespace {

void remove_if_present(hid_t object, const std::string& name) {
  if (has_attribute(object, name)) check(H5Adelete(object, name.c_str()), "cannot replace attribute " + name);
}

void write_scalar(hid_t object, const std::string& name, hid_t file_type, hid_t memory_type,
                  const void* value) {
  remove_if_present(object, name);
  auto s = space(H5Screate(H5S_SCALAR), "cannot make a dataspace");
  auto a = attribute(H5Acreate2(object, name.c_str(), file_type, s, H5P_DEFAULT, H5P_DEFAULT),
                     "cannot create attribute " + name);
  check(H5Awrite(a, memory_type, value), "cannot write attribute " + name);
}

}  // namespace

void write_attribute(hid_t object, const std::string& name, const std::string& text) {
  // Fixed-length, NUL-terminated: netCDF-C's NC_CHAR. An empty text still needs one byte.
  auto t = type(H5Tcopy(H5T_C_S1), "cannot make a string type");
  check(H5Tset_size(t, std::max<std::size_t>(text.size(), 1)), "cannot size a string type");
  check(H5Tset_strpad(t, H5T_STR_NULLTERM), "cannot make a string type");
  check(H5Tset_cset(t, H5T_CSET_UTF8), "cannot make a string type");
  std::string padded = text;
  padded.resize(std::max<std::size_t>(text.size(), 1), '\0');
  write_scalar(object, name, t, t, padded.data());
}

void write_attribute(hid_t object, const std::string& name, double value) {
  write_scalar(object, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void write_attribute(hid_t object, const std::string& name, std::int64_t value) {
  write_scalar(object, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
}

void write_int8_attribute(hid_t object, const std::string& name, std::int8_t value) {
  write_scalar(object, name, H5T_STD_I8LE, H5T_NATIVE_INT8, &value);
}

void write_attribute(hid_t object, const std::string& name, const std::vector<std::int8_t>& values) {
  remove_if_present(object, name);
  const hsize_t n = values.size();
  auto s = space(H5Screate_simple(1, &n, nullptr), "cannot make a dataspace");
  auto a = attribute(H5Acreate2(object, name.c_str(), H5T_STD_I8LE, s, H5P_DEFAULT, H5P_DEFAULT),
                     "cannot create attribute " + name);
  check(H5Awrite(a, H5T_NATIVE_INT8, values.data()), "cannot write attribute " + name);
}

bool has_attribute(hid_t object, const std::string& name) {
  return check(H5Aexists(object, name.c_str()), "cannot look for attribute " + name) > 0;
}

std::string read_text_attribute(hid_t object, const std::string& name) {
  if (!has_attribute(object, name)) return {};
  auto a = attribute(H5Aopen(object, name.c_str(), H5P_DEFAULT), "cannot open attribute " + name);
  auto t = type(H5Aget_type(a), "cannot read attribute " + name);
  if (H5Tget_class(t) != H5T_STRING) throw CubeError("attribute " + name + " is not text");
  // One text: the buffers below hold one value, whatever the attribute declares.
  auto s = space(H5Aget_space(a), "cannot read attribute " + name);
  if (const auto n = H5Sget_simple_extent_npoints(s); n == 0) return {};
  else if (n != 1) throw CubeError("attribute " + name + " holds " + std::to_string(n) + " texts, not one");
  if (H5Tis_variable_str(t) > 0) {
    char* value = nullptr;
    auto memory = vlen_string_type();
    check(H5Aread(a, memory, &value), "cannot read attribute " + name);
    std::string text = value != nullptr ? value : "";
    H5free_memory(value);
    return text;
  }
  const std::size_t size = H5Tget_size(t);
  if (size > kMaxAttributeBytes) throw CubeError("attribute " + name + " declares " + std::to_string(size) + " bytes of text");
  std::string text(size, '\0');
  check(H5Aread(a, t, text.data()), "cannot read attribute " + name);
  text.resize(text.find('\0') == std::string::npos ? size : text.find('\0'));
  return text;
}

std::vector<std::int8_t> read_int8_attribute(hid_t object, const std::string& name) {
  auto a = attribute(H5Aopen(object, name.c_str(), H5P_DEFAULT), "cannot open attribute " + name);
  auto s = space(H5Aget_space(a), "cannot read attribute " + name);
  const auto n = H5Sget_simple_extent_npoints(s);
  if (n < 0 || static_cast<std::size_t>(n) > kMaxAttributeBytes)
    throw CubeError("attribute " + name + " declares " + std::to_string(n) + " values");
  std::vector<std::int8_t> values(static_cast<std::size_t>(n));
  check(H5Aread(a, H5T_NATIVE_INT8, values.data()), "cannot read attribute " + name);
  return values;
}

namespace {

herr_t collect_attribute(hid_t object, const char* name, const H5A_info_t*, void* data) {
  auto& out = *static_cast<std::vector<Attribute>*>(data);
  try {
    auto a = attribute(H5Aopen(object, name, H5P_DEFAULT), "cannot open attribute");
    auto t = type(H5Aget_type(a), "cannot read attribute type");
    auto s = space(H5Aget_space(a), "cannot read attribute space");
    const bool scalar = H5Sget_simple_extent_npoints(s) == 1;
    switch (H5Tget_class(t)) {
      case H5T_STRING:
        if (scalar) out.push_back({name, read_text_attribute(object, name)});
        break;
      case H5T_FLOAT:
        if (scalar) {
          double value = 0;
          check(H5Aread(a, H5T_NATIVE_DOUBLE, &value), "cannot read attribute");
          out.push_back({name, value});
        }
        break;
      case H5T_INTEGER:
        if (scalar) {
          std::int64_t value = 0;
          check(H5Aread(a, H5T_NATIVE_INT64, &value), "cannot read attribute");
          out.push_back({name, value});
        }
        break;
      default:
        break;  // references, arrays: dimension-scale bookkeeping, not user attributes
    }
  } catch (const CubeError&) {
    return -1;
  }
  return 0;
}

}  // namespace

std::vector<Attribute> read_attributes(hid_t object) {
  std::vector<Attribute> out;
  hsize_t position = 0;
  // Creation order when the file tracks it (ours do), name order otherwise.
  if (H5Aiterate2(object, H5_INDEX_CRT_ORDER, H5_ITER_INC, &position, collect_attribute, &out) < 0) {
    out.clear();
    position = 0;
    check(H5Aiterate2(object, H5_INDEX_NAME, H5_ITER_INC, &position, collect_attribute, &out),
          "cannot list attributes");
  }
  return out;
}

void write_strings(hid_t dataset, const std::vector<std::string>& values) {
  std::vector<const char*> pointers;
  pointers.reserve(values.size());
  for (const auto& v : values) pointers.push_back(v.c_str());
  auto t = vlen_string_type();
  check(H5Dwrite(dataset, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()),
        "cannot write text values");
}

std::vector<std::string> read_strings(hid_t dataset, const std::string& name) {
  auto s = space(H5Dget_space(dataset), "cannot read a dataspace");
  const auto n = static_cast<std::size_t>(std::max<hssize_t>(H5Sget_simple_extent_npoints(s), 0));
  auto file_type = type(H5Dget_type(dataset), "cannot read a type");
  if (H5Tget_class(file_type) != H5T_STRING) throw CubeError("'" + name + "' is not text");
  const bool variable = H5Tis_variable_str(file_type) > 0;
  check_readable(dataset, static_cast<double>(n), variable ? sizeof(char*) : static_cast<double>(H5Tget_size(file_type)), name);
  std::vector<std::string> values;
  values.reserve(n);
  if (variable) {
    std::vector<char*> pointers(n, nullptr);
    auto t = vlen_string_type();
    check(H5Dread(dataset, t, H5S_ALL, H5S_ALL, H5P_DEFAULT, pointers.data()), "cannot read text values");
    for (char* p : pointers) values.emplace_back(p != nullptr ? p : "");
    check(H5Dvlen_reclaim(t, s, H5P_DEFAULT, pointers.data()), "cannot free text values");
    return values;
  }
  const std::size_t width = H5Tget_size(file_type);
  std::string buffer(n * width, '\0');
  check(H5Dread(dataset, file_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, buffer.data()), "cannot read text values");
  for (std::size_t i = 0; i < n; ++i) {
    std::string v = buffer.substr(i * width, width);
    values.push_back(v.substr(0, v.find('\0')));
  }
  return values;
}

}  // namespace pcrf::cube::h5

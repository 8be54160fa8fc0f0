// Result cube reader (see cube_reader.hpp). Dimensions come from the dimension scales
// attached to `status`; auxiliary coordinates from its CF `coordinates` attribute; metrics
// are the other float variables over the same dimensions.
#include "pcrf/cube/cube_reader.hpp"

#include <hdf5_hl.h>

#include <algorithm>
#include <cstdio>
#include <initializer_list>
#include <sstream>
#include <system_error>

#include "cube/hdf5_util.hpp"
#include "pcrf/cube/chunk_grid.hpp"

namespace pcrf::cube {
namespace {

/// Name of an object from its path ("/kappa" → "kappa").
std::string base_name(hid_t object) {
  const ssize_t size = H5Iget_name(object, nullptr, 0);
  if (size <= 0) return {};
  std::string name(static_cast<std::size_t>(size) + 1, '\0');
  H5Iget_name(object, name.data(), name.size());
  name.resize(static_cast<std::size_t>(size));
  return name.substr(name.rfind('/') + 1);
}

herr_t scale_name(hid_t, unsigned, hid_t scale, void* data) {
  *static_cast<std::string*>(data) = base_name(scale);
  return 1;  // the first attached scale is enough
}

/// Name of the dimension scale attached to dimension `dim` of a dataset.
std::string dimension_name(hid_t dataset, unsigned dim) {
  std::string name;
  if (H5DSget_num_scales(dataset, dim) <= 0) return name;
  H5DSiterate_scales(dataset, dim, nullptr, scale_name, &name);
  return name;
}

/// The extents of a variable's chunks when they cut the cube as a ChunkGrid does (every cube
/// pcrf writes); empty otherwise (a cube rechunked by another tool: the grid's rule then).
std::vector<std::size_t> grid_chunk_shape(hid_t dataset, const std::vector<std::size_t>& shape) {
  const h5::Handle dcpl(H5Dget_create_plist(dataset), H5Pclose);
  if (dcpl < 0 || H5Pget_layout(dcpl) != H5D_CHUNKED) return {};
  std::vector<hsize_t> chunk(shape.size() + 1, 0);
  if (H5Pget_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data()) != static_cast<int>(shape.size())) return {};
  std::vector<std::size_t> extents(chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(shape.size()));
  return ChunkGrid::valid_chunk_shape(shape, extents) ? extents : std::vector<std::size_t>{};
}

std::vector<std::string> split_words(const std::string& text) {
  std::istringstream in(text);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

herr_t collect_link(hid_t, const char* name, const H5L_info_t*, void* data) {
  static_cast<std::vector<std::string>*>(data)->push_back(name);
  return 0;
}

/// Names of the links in a group, in creation order when tracked.
std::vector<std::string> link_names(hid_t group) {
  std::vector<std::string> names;
  hsize_t position = 0;
  if (H5Literate(group, H5_INDEX_CRT_ORDER, H5_ITER_INC, &position, collect_link, &names) < 0) {
    names.clear();
    position = 0;
    h5::check(H5Literate(group, H5_INDEX_NAME, H5_ITER_INC, &position, collect_link, &names),
              "cannot list a group");
  }
  return names;
}

}  // namespace

struct CubeReader::Impl {
  h5::Handle file;
  std::string label;
  std::string what(const std::string& problem) const { return label + ": " + problem; }

  h5::Handle open(const std::string& name) const {
    return h5::dataset(H5Dopen2(file, name.c_str(), H5P_DEFAULT), what("has no variable '" + name + "'"));
  }
  /// A variable checked against the layout before a byte of it is read: its type class one
  /// of `classes`, its dimensions `shape`, its size one the file and memory can hold.
  h5::Handle open_checked(const std::string& name, std::initializer_list<H5T_class_t> classes,
                          const std::vector<hsize_t>& shape, double bytes_each) const;
  /// Runs a check of hdf5_util, whose messages name no file, with this file's name.
  template <class Check>
  auto labelled(Check check) const {
    try {
      return check();
    } catch (const CubeError& e) {
      const std::string text = e.what();
      if (text.rfind(label, 0) == 0) throw;
      throw CubeError(what(text), e.cause());
    }
  }
  Coordinate read_coordinate(const std::string& name, const std::vector<Dimension>& dimensions) const;
  /// chunk_span, its errors naming this file.
  ChunkSpan span_of(const ChunkGrid& grid, std::size_t first_chunk, std::size_t end_chunk) const {
    try {
      return chunk_span(grid, first_chunk, end_chunk);
    } catch (const std::exception& e) {
      throw CubeError(what(e.what()));
    }
  }
};

namespace {

std::string class_text(H5T_class_t type_class) {
  switch (type_class) {
    case H5T_INTEGER: return "integers";
    case H5T_FLOAT: return "floating-point numbers";
    case H5T_STRING: return "text";
    default: return "values of another kind";
  }
}

}  // namespace

h5::Handle CubeReader::Impl::open_checked(const std::string& name, std::initializer_list<H5T_class_t> classes,
                                          const std::vector<hsize_t>& shape, double bytes_each) const {
  auto d = open(name);
  auto t = h5::type(H5Dget_type(d), what("cannot read the type of '" + name + "'"));
  const auto type_class = H5Tget_class(t);
  if (std::find(classes.begin(), classes.end(), type_class) == classes.end())
    throw CubeError(what("'" + name + "' holds " + class_text(type_class) + ", not " + class_text(*classes.begin()) +
                         ": a damaged or foreign cube"));
  const auto dims = h5::extent(d, what("cannot read the shape of '" + name + "'"));
  if (dims != shape)
    throw CubeError(what("'" + name + "' has shape " + h5::shape_text(dims) + " where the cube's layout gives " +
                         h5::shape_text(shape) + ": a damaged or foreign cube"));
  double values = 1.0;
  for (auto n : shape) values *= static_cast<double>(n);
  labelled([&] { h5::check_readable(d, values, bytes_each, name); });
  return d;
}

Coordinate CubeReader::Impl::read_coordinate(const std::string& name, const std::vector<Dimension>& dimensions) const {
  auto d = open(name);
  Coordinate c;
  c.name = name;
  c.dimension = H5DSis_scale(d) > 0 ? name : dimension_name(d, 0);
  const auto dimension = std::find_if(dimensions.begin(), dimensions.end(),
                                      [&](const Dimension& x) { return x.name == c.dimension; });
  if (dimension == dimensions.end())
    throw CubeError(what("coordinate '" + name + "' is over no dimension of 'status': a damaged or foreign cube"));
  d = open_checked(name, {H5T_FLOAT, H5T_INTEGER, H5T_STRING}, {static_cast<hsize_t>(dimension->size)}, sizeof(double));
  c.units = h5::read_text_attribute(d, "units");
  c.long_name = h5::read_text_attribute(d, "long_name");
  auto t = h5::type(H5Dget_type(d), what("cannot read the type of '" + name + "'"));
  const auto type_class = H5Tget_class(t);
  if (type_class == H5T_STRING) {
    c.is_text = true;
    c.strings = labelled([&] { return h5::read_strings(d, name); });
    return c;
  }
  c.is_index = type_class == H5T_INTEGER;
  c.numbers.resize(dimension->size);
  if (!c.numbers.empty())
    h5::check(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, c.numbers.data()),
              what("cannot read '" + name + "'"));
  return c;
}

namespace {

/// The file a reader may open: a regular file (not a folder, a FIFO — which would block —
/// or a link loop), named in the one-line message that refuses any other.
void check_regular_file(const std::filesystem::path& file, const std::string& label) {
  std::error_code error;
  const auto status = std::filesystem::status(file, error);
  if (status.type() == std::filesystem::file_type::not_found) throw CubeError(label + ": no such file");
  if (error) throw CubeError(label + ": cannot open: " + error.message());
  if (!std::filesystem::is_regular_file(status)) throw CubeError(label + ": not a regular file");
}

}  // namespace

CubeReader::CubeReader(const std::filesystem::path& file) : file_(file), impl_(std::make_unique<Impl>()) {
  h5::silence_library_errors();
  impl_->label = file.string();
  // Every CubeError, also those of hdf5_util (which name no file), names this file.
  impl_->labelled([&] {
    check_regular_file(file, impl_->label);
    if (H5Fis_hdf5(file.c_str()) <= 0) throw CubeError(impl_->what("not an HDF5 file"));
    impl_->file = h5::file(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), impl_->what("cannot open"));
    if (H5Lexists(impl_->file, kStatusName, H5P_DEFAULT) <= 0)
      throw CubeError(impl_->what("not a pcrf result cube (no 'status' variable)"));
    auto status = impl_->open(kStatusName);
    const auto dims = h5::extent(status, impl_->what("cannot read 'status'"));
    const int rank = static_cast<int>(dims.size());
    for (std::size_t d = 0; d < dims.size(); ++d) {
      const std::string name = dimension_name(status, static_cast<unsigned>(d));
      if (name.empty()) throw CubeError(impl_->what("dimension " + std::to_string(d) + " of 'status' has no coordinate"));
      layout_.dimensions.push_back({name, static_cast<std::size_t>(dims[d])});
    }
    // Every case's status is read whole: refused here when the file cannot hold so many.
    status = impl_->open_checked(kStatusName, {H5T_INTEGER}, dims, 1.0);
    layout_.chunk_shape = grid_chunk_shape(status, layout_.shape());
    for (const auto& dimension : layout_.dimensions)
      layout_.coordinates.push_back(impl_->read_coordinate(dimension.name, layout_.dimensions));
    for (const auto& name : split_words(h5::read_text_attribute(status, "coordinates")))
      layout_.coordinates.push_back(impl_->read_coordinate(name, layout_.dimensions));
    const auto values = h5::read_int8_attribute(status, "flag_values");
    const auto meanings = split_words(h5::read_text_attribute(status, "flag_meanings"));
    for (std::size_t i = 0; i < values.size() && i < meanings.size(); ++i)
      layout_.status_flags.push_back({values[i], meanings[i]});
    // Metrics: float variables with the rank of `status` that are not coordinates.
    for (const auto& name : link_names(impl_->file)) {
      if (name == kStatusName || layout_.find_coordinate(name) != nullptr) continue;
      if (!h5::is_dataset(impl_->file, name)) continue;
      auto d = impl_->open(name);
      auto t = h5::type(H5Dget_type(d), impl_->what("cannot read '" + name + "'"));
      auto ds = h5::space(H5Dget_space(d), impl_->what("cannot read '" + name + "'"));
      if (H5Tget_class(t) != H5T_FLOAT) continue;
      const int variable_rank = H5Sget_simple_extent_ndims(ds);
      if (variable_rank == rank) {
        layout_.metrics.push_back({name, h5::read_text_attribute(d, "units"), h5::read_text_attribute(d, "long_name")});
      } else if (variable_rank > 0 && variable_rank < rank) {
        SideVariable side{name, h5::read_text_attribute(d, "units"), h5::read_text_attribute(d, "long_name"), {}, {}};
        for (int k = 0; k < variable_rank; ++k) side.dimensions.push_back(dimension_name(d, static_cast<unsigned>(k)));
        layout_.side_variables.push_back(std::move(side));
      }
    }
    auto root = h5::group(H5Gopen2(impl_->file, "/", H5P_DEFAULT), impl_->what("cannot open the root group"));
    layout_.attributes = h5::read_attributes(root);
  });
}

CubeReader::~CubeReader() = default;

namespace {

std::vector<hsize_t> to_hsize(const std::vector<std::size_t>& shape) { return {shape.begin(), shape.end()}; }

}  // namespace

std::vector<std::int8_t> CubeReader::read_status() const {
  auto d = impl_->open_checked(kStatusName, {H5T_INTEGER}, to_hsize(layout_.shape()), 1.0);
  std::vector<std::int8_t> values(static_cast<std::size_t>(layout_.case_count()));
  h5::check(H5Dread(d, H5T_NATIVE_INT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
            impl_->what("cannot read 'status'"));
  return values;
}

std::vector<double> CubeReader::read_metric(const std::string& name) const {
  const bool known = std::any_of(layout_.metrics.begin(), layout_.metrics.end(),
                                 [&](const MetricVariable& m) { return m.name == name; });
  if (!known) throw CubeError(impl_->what("has no metric '" + name + "'"));
  auto d = impl_->open_checked(name, {H5T_FLOAT}, to_hsize(layout_.shape()), sizeof(double));
  std::vector<double> values(static_cast<std::size_t>(layout_.case_count()));
  h5::check(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
            impl_->what("cannot read '" + name + "'"));
  return values;
}

std::vector<double> CubeReader::read_metric_chunks(const std::string& name, const ChunkGrid& grid, std::size_t first_chunk,
                                                   std::size_t end_chunk) const {
  const bool known = std::any_of(layout_.metrics.begin(), layout_.metrics.end(),
                                 [&](const MetricVariable& m) { return m.name == name; });
  if (!known) throw CubeError(impl_->what("has no metric '" + name + "'"));
  if (grid.shape() != layout_.shape()) throw CubeError(impl_->what("is read with a chunk grid of another shape"));
  const ChunkSpan span = impl_->span_of(grid, first_chunk, end_chunk);
  auto d = impl_->open_checked(name, {H5T_FLOAT}, to_hsize(layout_.shape()), sizeof(double));
  std::vector<double> values(static_cast<std::size_t>(span.count));
  const std::string problem = impl_->what("cannot read '" + name + "'");
  for (std::size_t c = first_chunk; c < end_chunk; ++c) {
    const auto r = grid.range(c);
    const auto start = to_hsize(r.start);
    const auto extent = to_hsize(r.extent);
    const auto count = static_cast<hsize_t>(r.count);
    auto memory = h5::space(H5Screate_simple(1, &count, nullptr), problem);
    auto selection = h5::space(H5Dget_space(d), problem);
    h5::check(H5Sselect_hyperslab(selection, H5S_SELECT_SET, start.data(), nullptr, extent.data(), nullptr), problem);
    h5::check(H5Dread(d, H5T_NATIVE_DOUBLE, memory, selection, H5P_DEFAULT,
                      values.data() + static_cast<std::size_t>(r.first - span.first)),
              problem);
  }
  return values;
}

std::vector<double> CubeReader::read_side(const std::string& name) const {
  const SideVariable* v = layout_.find_side_variable(name);
  if (v == nullptr) throw CubeError(impl_->what("has no variable '" + name + "' (over some of its dimensions)"));
  std::vector<hsize_t> shape;
  for (const auto& dimension : v->dimensions) {
    const auto d = layout_.find_dimension(dimension);
    if (!d) throw CubeError(impl_->what("'" + name + "' is over '" + dimension + "', no dimension of 'status': a damaged or foreign cube"));
    shape.push_back(layout_.dimensions[*d].size);
  }
  auto d = impl_->open_checked(name, {H5T_FLOAT}, shape, sizeof(double));
  std::vector<double> values(layout_.side_size(*v));
  h5::check(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
            impl_->what("cannot read '" + name + "'"));
  return values;
}

std::vector<std::pair<std::int64_t, std::string>> CubeReader::read_notes() const {
  std::vector<std::pair<std::int64_t, std::string>> notes;
  if (H5Lexists(impl_->file, "messages", H5P_DEFAULT) <= 0) return notes;
  // Two 1-D variables of one length: a case's index and its message.
  const auto count = h5::extent(impl_->open("messages/case_index"), impl_->what("cannot read messages"));
  if (count.size() != 1) throw CubeError(impl_->what("'messages/case_index' is not 1-D: a damaged or foreign cube"));
  auto indices_set = impl_->open_checked("messages/case_index", {H5T_INTEGER}, count, sizeof(std::int64_t));
  auto messages_set = impl_->open_checked("messages/text", {H5T_STRING}, count, sizeof(char*));
  std::vector<std::int64_t> indices(static_cast<std::size_t>(count[0]));
  if (indices.empty()) return notes;
  h5::check(H5Dread(indices_set, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, indices.data()),
            impl_->what("cannot read messages"));
  const auto messages = impl_->labelled([&] { return h5::read_strings(messages_set, "messages/text"); });
  for (std::size_t i = 0; i < indices.size() && i < messages.size(); ++i) notes.emplace_back(indices[i], messages[i]);
  return notes;
}

std::vector<std::string> CubeReader::damage() const {
  std::vector<std::string> problems;
  auto attempt = [&](const std::string& name, const auto& read) {
    try {
      read();
    } catch (const CubeError& e) {
      problems.push_back(name + ": " + e.what());
    }
  };
  attempt(kStatusName, [&] { (void)read_status(); });
  for (const auto& m : layout_.metrics) attempt(m.name, [&] { (void)read_metric(m.name); });
  for (const auto& v : layout_.side_variables) attempt(v.name, [&] { (void)read_side(v.name); });
  attempt("messages", [&] { (void)read_notes(); });
  return problems;
}

HistoryTable CubeReader::read_history(const std::string& name) const {
  const std::string where = "histories/" + name;
  auto group = h5::group(H5Gopen2(impl_->file, where.c_str(), H5P_DEFAULT), impl_->what("cannot open " + where));
  HistoryTable table;
  table.name = name;
  table.attributes = h5::read_attributes(group);
  for (const auto& column : link_names(group)) {  // creation order: the time axis first
    const auto length = h5::extent(impl_->open(where + "/" + column), impl_->what("cannot read " + where));
    if (length.size() != 1) throw CubeError(impl_->what("'" + where + "/" + column + "' is not 1-D: a damaged or foreign cube"));
    auto d = impl_->open_checked(where + "/" + column, {H5T_FLOAT, H5T_INTEGER}, length, sizeof(double));
    std::vector<double> values(static_cast<std::size_t>(length[0]));
    if (!values.empty())
      h5::check(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
                impl_->what("cannot read " + where + "/" + column));
    table.columns.push_back({column, h5::read_text_attribute(d, "units"), h5::read_text_attribute(d, "long_name")});
    table.values.push_back(std::move(values));
  }
  return table;
}

std::vector<std::string> CubeReader::history_names() const {
  if (H5Lexists(impl_->file, "histories", H5P_DEFAULT) <= 0) return {};
  auto group = h5::group(H5Gopen2(impl_->file, "histories", H5P_DEFAULT), impl_->what("cannot open histories"));
  return link_names(group);
}

}  // namespace pcrf::cube

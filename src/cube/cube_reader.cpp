// Result cube reader (see cube_reader.hpp). Dimensions come from the dimension scales
// attached to `status`; auxiliary coordinates from its CF `coordinates` attribute; metrics
// are the other float variables over the same dimensions.
#include "pcrf/cube/cube_reader.hpp"

#include <hdf5_hl.h>

#include <algorithm>
#include <sstream>

#include "cube/hdf5_util.hpp"

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
  Coordinate read_coordinate(const std::string& name) const;
};

Coordinate CubeReader::Impl::read_coordinate(const std::string& name) const {
  auto d = open(name);
  Coordinate c;
  c.name = name;
  c.dimension = H5DSis_scale(d) > 0 ? name : dimension_name(d, 0);
  c.units = h5::read_text_attribute(d, "units");
  c.long_name = h5::read_text_attribute(d, "long_name");
  auto t = h5::type(H5Dget_type(d), what("cannot read the type of '" + name + "'"));
  const auto type_class = H5Tget_class(t);
  if (type_class == H5T_STRING) {
    c.is_text = true;
    c.strings = h5::read_strings(d);
    return c;
  }
  c.is_index = type_class == H5T_INTEGER;
  auto s = h5::space(H5Dget_space(d), what("cannot read '" + name + "'"));
  c.numbers.resize(static_cast<std::size_t>(H5Sget_simple_extent_npoints(s)));
  h5::check(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, c.numbers.data()),
            what("cannot read '" + name + "'"));
  return c;
}

CubeReader::CubeReader(const std::filesystem::path& file) : file_(file), impl_(std::make_unique<Impl>()) {
  h5::silence_library_errors();
  impl_->label = file.string();
  if (!std::filesystem::exists(file)) throw CubeError(impl_->what("no such file"));
  if (H5Fis_hdf5(file.c_str()) <= 0) throw CubeError(impl_->what("not an HDF5 file"));
  impl_->file = h5::file(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), impl_->what("cannot open"));
  if (H5Lexists(impl_->file, kStatusName, H5P_DEFAULT) <= 0)
    throw CubeError(impl_->what("not a pcrf result cube (no 'status' variable)"));
  auto status = impl_->open(kStatusName);
  auto s = h5::space(H5Dget_space(status), impl_->what("cannot read 'status'"));
  const int rank = H5Sget_simple_extent_ndims(s);
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
  H5Sget_simple_extent_dims(s, dims.data(), nullptr);
  for (std::size_t d = 0; d < dims.size(); ++d) {
    const std::string name = dimension_name(status, static_cast<unsigned>(d));
    if (name.empty()) throw CubeError(impl_->what("dimension " + std::to_string(d) + " of 'status' has no coordinate"));
    layout_.dimensions.push_back({name, static_cast<std::size_t>(dims[d])});
    layout_.coordinates.push_back(impl_->read_coordinate(name));
  }
  for (const auto& name : split_words(h5::read_text_attribute(status, "coordinates")))
    layout_.coordinates.push_back(impl_->read_coordinate(name));
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
}

CubeReader::~CubeReader() = default;

std::vector<std::int8_t> CubeReader::read_status() const {
  auto d = impl_->open(kStatusName);
  std::vector<std::int8_t> values(static_cast<std::size_t>(layout_.case_count()));
  h5::check(H5Dread(d, H5T_NATIVE_INT8, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
            impl_->what("cannot read 'status'"));
  return values;
}

std::vector<double> CubeReader::read_metric(const std::string& name) const {
  const bool known = std::any_of(layout_.metrics.begin(), layout_.metrics.end(),
                                 [&](const MetricVariable& m) { return m.name == name; });
  if (!known) throw CubeError(impl_->what("has no metric '" + name + "'"));
  auto d = impl_->open(name);
  std::vector<double> values(static_cast<std::size_t>(layout_.case_count()));
  h5::check(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
            impl_->what("cannot read '" + name + "'"));
  return values;
}

std::vector<double> CubeReader::read_side(const std::string& name) const {
  const SideVariable* v = layout_.find_side_variable(name);
  if (v == nullptr) throw CubeError(impl_->what("has no variable '" + name + "' (over some of its dimensions)"));
  auto d = impl_->open(name);
  std::vector<double> values(layout_.side_size(*v));
  h5::check(H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
            impl_->what("cannot read '" + name + "'"));
  return values;
}

std::vector<std::pair<std::int64_t, std::string>> CubeReader::read_notes() const {
  std::vector<std::pair<std::int64_t, std::string>> notes;
  if (H5Lexists(impl_->file, "messages", H5P_DEFAULT) <= 0) return notes;
  auto indices_set = impl_->open("messages/case_index");
  auto messages_set = impl_->open("messages/text");
  auto s = h5::space(H5Dget_space(indices_set), impl_->what("cannot read messages"));
  std::vector<std::int64_t> indices(static_cast<std::size_t>(H5Sget_simple_extent_npoints(s)));
  if (!indices.empty())
    h5::check(H5Dread(indices_set, H5T_NATIVE_INT64, H5S_ALL, H5S_ALL, H5P_DEFAULT, indices.data()),
              impl_->what("cannot read messages"));
  const auto messages = indices.empty() ? std::vector<std::string>{} : h5::read_strings(messages_set);
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
    auto d = impl_->open(where + "/" + column);
    auto s = h5::space(H5Dget_space(d), impl_->what("cannot read " + where));
    std::vector<double> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(s)));
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

// Result cube writer (see cube_writer.hpp): creates or reopens the file, keeps the cube in
// memory and writes the chunks that changed at each flush.
#include "pcrf/cube/cube_writer.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include <hdf5_hl.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <tuple>

#include "cube/hdf5_util.hpp"
#include "pcrf/cube/chunk_grid.hpp"
#include "pcrf/cube/cube_journal.hpp"
#include "pcrf/cube/cube_part.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/sealed_chunk.hpp"
#include "pcrf/io/atomic_file.hpp"
#include "pcrf/io/checked_stream.hpp"
#include "pcrf/io/file_kind.hpp"

namespace pcrf::cube {
namespace {

constexpr const char* kMessagesGroup = "messages";
constexpr const char* kHistoriesGroup = "histories";
// kDeflateLevel (sealed_chunk.hpp): the one zlib level of the cube's chunked variables.
constexpr hsize_t kNotesChunk = 256;
// coordinate_chunk_values (chunk_grid.hpp): values per chunk of a chunked coordinate.
const double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Creation-order tracking as netCDF-4 files have it (readers then list in that order).
h5::Handle ordered_plist(hid_t plist_class) {
  auto p = h5::plist(H5Pcreate(plist_class), "cannot make a property list");
  const unsigned flags = H5P_CRT_ORDER_TRACKED | H5P_CRT_ORDER_INDEXED;
  if (plist_class != H5P_DATASET_CREATE) h5::check(H5Pset_link_creation_order(p, flags), "cannot set link order");
  h5::check(H5Pset_attr_creation_order(p, flags), "cannot set attribute order");
  return p;
}

std::vector<hsize_t> to_hsize(const std::vector<std::size_t>& values) {
  return {values.begin(), values.end()};
}

void write_descriptive_attributes(hid_t object, const std::string& units, const std::string& long_name) {
  if (!units.empty()) h5::write_attribute(object, "units", units);
  if (!long_name.empty()) h5::write_attribute(object, "long_name", long_name);
}

/// True for a coordinate whose values are written into the cube on disk after its creation,
/// piece by piece (write_long_coordinates), not into the in-memory image.
bool written_later(const Coordinate& c) { return c.written_later(); }

/// The chunk extents of dataset `set` (of `rank` dimensions) when it stores its chunks filtered
/// as a sealed chunk is (shuffled, then deflated: sealed_chunk.hpp), so that a raw chunk write
/// takes a sealed chunk's bytes as they are; nullopt otherwise (contiguous, or filtered
/// otherwise: a variable of an earlier version's cube).
std::optional<std::vector<hsize_t>> sealed_chunk_extents(hid_t set, std::size_t rank, const std::string& problem) {
  auto dcpl = h5::plist(H5Dget_create_plist(set), problem);
  std::vector<hsize_t> chunk(rank + 1, 0);
  if (H5Pget_layout(dcpl) != H5D_CHUNKED ||
      H5Pget_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data()) != static_cast<int>(rank) ||
      H5Pget_nfilters(dcpl) != 2)
    return std::nullopt;
  auto filter = [&](unsigned k) {
    unsigned flags = 0, config = 0, values[8] = {};
    std::size_t n = 8;
    char name[64] = {};
    return H5Pget_filter2(dcpl, k, &flags, &n, values, sizeof name, name, &config);
  };
  if (filter(0) != H5Z_FILTER_SHUFFLE || filter(1) != H5Z_FILTER_DEFLATE) return std::nullopt;
  chunk.resize(rank);
  return chunk;
}

/// A 1-D coordinate variable (text, index or numbers); its values are written here unless
/// written_later. A chunked one in chunks of `chunk_values` (coordinate_chunk_values); one
/// written_live with the fill NaN (HDF5's and netCDF's `_FillValue`), as a metric: until its
/// chunk is written, a reader sees no value there.
h5::Handle create_coordinate(hid_t parent, const Coordinate& c, std::size_t chunk_values) {
  const std::string what = "cannot create coordinate '" + c.name + "'";
  const hsize_t n = c.size();
  auto s = h5::space(H5Screate_simple(1, &n, nullptr), what);
  auto dcpl = ordered_plist(H5P_DATASET_CREATE);
  if (c.chunked()) {
    const hsize_t chunk = chunk_values;
    h5::check(H5Pset_chunk(dcpl, 1, &chunk), what);
    h5::check(H5Pset_shuffle(dcpl), what);
    h5::check(H5Pset_deflate(dcpl, kDeflateLevel), what);
  }
  if (c.written_live()) h5::check(H5Pset_fill_value(dcpl, H5T_NATIVE_DOUBLE, &kNaN), what);
  const bool later = written_later(c);
  h5::Handle d;
  if (c.is_text) {
    auto t = h5::vlen_string_type();
    d = h5::dataset(H5Dcreate2(parent, c.name.c_str(), t, s, H5P_DEFAULT, dcpl, H5P_DEFAULT), what);
    if (!later) h5::write_strings(d, c.strings);
  } else if (c.is_index) {
    d = h5::dataset(H5Dcreate2(parent, c.name.c_str(), H5T_STD_I32LE, s, H5P_DEFAULT, dcpl, H5P_DEFAULT), what);
    std::vector<std::int32_t> values(c.numbers.begin(), c.numbers.end());
    if (!later) h5::check(H5Dwrite(d, H5T_NATIVE_INT32, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), what);
  } else {
    d = h5::dataset(H5Dcreate2(parent, c.name.c_str(), H5T_IEEE_F64LE, s, H5P_DEFAULT, dcpl, H5P_DEFAULT), what);
    if (!later) h5::check(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, c.numbers.data()), what);
    if (c.written_live()) h5::write_attribute(d, "_FillValue", kNaN);
  }
  write_descriptive_attributes(d, c.units, c.long_name);
  return d;
}

/// Writes values [first, first + count) of a coordinate into its dataset `d`.
void write_coordinate_piece(hid_t d, const Coordinate& c, hsize_t first, hsize_t count, const std::string& what) {
  auto file_space = h5::space(H5Dget_space(d), what);
  h5::check(H5Sselect_hyperslab(file_space, H5S_SELECT_SET, &first, nullptr, &count, nullptr), what);
  auto memory = h5::space(H5Screate_simple(1, &count, nullptr), what);
  const auto at = [&](hsize_t k) { return static_cast<std::size_t>(first + k); };
  if (c.is_text) {
    std::vector<std::string> texts(count);
    std::vector<const char*> pointers(count);
    for (hsize_t k = 0; k < count; ++k) {
      texts[k] = c.text(at(k));
      pointers[k] = texts[k].c_str();
    }
    auto t = h5::vlen_string_type();
    h5::check(H5Dwrite(d, t, memory, file_space, H5P_DEFAULT, pointers.data()), what);
  } else if (c.is_index) {
    std::vector<std::int32_t> values(count);
    for (hsize_t k = 0; k < count; ++k) values[k] = static_cast<std::int32_t>(c.number(at(k)));
    h5::check(H5Dwrite(d, H5T_NATIVE_INT32, memory, file_space, H5P_DEFAULT, values.data()), what);
  } else {
    std::vector<double> values(count);
    for (hsize_t k = 0; k < count; ++k) values[k] = c.number(at(k));
    h5::check(H5Dwrite(d, H5T_NATIVE_DOUBLE, memory, file_space, H5P_DEFAULT, values.data()), what);
  }
}

void write_global_attribute(hid_t file, const Attribute& a) {
  std::visit([&](const auto& value) { h5::write_attribute(file, a.name, value); }, a.value);
}

std::string join(const std::vector<std::string>& words) {
  std::string text;
  for (const auto& w : words) text += (text.empty() ? "" : " ") + w;
  return text;
}

CheckpointObserver checkpoint_observer = nullptr;

/// A kill point of a checkpoint (crash tests stop the process here).
void reached(CheckpointStep step) {
  if (checkpoint_observer != nullptr) checkpoint_observer(step);
}

/// A fresh journal id for a fold: positive, never 0 (which means "none").
std::int64_t draw_journal_id() {
  std::random_device device;
  const std::uint64_t high = device(), low = device();
  const auto id = static_cast<std::int64_t>(((high << 32) ^ low) & 0x7fff'ffff'ffff'ffffull);
  return id == 0 ? 1 : id;
}

}  // namespace

void observe_checkpoints(CheckpointObserver observer) { checkpoint_observer = observer; }

bool valid_group_name(std::string_view name) {
  return !name.empty() && name.size() <= 255 && name != "." && name != ".." &&
         std::all_of(name.begin(), name.end(), [](char c) {
           return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
         });
}

struct CubeWriter::Impl {
  std::filesystem::path path;
  CubeLayout layout;
  ChunkGrid grid;
  h5::Handle file;  // declared first: closed last
  std::vector<h5::Handle> scales;  // one per dimension
  std::vector<h5::Handle> metric_sets;
  std::vector<h5::Handle> side_sets;  // one per layout.side_variables
  h5::Handle status_set;
  /// The values stored since the last checkpoint, per chunk: rank 0 holds only these (and
  /// the status of every case), never the whole cube.
  struct ChunkValues {
    std::vector<double> values;  ///< [metric * count + k]
    std::vector<char> stored;    ///< [k]: this case has values here
  };
  std::map<std::size_t, ChunkValues> pending_chunks;
  /// Chunks sealed whole by a worker since the last checkpoint (their results never unpacked here).
  std::map<std::size_t, SealedChunk> pending_sealed;
  std::size_t pending_bytes = 0;
  std::vector<std::pair<std::int64_t, std::string>> pending_notes;  // since the last checkpoint
  bool rewrite_notes = false;  // the file's notes are all in pending_notes: write them anew
  std::vector<HistoryTable> pending_histories;                      // likewise
  std::int64_t pending_results = 0;  // store() calls since the last checkpoint
  bool sides_changed = true;
  bool on_disk = false;  // `path` holds this cube's last fold
  bool closed = false;
  struct stat identity {};  // of the file at `path` this writer made or opened (when on_disk)
  // The journal (cube_journal.hpp): what was checkpointed since the last fold.
  std::int64_t journal_id = 0;             // the folded cube's; 0: none (a new cube, or an earlier version's)
  std::unique_ptr<JournalWriter> journal;  // open since the first append after the last fold
  std::uint64_t journal_keep_bytes = 0;    // --resume: where the first append continues the journal
  std::int64_t journal_records = 0;        // records appended since the last fold
  std::int64_t journal_results = 0;        // case results among them
  std::int64_t folded_results = 0;         // cases done in the folded cube
  std::vector<std::string> resume_notes;   // what --resume did to the journal (CubeWriter::resume_notes)
  // Ranks' parts (cube_part.hpp): chunks workers sealed and kept, folded by the next fold.
  std::int64_t part_id = 0;  // the cube's; 0: an earlier version's cube, whose workers send their chunks
  struct PartChunk {
    std::size_t part = 0;    // in `parts`
    std::size_t record = 0;  // its sealed record there
    bool counted = false;    // its statuses are in the writer's already (a --resume's part, read whole)
  };
  std::vector<std::unique_ptr<JournalReader>> parts;   // the parts read, open: records are read by reference
  std::map<std::size_t, PartChunk> part_chunks;         // chunks the next fold takes from them
  std::vector<std::filesystem::path> parts_to_remove;  // after the next fold's rename
  CoordinateSource* coordinate_source = nullptr;  // while the constructor creates the cube; null: seal here
  bool closing = false;  // the last fold (close): every coordinate chunk still missing is written
  // The live coordinates whose chunks the units carry (CubeWriter::unit_coordinates), and
  // their datasets in the file being written (opened at a unit's first piece).
  std::vector<UnitCoordinate> unit_coordinates;
  std::map<std::size_t, h5::Handle> coordinate_sets;
  // Coordinate chunks [coordinate][piece] this writer put in the cube or in the file being
  // folded: a hint that spares the close HDF5's look-up of each (2 k instructions a chunk, 1 a
  // result at 1.2 million cases); forgotten whenever a file being folded is dropped, so that
  // each one in it is in the file the next fold writes (a copy of the cube, or the stream).
  // A flag a piece, not a tree of pairs: marked for each of a unit's pieces during the run and
  // looked up for every piece at close (rank_costs.py: 0.2 instructions a result as a std::set).
  std::vector<std::vector<char>> pieces_written;
  bool piece_written(std::size_t coordinate, std::size_t piece) const {
    return coordinate < pieces_written.size() && piece < pieces_written[coordinate].size() &&
           pieces_written[coordinate][piece] != 0;
  }
  bool any_piece_written(std::size_t coordinate) const {
    return coordinate < pieces_written.size() &&
           std::find(pieces_written[coordinate].begin(), pieces_written[coordinate].end(), 1) != pieces_written[coordinate].end();
  }
  void mark_written(std::size_t coordinate, std::size_t piece, std::size_t pieces) {
    if (pieces_written.size() <= coordinate) pieces_written.resize(layout.coordinates.size());
    auto& flags = pieces_written[coordinate];
    if (flags.size() < pieces) flags.resize(pieces, 0);
    flags[piece] = 1;
  }
  // The streaming fold (CubeWriter::stream_kept): the next fold's <cube>.partial, open during
  // the run, into which the chunks workers report kept are written as they come. While it is
  // open, `file`, `metric_sets` and `status_set` are its handles (declared after `file`: the
  // .partial is removed before they close, and with it what was streamed).
  std::unique_ptr<io::AtomicFile> stream;
  struct stat stream_identity {};  // of the .partial the stream copied the cube into (fstat)
  bool stream_off = false;  // streaming failed once (or cannot be): the end's fold assembles the parts
  std::string stream_note;  // why, until said (CubeWriter::take_stream_note)
  struct Streamed {
    int rank = -1;                      // whose part it came from; -1: not streamed
    bool alike = false;                 // its status variable: one code for the whole chunk …
    std::int8_t code = kStatusNotRun;   // … this one (else each case's, read from the part at the fold)
  };
  std::vector<Streamed> streamed;         // [chunk], sized at the first chunk streamed: in the open
                                          // stream, or in a cube a streaming fold renamed into place
  std::vector<std::size_t> stream_chunks;  // those in the open stream (reset when it is dropped)
  std::map<int, std::unique_ptr<JournalReader>> live_parts;  // parts read during the run, by rank (released)

  Impl(std::filesystem::path p, CubeLayout l)
      : path(std::move(p)), layout(std::move(l)), grid(layout_grid(layout)) {
    // The id is the writer's to draw (a merged cube's layout comes from a part).
    std::erase_if(layout.attributes,
                  [](const Attribute& a) { return a.name == kJournalIdName || a.name == kPartIdName; });
  }

  std::string what(const std::string& problem) const { return path.string() + ": " + problem; }

  void create(const std::filesystem::path& target);
  enum class Checkpoint { kAppendOrFold, kAppend, kFold };
  void checkpoint(StatusBook& status, Checkpoint how);
  bool fold_due() const;
  void append(const StatusBook& status);
  void fold(StatusBook& status);
  void fold_copy(StatusBook& status, std::int64_t new_id);
  void clear_pending();
  void write_new_file(io::AtomicFile& target);
  void write_long_coordinates(const std::filesystem::path& target);
  void write_sealed_piece(hid_t d, const CoordinatePiece& piece, const std::string& problem);
  std::size_t chunk_values_of(const Coordinate& c) const;
  void write_missing_coordinates(const StatusBook& status);
  void find_unit_coordinates(hid_t in);
  void write_piece(std::size_t unit, std::size_t coordinate, std::size_t piece, const char* bytes, std::size_t size);
  void update(const std::filesystem::path& target, StatusBook& status, std::int64_t new_id);
  void open_for_writing(const std::filesystem::path& target);
  void check_free_space(const std::filesystem::path& target, bool copied = false) const;
  void remember_identity();
  void check_identity() const;
  [[noreturn]] void fail(const CubeError& error) const;
  void close_handles();
  void open_existing(StatusBook& status);
  void replay_journal(StatusBook& status);
  void set_aside_journal(const std::string& problem);
  void set_aside(const std::filesystem::path& from, const std::string& problem, const std::string& what);
  void read_part(const std::filesystem::path& part, StatusBook& status, bool inflate, bool count_now,
                 std::unique_ptr<JournalReader> live = nullptr);
  void take_run_parts(StatusBook& status, bool count_now);
  void write_parts(std::vector<std::pair<std::int64_t, std::string>>& notes, StatusBook& status);
  PartHeader part_header_of_cube() const {
    return {part_id, layout.case_count(), layout.metrics.size(), layout.text_attribute(kFingerprintName)};
  }
  void remove_parts();
  void stream_kept(std::size_t chunk, int rank);
  JournalReader* live_part(int rank);
  void open_stream();
  bool fold_stream(StatusBook& status, std::int64_t new_id);
  void drop_stream(const std::string& reason);
  void check_stream_identity(const struct stat& now, const std::filesystem::path& partial, const char* when) const;
  bool streamed_from(std::size_t chunk, int rank) const;
  h5::Handle create_cube_variable(const std::string& name, hid_t file_type, hid_t memory_type,
                                  const void* fill);
  h5::Handle create_side_variable(const SideVariable& v);
  void write_side(std::size_t index);
  void write_chunk(std::size_t chunk, const std::vector<JournalCases>& journaled, const ChunkValues* pending,
                   const StatusBook& status);
  bool raw_writable() const;
  void write_sealed(const SealedChunk& sealed, bool raw, std::vector<JournalCases>& unsealed);
  void write_variable_raw(const std::vector<hsize_t>& offset, std::size_t v, const char* bytes, std::size_t size);
  void append_notes(const std::vector<std::pair<std::int64_t, std::string>>& notes);
  void write_history(const HistoryTable& table);
};

CubeWriter::CubeWriter(std::filesystem::path file, CubeLayout layout, OpenMode mode, CoordinateSource* coordinates)
    : impl_(std::make_unique<Impl>(std::move(file), std::move(layout))),
      statuses_(impl_->grid, static_cast<std::size_t>(impl_->layout.case_count())) {
  impl_->coordinate_source = coordinates;
  struct Forget {  // the source serves the creation only: it may not outlive the constructor
    Impl& impl;
    ~Forget() { impl.coordinate_source = nullptr; }
  } forget{*impl_};
  h5::silence_library_errors();
  // The files beside the cube are made by the writer alone: a symbolic link, a FIFO or a
  // second name of another file there is refused before anything is read or written.
  try {
    io::check_sidecar(journal_path(impl_->path), io::kJournalWhat);
    io::check_sidecar(impl_->path.string() + ".partial", io::kPartialWhat);
    for (const auto& part : part_files(impl_->path)) io::check_sidecar(part, io::kPartWhat);
  } catch (const io::OutputError& e) {
    throw CubeError(e.what());
  }
  std::error_code error;  // a link loop, a folder that cannot be searched: one line, not an exception
  const bool exists = std::filesystem::exists(impl_->path, error);
  if (error) throw CubeError(impl_->what("cannot open: " + error.message()));
  if (mode == OpenMode::kCreate && exists) throw CubeError(impl_->what("already exists"));
  if (mode == OpenMode::kResume && exists) {
    impl_->open_existing(statuses_);
    impl_->on_disk = true;
    impl_->remember_identity();
    resumed_ = true;
    // The parts of the stopped run: untrusted, read whole (a forged or foreign one is set
    // aside); their chunks not done yet count as done and go in at the first fold, below.
    for (const auto& part : part_files(impl_->path)) impl_->read_part(part, statuses_, true, true);
  } else {
    // A new cube (--overwrite's included) has parts of its own: any left here are another
    // cube's, removed (regular files only, checked above) once the new cube is in place.
    impl_->part_id = draw_journal_id();
    impl_->layout.attributes.push_back({kPartIdName, impl_->part_id});
    impl_->parts_to_remove = part_files(impl_->path);
  }
  flush();  // the file exists, complete, from the start (an overwritten one is replaced whole)
}

CubeWriter::~CubeWriter() {
  if (impl_ && !impl_->closed) {
    try {
      append();  // keep what was computed even when the run is failing: the cheapest checkpoint
    } catch (...) {
    }
  }
}

void CubeWriter::Impl::create(const std::filesystem::path& target) {
  auto fcpl = ordered_plist(H5P_FILE_CREATE);
  // In memory (the core driver, no backing store): the file image is written to disk by
  // checkpoint(), so a full disk is a write() error of ours, never a half-closed HDF5 file.
  auto fapl = h5::plist(H5Pcreate(H5P_FILE_ACCESS), what("cannot make a property list"));
  h5::check(H5Pset_fapl_core(fapl, 1 << 20, 0), what("cannot use the in-memory driver"));
  file = h5::file(H5Fcreate(target.c_str(), H5F_ACC_TRUNC, fcpl, fapl), what("cannot create the file"));
  h5::use_chunk_indices_of_1_10(file, what("cannot choose the file format"));
  for (const auto& a : layout.attributes) write_global_attribute(file, a);
  // Dimension coordinates first (netCDF-4 dimensions), then auxiliary coordinates.
  for (const auto& dim : layout.dimensions) {
    const Coordinate* c = layout.find_coordinate(dim.name);
    if (c == nullptr || c->size() != dim.size)
      throw CubeError(what("dimension '" + dim.name + "' needs a coordinate of " + std::to_string(dim.size) + " values"));
    scales.push_back(create_coordinate(file, *c, chunk_values_of(*c)));
    h5::check(H5DSset_scale(scales.back(), dim.name.c_str()), what("cannot make '" + dim.name + "' a dimension"));
  }
  for (const auto& c : layout.coordinates) {
    if (c.name == c.dimension) continue;
    auto dim = std::find_if(layout.dimensions.begin(), layout.dimensions.end(),
                            [&](const Dimension& d) { return d.name == c.dimension; });
    if (dim == layout.dimensions.end()) throw CubeError(what("coordinate '" + c.name + "' is over an unknown dimension"));
    auto d = create_coordinate(file, c, chunk_values_of(c));
    h5::check(H5DSattach_scale(d, scales[static_cast<std::size_t>(dim - layout.dimensions.begin())], 0),
              what("cannot attach dimension to '" + c.name + "'"));
  }
  find_unit_coordinates(file);
  for (const auto& m : layout.metrics) {
    metric_sets.push_back(create_cube_variable(m.name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &kNaN));
    write_descriptive_attributes(metric_sets.back(), m.units, m.long_name);
  }
  for (std::size_t v = 0; v < layout.side_variables.size(); ++v) {
    side_sets.push_back(create_side_variable(layout.side_variables[v]));
  }
  const std::int8_t not_run = kStatusNotRun;
  status_set = create_cube_variable(kStatusName, H5T_STD_I8LE, H5T_NATIVE_INT8, &not_run);
  std::vector<std::int8_t> flag_values;
  std::vector<std::string> flag_meanings;
  for (const auto& f : layout.status_flags) {
    flag_values.push_back(f.value);
    flag_meanings.push_back(f.meaning);
  }
  if (std::find(flag_values.begin(), flag_values.end(), kStatusNotRun) == flag_values.end()) {
    flag_values.push_back(kStatusNotRun);  // the fill: a case not run (yet)
    flag_meanings.push_back(kStatusNotRunName);
  }
  h5::write_attribute(status_set, "long_name", std::string("how the case ended"));
  h5::write_attribute(status_set, "flag_values", flag_values);
  h5::write_attribute(status_set, "flag_meanings", join(flag_meanings));
}

h5::Handle CubeWriter::Impl::create_cube_variable(const std::string& name, hid_t file_type,
                                                  hid_t memory_type, const void* fill) {
  const std::string problem = "cannot create variable '" + name + "'";
  const auto dims = to_hsize(layout.shape());
  auto s = h5::space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), what(problem));
  auto dcpl = ordered_plist(H5P_DATASET_CREATE);
  const auto chunk = to_hsize(grid.chunk_shape());
  h5::check(H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data()), what(problem));
  h5::check(H5Pset_shuffle(dcpl), what(problem));
  h5::check(H5Pset_deflate(dcpl, kDeflateLevel), what(problem));
  h5::check(H5Pset_fill_value(dcpl, memory_type, fill), what(problem));
  auto d = h5::dataset(H5Dcreate2(file, name.c_str(), file_type, s, H5P_DEFAULT, dcpl, H5P_DEFAULT), what(problem));
  // The metrics' _FillValue is NaN (a value that does not exist). The status has none: its
  // fill (not run) is one of its CF flags, and an integer with a _FillValue reaches xarray as
  // floats with NaN, where it must stay an integer with flag meanings.
  if (memory_type != H5T_NATIVE_INT8) h5::write_attribute(d, "_FillValue", *static_cast<const double*>(fill));
  for (std::size_t i = 0; i < scales.size(); ++i)
    h5::check(H5DSattach_scale(d, scales[i], static_cast<unsigned>(i)), what(problem + ": cannot attach dimensions"));
  const auto auxiliary = layout.auxiliary_names();
  if (!auxiliary.empty()) h5::write_attribute(d, "coordinates", join(auxiliary));
  return d;
}

h5::Handle CubeWriter::Impl::create_side_variable(const SideVariable& v) {
  const std::string problem = "cannot create variable '" + v.name + "'";
  std::vector<hsize_t> dims;
  std::vector<std::size_t> scale_of;
  for (const auto& name : v.dimensions) {
    const auto d = layout.find_dimension(name);
    if (!d) throw CubeError(what(problem + ": no dimension '" + name + "'"));
    dims.push_back(layout.dimensions[*d].size);
    scale_of.push_back(*d);
  }
  auto s = h5::space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), what(problem));
  auto dcpl = ordered_plist(H5P_DATASET_CREATE);
  h5::check(H5Pset_fill_value(dcpl, H5T_NATIVE_DOUBLE, &kNaN), what(problem));
  auto d = h5::dataset(H5Dcreate2(file, v.name.c_str(), H5T_IEEE_F64LE, s, H5P_DEFAULT, dcpl, H5P_DEFAULT), what(problem));
  h5::write_attribute(d, "_FillValue", kNaN);
  write_descriptive_attributes(d, v.units, v.long_name);
  for (std::size_t i = 0; i < scale_of.size(); ++i)
    h5::check(H5DSattach_scale(d, scales[scale_of[i]], static_cast<unsigned>(i)), what(problem + ": cannot attach dimensions"));
  return d;
}

void CubeWriter::Impl::write_side(std::size_t index) {
  const auto& v = layout.side_variables[index];
  if (v.values.empty()) return;
  h5::check(H5Dwrite(side_sets[index], H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.values.data()),
            what("cannot write '" + v.name + "'"));
}

void CubeWriter::store_side(const std::string& name, std::vector<double> values) {
  auto& vars = impl_->layout.side_variables;
  for (std::size_t v = 0; v < vars.size(); ++v) {
    if (vars[v].name != name) continue;
    if (values.size() != impl_->layout.side_size(vars[v]))
      throw CubeError(impl_->what("'" + name + "' takes " + std::to_string(impl_->layout.side_size(vars[v])) +
                                  " values, got " + std::to_string(values.size())));
    vars[v].values = std::move(values);
    impl_->sides_changed = true;
    return;
  }
  throw CubeError(impl_->what("has no side variable '" + name + "'"));
}

void CubeWriter::Impl::open_existing(StatusBook& status) {
  CubeReader reader(path);
  const auto& old = reader.layout();
  const std::string ours = layout.text_attribute(kFingerprintName);
  const std::string theirs = old.text_attribute(kFingerprintName);
  if (ours != theirs)
    throw CubeError(what("was made by a different study (its fingerprint " + theirs +
                         ", this study's " + ours + "); give another output file or use --overwrite"));
  if (old.shape() != layout.shape() || old.metrics.size() != layout.metrics.size())
    throw CubeError(what("has another shape or other metrics than this study"));
  // Its chunks as its file has them (an earlier version's may be cut otherwise than this
  // study's would be): its journal, its parts and the workers' units count them so, and so
  // do its statuses, per chunk.
  layout.chunk_shape = old.chunk_shape;
  grid = layout_grid(layout);
  status = StatusBook(grid, static_cast<std::size_t>(layout.case_count()));
  status.assign(reader.read_status());
  {  // which of its coordinates the units carry: those it stores as this version does
    const std::string cannot_open = what("cannot open");
    auto in = h5::file(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), cannot_open);
    find_unit_coordinates(in);
  }
  folded_results = status.done();
  journal_id = journal_id_of(old);
  part_id = part_id_of(old);
  // Values, notes and histories stay in the file (each fold starts from a copy of it) and in
  // the journal (each fold lays it over that copy). A cube of an earlier version has no
  // journal id, and fixed-size notes that cannot take more: its first checkpoint is a fold
  // that writes its notes once more, into extendible datasets.
  if (journal_id == 0) {
    pending_notes = reader.read_notes();
    rewrite_notes = true;
  } else {
    replay_journal(status);
  }
  // Side variables start from the study's values (the producer stores new ones).
}

/// The statuses of the journal's cases over the cube's; where appends continue it (its torn
/// tail, if any, cut off then). Every record is read once here, so that a damaged one stops
/// the run before it starts, not at a fold.
void CubeWriter::Impl::replay_journal(StatusBook& status) {
  std::optional<JournalReader> read;
  try {
    read.emplace(path, layout, journal_id);
    read->check_all();
  } catch (const JournalDamage& e) {
    set_aside_journal(e.what());  // its cases are computed again; nothing of it reaches the cube
    return;
  }
  const JournalReader& journaled = *read;
  if (!journaled.current()) return;  // none, or stale: the first append starts it anew
  // A chunk's last sealed record, then its records of cases that came after it.
  std::map<std::size_t, std::size_t> sealed_at;
  for (const auto& [chunk, records] : journaled.sealed_chunks()) {
    sealed_at[chunk] = records.back();
    const SealedChunk c = journaled.sealed(records.back());
    status.set_chunk(chunk, c.status);
  }
  for (const auto& [chunk, records] : journaled.chunks())
    for (const std::size_t r : records) {
      if (const auto s = sealed_at.find(chunk); s != sealed_at.end() && r < s->second) continue;
      const JournalCases c = journaled.cases(r);
      const auto first = static_cast<std::size_t>(grid.range(c.chunk).first);
      for (std::size_t j = 0; j < c.offsets.size(); ++j)
        status.set(c.chunk, static_cast<std::int64_t>(first + c.offsets[j]), c.status[j]);
    }
  if (journaled.dropped_bytes() > 0) {
    std::string text = journal_path(path).string() + ": its last " + std::to_string(journaled.dropped_bytes()) +
                       " bytes are dropped: ";
    if (journaled.dropped_records() > 0)
      text += std::to_string(journaled.dropped_records()) + " complete records of a checkpoint never closed (" +
              std::to_string(journaled.dropped_results()) + " results)" + (journaled.damaged() ? ", then " : "");
    if (journaled.damaged()) text += "a record that is torn or damaged (its results cannot be counted)";
    resume_notes.push_back(text + "; a run killed while it wrote, or damage: their cases are computed again");
  }
  journal_keep_bytes = journaled.valid_bytes();
  journal_results = journaled.results();
  journal_records = 1;  // at least the header: the next fold reads it
}

/// Renames a journal that cannot be replayed out of the way, exclusively (never over a file
/// there: <journal>.set-aside-1, -2, …), and says so: the next append starts a new journal.
void CubeWriter::Impl::set_aside_journal(const std::string& problem) {
  set_aside(journal_path(path), problem, "journal");
}

/// Renames a journal or a part that cannot be used out of the way, exclusively (never over a
/// file there: <file>.set-aside-1, -2, …), and says so.
void CubeWriter::Impl::set_aside(const std::filesystem::path& from, const std::string& problem, const std::string& what) {
  for (int k = 1; k <= 1000; ++k) {
    const std::filesystem::path to = from.string() + ".set-aside-" + std::to_string(k);
    bool moved = ::renameat2(AT_FDCWD, from.c_str(), AT_FDCWD, to.c_str(), RENAME_NOREPLACE) == 0;
    if (!moved && (errno == EINVAL || errno == ENOSYS)) {  // no RENAME_NOREPLACE here: link() never replaces
      moved = ::link(from.c_str(), to.c_str()) == 0;
      if (moved) ::unlink(from.c_str());
    }
    if (moved) {
      resume_notes.push_back(problem + ": the " + what + " cannot be replayed, so it is set aside as " + to.string() +
                             " and nothing of it is used; the cases it held are computed again (the cube's last fold holds " +
                             std::to_string(folded_results) + " of " + std::to_string(layout.case_count()) + " cases)");
      return;
    }
    if (errno != EEXIST) break;
  }
  throw CubeError(problem + "; it cannot be set aside (" + std::strerror(errno) + "): move it away to resume from the cube's last fold");
}

/// A rank's part (cube_part.hpp), read up to its first invalid record and checked against the
/// cube (`inflate`: every CRC computed and every sealed chunk inflated too, as --resume checks
/// the journal; a part of this run at its end, which its workers synced under its lock before
/// they reported each chunk and no kill can have torn since, is checked by its frames and
/// sizes here and by its statuses when each record is written: its CRCs were 150 instructions
/// a result, nearly all of the assembly). Its chunks that `status` has none done of are taken
/// by the next fold, read from the part then; a chunk done already (in the cube, its journal
/// or an earlier part) is skipped. With `count_now` their statuses count at once, each case's
/// (--resume: the run that continues must not compute them; take_parts: a producer reads
/// them before the last fold); at the end of a run they count when the fold writes them
/// (write_parts), chunk by chunk, not case by case. A part that cannot be used
/// (forged, foreign: another cube's or study's) is set aside and its cases computed again; one
/// that holds nothing is removed by the next fold.
void CubeWriter::Impl::read_part(const std::filesystem::path& part, StatusBook& status, bool inflate, bool count_now,
                                 std::unique_ptr<JournalReader> live) {
  std::unique_ptr<JournalReader> read;
  try {
    if (live) {  // read during the run (stream_kept): the records committed since, checked alike
      try {
        live->reopen_file();
        live->extend();
        read = std::move(live);
      } catch (const JournalDamage&) {
        throw;
      } catch (const CubeError&) {  // replaced or cut since: read anew, as it was before streaming
      }
    }
    if (!read) read = std::make_unique<JournalReader>(part, layout, part_header_payload(part_header_of_cube()), inflate);
    if (inflate) read->check_all();
  } catch (const JournalDamage& e) {
    set_aside(part, e.what(), "part");
    return;
  }
  if (read->foreign()) {
    set_aside(part, part.string() + ": is not a part of this cube (no part header of its id, cases, metrics and study)",
              "part");
    return;
  }
  parts_to_remove.push_back(part);
  if (!read->current()) return;  // its header torn as it was made: nothing in it
  if (read->dropped_bytes() > 0)
    resume_notes.push_back(part.string() + ": its last " + std::to_string(read->dropped_bytes()) + " bytes are dropped (" +
                           std::to_string(read->dropped_records()) + " complete records of a chunk never committed" +
                           (read->damaged() ? ", then a torn or damaged record" : "") +
                           "): a rank killed while it wrote, or damage; their cases are computed again");
  bool used = false;
  for (const auto& [chunk, records] : read->sealed_chunks()) {
    if (part_chunks.count(chunk) > 0 || status.chunk_done(chunk) > 0) continue;
    if (count_now) status.set_chunk(chunk, read->sealed_status(records.front()));
    part_chunks[chunk] = {parts.size(), records.front(), count_now};
    used = true;
  }
  if (!used) return;
  read->release_file();  // one part open at a time, however many ranks there were (write_parts)
  parts.push_back(std::move(read));
}

std::vector<double> CubeWriter::read_values(const std::string& metric) const {
  return read_values(metric, 0, impl_->grid.chunk_count());
}

/// The file's values of chunks [first_chunk, end_chunk), then, restricted to those chunks, the
/// journal's records, the taken parts' chunks and the pending ones laid over them, as a fold
/// would: each overlay is the one read_values() of the whole cube applies.
std::vector<double> CubeWriter::read_values(const std::string& metric, std::size_t first_chunk, std::size_t end_chunk) const {
  const auto& metrics = impl_->layout.metrics;
  const auto m = static_cast<std::size_t>(
      std::find_if(metrics.begin(), metrics.end(), [&](const MetricVariable& v) { return v.name == metric; }) -
      metrics.begin());
  if (m == metrics.size()) throw CubeError(impl_->what("has no metric '" + metric + "'"));
  const auto& grid = impl_->grid;
  ChunkSpan span;
  try {
    span = chunk_span(grid, first_chunk, end_chunk);
  } catch (const std::exception& e) {
    throw CubeError(impl_->what(e.what()));
  }
  std::vector<double> values = impl_->on_disk ? CubeReader(impl_->path).read_metric_chunks(metric, grid, first_chunk, end_chunk)
                                              : std::vector<double>(static_cast<std::size_t>(span.count), kNaN);
  const auto in_range = [&](std::size_t chunk) { return chunk >= first_chunk && chunk < end_chunk; };
  const auto at = [&](std::size_t chunk) { return static_cast<std::size_t>(grid.range(chunk).first - span.first); };
  const std::size_t padded = padded_elements(grid);
  auto lay_sealed = [&](const SealedChunk& c) {
    const auto r = grid.range(c.chunk);
    const std::vector<char> plain = unfilter(c.filtered[m], padded, sizeof(double), impl_->what("chunk " + std::to_string(c.chunk)));
    std::memcpy(values.data() + at(c.chunk), plain.data(), static_cast<std::size_t>(r.count) * sizeof(double));
  };
  if (impl_->journal_records > 0) {
    const JournalReader journaled(impl_->path, impl_->layout, impl_->journal_id);
    std::map<std::size_t, std::size_t> sealed_at;
    for (const auto& [chunk, records] : journaled.sealed_chunks()) {
      if (!in_range(chunk)) continue;
      sealed_at[chunk] = records.back();
      lay_sealed(journaled.sealed(records.back()));
    }
    for (const auto& [chunk, records] : journaled.chunks()) {
      if (!in_range(chunk)) continue;
      for (const std::size_t r : records) {
        if (const auto s = sealed_at.find(chunk); s != sealed_at.end() && r < s->second) continue;
        const JournalCases c = journaled.cases(r);
        const std::size_t first = at(c.chunk);
        for (std::size_t j = 0; j < c.offsets.size(); ++j) values[first + c.offsets[j]] = c.values[m * c.offsets.size() + j];
      }
    }
  }
  // The ranks' parts taken (--resume, take_parts): part by part, one open at a time, as a fold reads them.
  std::vector<std::vector<std::size_t>> by_part(impl_->parts.size());  // their records
  for (const auto& [chunk, on] : impl_->part_chunks)
    if (in_range(chunk)) by_part[on.part].push_back(on.record);
  for (std::size_t p = 0; p < by_part.size(); ++p) {
    if (by_part[p].empty()) continue;
    JournalReader& part = *impl_->parts[p];
    part.reopen_file();
    for (const std::size_t record : by_part[p]) lay_sealed(part.sealed(record));
    part.release_file();
  }
  for (const auto& [chunk, sealed] : impl_->pending_sealed)
    if (in_range(chunk)) lay_sealed(sealed);
  for (const auto& [chunk, stored] : impl_->pending_chunks) {
    if (!in_range(chunk)) continue;
    const auto count = static_cast<std::size_t>(grid.range(chunk).count);
    const std::size_t first = at(chunk);
    for (std::size_t k = 0; k < count; ++k)
      if (stored.stored[k]) values[first + k] = stored.values[m * count + k];
  }
  return values;
}

std::size_t CubeWriter::pending_bytes() const { return impl_->pending_bytes; }

void CubeWriter::store(std::int64_t index, std::int8_t status, const std::vector<double>& values) {
  if (index < 0 || static_cast<std::size_t>(index) >= statuses_.cases())
    throw CubeError(impl_->what("case index " + std::to_string(index) + " is outside the cube"));
  const std::size_t metrics = impl_->layout.metrics.size();
  if (values.size() != metrics)
    throw CubeError(impl_->what("case " + std::to_string(index) + " has " + std::to_string(values.size()) +
                                " values for " + std::to_string(metrics) + " metrics"));
  const std::size_t chunk = impl_->grid.chunk_of(index);
  statuses_.set(chunk, index, status);
  const auto r = impl_->grid.range(chunk);
  auto [it, fresh] = impl_->pending_chunks.try_emplace(chunk);
  auto& pending = it->second;
  const auto count = static_cast<std::size_t>(r.count);
  if (fresh) {
    pending.values.assign(metrics * count, kNaN);
    pending.stored.assign(count, 0);
    impl_->pending_bytes += metrics * count * sizeof(double) + count;
  }
  const auto k = static_cast<std::size_t>(index - r.first);
  pending.stored[k] = 1;
  ++impl_->pending_results;
  for (std::size_t m = 0; m < metrics; ++m) pending.values[m * count + k] = values[m];
}

void CubeWriter::store_sealed(SealedChunk sealed) {
  auto& impl = *impl_;
  if (sealed.chunk >= impl.grid.chunk_count() || sealed.filtered.size() != impl.layout.metrics.size() + 1 ||
      sealed.status.size() != static_cast<std::size_t>(impl.grid.range(sealed.chunk).count))
    throw CubeError(impl.what("a sealed chunk (" + std::to_string(sealed.chunk) + ") does not fit the cube"));
  const auto r = impl.grid.range(sealed.chunk);
  statuses_.set_chunk(sealed.chunk, sealed.status);
  if (const auto plain = impl.pending_chunks.find(sealed.chunk); plain != impl.pending_chunks.end()) {
    impl.pending_bytes -= plain->second.values.size() * sizeof(double) + plain->second.stored.size();
    impl.pending_chunks.erase(plain);  // the sealed chunk holds every case of it, newer
  }
  for (auto& note : sealed.notes) impl.pending_notes.push_back(std::move(note));
  sealed.notes.clear();
  std::size_t bytes = sealed.status.size();
  for (const auto& f : sealed.filtered) bytes += f.size();
  for (const auto& piece : sealed.coordinates) bytes += piece.filtered.size();  // held until the checkpoint too
  impl.pending_bytes += bytes;
  impl.pending_results += r.count;
  const std::size_t chunk = sealed.chunk;
  impl.pending_sealed.insert_or_assign(chunk, std::move(sealed));
}

const ChunkGrid& CubeWriter::grid() const { return impl_->grid; }

std::vector<std::size_t> CubeWriter::shape() const { return impl_->layout.shape(); }

void CubeWriter::store_note(std::int64_t index, std::string note) {
  impl_->pending_notes.emplace_back(index, std::move(note));
}

void CubeWriter::store_history(HistoryTable table) {
  auto& all = impl_->pending_histories;  // a case recomputed after --resume replaces its history
  std::erase_if(all, [&](const HistoryTable& t) { return t.name == table.name; });
  all.push_back(std::move(table));
}

/// One chunk: the values journaled since the last fold, then those stored since the last
/// checkpoint (`pending`, may be null), laid over what the file holds (a chunk may be
/// finished over several checkpoints), and the chunk's status.
void CubeWriter::Impl::write_chunk(std::size_t chunk, const std::vector<JournalCases>& journaled,
                                   const ChunkValues* pending, const StatusBook& status) {
  const auto r = grid.range(chunk);
  const auto start = to_hsize(r.start);
  const auto extent = to_hsize(r.extent);
  const auto count = static_cast<hsize_t>(r.count);
  auto memory = h5::space(H5Screate_simple(1, &count, nullptr), what("cannot make a dataspace"));
  auto select = [&](hid_t set, const std::string& name) {
    auto selection = h5::space(H5Dget_space(set), what("cannot select in '" + name + "'"));
    h5::check(H5Sselect_hyperslab(selection, H5S_SELECT_SET, start.data(), nullptr, extent.data(), nullptr),
              what("cannot select in '" + name + "'"));
    return selection;
  };
  std::vector<double> values(static_cast<std::size_t>(count));
  for (std::size_t m = 0; m < metric_sets.size(); ++m) {
    const auto& name = layout.metrics[m].name;
    const auto selection = select(metric_sets[m], name);
    h5::check(H5Dread(metric_sets[m], H5T_NATIVE_DOUBLE, memory, selection, H5P_DEFAULT, values.data()),
              what("cannot read '" + name + "'"));
    for (const auto& c : journaled)
      for (std::size_t j = 0; j < c.offsets.size(); ++j) values[c.offsets[j]] = c.values[m * c.offsets.size() + j];
    if (pending != nullptr)
      for (std::size_t k = 0; k < values.size(); ++k)
        if (pending->stored[k]) values[k] = pending->values[m * values.size() + k];
    h5::check(H5Dwrite(metric_sets[m], H5T_NATIVE_DOUBLE, memory, selection, H5P_DEFAULT, values.data()),
              what("cannot write '" + name + "'"));
  }
  const auto selection = select(status_set, kStatusName);
  std::vector<std::int8_t> scratch;
  h5::check(H5Dwrite(status_set, H5T_NATIVE_INT8, memory, selection, H5P_DEFAULT, status.chunk_codes(chunk, scratch).data()),
            what("cannot write '" + std::string(kStatusName) + "'"));
}

/// True when every metric and the status are stored as a sealed chunk is filtered: chunks of
/// the grid's shape, shuffled, then deflated (a cube of an earlier version may differ: its
/// sealed chunks are then written value by value).
bool CubeWriter::Impl::raw_writable() const {
  auto stores_sealed = [&](hid_t set) {
    const auto& shape = grid.chunk_shape();
    const auto chunk = sealed_chunk_extents(set, shape.size(), what("cannot read a variable's storage"));
    return chunk && std::equal(chunk->begin(), chunk->end(), shape.begin(), shape.end());
  };
  return std::all_of(metric_sets.begin(), metric_sets.end(), [&](const h5::Handle& m) { return stores_sealed(m); }) &&
         stores_sealed(status_set);
}

/// A sealed chunk into the file: raw, its filtered bytes as they are (H5Dwrite_chunk, no
/// filter skipped); otherwise unfiltered into `unsealed`, a record of every case of the chunk
/// for write_chunk.
/// One variable of a sealed chunk (metric v, or the status after the metrics) written raw, its
/// filtered bytes as they are, at the chunk that starts at `offset`.
void CubeWriter::Impl::write_variable_raw(const std::vector<hsize_t>& offset, std::size_t v, const char* bytes,
                                          std::size_t size) {
  const std::size_t metrics = metric_sets.size();
  const hid_t set = v < metrics ? static_cast<hid_t>(metric_sets[v]) : static_cast<hid_t>(status_set);
  h5::check_lazily(H5Dwrite_chunk(set, H5P_DEFAULT, 0, offset.data(), size, bytes), [&] {
    return what("cannot write a chunk of '" + (v < metrics ? layout.metrics[v].name : std::string(kStatusName)) + "'");
  });
}

void CubeWriter::Impl::write_sealed(const SealedChunk& sealed, bool raw, std::vector<JournalCases>& unsealed) {
  const auto r = grid.range(sealed.chunk);
  const std::size_t metrics = metric_sets.size();
  if (sealed.filtered.size() != metrics + 1 || sealed.status.size() != static_cast<std::size_t>(r.count))
    throw CubeError(what("a sealed chunk does not fit the cube"));
  if (raw) {
    const auto offset = to_hsize(r.start);
    for (std::size_t v = 0; v <= metrics; ++v) write_variable_raw(offset, v, sealed.filtered[v].data(), sealed.filtered[v].size());
    for (const auto& p : sealed.coordinates) write_piece(sealed.chunk, p.coordinate, p.piece, p.filtered.data(), p.filtered.size());
    return;
  }
  JournalCases all;
  all.chunk = sealed.chunk;
  const auto count = static_cast<std::size_t>(r.count);
  for (std::size_t k = 0; k < count; ++k) all.offsets.push_back(static_cast<std::uint32_t>(k));
  all.status = sealed.status;
  const std::size_t padded = padded_elements(grid);
  for (std::size_t m = 0; m < metrics; ++m) {
    const std::vector<char> plain = unfilter(sealed.filtered[m], padded, sizeof(double), what("chunk " + std::to_string(sealed.chunk)));
    const auto* values = reinterpret_cast<const double*>(plain.data());
    all.values.insert(all.values.end(), values, values + count);
  }
  unsealed.push_back(std::move(all));
}

/// Notes appended to /messages/case_index and /messages/text (extendible along their one
/// dimension).
void CubeWriter::Impl::append_notes(const std::vector<std::pair<std::int64_t, std::string>>& notes) {
  if (notes.empty()) return;
  const std::string problem = what("cannot write case messages");
  auto t = h5::vlen_string_type();
  h5::Handle index_set, message_set;
  hsize_t old_size = 0;
  if (rewrite_notes && H5Lexists(file, kMessagesGroup, H5P_DEFAULT) > 0)
    h5::check(H5Ldelete(file, kMessagesGroup, H5P_DEFAULT), problem);
  rewrite_notes = false;
  if (H5Lexists(file, kMessagesGroup, H5P_DEFAULT) > 0) {
    auto group = h5::group(H5Gopen2(file, kMessagesGroup, H5P_DEFAULT), problem);
    index_set = h5::dataset(H5Dopen2(group, "case_index", H5P_DEFAULT), problem);
    message_set = h5::dataset(H5Dopen2(group, "text", H5P_DEFAULT), problem);
    auto s = h5::space(H5Dget_space(index_set), problem);
    h5::check(H5Sget_simple_extent_dims(s, &old_size, nullptr), problem);
  } else {
    auto gcpl = ordered_plist(H5P_GROUP_CREATE);
    auto group = h5::group(H5Gcreate2(file, kMessagesGroup, H5P_DEFAULT, gcpl, H5P_DEFAULT), problem);
    const hsize_t zero = 0, unlimited = H5S_UNLIMITED;
    auto s = h5::space(H5Screate_simple(1, &zero, &unlimited), problem);
    auto dcpl = ordered_plist(H5P_DATASET_CREATE);
    h5::check(H5Pset_chunk(dcpl, 1, &kNotesChunk), problem);
    index_set = h5::dataset(H5Dcreate2(group, "case_index", H5T_STD_I64LE, s, H5P_DEFAULT, dcpl, H5P_DEFAULT), problem);
    h5::write_attribute(index_set, "long_name", std::string("linear index of the case"));
    h5::check(H5DSset_scale(index_set, "case_index"), problem);
    message_set = h5::dataset(H5Dcreate2(group, "text", t, s, H5P_DEFAULT, dcpl, H5P_DEFAULT), problem);
    h5::check(H5DSattach_scale(message_set, index_set, 0), problem);
  }
  const hsize_t added = notes.size(), new_size = old_size + added;
  std::vector<std::int64_t> indices;
  std::vector<const char*> texts;
  for (const auto& [index, text] : notes) {
    indices.push_back(index);
    texts.push_back(text.c_str());
  }
  auto memory = h5::space(H5Screate_simple(1, &added, nullptr), problem);
  for (auto [set, type, data] : {std::tuple<hid_t, hid_t, const void*>{index_set, H5T_NATIVE_INT64, indices.data()},
                                 std::tuple<hid_t, hid_t, const void*>{message_set, t, texts.data()}}) {
    h5::check(H5Dset_extent(set, &new_size), problem);
    auto selection = h5::space(H5Dget_space(set), problem);
    h5::check(H5Sselect_hyperslab(selection, H5S_SELECT_SET, &old_size, nullptr, &added, nullptr), problem);
    h5::check(H5Dwrite(set, type, memory, selection, H5P_DEFAULT, data), problem);
  }
}

void CubeWriter::Impl::write_history(const HistoryTable& table) {
  const std::string problem = what("cannot write history '" + table.name + "'");
  if (table.columns.empty() || table.columns.size() != table.values.size())
    throw CubeError(problem + ": columns and values do not match");
  h5::Handle parent;
  if (H5Lexists(file, kHistoriesGroup, H5P_DEFAULT) > 0) {
    parent = h5::group(H5Gopen2(file, kHistoriesGroup, H5P_DEFAULT), problem);
  } else {
    auto gcpl = ordered_plist(H5P_GROUP_CREATE);
    parent = h5::group(H5Gcreate2(file, kHistoriesGroup, H5P_DEFAULT, gcpl, H5P_DEFAULT), problem);
  }
  if (H5Lexists(parent, table.name.c_str(), H5P_DEFAULT) > 0)  // recomputed after --resume
    h5::check(H5Ldelete(parent, table.name.c_str(), H5P_DEFAULT), problem);
  auto gcpl = ordered_plist(H5P_GROUP_CREATE);
  auto group = h5::group(H5Gcreate2(parent, table.name.c_str(), H5P_DEFAULT, gcpl, H5P_DEFAULT), problem);
  for (const auto& a : table.attributes) write_global_attribute(group, a);
  h5::Handle time_scale;
  for (std::size_t c = 0; c < table.columns.size(); ++c) {
    const auto& column = table.columns[c];
    const hsize_t n = table.values[c].size();
    auto s = h5::space(H5Screate_simple(1, &n, nullptr), problem);
    auto dcpl = ordered_plist(H5P_DATASET_CREATE);
    if (n > 0) {
      const hsize_t chunk = std::min<hsize_t>(n, 8192);
      h5::check(H5Pset_chunk(dcpl, 1, &chunk), problem);
      h5::check(H5Pset_deflate(dcpl, kDeflateLevel), problem);
    }
    auto d = h5::dataset(H5Dcreate2(group, column.name.c_str(), H5T_IEEE_F64LE, s, H5P_DEFAULT, dcpl, H5P_DEFAULT), problem);
    if (n > 0) h5::check(H5Dwrite(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, table.values[c].data()), problem);
    write_descriptive_attributes(d, column.units, column.long_name);
    if (c == 0) {
      h5::check(H5DSset_scale(d, column.name.c_str()), problem);
      time_scale = std::move(d);
    } else {
      h5::check(H5DSattach_scale(d, time_scale, 0), problem);
    }
  }
}

void CubeWriter::Impl::close_handles() {
  coordinate_sets.clear();
  metric_sets.clear();
  side_sets.clear();
  status_set.reset();
  scales.clear();
  file.reset();
}

/// The folder that holds a file ("." for a bare name).
std::filesystem::path folder_of(const std::filesystem::path& file) {
  return file.parent_path().empty() ? std::filesystem::path(".") : file.parent_path();
}

/// A new cube with its coordinates, attributes and empty variables: built in memory (the
/// core driver) and written by us into `target`, so that a full disk is a write() error of ours.
void CubeWriter::Impl::write_new_file(io::AtomicFile& target) {
  std::vector<char> image;
  try {
    create(target.temporary());
    // The short coordinates are in the image now, and every later fold starts from a copy of
    // the file: their values need not stay in memory, neither while the image is copied out
    // nor for the run.
    for (auto& c : layout.coordinates)
      if (!written_later(c)) c.release_values();
    h5::check(H5Fflush(file, H5F_SCOPE_GLOBAL), what("cannot flush"));
    const ssize_t size = H5Fget_file_image(file, nullptr, 0);
    if (size <= 0) throw CubeError(what("cannot take the file's image"));
    image.resize(static_cast<std::size_t>(size));
    if (H5Fget_file_image(file, image.data(), image.size()) != size) throw CubeError(what("cannot take the file's image"));
    close_handles();
  } catch (...) {
    close_handles();
    throw;
  }
  target.write(image.data(), image.size());
  std::vector<char>().swap(image);
  target.close();
  write_long_coordinates(target.temporary());
}

/// Writes the long and computed coordinates (written_later) into the new cube at `target`,
/// on disk, one chunk (coordinate_chunk_values) at a time, then drops them: whatever the
/// number of cases, creating a cube holds one chunk of a coordinate, not the whole of it
/// (issue 38; an LHS of 10^6 frames held its eight parameters, then their image, 130 B a case).
/// A chunked one goes in as sealed pieces, each written raw (H5Dwrite_chunk, no filter
/// skipped): from `coordinate_source` (other ranks computed and compressed them), or sealed
/// here; any other (text, or short) value by value.
void CubeWriter::Impl::write_long_coordinates(const std::filesystem::path& target) {
  bool any = false;
  for (const auto& c : layout.coordinates) any = any || (written_later(c) && !c.written_live());
  if (!any) return;
  try {
    const std::string cannot_open = what("cannot open " + target.string());
    file = h5::file(H5Fopen(target.c_str(), H5F_ACC_RDWR, h5::writing_access(cannot_open)), cannot_open);
    for (std::size_t k = 0; k < layout.coordinates.size(); ++k) {
      auto& c = layout.coordinates[k];
      if (!written_later(c) || c.written_live()) continue;  // written live: with the units, and at close
      const std::string problem = what("cannot write coordinate '" + c.name + "'");
      auto d = h5::dataset(H5Dopen2(file, c.name.c_str(), H5P_DEFAULT), problem);
      const std::size_t values = chunk_values_of(c);
      if (c.chunked()) {
        for (std::size_t p = 0; p < piece_count(c.size(), values); ++p) write_sealed_piece(d, {k, p, values}, problem);
      } else {
        const hsize_t n = c.size();
        for (hsize_t first = 0; first < n; first += values)
          write_coordinate_piece(d, c, first, std::min<hsize_t>(values, n - first), problem);
      }
      c.release_values();
    }
    const hid_t id = file.release();
    h5::check(H5Fclose(id), what("cannot write " + target.string()));
  } catch (...) {
    close_handles();
    throw;
  }
}

/// One sealed piece of a chunked coordinate into its dataset `d`, raw. Bytes from another
/// rank are checked for their size; HDF5 inflates them only when read (the creating rank
/// trusts the ranks of its own run, which run this binary).
void CubeWriter::Impl::write_sealed_piece(hid_t d, const CoordinatePiece& piece, const std::string& problem) {
  const Coordinate& c = layout.coordinates[piece.coordinate];
  std::vector<char> here;
  const std::span<const char> bytes = coordinate_source != nullptr
                                          ? coordinate_source->sealed(layout, piece)
                                          : std::span<const char>(here = seal_coordinate_piece(c, piece.chunk_values, piece.piece));
  if (bytes.empty() || bytes.size() > sealed_piece_bound(c, piece.chunk_values))
    throw CubeError(problem + ": piece " + std::to_string(piece.piece) + " has " + std::to_string(bytes.size()) +
                    " bytes, not a sealed chunk");
  const hsize_t offset = static_cast<hsize_t>(piece.piece * piece.chunk_values);
  h5::check(H5Dwrite_chunk(d, H5P_DEFAULT, 0, &offset, bytes.size(), bytes.data()), problem);
}

/// Values per chunk of a chunked coordinate of this cube (coordinate_chunk_values of its grid:
/// a unit's extent for one written live, kCreationCoordinateChunk for one written at the
/// creation; a short one's "pieces" as it is written value by value: kContiguousCoordinateMax).
std::size_t CubeWriter::Impl::chunk_values_of(const Coordinate& c) const {
  if (!c.chunked()) return kContiguousCoordinateMax;
  const auto d = layout.find_dimension(c.dimension);
  if (!d) throw CubeError(what("coordinate '" + c.name + "' is over an unknown dimension"));
  return coordinate_chunk_values(grid, *d, c);
}

/// The live coordinates (Coordinate::written_live) that the file `in` stores in chunks of the
/// grid's extent along their dimension (this version's), shuffled and deflated: a unit's worker
/// seals its piece of each (unit_piece), which goes in raw with the unit. An earlier version's
/// cube has none (its coordinates are written whole).
void CubeWriter::Impl::find_unit_coordinates(hid_t in) {
  unit_coordinates.clear();
  for (std::size_t k = 0; k < layout.coordinates.size(); ++k) {
    const Coordinate& c = layout.coordinates[k];
    const auto d = c.written_live() ? layout.find_dimension(c.dimension) : std::nullopt;
    if (!d || H5Lexists(in, c.name.c_str(), H5P_DEFAULT) <= 0) continue;
    const std::string problem = what("cannot read coordinate '" + c.name + "'");
    auto set = h5::dataset(H5Dopen2(in, c.name.c_str(), H5P_DEFAULT), problem);
    const auto extents = sealed_chunk_extents(set, 1, problem);
    if (!extents) continue;
    const hsize_t chunk = extents->front();
    if (chunk != grid.chunk_shape()[*d] || chunk != coordinate_chunk_values(grid, *d)) continue;
    unit_coordinates.push_back({k, c.name, *d, static_cast<std::size_t>(chunk)});
  }
}

/// A coordinate piece a unit's worker sealed (SealedChunk::coordinates), raw into the file
/// being written: only where it is that unit's piece of a coordinate the units carry
/// (unit_piece); any other is left out (a fold seals the chunk here if the file lacks it).
void CubeWriter::Impl::write_piece(std::size_t unit, std::size_t coordinate, std::size_t piece, const char* bytes,
                                   std::size_t size) {
  const auto it = std::find_if(unit_coordinates.begin(), unit_coordinates.end(),
                               [&](const UnitCoordinate& u) { return u.coordinate == coordinate; });
  if (it == unit_coordinates.end()) return;
  const auto expected = unit_piece(grid, unit, *it);
  if (!expected || *expected != piece || size == 0 || size > sealed_piece_bound(layout.coordinates[coordinate], it->chunk_values))
    return;
  auto& set = coordinate_sets[coordinate];
  // The error's text made only for an error (built for each of a unit's 8 pieces, it was 0.4
  // instructions a result of rank 0's run, rank_costs.py --ranks 4).
  const auto problem = [&] { return what("cannot write coordinate '" + it->name + "'"); };
  if (!set.valid()) set = h5::dataset(H5Dopen2(file, it->name.c_str(), H5P_DEFAULT), problem());
  const hsize_t offset = static_cast<hsize_t>(piece * it->chunk_values);
  h5::check_lazily(H5Dwrite_chunk(set, H5P_DEFAULT, 0, &offset, size, bytes), problem);
  mark_written(coordinate, piece, piece_count(layout.coordinates[coordinate].size(), it->chunk_values));
}

/// The chunks of the coordinates written live (Coordinate::written_live) that the file being
/// folded lacks, sealed here from the layout's values and written raw: at a fold, those of
/// the cases of every unit done in it (each case it holds has its coordinates); at close,
/// every one. Which chunks the file holds is HDF5's to say (H5Dget_chunk_storage_size), so that a
/// --resume, a shard or a stopped run needs no record of them: a chunk a worker's unit brought
/// in (issue 38) is found there and left as it is. A coordinate the file stores otherwise (an
/// earlier version's cube: contiguous, or written whole at its creation) has nothing missing.
void CubeWriter::Impl::write_missing_coordinates(const StatusBook& status) {
  std::vector<char> unit_in;  // [unit]: in the file being folded (done, or streamed into it)
  for (std::size_t k = 0; k < layout.coordinates.size(); ++k) {
    const Coordinate& c = layout.coordinates[k];
    if (!c.written_live()) continue;
    const auto dim = layout.find_dimension(c.dimension);
    if (!dim) continue;
    const std::string problem = what("cannot write coordinate '" + c.name + "'");
    auto d = h5::dataset(H5Dopen2(file, c.name.c_str(), H5P_DEFAULT), problem);
    const auto extents = sealed_chunk_extents(d, 1, problem);
    if (!extents || extents->front() == 0) continue;
    const auto values = static_cast<std::size_t>(extents->front());
    const std::size_t pieces = piece_count(c.size(), values);
    std::vector<char> wanted(pieces, closing ? 1 : 0);
    if (!closing) {
      if (unit_in.empty()) {
        unit_in.assign(grid.chunk_count(), 0);
        for (std::size_t u = 0; u < unit_in.size(); ++u)
          unit_in[u] = status.chunk_done(u) > 0 || (u < streamed.size() && streamed[u].rank >= 0);
      }
      for (std::size_t u = 0; u < unit_in.size(); ++u) {
        if (!unit_in[u]) continue;
        const auto r = grid.range(u);
        const std::size_t first = r.start[*dim], last = first + r.extent[*dim] - 1;
        for (std::size_t p = first / values; p <= last / values && p < pieces; ++p) wanted[p] = 1;
      }
    }
    // A dataset none of whose chunks is written has no chunk index yet (HDF5 1.10.8 then
    // refuses the query below): every chunk is missing. HDF5 says so by summing the storage of
    // every chunk (H5Dget_space_status: 4.5 k instructions a unit at close, rank_costs.py), so
    // it is asked only for a piece not known written, and only when none of the coordinate's
    // pieces is known written into this file (which would have made its index).
    H5D_space_status_t space = H5D_SPACE_STATUS_ERROR;
    for (std::size_t p = 0; p < pieces; ++p) {
      if (!wanted[p] || piece_written(k, p)) continue;
      if (space == H5D_SPACE_STATUS_ERROR) {
        if (any_piece_written(k)) space = H5D_SPACE_STATUS_PART_ALLOCATED;
        else h5::check(H5Dget_space_status(d, &space), problem);
      }
      hsize_t offset = static_cast<hsize_t>(p * values);
      // Not H5Dget_chunk_info_by_coord: HDF5 1.10.8 finds the chunk by a pass over the
      // dataset's chunk index (callgrind: 6 k instructions a query at 18 chunks, 25 k at 72, so
      // a close of N units cost O(N^2), 14 instructions a result at 1.2 million cases). The
      // storage size is a lookup of the chunk in the index: 0, or (1.10.8) an error "chunk
      // storage is not allocated", where none is written. Any failure counts as missing: the
      // chunk is then sealed and written here, the same bytes a unit would have brought, and a
      // write that cannot be made fails on its own.
      hsize_t stored = 0;
      if (space != H5D_SPACE_STATUS_NOT_ALLOCATED && H5Dget_chunk_storage_size(d, &offset, &stored) < 0) stored = 0;
      if (stored == 0) {
        const std::vector<char> bytes = seal_coordinate_piece(c, values, p);
        h5::check(H5Dwrite_chunk(d, H5P_DEFAULT, 0, &offset, bytes.size(), bytes.data()), problem);
      }
      mark_written(k, p, pieces);
    }
  }
}

/// Opens the new file of a fold at `target` (a copy of the cube, or the streaming fold's) for
/// its writes: `file` (h5::writing_access), `metric_sets` and `status_set`.
void CubeWriter::Impl::open_for_writing(const std::filesystem::path& target) {
  const std::string cannot_open = what("cannot open " + target.string());
  file = h5::file(H5Fopen(target.c_str(), H5F_ACC_RDWR, h5::writing_access(cannot_open)), cannot_open);
  for (const auto& m : layout.metrics)
    metric_sets.push_back(h5::dataset(H5Dopen2(file, m.name.c_str(), H5P_DEFAULT), what("cannot open '" + m.name + "'")));
  status_set = h5::dataset(H5Dopen2(file, kStatusName, H5P_DEFAULT), what("cannot open 'status'"));
}

/// Writes what changed since the last fold into `target` (a copy of it, or a new cube): the
/// journal's records, then what was stored since the last checkpoint, and the new journal id.
void CubeWriter::Impl::update(const std::filesystem::path& target, StatusBook& status,
                              std::int64_t new_id) {
  try {
    if (!file.valid()) open_for_writing(target);  // else the streaming fold's, open on `target`
    const JournalReader journaled(path, layout, journal_records > 0 ? journal_id : 0);
    // The ranks' parts first (chunks no journal record touches: each went to one worker).
    std::vector<std::pair<std::int64_t, std::string>> notes;
    write_parts(notes, status);
    // Sealed chunks go in as their filtered bytes (one raw write a variable), the newest of
    // each chunk: the pending one, else the journal's last. Cases of the chunk stored after
    // it (records later in the journal, or pending) are laid over it below.
    const bool raw = raw_writable();
    std::map<std::size_t, std::size_t> sealed_at;  // chunk -> its last sealed record (SIZE_MAX: pending)
    for (const auto& [chunk, records] : journaled.sealed_chunks()) sealed_at[chunk] = records.back();
    for (const auto& [chunk, sealed] : pending_sealed) sealed_at[chunk] = std::numeric_limits<std::size_t>::max();
    std::map<std::size_t, std::vector<JournalCases>> unsealed;  // sealed chunks this file cannot take raw
    for (const auto& [chunk, record] : sealed_at) {
      const auto it = pending_sealed.find(chunk);
      write_sealed(it != pending_sealed.end() ? it->second : journaled.sealed(record), raw, unsealed[chunk]);
    }
    std::set<std::size_t> chunks;  // in order: each chunk read and written once
    for (const auto& [chunk, records] : journaled.chunks()) chunks.insert(chunk);
    for (const auto& [chunk, stored] : pending_chunks) chunks.insert(chunk);
    for (const auto& [chunk, cases] : unsealed)
      if (!cases.empty()) chunks.insert(chunk);
    for (const std::size_t chunk : chunks) {
      std::vector<JournalCases> records = std::move(unsealed[chunk]);
      const auto last_sealed = sealed_at.find(chunk);
      if (const auto it = journaled.chunks().find(chunk); it != journaled.chunks().end())
        for (const std::size_t r : it->second)
          if (last_sealed == sealed_at.end() || r > last_sealed->second) records.push_back(journaled.cases(r));
      const auto it = pending_chunks.find(chunk);
      write_chunk(chunk, records, it == pending_chunks.end() ? nullptr : &it->second, status);
    }
    auto journal_notes = journaled.notes();
    notes.insert(notes.end(), std::make_move_iterator(journal_notes.begin()), std::make_move_iterator(journal_notes.end()));
    notes.insert(notes.end(), pending_notes.begin(), pending_notes.end());
    append_notes(notes);
    write_missing_coordinates(status);  // after every unit of this fold has its statuses
    journaled.for_each_history([&](HistoryTable&& table) { write_history(table); });
    for (const auto& table : pending_histories) write_history(table);
    h5::write_attribute(file, kJournalIdName, new_id);
    for (std::size_t v = 0; v < layout.side_variables.size(); ++v) {
      const auto& name = layout.side_variables[v].name;
      side_sets.push_back(h5::dataset(H5Dopen2(file, name.c_str(), H5P_DEFAULT), what("cannot open '" + name + "'")));
      write_side(v);
    }
    coordinate_sets.clear();
    metric_sets.clear();
    side_sets.clear();
    status_set.reset();
    const hid_t id = file.release();
    h5::check(H5Fclose(id), what("cannot write " + target.string()));
  } catch (...) {
    close_handles();
    pieces_written.clear();
    throw;
  }
}

/// Refuses to start a checkpoint that cannot fit: the old cube's size plus every value
/// stored since (uncompressed), and a margin. HDF5 then writes into space that exists.
/// `copied`: the copy of the cube is at `target` already (the streaming fold's): its size is
/// not counted again (its parts are, whole: a bound).
void CubeWriter::Impl::check_free_space(const std::filesystem::path& target, bool copied) const {
  std::error_code ec;
  const auto space = std::filesystem::space(folder_of(target), ec);
  if (ec) return;  // unknown: the writes themselves will tell
  auto size_of = [](const std::filesystem::path& of) {
    std::error_code error;
    const auto bytes = std::filesystem::file_size(of, error);
    return error ? 0.0 : static_cast<double>(bytes);
  };
  double needed = 0.0;
  if (on_disk && !copied) needed += size_of(path);
  // A new cube: room for the coordinates its run writes too (uncompressed, a bound), so that a
  // disk too small for them refuses the study before its first case, as when they were
  // written at the creation, not at a fold hours later.
  if (!on_disk)
    for (const auto& c : layout.coordinates)
      if (c.written_live()) needed += 8.0 * static_cast<double>(c.size());
  if (journal_records > 0) needed += size_of(journal_path(path));  // its results, uncompressed
  for (const auto& part : parts) needed += size_of(part->file());   // its chunks, as the cube stores them
  needed += static_cast<double>(pending_bytes);
  for (const auto& [index, text] : pending_notes) needed += 16.0 + static_cast<double>(text.size());
  for (const auto& table : pending_histories)
    for (const auto& column : table.values) needed += 8.0 * static_cast<double>(column.size());
  needed = 1.05 * needed + 16384.0;  // HDF5's metadata for the new chunks
  if (static_cast<double>(space.available) < needed) {
    char text[160];
    std::snprintf(text, sizeof text, "cannot write %s: No space left on device (a checkpoint needs about %.3g MB, "
                  "%.3g MB are free)", target.c_str(), needed / 1e6, static_cast<double>(space.available) / 1e6);
    throw CubeError(what(text), CubeError::Cause::kNoSpace);
  }
}

void CubeWriter::Impl::remember_identity() {
  if (::stat(path.c_str(), &identity) != 0) identity = {};
}

/// The file at `path` is still the one this writer put there: not removed (with its folder)
/// nor replaced by another file, whose content a checkpoint would otherwise copy and overwrite.
void CubeWriter::Impl::check_identity() const {
  struct stat now {};
  if (::stat(path.c_str(), &now) != 0) {
    const int error = errno;
    throw CubeError(what("is gone (removed during the run, or its folder): " + std::string(std::strerror(error))),
                    error == ENOENT ? CubeError::Cause::kGone : CubeError::cause_of(error));
  }
  if (now.st_dev != identity.st_dev || now.st_ino != identity.st_ino)
    throw CubeError(what("was replaced by another file during the run; that file is left as it is"),
                    CubeError::Cause::kReplaced);
}

/// Throws `error`, or the cube's own problem when the write failed because the cube or its
/// folder went away, whether or not the reason quotes the system's error (HDF5 1.14's
/// "can't retrieve stat info for file" does not).
void CubeWriter::Impl::fail(const CubeError& error) const {
  if (on_disk && error.cause() == CubeError::Cause::kOther) check_identity();
  throw error;
}

/// A checkpoint: what changed since the last one goes to disk, by an append to the journal
/// (cost: what changed) or by a fold (cost: the cube). Kill points (CheckpointStep, and
/// docs/checkpoint.md): a kill at any moment leaves the last folded cube whole, and a
/// journal whose complete records extend it, or a stale one that --resume ignores.
void CubeWriter::Impl::checkpoint(StatusBook& status, Checkpoint how) {
  const bool changed = !pending_chunks.empty() || !pending_sealed.empty() || !pending_notes.empty() ||
                       !pending_histories.empty();
  // Parts found (a --resume's, or another cube's left beside a new one) go in, or go, at once.
  const bool parts_due = !parts_to_remove.empty() && how != Checkpoint::kAppend;
  // The last fold writes the coordinate chunks still missing (write_missing_coordinates): it
  // is made even when nothing else changed (a --resume that found every case done).
  const bool coordinates_due =
      closing && std::any_of(layout.coordinates.begin(), layout.coordinates.end(),
                             [](const Coordinate& c) { return c.written_live(); });
  if (how == Checkpoint::kFold || !on_disk || journal_id == 0 || parts_due ||
      (how == Checkpoint::kAppendOrFold && fold_due() && !stream)) {
    if (parts_due) return fold(status);
    // Nothing new: the cube on disk is already this state.
    if (on_disk && journal_id != 0 && !changed && !sides_changed && journal_records == 0 && !coordinates_due) return;
    fold(status);
  } else if (changed) {
    append(status);  // side variables wait for the next fold (their producer stores them anew on --resume)
  }
}

/// A fold is due once the journal (with what waits to join it) holds more results than
/// kFoldJournalShare of the folded cube's: the folds then copy the cube a bounded number of
/// times over the run (a geometric series), however many checkpoints there are.
bool CubeWriter::Impl::fold_due() const {
  return static_cast<double>(journal_results + pending_results) > kFoldJournalShare * static_cast<double>(folded_results);
}

/// Appends what was stored since the last checkpoint to the journal, closed by a commit
/// record, and syncs it.
///   kill while writing (kJournalWritten not reached): records without their commit at the
///     journal's end, dropped by --resume (their cases are computed again); the cube is untouched;
///   kJournalWritten: the records are complete in the page cache: --resume keeps them (a
///     power loss now may tear them: dropped as above);
///   kJournalSynced: the checkpoint is durable.
void CubeWriter::Impl::append(const StatusBook& status) {
  check_identity();
  try {
    if (!journal) {
      journal = std::make_unique<JournalWriter>(path, layout, journal_id, journal_keep_bytes);
      journal_records = std::max<std::int64_t>(journal_records, 1);  // its header
    } else if (!journal->in_place()) {
      throw CubeError(what("its journal " + journal_path(path).string() + " was removed or replaced during the run; "
                           "the results since the last fold are lost with it"));
    }
    // Sealed chunks first: a chunk's cases stored after it was sealed come after it on replay.
    for (const auto& [chunk, sealed] : pending_sealed) journal->add_sealed(sealed);
    std::vector<std::int8_t> scratch;
    for (const auto& [chunk, stored] : pending_chunks)
      journal->add_cases(chunk, stored.stored, stored.values, status.chunk_codes(chunk, scratch).data());
    journal->add_notes(pending_notes);
    for (const auto& table : pending_histories) journal->add_history(table);
    journal->commit();
    reached(CheckpointStep::kJournalWritten);
    journal->sync();
    reached(CheckpointStep::kJournalSynced);
  } catch (const CubeError& e) {
    fail(e);
  }
  journal_records += static_cast<std::int64_t>(pending_chunks.size() + pending_sealed.size() + pending_histories.size() +
                                               !pending_notes.empty());
  journal_results += pending_results;
  clear_pending();
}

/// Folds the journal and what was stored since the last checkpoint into the cube, by the one
/// atomic-file rule (io::AtomicFile): a complete new file beside the cube — a copy of the last
/// fold with every change written into it, or a new cube — synced, then renamed over it.
/// Memory: one chunk at a time, and what was stored since the last checkpoint.
///   kill before kFoldWritten (kFoldCopied: the copy is made): a stray <cube>.partial,
///     truncated by the next fold; the cube and its journal are as they were;
///   kFoldWritten: the new cube is complete and synced beside the old; as above;
///   kFoldRenamed: the new cube is in place with a new journal id; the old journal, not yet
///     removed, is stale (its results are in the cube): ignored, then replaced;
///   kJournalRemoved: the fold is complete.
/// On failure the cube and its journal are untouched: only the new file goes.
/// With a streaming fold open (stream_kept) the new file is that one, which holds the copy and
/// the chunks streamed into it already (fold_stream); should it fail before its rename, the
/// fold is made from a new copy (fold_copy).
void CubeWriter::Impl::fold(StatusBook& status) {
  if (on_disk) check_identity();
  const std::int64_t new_id = draw_journal_id();
  if (!(stream && fold_stream(status, new_id))) fold_copy(status, new_id);
  reached(CheckpointStep::kFoldRenamed);
  journal.reset();
  std::error_code ignored;  // a journal left behind is stale (another id): tidiness, not safety
  std::filesystem::remove(journal_path(path), ignored);
  reached(CheckpointStep::kJournalRemoved);
  remove_parts();
  on_disk = true;
  remember_identity();
  journal_id = new_id;
  journal_keep_bytes = 0;
  journal_records = journal_results = 0;
  folded_results = status.done();
  clear_pending();
  sides_changed = false;
}

/// The new file of a fold made from a copy of the cube (or as a new cube), written and
/// renamed over the cube (fold()).
void CubeWriter::Impl::fold_copy(StatusBook& status, std::int64_t new_id) {
  try {
    io::AtomicFile next(path, true, io::AtomicFile::Temporary::kPartial);
    check_free_space(next.temporary());
    if (on_disk) {
      next.copy_from(path);
      check_identity();  // what was copied is this writer's cube, not a file put there meanwhile
    } else {
      write_new_file(next);
    }
    next.close();
    reached(CheckpointStep::kFoldCopied);
    update(next.temporary(), status, new_id);
    next.sync();
    reached(CheckpointStep::kFoldWritten);
    if (on_disk) check_identity();  // the fold took time: nothing took the cube's place since
    next.commit();
  } catch (const io::OutputError& e) {
    pieces_written.clear();
    fail(CubeError(e.what(), CubeError::cause_of(e.os_error())));
  } catch (const CubeError& e) {
    pieces_written.clear();
    fail(e);
  }
}

/// The parts' chunks into the file being folded, part by part (one part open at a time,
/// whatever the number of ranks): each sealed record read from its part by reference when its
/// turn comes (one chunk in memory at a time, whatever the number of cases) and written raw;
/// their statuses into `status` (unless counted when read), per chunk where the record's status
/// variable says one code for all (JournalReader::with_sealed), else case by case; their notes
/// added to `notes`.
void CubeWriter::Impl::write_parts(std::vector<std::pair<std::int64_t, std::string>>& notes, StatusBook& status) {
  if (part_chunks.empty()) return;
  const bool raw = raw_writable();
  std::vector<std::vector<std::pair<std::size_t, PartChunk>>> by_part(parts.size());
  for (const auto& [chunk, at] : part_chunks) by_part[at.part].emplace_back(chunk, at);
  for (std::size_t p = 0; p < parts.size(); ++p) {
    JournalReader& part = *parts[p];
    part.reopen_file();
    const int rank = part_rank(path, part.file()).value_or(-1);  // once a part, not a name a chunk
    for (const auto& [chunk, at] : by_part[p]) {
      const std::size_t record = at.record;
      if (streamed_from(chunk, rank)) {  // in the file already (stream_kept): its statuses only
        const Streamed& s = streamed[chunk];
        if (!at.counted) {
          if (s.alike) status.set_chunk_to(chunk, s.code);
          else status.set_chunk(chunk, part.sealed_status(record));
        }
      } else if (raw) {  // each variable's bytes from the part's one read of the record to the file
        const auto offset = to_hsize(grid.range(chunk).start);
        part.with_sealed(
            record,
            [&](const SealedStatuses& s) {
              if (at.counted) return;
              if (s.alike) status.set_chunk_to(chunk, s.code);
              else status.set_chunk(chunk, s.each);
            },
            [&](std::size_t v, const char* bytes, std::size_t size) { write_variable_raw(offset, v, bytes, size); },
            [&](std::size_t coordinate, std::size_t piece, const char* bytes, std::size_t size) {
              write_piece(chunk, coordinate, piece, bytes, size);
            });
      } else {
        const SealedChunk sealed = part.sealed(record);
        if (!at.counted) status.set_chunk(chunk, sealed.status);
        std::vector<JournalCases> unsealed;
        write_sealed(sealed, raw, unsealed);
        write_chunk(chunk, unsealed, nullptr, status);
      }
      for (auto& note : part.notes_after(record)) notes.push_back(std::move(note));
    }
    part.release_file();
  }
}

/// After a fold's rename: the parts it took (or found beside a new cube) go. A kill before
/// leaves them beside a cube that holds their chunks: --resume skips those (done) and removes
/// them at its first fold.
///   kPartsRemoved: the parts are gone.
void CubeWriter::Impl::remove_parts() {
  if (parts_to_remove.empty()) return;
  parts.clear();
  part_chunks.clear();
  std::error_code ignored;  // a part left behind holds chunks the cube has: tidiness, not safety
  for (const auto& part : parts_to_remove) std::filesystem::remove(part, ignored);
  parts_to_remove.clear();
  live_parts.clear();  // their files are gone
  reached(CheckpointStep::kPartsRemoved);
}

void CubeWriter::Impl::clear_pending() {
  pending_chunks.clear();
  pending_sealed.clear();
  pending_bytes = 0;
  pending_results = 0;
  pending_notes.clear();
  pending_histories.clear();
}

const std::vector<std::string>& CubeWriter::resume_notes() const { return impl_->resume_notes; }

PartHeader CubeWriter::part_header() const { return impl_->part_header_of_cube(); }

void CubeWriter::flush() { impl_->checkpoint(statuses_, Impl::Checkpoint::kAppendOrFold); }

void CubeWriter::append() { impl_->checkpoint(statuses_, Impl::Checkpoint::kAppend); }

void CubeWriter::fold() { impl_->checkpoint(statuses_, Impl::Checkpoint::kFold); }

void CubeWriter::close() {
  impl_->closing = true;  // the last fold: every coordinate chunk still missing goes in
  impl_->take_run_parts(statuses_, false);  // their statuses counted chunk by chunk as the fold writes them
  fold();
  impl_->closed = true;
}

void CubeWriter::take_parts() { impl_->take_run_parts(statuses_, true); }

const std::vector<UnitCoordinate>& CubeWriter::unit_coordinates() const { return impl_->unit_coordinates; }

void CubeWriter::stream_kept(std::size_t chunk, int rank) { impl_->stream_kept(chunk, rank); }

std::string CubeWriter::take_stream_note() { return std::exchange(impl_->stream_note, {}); }

/// One chunk a worker kept into the streaming fold (CubeWriter::stream_kept), which the first
/// such chunk opens. Its part is read by the records its worker committed since the last chunk
/// read from it (JournalReader::extend: frames and sizes, as the end's assembly reads a part of
/// this run), the chunk's record checked as write_parts checks it (JournalReader::with_sealed:
/// sizes, and statuses the cube's flags name) and written raw, variable by variable.
///   kill at kStreamOpened or kChunkStreamed: a stray <cube>.partial (removed by the next
///     fold, which makes it anew exclusively); the cube, its journal and the parts as they were.
void CubeWriter::Impl::stream_kept(std::size_t chunk, int rank) {
  if (stream_off || closed || part_id == 0 || !on_disk || journal_id == 0 || rank < 0 || chunk >= grid.chunk_count())
    return;
  if (!streamed.empty() && streamed[chunk].rank >= 0) return;
  try {
    JournalReader* part = live_part(rank);
    if (part == nullptr) return;
    struct Release {
      JournalReader& part;
      ~Release() { part.release_file(); }  // one part open at a time, whatever the number of ranks
    } release{*part};
    auto found = part->sealed_chunks().find(chunk);
    if (found == part->sealed_chunks().end()) {
      part->extend();
      found = part->sealed_chunks().find(chunk);
      if (found == part->sealed_chunks().end()) return;  // not there (yet): the end's fold takes it
    }
    const std::size_t record = found->second.front();
    if (!stream) open_stream();
    if (streamed.empty()) streamed.resize(grid.chunk_count());
    Streamed in{rank};
    const auto offset = to_hsize(grid.range(chunk).start);
    part->with_sealed(
        record,
        [&](const SealedStatuses& s) {
          in.alike = s.alike;
          in.code = s.code;
        },
        [&](std::size_t v, const char* bytes, std::size_t size) { write_variable_raw(offset, v, bytes, size); },
        [&](std::size_t coordinate, std::size_t piece, const char* bytes, std::size_t size) {
          write_piece(chunk, coordinate, piece, bytes, size);
        });
    streamed[chunk] = in;
    stream_chunks.push_back(chunk);
    reached(CheckpointStep::kChunkStreamed);
  } catch (const std::exception& e) {
    drop_stream(e.what());
  }
}

/// Rank `rank`'s part as read during the run, reopened (the caller releases it); null when it
/// is not there or not this cube's (the end's fold then reads it as before).
JournalReader* CubeWriter::Impl::live_part(int rank) {
  auto& part = live_parts[rank];
  if (!part) {
    auto read = std::make_unique<JournalReader>(part_path(path, rank), layout,
                                                part_header_payload(part_header_of_cube()), false);
    if (read->foreign()) throw CubeError(read->file().string() + ": is not a part of this cube");
    if (!read->current()) {  // not there, or its header not complete: looked for again at its next chunk
      live_parts.erase(rank);
      return nullptr;
    }
    part = std::move(read);
    return part.get();  // open
  }
  part->reopen_file();
  return part.get();
}

/// Makes the streaming fold: <cube>.partial as a fold makes it (io::AtomicFile, exclusively,
/// never followed), a copy of the cube, opened for the raw writes. The folder must have room
/// for the copy and a margin; what the chunks add is checked by their writes (a full disk then
/// drops the stream).
void CubeWriter::Impl::open_stream() {
  check_identity();
  auto next = std::make_unique<io::AtomicFile>(path, true, io::AtomicFile::Temporary::kPartial);
  std::error_code ec;
  const auto space = std::filesystem::space(folder_of(next->temporary()), ec);
  const auto cube_bytes = std::filesystem::file_size(path, ec);
  if (!ec) {
    const double needed = 1.05 * static_cast<double>(cube_bytes) + (1 << 20);
    if (static_cast<double>(space.available) < needed)
      throw CubeError(what("no room for its streaming fold " + next->temporary().string() + " (about " +
                           std::to_string(static_cast<long long>(needed / 1e6)) + " MB)"),
                      CubeError::Cause::kNoSpace);
  }
  next->copy_from(path);
  check_identity();  // what was copied is this writer's cube
  if (::fstat(next->fd(), &stream_identity) != 0)
    throw CubeError(what("cannot stat its streaming fold " + next->temporary().string()));
  next->close();
  try {
    open_for_writing(next->temporary());
    void* handle = nullptr;  // the file HDF5 opened by the name is the copy made above
    struct stat opened {};
    if (H5Fget_vfd_handle(file, H5P_DEFAULT, &handle) < 0 || handle == nullptr ||
        ::fstat(*static_cast<int*>(handle), &opened) != 0)
      throw CubeError(what("cannot stat its streaming fold " + next->temporary().string()));
    check_stream_identity(opened, next->temporary(), "before HDF5 opened it");
    if (!raw_writable()) throw CubeError(what("its variables are not stored as sealed chunks are"));
  } catch (...) {
    close_handles();
    throw;
  }
  stream = std::move(next);
  reached(CheckpointStep::kStreamOpened);
}

/// The fold into the open streaming fold: update() writes what it does not hold yet (the parts'
/// other chunks, the journal, what was stored since, notes, histories, side variables), then it
/// is synced and renamed over the cube as a fold's copy is. False, the stream dropped, when
/// anything before the rename fails: the caller then folds as before, from a new copy.
bool CubeWriter::Impl::fold_stream(StatusBook& status, std::int64_t new_id) {
  try {
    struct stat now {};  // the name still holds the file streamed into: else the rename would
    if (::lstat(stream->temporary().c_str(), &now) != 0)  // put another in the cube's place
      throw CubeError(what("its streaming fold " + stream->temporary().string() + " is gone: " + std::strerror(errno)));
    check_stream_identity(now, stream->temporary(), "during the run");
    check_free_space(stream->temporary(), true);
    update(stream->temporary(), status, new_id);
    stream->sync();
    reached(CheckpointStep::kFoldWritten);
    check_identity();  // the fold took time: nothing took the cube's place since
  } catch (const std::exception& e) {
    drop_stream(e.what());
    return false;
  }
  try {
    stream->commit();
  } catch (const io::OutputError& e) {
    fail(CubeError(e.what(), CubeError::cause_of(e.os_error())));
  }
  stream.reset();
  stream_chunks.clear();  // in the cube now: every later fold copies them
  return true;
}

/// The file `now` is the streaming fold's copy (same device and inode, a regular file), or
/// a CubeError that drops the stream: another file was put at its name `partial` `when`, and
/// the rename would have put that file in the cube's place (the streamed chunks, kept in the
/// parts until the last fold, then go in from a new copy).
void CubeWriter::Impl::check_stream_identity(const struct stat& now, const std::filesystem::path& partial,
                                             const char* when) const {
  if (!S_ISREG(now.st_mode) || now.st_dev != stream_identity.st_dev || now.st_ino != stream_identity.st_ino)
    throw CubeError(what("its streaming fold " + partial.string() + " was replaced by another file " + when));
}

/// Drops the streaming fold (its .partial removed, what it held written by the end's fold
/// instead) and stops streaming for this run.
void CubeWriter::Impl::drop_stream(const std::string& reason) {
  close_handles();
  pieces_written.clear();
  stream.reset();
  for (const std::size_t chunk : stream_chunks) streamed[chunk] = {};
  stream_chunks.clear();
  live_parts.clear();
  stream_off = true;
  if (stream_note.empty())
    stream_note = reason + "; the ranks' parts go into the cube at the end of the run instead, as before";
}

/// True when `chunk` was streamed from the part of rank `rank` (part_rank: its record there)
/// into the file being folded.
bool CubeWriter::Impl::streamed_from(std::size_t chunk, int rank) const {
  return rank >= 0 && chunk < streamed.size() && streamed[chunk].rank == rank;
}

/// The ranks' parts of this run (its workers', made under its lock), to go in with the next
/// fold; `count_now`: their statuses join `status` at once (read_part). A part the stream read
/// during the run is read on from where it stopped (JournalReader::extend: the same frames and
/// checks as a new reader's), not again from its start (2 k instructions a unit at close).
void CubeWriter::Impl::take_run_parts(StatusBook& status, bool count_now) {
  if (part_id == 0) return;
  for (const auto& part : part_files(path)) {
    if (std::find(parts_to_remove.begin(), parts_to_remove.end(), part) != parts_to_remove.end()) continue;
    try {
      io::check_sidecar(part, io::kPartWhat);
    } catch (const io::OutputError& e) {
      throw CubeError(e.what());
    }
    std::unique_ptr<JournalReader> live;  // the reader of this rank's part during the run, if any
    if (const auto rank = part_rank(path, part); rank && live_parts.count(*rank) > 0) {
      live = std::move(live_parts[*rank]);
      live_parts.erase(*rank);  // a later stream_kept of that rank reads its part anew
    }
    read_part(part, status, false, count_now, std::move(live));
  }
}

}  // namespace pcrf::cube

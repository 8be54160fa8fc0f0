// A rank's own part of a result cube (see cube_part.hpp): the journal's records, in a file of
// the rank's own.
#include "pcrf/cube/cube_part.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <optional>

#include "pcrf/cube/cube_journal.hpp"
#include "pcrf/io/file_kind.hpp"
#include "pcrf/io/record_log.hpp"

namespace pcrf::cube {

std::filesystem::path part_path(const std::filesystem::path& cube, int rank) {
  return cube.string() + ".part-" + std::to_string(rank);
}

namespace {

/// The rank a file name `name` gives a part of the cube named `cube_name` (`<cube_name>.part-<rank>`,
/// rank 0 to 999999 without leading zeros); nothing for any other name.
std::optional<int> rank_in_name(const std::string& cube_name, const std::string& name) {
  const std::string prefix = cube_name + ".part-";
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return std::nullopt;
  const std::string rank = name.substr(prefix.size());
  if (rank.size() > 6 || (rank.front() == '0' && rank.size() > 1) ||
      !std::all_of(rank.begin(), rank.end(), [](char c) { return c >= '0' && c <= '9'; }))
    return std::nullopt;
  return std::stoi(rank);
}

}  // namespace

std::optional<int> part_rank(const std::filesystem::path& cube, const std::filesystem::path& part) {
  return rank_in_name(cube.filename().string(), part.filename().string());
}

std::vector<std::filesystem::path> part_files(const std::filesystem::path& cube) {
  const std::string cube_name = cube.filename().string();
  const std::filesystem::path folder = cube.parent_path().empty() ? std::filesystem::path(".") : cube.parent_path();
  std::vector<std::pair<long, std::filesystem::path>> found;
  std::error_code error;
  for (std::filesystem::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (const auto rank = rank_in_name(cube_name, name)) found.emplace_back(*rank, cube.parent_path() / name);
  }
  std::sort(found.begin(), found.end());
  std::vector<std::filesystem::path> parts;
  for (auto& [rank, path] : found) parts.push_back(std::move(path));
  return parts;
}

std::int64_t part_id_of(const CubeLayout& layout) {
  for (const auto& a : layout.attributes)
    if (a.name == kPartIdName)
      if (const auto* id = std::get_if<std::int64_t>(&a.value)) return *id;
  return 0;
}

PartHeader part_header_of(const CubeLayout& layout) {
  return {part_id_of(layout), layout.case_count(), layout.metrics.size(), layout.text_attribute(kFingerprintName)};
}

std::string part_header_payload(const PartHeader& header) {
  std::string out;
  io::append_le(out, static_cast<std::uint64_t>(header.id), 8);
  io::append_le(out, static_cast<std::uint64_t>(header.cases), 8);
  io::append_le(out, header.metrics, 4);
  io::append_le(out, header.fingerprint.size(), 4);
  out += header.fingerprint;
  return out;
}

PartWriter::PartWriter(const std::filesystem::path& part, const PartHeader& header) : file_(part) {
  // Never over anything: rank 0 removed the parts of earlier runs before the run began, so
  // whatever is here now (a file, a link, a FIFO, a folder) is not this rank's to replace.
  struct stat st {};
  if (::lstat(part.c_str(), &st) == 0)
    throw CubeError(part.string() + ": is there already (" + io::kind_of(st.st_mode) + "); a rank makes its part itself");
  if (errno != ENOENT) throw CubeError(part.string() + ": cannot be made: " + std::strerror(errno), CubeError::cause_of(errno));
  log_ = std::make_unique<JournalWriter>(part, header.metrics, part_header_payload(header));
}

PartWriter::~PartWriter() = default;

void PartWriter::add(const SealedChunk& sealed) { add(view_of(sealed)); }

void PartWriter::add(const SealedChunkView& sealed) {
  log_->add_sealed(sealed);
  log_->add_notes(sealed.notes);
  log_->commit();
  log_->sync();
}

}  // namespace pcrf::cube

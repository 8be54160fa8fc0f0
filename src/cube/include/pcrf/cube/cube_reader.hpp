/// \file cube_reader.hpp
/// \brief Reads a result cube written by CubeWriter: its layout, the status of every case,
/// metric values, failure messages and histories.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "pcrf/cube/cube_layout.hpp"
#include "pcrf/cube/cube_writer.hpp"

namespace pcrf::cube {

class CubeReader {
 public:
  /// \throws CubeError naming the file when it is missing or not a pcrf cube.
  explicit CubeReader(const std::filesystem::path& file);
  ~CubeReader();
  CubeReader(const CubeReader&) = delete;
  CubeReader& operator=(const CubeReader&) = delete;

  const std::filesystem::path& file() const { return file_; }
  /// Dimensions, coordinates, metrics, status flags and global attributes.
  const CubeLayout& layout() const { return layout_; }

  std::vector<std::int8_t> read_status() const;
  /// A metric over the whole cube, in linear case order. \throws CubeError if unknown.
  std::vector<double> read_metric(const std::string& name) const;
  /// A metric over the cases of chunks [first_chunk, end_chunk) of `grid` (the cube's), in
  /// linear case order from grid.range(first_chunk).first: one hyperslab read per chunk, so
  /// that only those cases' values are held. \throws CubeError if unknown, if the grid is not
  /// the cube's or the chunks are outside it.
  std::vector<double> read_metric_chunks(const std::string& name, const ChunkGrid& grid, std::size_t first_chunk,
                                         std::size_t end_chunk) const;
  /// A side variable (over some dimensions), row-major over its dimensions. \throws CubeError.
  std::vector<double> read_side(const std::string& name) const;
  /// (case index, message) of every case that left a note, in the order they were stored.
  std::vector<std::pair<std::int64_t, std::string>> read_notes() const;
  /// Reads every variable in full (decompressing every chunk) and returns what cannot be
  /// read, one line each ("theta_max_rad: cannot read (…)"); empty when the file is whole.
  std::vector<std::string> damage() const;
  /// Names of the stored time-history groups.
  std::vector<std::string> history_names() const;
  /// One history group, as CubeWriter::store_history took it. \throws CubeError.
  HistoryTable read_history(const std::string& name) const;

 private:
  struct Impl;
  std::filesystem::path file_;
  std::unique_ptr<Impl> impl_;
  CubeLayout layout_;
};

}  // namespace pcrf::cube

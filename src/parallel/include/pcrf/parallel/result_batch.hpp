/// \file result_batch.hpp
/// \brief What the scheduler carries back from a worker: finished cases, each with a status
/// code, a fixed-width row of doubles and an optional text note, and their byte form for
/// MPI messages.
///
/// The scheduler never interprets a status or a row: the codes, the row's width and the
/// meaning of each column are agreed between the code that evaluates a case and the code
/// that stores it. The one code the scheduler sets itself is kEvaluatorThrew.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace pcrf::parallel {

/// Status of a case whose evaluator threw instead of returning an outcome.
inline constexpr std::int8_t kEvaluatorThrew = -2;

/// One finished case.
struct CaseOutcome {
  std::int64_t case_index = -1;  ///< linear index of the case in its study
  std::int8_t status = kEvaluatorThrew;  ///< how the case ended, in the evaluator's codes
  std::vector<double> row;       ///< fixed-width values (width agreed by both ends)
  std::string note;              ///< free text (e.g. a failure message); usually empty
};

/// Outcomes travelling together in one message.
using ResultBatch = std::vector<CaseOutcome>;

/// A unit of work a worker finished whole and sealed itself (e.g. one chunk of a result
/// cube, compressed): the master passes its bytes on without looking at each case.
/// Or one the worker kept itself (ScheduleOptions::keep: e.g. in a file of its own, durable
/// before it is reported): then only its number, its case count and its failure count travel.
struct SealedUnit {
  std::int64_t unit = -1;   ///< which unit (the work source's number)
  std::int64_t cases = 0;   ///< cases it holds
  std::vector<char> bytes;  ///< what the sealer made of them (opaque here); empty when kept
  bool kept = false;        ///< true: the worker kept the bytes itself
  std::int64_t failed = 0;  ///< when kept: its cases that failed (the keeper's count)
  /// The rank whose worker sent it (0: the master's own worker thread): set by the master as
  /// it receives the message, not part of it; -1 until then.
  int worker = -1;
};
using SealedUnits = std::vector<SealedUnit>;

/// A row of `width` values, each `fill`: one this thread gave back (recycle_rows), its memory
/// reused, or a new one. A worker's rows then cost no allocation once its first unit is sealed
/// (issue 38 item 5: a row's allocation and its free among a unit's 16 384 were about 240
/// instructions a non-lifting case).
std::vector<double> pooled_row(std::size_t width, double fill);
/// Gives the rows of `outcomes` (left empty) to this thread's pool for pooled_row; the pool
/// keeps at most kPooledRows, the rest are freed.
void recycle_rows(std::span<CaseOutcome> outcomes);
/// Rows a thread's pool keeps at most: a chunk of the cube's cases (cube::kChunkCases).
inline constexpr std::size_t kPooledRows = 16384;

/// Serializes a batch. \throws std::invalid_argument if a row's width is not `row_width`.
std::vector<char> pack_results(const ResultBatch& batch, std::size_t row_width);

/// Inverse of pack_results. \throws std::runtime_error on a malformed or mismatched buffer.
ResultBatch unpack_results(const std::vector<char>& bytes, std::size_t row_width);

/// A worker's message: its outcomes, then its sealed units.
std::vector<char> pack_message(const ResultBatch& batch, const SealedUnits& sealed, std::size_t row_width);
/// Inverse of pack_message. \throws std::runtime_error on a malformed or mismatched buffer.
std::pair<ResultBatch, SealedUnits> unpack_message(const std::vector<char>& bytes, std::size_t row_width);

}  // namespace pcrf::parallel

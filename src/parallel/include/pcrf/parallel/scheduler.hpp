/// \file scheduler.hpp
/// \brief Dynamic master–worker scheduling of case indices over MPI.
///
/// Rank 0 is the master: it hands out batches of case indices on request and receives
/// finished rows. It also runs a worker of its own in a second thread, so one rank does all
/// the work through the same code path, and rank 0's cores are not wasted with several.
/// Every worker keeps one request in flight while it computes (prefetch), so the master's
/// answer is already there when a batch ends.
///
/// The scheduler moves integers and fixed-width rows of doubles; it knows nothing of what a
/// case is. Only the master thread calls MPI (MPI_THREAD_FUNNELED is enough).
#pragma once

#include <mpi.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <vector>

#include "pcrf/parallel/result_batch.hpp"
#include "pcrf/parallel/work_source.hpp"

namespace pcrf::parallel {

/// Computes one case. Should not throw: if it does anyway, the scheduler reports the case
/// with status kEvaluatorThrew, a row of NaN and the exception text as its note.
using CaseEvaluator = std::function<CaseOutcome(const WorkItem& item)>;

/// Computes several cases handed out together (at most ScheduleOptions::evaluate_together),
/// one outcome each, in their order: what a worker computes faster together than one by one.
/// Should not throw: if it does anyway, every case of the call is reported as above.
using CasesEvaluator = std::function<ResultBatch(std::span<const WorkItem> items)>;

/// Master thread: receives outcomes as they arrive.
using OutcomeHandler = std::function<void(ResultBatch&&)>;

/// Worker: turns the outcomes of a whole unit (a batch the work source marked as one, see
/// WorkSource) into bytes the master passes on as they are (e.g. a compressed chunk of the
/// result cube, so that no rank handles every result). nullopt: report them case by case.
using Sealer = std::function<std::optional<std::vector<char>>(std::int64_t unit, std::span<const CaseOutcome> outcomes)>;

/// Worker: keeps what the sealer made of a unit itself (e.g. appends it to a file of its own
/// and makes it durable) instead of sending the bytes to the master, and returns how many of
/// its cases failed (reported with it). nullopt: not kept, the bytes travel as before.
using Keeper = std::function<std::optional<std::int64_t>(std::int64_t unit, const std::vector<char>& bytes)>;

/// Worker: what a UnitEvaluator computes cases with. Computes `items` as the worker's
/// evaluator does (a throw becomes a kEvaluatorThrew outcome) and returns their outcomes
/// (valid until the next call), or nullopt once the run is being stopped (an interrupt, a
/// failing master): the unit evaluator then returns at once, and the cases it ran are
/// reported one by one.
using UnitCases = std::function<std::optional<std::span<const CaseOutcome>>(std::span<const WorkItem> items)>;

/// Worker: computes a unit itself instead of its listed cases one by one, for a plan whose
/// cases within a unit depend on each other's results (an IDA's curves of one chunk of the
/// cube: which run a curve makes next depends on its last one). `cases` lists the unit's
/// cases (arguments 0); the evaluator runs those it chooses, with the arguments it chooses,
/// through `run`. The cases it never runs stay not run: the sealer must allow them.
/// Should not throw: if it does anyway, the cases it ran are reported one by one.
using UnitEvaluator = std::function<void(std::int64_t unit, std::span<const WorkItem> cases, const UnitCases& run)>;

/// Master thread: receives the sealed units as they arrive.
using SealedHandler = std::function<void(SealedUnits&&)>;

/// Master thread: called between messages, at least every poll interval (flushes, progress).
using IdleHandler = std::function<void()>;

struct ScheduleOptions {
  std::size_t row_width = 0;        ///< values per result row, the same on every rank
  std::size_t fixed_batch = 0;      ///< 0: guided batch sizes (see WorkQueue)
  std::size_t max_batch = 64;       ///< cap of guided batches
  double poll_interval_s = 0.002;   ///< master's sleep when nothing arrives
  /// Cases of a batch a CasesEvaluator takes in one call (≥ 1); a stop or an interrupt is
  /// looked at between two calls.
  std::size_t evaluate_together = 1;
  /// Set (nonzero) when the run is being stopped (a signal): every worker then reports the
  /// cases of its batch done so far at once, leaves the rest, and stops. Null: never.
  const std::atomic<int>* interrupt = nullptr;
  /// Workers: seals the units the work source hands out whole (null: every case is reported).
  Sealer seal;
  /// Workers: keeps sealed units on the worker (null: they travel). Rank 0's worker thread
  /// keeps too when the options given to run_master have one (called in that thread); without,
  /// its units reach the master in memory, without a copy.
  Keeper keep;
  /// Master: receives what workers sealed (must be set when the work source hands out units).
  SealedHandler on_sealed;
  /// Workers: computes each unit itself (null: a unit's listed cases are evaluated one by
  /// one). A unit so computed may report fewer cases than it was handed (SealedUnit::cases:
  /// those it ran); the master counts the unit back whole.
  UnitEvaluator evaluate_unit;
};

/// Rank 0. Returns when `work` is exhausted, every case handed out has come back and every
/// worker has stopped. A worker that asks while nothing is ready waits (its request is held
/// until the source has work, or says it never will). `evaluate` runs in rank 0's worker
/// thread. If a handler throws, the local worker is stopped and the exception propagates:
/// the caller must then MPI_Abort (remote workers would wait forever otherwise).
void run_master(MPI_Comm comm, WorkSource& work, const ScheduleOptions& options,
                const CasesEvaluator& evaluate, const OutcomeHandler& on_outcomes,
                const IdleHandler& on_idle);
/// The same with a case-by-case evaluator.
void run_master(MPI_Comm comm, WorkSource& work, const ScheduleOptions& options,
                const CaseEvaluator& evaluate, const OutcomeHandler& on_outcomes,
                const IdleHandler& on_idle);

/// Number of workers a master has: every rank, rank 0's worker thread included.
int worker_count(MPI_Comm comm);

/// Ranks ≥ 1. Returns when the master says there is no more work.
void run_worker(MPI_Comm comm, const ScheduleOptions& options, const CasesEvaluator& evaluate);
void run_worker(MPI_Comm comm, const ScheduleOptions& options, const CaseEvaluator& evaluate);

/// A CasesEvaluator that calls `evaluate` case by case.
CasesEvaluator one_by_one(CaseEvaluator evaluate);

}  // namespace pcrf::parallel

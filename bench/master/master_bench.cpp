// pcrf_master_bench: how many results per second one master takes. Workers return at once
// (a row of 17 NaNs, like a study storing every metric), so the master — handing out guided
// batches, receiving and unpacking result messages — is the only cost. Run it at 1..N ranks:
//
//   mpirun --oversubscribe -n 3 build/bench/master/pcrf_master_bench [--cases 4000000] [--batch 0]
//
// Prints cases/s, messages/s and the master's time per message; from those, how many
// workers at 2 ms per case one master can feed.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <limits>
#include <vector>

#include "pcrf/parallel/mpi_session.hpp"
#include "pcrf/parallel/scheduler.hpp"
#include "pcrf/parallel/work_queue.hpp"

using namespace pcrf::parallel;

int main(int argc, char** argv) {
  CLI::App app{"Master throughput: results per second with workers that return at once"};
  long cases = 4'000'000;
  std::size_t batch = 0, width = 17;
  app.add_option("--cases", cases, "cases to hand out")->capture_default_str();
  app.add_option("--batch", batch, "fixed batch size; 0: guided (up to 64)")->capture_default_str();
  app.add_option("--width", width, "values per result row")->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  MpiSession mpi;
  ScheduleOptions options;
  options.row_width = width;
  options.fixed_batch = batch;
  const std::vector<double> row(width, std::numeric_limits<double>::quiet_NaN());
  auto evaluate = [&](const WorkItem& item) { return CaseOutcome{item.case_index, 0, row, {}}; };
  if (!mpi.is_master()) {
    run_worker(mpi.comm(), options, evaluate);
    return 0;
  }
  std::vector<std::int64_t> all(static_cast<std::size_t>(cases));
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<std::int64_t>(i);
  WorkQueue work(std::move(all), {}, mpi.size(), batch);
  long received = 0, messages = 0;
  const auto start = std::chrono::steady_clock::now();
  run_master(mpi.comm(), work, options, evaluate,
             [&](ResultBatch&& b) {
               received += static_cast<long>(b.size());
               ++messages;
             },
             [] {});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double rate = static_cast<double>(received) / seconds;
  std::printf("ranks %d  cases %ld  batch %s  time %.3f s  cases/s %.0f  messages/s %.0f  cases/message %.1f  "
              "master time per message %.2f us  workers fed at 2 ms/case: %.0f\n",
              mpi.size(), received, batch ? std::to_string(batch).c_str() : "guided", seconds, rate,
              static_cast<double>(messages) / seconds, static_cast<double>(received) / static_cast<double>(messages),
              1e6 * seconds / static_cast<double>(messages), rate * 0.002);
  return 0;
}

// `pcrf cube info|export|stats|fragility|sensitivity|merge`: looks into result cubes.
#include <CLI/CLI.hpp>

#include <functional>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/commands.hpp"
#include "pcrf/cube/cube_merge.hpp"
#include "pcrf/cube/cube_query.hpp"
#include "pcrf/io/output_file.hpp"
#include "pcrf/io/run_lock.hpp"
#include "pcrf/post/cube_fragility.hpp"
#include "pcrf/post/cube_p695.hpp"
#include "pcrf/post/cube_sensitivity.hpp"
#include "pcrf/study/cube_vocabulary.hpp"

namespace pcrf::cli {
namespace {

struct CubeArguments {
  std::string file;
  std::vector<std::string> parts;
  bool overwrite = false;
  bool allow_missing = false;
  std::optional<double> mce;
  std::string csv;
  std::vector<std::string> metrics;
  std::string metric;
  std::vector<std::string> where;
  std::string by;
  std::string output;
  std::string history;
  std::string points;
  bool json = false;
  // cube p695
  std::string sdc = "Dmax";
  double period_s = 0.0;
  double mu_t = 0.0;  // 0: each frame's own (docs/p695_rocking_frame.md)
  std::string ratings = "B,B,B";
};

std::vector<cube::Selector> selectors(const std::vector<std::string>& texts) {
  std::vector<cube::Selector> result;
  for (const auto& t : texts) result.push_back(cube::parse_selector(t));
  return result;
}

/// A cube that a study run is writing is read as its last complete checkpoint (each is
/// renamed into place whole); says so on stderr.
void note_running(const std::string& file) {
  const std::string who = io::RunLock::holder(file);
  if (!who.empty())
    std::cerr << "pcrf cube: " << file << ": a run holds it (" << who << "): read as its last complete checkpoint\n";
}

/// A cube with cases never run (stopped early, merged from some shards): says how many on
/// stderr, since what is printed covers the cases run only.
void note_partial(const std::string& command, const std::string& file, const cube::CubeReader& reader) {
  const auto missing = study::vocabulary::not_run(reader);
  if (missing.count > 0)
    std::cerr << "pcrf cube " << command << ": " << file << ": " << missing.count << " of " << missing.total << " "
              << missing.unit << " not run (a partial cube): left out\n";
}

/// Cases that say nothing about the frame because it was still rocking when they ended, and
/// (IDA cubes) collapse statuses that occurred but the study's [ida] collapse leaves out:
/// one line each on stderr, since what is printed cannot show them. `treatment`: what the
/// command does with the unresolved cases.
void note_verdicts(const std::string& command, const std::string& file, const cube::CubeReader& reader,
                   const std::string& treatment) {
  namespace v = study::vocabulary;
  const auto status = reader.read_status();
  const bool ida = reader.layout().find_side_variable(v::kIdaRuns) != nullptr;
  const std::string note = v::unresolved_note(v::unresolved_count(status), ida ? "runs" : "cases",
                                              ida ? "counted as collapses by the IDA's search (conservative)" : treatment);
  if (!note.empty()) std::cerr << "pcrf cube " << command << ": " << file << ": " << note << '\n';
  if (!ida) return;
  for (const auto& line : v::uncounted_collapse_notes(status, reader.layout().text_attribute(v::kIdaCollapseAttribute)))
    std::cerr << "pcrf cube " << command << ": " << file << ": warning: " << line << '\n';
}

/// Runs a cube action; cube problems (missing file, unknown name) are usage errors.
template <class Action>
void guarded(const std::string& file, Action action) {
  note_running(file);
  try {
    action();
  } catch (const cube::CubeError& e) {
    const std::string text = e.what();
    throw UsageError(text.rfind(file, 0) == 0 ? text : file + ": " + text);
  }
}

bool is_stdout(const std::string& path) { return path.empty() || path == "-"; }

/// Refuses an output file before anything is computed (see io::check_output).
void check_output(const std::string& path, const std::vector<std::filesystem::path>& inputs, bool overwrite) {
  if (!is_stdout(path)) io::check_output(path, inputs, overwrite);
}

/// Writes `path` (stdout for "" or "-") by the one output rule (io::OutputFile): never one
/// of `inputs`, an existing file replaced only with --overwrite, complete or not at all.
void with_output(const std::string& path, const std::vector<std::filesystem::path>& inputs, bool overwrite,
                 const std::function<void(std::ostream&)>& write) {
  if (is_stdout(path)) {
    write(std::cout);
    return;
  }
  io::OutputFile out(path, inputs, overwrite);
  write(out.stream());
  out.commit();
}

void add_overwrite(CLI::App* cmd, CubeArguments& args) {
  cmd->add_flag("--overwrite", args.overwrite, "replace existing output files (never the cube read)");
}

void add_where(CLI::App* cmd, CubeArguments& args) {
  cmd->add_option("-w,--where", args.where, "keep cases with NAME=VALUE (any coordinate; repeatable)");
}

}  // namespace

void add_cube_command(CLI::App& app) {
  auto args = std::make_shared<CubeArguments>();
  auto* cube_cmd = app.add_subcommand("cube", "Look into a result cube");
  cube_cmd->require_subcommand(1);

  auto* info = cube_cmd->add_subcommand("info", "Axes, metrics, completion and failures by status");
  info->add_option("FILE", args->file, "result cube")->required();
  info->add_flag("--json", args->json, "one JSON object for scripts (dimensions with values, metrics with units, …)");
  info->callback([args] {
    guarded(args->file, [&] {
      const cube::CubeReader reader(args->file);
      note_partial("info", args->file, reader);
      if (args->json) cube::print_info_json(reader, std::cout);
      else cube::print_info(reader, study::vocabulary::info_heading(reader.layout()), std::cout);
      // Vouch for nothing unread: a variable whose chunks no longer decompress is damage.
      const auto damage = reader.damage();
      if (!damage.empty()) {
        for (const auto& d : damage) std::cout << "DAMAGED: " << d << '\n';
        throw UsageError(args->file + ": damaged: " + std::to_string(damage.size()) +
                         " variables cannot be read; --resume cannot continue it");
      }
    });
  });

  auto* exporter = cube_cmd->add_subcommand("export", "Metrics as a long CSV table, one row per case");
  exporter->add_option("FILE", args->file, "result cube")->required();
  exporter->add_option("-m,--metric", args->metrics, "metric to export (repeatable; default: all)");
  add_where(exporter, *args);
  exporter->add_option("-o,--output", args->output, "CSV file (default: stdout)");
  add_overwrite(exporter, *args);
  auto* history = exporter->add_option("--history", args->history,
                                       "instead: the stored history group /histories/NAME, one row per time");
  history->excludes(exporter->get_option("--metric"))->excludes(exporter->get_option("--where"));
  exporter->callback([args] {
    guarded(args->file, [&] {
      check_output(args->output, {args->file}, args->overwrite);
      cube::CubeReader reader(args->file);
      if (!args->history.empty()) {
        with_output(args->output, {args->file}, args->overwrite,
                    [&](std::ostream& out) { cube::export_history_csv(reader, args->history, out); });
        return;
      }
      const auto chosen = selectors(args->where);
      with_output(args->output, {args->file}, args->overwrite,
                  [&](std::ostream& out) { cube::export_csv(reader, args->metrics, chosen, out); });
    });
  });

  auto* stats = cube_cmd->add_subcommand(
      "stats", "Median and 16th/84th percentiles of a metric across records, per value of a parameter; collapsed "
               "cases (tendon fracture, overturned) are counted apart, not in the percentiles");
  stats->add_option("FILE", args->file, "result cube")->required();
  stats->add_option("--by", args->by, "coordinate to group by (e.g. kappa, scale)")->required();
  stats->add_option("-m,--metric", args->metric, "metric to summarize")->required();
  add_where(stats, *args);
  stats->callback([args] {
    guarded(args->file, [&] {
      cube::CubeReader reader(args->file);
      note_partial("stats", args->file, reader);
      note_verdicts("stats", args->file, reader, "in the column `unresolved`, not in the percentiles");
      std::vector<std::string> pooled;
      const auto chosen = study::vocabulary::stats_selectors(reader.layout(), args->by, selectors(args->where));
      const auto result = cube::group_stats(reader, args->by, args->metric, chosen,
                                            {study::vocabulary::expected_pooling(), &pooled,
                                             study::vocabulary::collapse_statuses(), study::vocabulary::unresolved_statuses()});
      for (const auto& p : pooled) std::cerr << "pcrf cube stats: also pooled over " << p << '\n';
      cube::print_stats(args->by, study::vocabulary::kCollapses, result, std::cout);
    });
  });

  auto* fragility = cube_cmd->add_subcommand(
      "fragility", "Lognormal collapse fragility of each frame (median, beta, 90 % bootstrap intervals)");
  fragility->add_option("FILE", args->file, "result cube with an intensity axis")->required();
  add_where(fragility, *args);
  fragility->add_option("--mce", args->mce, "MCE intensity (the measure's units): adds the collapse margin ratio");
  fragility->add_option("--csv", args->csv, "also write the table as CSV to this file");
  fragility->add_option("--points", args->points,
                        "also write the fitted data as CSV to this file: stripes, or IDA collapse and censored intensities");
  add_overwrite(fragility, *args);
  fragility->callback([args] {
    guarded(args->file, [&] {
      if (args->mce && !(*args->mce > 0.0)) throw UsageError("--mce must be positive");
      const std::vector<std::filesystem::path> csv_inputs{args->file}, points_inputs{args->file, args->csv};
      check_output(args->csv, csv_inputs, args->overwrite);
      check_output(args->points, is_stdout(args->csv) ? csv_inputs : points_inputs, args->overwrite);
      cube::CubeReader reader(args->file);
      note_partial("fragility", args->file, reader);
      note_verdicts("fragility", args->file, reader, "counted in no stripe (neither safe nor collapsed)");
      const auto frames = post::cube_fragility(reader, selectors(args->where));
      const auto units = post::intensity_units(reader);
      post::print_fragility(frames, units, args->mce, false, std::cout);
      if (!args->csv.empty())
        with_output(args->csv, csv_inputs, args->overwrite,
                    [&](std::ostream& out) { post::print_fragility(frames, units, args->mce, true, out); });
      if (!args->points.empty())
        with_output(args->points, is_stdout(args->csv) ? csv_inputs : points_inputs, args->overwrite,
                    [&](std::ostream& out) { post::print_fragility_points(frames, out); });
    });
  });

  auto* sensitivity = cube_cmd->add_subcommand(
      "sensitivity", "First-order and total Sobol' indices of a saltelli cube, with 90 % bootstrap intervals");
  sensitivity->add_option("FILE", args->file, "result cube of a saltelli plan")->required();
  sensitivity->add_option("-m,--metric", args->metric, "a metric, or `collapse` (tendon fracture or overturned)")->required();
  add_where(sensitivity, *args);
  sensitivity->add_option("--by", args->by, "`record`: one set of indices per record (default: across records)");
  sensitivity->add_option("--csv", args->csv, "also write the table as CSV to this file");
  add_overwrite(sensitivity, *args);
  sensitivity->callback([args] {
    guarded(args->file, [&] {
      if (!args->by.empty() && args->by != "record") throw UsageError("--by takes `record` only");
      check_output(args->csv, {args->file}, args->overwrite);
      cube::CubeReader reader(args->file);
      note_partial("sensitivity", args->file, reader);
      note_verdicts("sensitivity", args->file, reader, "without a value (their base samples are left out)");
      const auto groups = post::cube_sensitivity(reader, args->metric, selectors(args->where), args->by == "record");
      for (const auto& g : groups)
        if (g.dropped > 0)
          std::cerr << "pcrf cube sensitivity: " << g.record << ": " << g.dropped
                    << " base samples left out (a frame without a value)\n";
      post::print_sensitivity(groups, false, std::cout);
      if (!args->csv.empty())
        with_output(args->csv, {args->file}, args->overwrite,
                    [&](std::ostream& out) { post::print_sensitivity(groups, true, out); });
    });
  });

  auto* p695_cmd = cube_cmd->add_subcommand(
      "p695", "FEMA P-695 from an IDA or stripe cube: CMR, SSF, ACMR, beta_TOT, ACMR10%/20%, P(collapse|MCE), verdicts");
  p695_cmd->add_option("FILE", args->file, "result cube with an intensity axis (Sa(T) for P-695's own numbers)")->required();
  add_where(p695_cmd, *args);
  p695_cmd->add_option("--sdc", args->sdc, "seismic design category: Dmax, Dmin, Cmax, Cmin, Bmax or Bmin (Table 5-1)")
      ->capture_default_str();
  p695_cmd->add_option("--period-s", args->period_s, "the archetype's period T [s]: max(C_u T_a, 0.25 s)")->required();
  p695_cmd->add_option("--mu-t", args->mu_t,
                       "period-based ductility mu_T (SSF and beta_RTR); default: each frame's own from its pushover "
                       "curve at --period-s (docs/p695_rocking_frame.md)");
  p695_cmd->add_option("--ratings", args->ratings,
                       "quality ratings A-D of design requirements, test data and modelling, e.g. B,B,C")
      ->capture_default_str();
  p695_cmd->add_flag("--json", args->json, "one JSON object on stdout");
  p695_cmd->callback([args] {
    guarded(args->file, [&] {
      post::P695Inputs in;
      std::string r = args->ratings;
      std::erase(r, ',');
      if (r.size() != 3) throw UsageError("--ratings: give three letters A-D, e.g. B,B,C (got '" + args->ratings + "')");
      try {
        in.sdc = p695::parse_sdc(args->sdc);
        for (const char c : r) (void)p695::rating_beta(c);
        if (!(args->mu_t >= 1.0 || args->mu_t == 0.0)) throw std::invalid_argument("--mu-t must be at least 1");
      } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
      }
      in.period_s = p695::archetype_period_s(args->period_s);
      in.mu_t = args->mu_t;
      in.design_rating = r[0], in.test_rating = r[1], in.model_rating = r[2];
      cube::CubeReader reader(args->file);
      note_partial("p695", args->file, reader);
      note_verdicts("p695", args->file, reader, "counted in no stripe (neither safe nor collapsed)");
      post::P695Report report;
      try {
        report = post::cube_p695(reader, selectors(args->where), in);
      } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
      }
      if (!report.measure_problem.empty()) std::cerr << "pcrf cube p695: warning: " << report.measure_problem << '\n';
      post::print_p695(report, in, args->json, std::cout);
    });
  });

  auto* merge = cube_cmd->add_subcommand("merge", "Join the cubes of a sharded run (pcrf study --shard K/N) into one");
  merge->add_option("PARTS", args->parts, "the shards' cubes")->required();
  merge->add_option("-o,--output", args->output, "the merged cube")->required();
  merge->add_flag("--overwrite", args->overwrite, "replace an existing output");
  merge->add_flag("--allow-missing", args->allow_missing,
                  "merge even when cases are in no part (shards not run): the merged cube says how many");
  merge->callback([args] {
    guarded(args->output, [&] {
      std::vector<std::filesystem::path> parts(args->parts.begin(), args->parts.end());
      for (const auto& part : args->parts) note_running(part);
      if (const auto who = io::RunLock::holder(args->output); !who.empty())
        throw UsageError(args->output + ": in use by a run (" + who + "); give another -o");
      const auto merged = cube::merge_cubes(parts, args->output, args->overwrite, study::vocabulary::kIdaRuns,
                                            args->allow_missing);
      if (merged.missing > 0)
        std::cerr << "pcrf cube merge: " << args->output << ": " << merged.missing << " of " << merged.total
                  << " cases are in no part: the merged cube is partial (attribute " << cube::kMissingCasesName << ")\n";
      std::cout << "merged " << parts.size() << " parts into " << args->output << '\n';
    });
  });
}

}  // namespace pcrf::cli

// `pcrf cube info|export|stats|fragility|sensitivity|p695|risk|merge`: looks into result cubes.
// One function per subcommand; stats, fragility, sensitivity and p695 compute a post::Report
// (cube_reports.hpp) and write it as text, CSV (--csv) or JSON (--json).
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
#include "pcrf/post/cube_notes.hpp"
#include "pcrf/post/cube_p695.hpp"
#include "pcrf/post/cube_reports.hpp"
#include "pcrf/post/cube_risk.hpp"
#include "pcrf/post/cube_sensitivity.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"

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
  std::vector<std::string> by;
  bool no_record_text = false;
  std::string reduce_over;  ///< stats, fragility: a dimension reduced over first (incidence_deg)
  std::string reduce_how;   ///< max, min or median over it; empty: the command's default (reduction_of)
  std::string output;
  std::string history;
  std::string points;
  bool json = false;
  // cube p695
  std::string sdc = "Dmax";
  double period_s = 0.0;
  double mu_t = 0.0;  // 0: each frame's own (docs/p695_rocking_frame.md)
  std::string ratings;  // empty: B,B,B, and the report says they are the default
  std::string s_ct = "counted";
  // cube risk
  std::string hazard;
  std::string tail = "power-law";
  double years = 50.0;
  risk::RiskTarget target;
};

std::vector<cube::Selector> selectors(const std::vector<std::string>& texts) {
  std::vector<cube::Selector> result;
  for (const auto& t : texts) result.push_back(cube::parse_selector(t));
  return result;
}

/// A cube that a study run is writing is read as its last fold; says so on stderr.
void note_running(const std::string& file) {
  if (const auto note = post::running_note(file); !note.empty()) std::cerr << "pcrf cube: " << note << '\n';
}

/// What the report `kind` of the cube should be read with (post::report_notes: results waiting
/// in its journal, cases never run, unresolved cases), one line each on stderr.
void note_report(const std::string& kind, const std::string& file, const cube::CubeReader& reader) {
  for (const auto& note : post::report_notes(kind, file, reader)) std::cerr << "pcrf cube " << kind << ": " << note << '\n';
}

/// Runs a cube action; cube problems (missing file, unknown name) are usage errors.
template <class Action>
void guarded(const std::string& file, Action action) {
  note_running(file);
  try {
    action();
  } catch (const cube::CubeError& e) {  // a cube that cannot be read is the user's input: named by its file
    throw post::unreadable_cube(file, e);
  }
}

bool is_stdout(const std::string& path) { return path.empty() || path == "-"; }

/// Every file the command reads: the cube and, for `cube risk`, the hazard curve. No output
/// may be one of them (io::check_output: the same file by device and inode).
std::vector<std::filesystem::path> inputs_of(const CubeArguments& args) {
  std::vector<std::filesystem::path> inputs{args.file};
  if (!args.hazard.empty()) inputs.emplace_back(args.hazard);
  return inputs;
}

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

/// --json and --csv of a reporting command: JSON alone on stdout; CSV to a file (beside the
/// text on stdout) or, with `--csv -`, alone on stdout.
void add_report_outputs(CLI::App* cmd, CubeArguments& args, const std::string& schema) {
  cmd->add_flag("--json", args.json, "one JSON object on stdout, full precision (schema below), instead of the text");
  cmd->add_option("--csv", args.csv, "also write the table as CSV (full precision) to this file; `-`: only the CSV, on stdout");
  add_overwrite(cmd, args);
  cmd->footer("--json writes {\"command\", the fields below, \"warnings\": [...], each table as a list of row objects, "
              "\"columns\": {table: [{\"name\", \"units\", \"description\"}]}}; null where a value does not exist.\n" +
              schema);
}

/// Writes a report: JSON, or the text (`text`, by default the table aligned) and the CSV
/// copy of `table` by add_report_outputs()' rules; the warnings on stderr, each prefixed.
void write_report(const post::Report& report, const std::string& table, const CubeArguments& args,
                  const std::string& warning_prefix, const std::function<void(std::ostream&)>& text = {}) {
  for (const auto& w : report.warnings) std::cerr << "pcrf cube " << report.command << ": " << warning_prefix << w << '\n';
  if (args.json) {
    post::write_json(report, std::cout);
  } else if (!is_stdout(args.csv) || args.csv.empty()) {
    if (text) text(std::cout);
    else post::write_text(report.table(table), std::cout);
  }
  if (!args.csv.empty())
    with_output(args.csv, inputs_of(args), args.overwrite, [&](std::ostream& out) { post::write_csv(report.table(table), out); });
}

/// Refuses --json with `--csv -` (both are stdout) and a CSV output that is the cube.
void check_report_outputs(const CubeArguments& args) {
  if (args.json && args.csv == "-") throw UserError(Where{}, "{} and {} - both write to stdout: choose one", {"json", "csv"});
  check_output(args.csv, inputs_of(args), args.overwrite);
}

std::string schema(const std::string& fields, const std::vector<std::pair<std::string, std::vector<post::Column>>>& tables) {
  std::string text = "fields: " + fields + "\n";
  for (const auto& [name, columns] : tables) text += "table " + name + ":\n" + post::describe_columns(columns);
  return text;
}

/// --reduce-over and --reduce of stats and fragility, which reduce differently by default:
/// the largest response (stats: θ_max's RotD100) and the smallest capacity (fragility: each
/// record's collapse intensity at its worst orientation).
void add_reduction(CLI::App* cmd, CubeArguments& args, const std::string& over_help, const std::string& default_how) {
  cmd->add_option("--reduce-over", args.reduce_over, over_help);
  cmd->add_option("--reduce", args.reduce_how, "how --reduce-over reduces: max, min or median (default: " + default_how + ")");
}

/// The reduction asked for, `default_how` unless --reduce says (post::reduction_of).
cube::Reduction reduction_of(const CubeArguments& args, const std::string& default_how) {
  return post::reduction_of(args.reduce_over, args.reduce_how, default_how);
}

void add_info(CLI::App* cube_cmd, const std::shared_ptr<CubeArguments>& args) {
  auto* info = cube_cmd->add_subcommand("info", "Axes, metrics, completion and failures by status");
  info->add_option("FILE", args->file, "result cube")->required();
  info->add_flag("--json", args->json, "one JSON object for scripts (dimensions with values, metrics with units, …)");
  info->callback([args] {
    guarded(args->file, [&] {
      const cube::CubeReader reader(args->file);
      for (const auto& note : post::completion_notes(args->file, reader)) std::cerr << "pcrf cube info: " << note << '\n';
      const auto completion = schema::completion(reader);
      if (args->json) cube::print_info_json(reader, std::cout, completion);
      else cube::print_info(reader, schema::info_heading(reader.layout()), std::cout, completion);
      if (const auto states = schema::curve_states_text(schema::curve_states(reader));
          !states.empty())
        (args->json ? std::cerr : std::cout) << states << '\n';
      for (const auto& line : post::verdict_lines("info", args->file, reader)) std::cerr << "pcrf cube info: " << line << '\n';
      // Vouch for nothing unread: a variable whose chunks no longer decompress is damage.
      const auto damage = reader.damage();
      if (!damage.empty()) {
        for (const auto& d : damage) std::cout << "DAMAGED: " << d << '\n';
        throw UserError(Where{{}, args->file, 0}, "damaged: " + std::to_string(damage.size()) +
                                                      " variables cannot be read; --resume cannot continue it");
      }
    });
  });
}

void add_export(CLI::App* cube_cmd, const std::shared_ptr<CubeArguments>& args) {
  auto* exporter = cube_cmd->add_subcommand("export", "Metrics as a long CSV table, one row per case");
  exporter->add_option("FILE", args->file, "result cube")->required();
  exporter->add_option("-m,--metric", args->metrics, "metric to export (repeatable; default: all)");
  add_where(exporter, *args);
  exporter->add_option("-o,--output", args->output, "CSV file (default: stdout)");
  exporter->add_flag("--no-record-text", args->no_record_text,
                     "leave out the records' long texts (where each comes from, its title): the record column names it");
  add_overwrite(exporter, *args);
  auto* history = exporter->add_option("--history", args->history,
                                       "instead: the stored history group /histories/NAME, one row per time");
  history->excludes(exporter->get_option("--metric"))->excludes(exporter->get_option("--where"));
  exporter->callback([args] {
    guarded(args->file, [&] {
      check_output(args->output, inputs_of(*args), args->overwrite);
      cube::CubeReader reader(args->file);
      if (!args->history.empty()) {
        with_output(args->output, inputs_of(*args), args->overwrite,
                    [&](std::ostream& out) { cube::export_history_csv(reader, args->history, out); });
        return;
      }
      const auto chosen = selectors(args->where);
      const auto leave_out = args->no_record_text ? schema::record_text_coordinates() : std::vector<std::string>{};
      with_output(args->output, inputs_of(*args), args->overwrite,
                  [&](std::ostream& out) { cube::export_csv(reader, args->metrics, chosen, out, leave_out); });
    });
  });
}

void add_stats(CLI::App* cube_cmd, const std::shared_ptr<CubeArguments>& args) {
  auto* stats = cube_cmd->add_subcommand(
      "stats", "Median and 16th/84th percentiles of a metric across records, per value of one or more coordinates; "
               "collapsed cases (tendon fracture, overturned) are counted apart, not in the percentiles. "
               "Default output: CSV on stdout");
  stats->add_option("FILE", args->file, "result cube")->required();
  stats->add_option("--by", args->by, "coordinate to group by (e.g. kappa, scale); repeat for combinations")->required();
  stats->add_option("-m,--metric", args->metric, "metric to summarize (or an IDA's collapse_intensity with --reduce-over)")->required();
  add_reduction(stats, *args,
                "first reduce the metric over this dimension (e.g. incidence_deg: each record and frame's worst "
                "orientation with --reduce max, RotD100; the median, RotD50; for an IDA's collapse_intensity the "
                "worst orientation is --reduce min); one --by",
                post::kStatsReduction);
  add_where(stats, *args);
  add_report_outputs(stats, *args, schema("file, metric, metric_units, by (comma-separated), reduced_over and reduction (when reduced)",
                                          {{"groups", post::stats_columns()}}));
  stats->callback([args] {
    guarded(args->file, [&] {
      check_report_outputs(*args);
      const auto reduction = reduction_of(*args, post::kStatsReduction);
      cube::CubeReader reader(args->file);
      note_report("stats", args->file, reader);
      const auto report = post::stats_report(reader, {args->by, args->metric, selectors(args->where), reduction});
      // The text of stats is its CSV (as it always was): --csv FILE adds a copy.
      write_report(report, "groups", *args, "",
                   [&](std::ostream& out) { post::write_csv(report.table("groups"), out); });
    });
  });
}

void add_fragility(CLI::App* cube_cmd, const std::shared_ptr<CubeArguments>& args) {
  auto* fragility = cube_cmd->add_subcommand(
      "fragility", "Lognormal collapse fragility of each frame (median, beta, 90 % bootstrap intervals)");
  fragility->add_option("FILE", args->file, "result cube with an intensity axis")->required();
  add_where(fragility, *args);
  fragility->add_option("--mce", args->mce, "MCE intensity (the measure's units): adds the collapse margin ratio");
  add_reduction(fragility, *args,
                "IDA cubes: first reduce each record's collapse intensities over this dimension (incidence_deg: "
                "--reduce min, the default, fits each record's worst orientation; median its RotD50-like value; max "
                "the best); a curve that never collapsed stays censored where it could change the reduced value",
                post::kFragilityReduction);
  fragility->add_option("--points", args->points,
                        "also write the fitted data as CSV to this file: stripes, or IDA collapse and censored intensities");
  add_report_outputs(fragility, *args,
                     schema("file, intensity_units, mce, reduced_over and reduction (when reduced)", {{"frames", post::fragility_columns()},
                                                           {"points", post::fragility_point_columns()}}));
  fragility->callback([args] {
    guarded(args->file, [&] {
      post::check_mce(args->mce);
      check_report_outputs(*args);
      const auto csv_inputs = inputs_of(*args);
      auto points_inputs = csv_inputs;
      points_inputs.emplace_back(args->csv);
      check_output(args->points, is_stdout(args->csv) ? csv_inputs : points_inputs, args->overwrite);
      const auto reduction = reduction_of(*args, post::kFragilityReduction);
      cube::CubeReader reader(args->file);
      note_report("fragility", args->file, reader);
      const auto report = post::fragility_report(reader, {selectors(args->where), args->mce}, reduction);
      write_report(report, "frames", *args, "");
      if (!args->points.empty())
        with_output(args->points, is_stdout(args->csv) ? csv_inputs : points_inputs, args->overwrite,
                    [&](std::ostream& out) { post::write_csv(report.table("points"), out); });
    });
  });
}

void add_sensitivity(CLI::App* cube_cmd, const std::shared_ptr<CubeArguments>& args) {
  auto* sensitivity = cube_cmd->add_subcommand(
      "sensitivity", "First-order and total Sobol' indices of a saltelli cube, with 90 % bootstrap intervals");
  sensitivity->add_option("FILE", args->file, "result cube of a saltelli plan")->required();
  sensitivity->add_option("-m,--metric", args->metric, "a metric, or `collapse` (tendon fracture or overturned)")->required();
  add_where(sensitivity, *args);
  sensitivity->add_option("--by", args->by, "`record`: one set of indices per record (default: across records)");
  add_report_outputs(sensitivity, *args,
                     schema("file, metric, by_record (0 or 1)", {{"indices", post::sensitivity_columns()}}));
  sensitivity->callback([args] {
    guarded(args->file, [&] {
      const bool by_record = !args->by.empty();
      if (args->by.size() > 1 || (by_record && args->by.front() != "record")) throw UserError("by", "takes `record` only");
      check_report_outputs(*args);
      cube::CubeReader reader(args->file);
      note_report("sensitivity", args->file, reader);
      write_report(post::sensitivity_report(reader, {args->metric, selectors(args->where), by_record}), "indices", *args, "");
    });
  });
}

/// The P-695 inputs of the command line, checked (post::p695_inputs).
post::P695Inputs p695_inputs(const CubeArguments& args) {
  return post::p695_inputs(args.sdc, args.period_s, args.mu_t, args.ratings, args.s_ct);
}

void add_p695(CLI::App* cube_cmd, const std::shared_ptr<CubeArguments>& args) {
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
                       "quality ratings A-D of design requirements, test data and modelling, e.g. B,B,C "
                       "(default B,B,B, which the report then notes)");
  p695_cmd->add_option("--s-ct", args->s_ct,
                       "which median collapse intensity feeds CMR and ACMR: counted (P-695 Sections 6.3-6.4: the "
                       "intensity at which half the records collapse) or lognormal (the fitted fragility's median)")
      ->capture_default_str();
  add_report_outputs(p695_cmd, *args,
                     schema("file, sdc, period_s, mu_t, ratings, ratings_source (given or default), s_ct (counted or lognormal), group_mean_acmr, group_acmr10, group (pass or fail), "
                            "measure_problem (empty when the cube is at Sa(T)), " + post::model_field_names() +
                                ", model_p_collapse_mce_measured, model_p_collapse_mce_rated",
                            {{"frames", post::p695_columns()}}));
  p695_cmd->callback([args] {
    guarded(args->file, [&] {
      const post::P695Inputs in = p695_inputs(*args);
      check_report_outputs(*args);
      cube::CubeReader reader(args->file);
      note_report("p695", args->file, reader);
      const post::P695Report result = post::cube_p695(reader, selectors(args->where), in);
      write_report(post::p695_report(result, in, args->file), "frames", *args, "warning: ",
                   [&](std::ostream& out) { post::print_p695(result, in, out); });
    });
  });
}

void add_risk(CLI::App* cube_cmd, const std::shared_ptr<CubeArguments>& args) {
  auto* risk_cmd = cube_cmd->add_subcommand(
      "risk", "Annual collapse rate of each frame at a site: its fragility integrated against a hazard curve, "
              "p in --years, deaggregation, risk-targeted intensity (docs/risk.md)");
  risk_cmd->add_option("FILE", args->file, "result cube with an intensity axis (IDA or stripes)")->required();
  risk_cmd->add_option("--hazard", args->hazard,
                       "hazard curve CSV: header MEASURE,annual_rate_per_yr (the cube's measure, e.g. sa_g with a "
                       "'# period_s = T' line before it), then intensity,rate rows")
      ->required();
  risk_cmd->add_option("--years", args->years, "t of p_collapse_in_years = 1 - exp(-lambda_c t) [yr]")->capture_default_str();
  risk_cmd->add_option("--tail", args->tail,
                       "beyond the curve's last point: power-law (its last two points' slope) or cut-off (the rate of "
                       "exceeding the last point counted there: a lower bound)")
      ->capture_default_str();
  risk_cmd->add_option("--target-probability", args->target.target_probability,
                       "risk target: collapse probability in --target-years")->capture_default_str();
  risk_cmd->add_option("--target-years", args->target.years, "risk target's years")->capture_default_str();
  risk_cmd->add_option("--generic-beta", args->target.beta,
                       "beta of the generic fragility of the risk-targeted intensity (ASCE 7-16: 0.6)")->capture_default_str();
  risk_cmd->add_option("--generic-probability", args->target.collapse_probability,
                       "collapse probability of the generic fragility at the risk-targeted intensity (ASCE 7-16: 0.1)")
      ->capture_default_str();
  risk_cmd->add_option("--ratings", args->ratings,
                       "FEMA P-695 quality ratings A-D (design, tests, model) whose dispersions are added to each fit's beta "
                       "for a second lambda_c")
      ->capture_default_str();
  add_where(risk_cmd, *args);
  add_report_outputs(risk_cmd, *args,
                     schema("file, hazard_file, measure, period_s, tail, years, target_probability, target_years, "
                            "target_rate_per_yr, generic_beta, generic_collapse_probability, risk_targeted_intensity, "
                            "ratings, ratings_beta, "
                            "uniform_hazard_intensity_2pct_50yr, risk_coefficient, group_frames, "
                            "group_lambda_collapse_per_yr, group_p_collapse_in_years, group_lambda_collapse_max_per_yr, " +
                                post::model_field_names() +
                                ", model_lambda_pooled_per_yr, model_lambda_measured_per_yr, model_lambda_rated_per_yr; "
                                "tables hazard (the curve read) and empirical (each frame's step fragility) for figures",
                            {{"frames", post::risk_columns()}, {"deaggregation", post::risk_deaggregation_columns()}}));
  risk_cmd->callback([args] {
    guarded(args->file, [&] {
      post::RiskInputs in;
      in.hazard = args->hazard;
      in.years = args->years;
      in.target = args->target;
      post::Report report;
      in.tail = risk::parse_tail(args->tail);
      const auto ratings = post::p695_inputs("Dmax", 1.0, 0.0, args->ratings);  // the ratings checked as p695 checks them
      in.design_rating = ratings.design_rating, in.test_rating = ratings.test_rating, in.model_rating = ratings.model_rating;
      check_report_outputs(*args);
      cube::CubeReader reader(args->file);
      note_report("risk", args->file, reader);
      report = post::risk_report(post::cube_risk(reader, selectors(args->where), in), in, args->file);
      write_report(report, "frames", *args, "warning: ", [&](std::ostream& out) { post::print_risk(report, out); });
    });
  });
}

void add_merge(CLI::App* cube_cmd, const std::shared_ptr<CubeArguments>& args) {
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
        throw UserError(Where{}, args->output + ": in use by a run (" + who + "); give another {}", {"output"});
      const auto merged = cube::merge_cubes(parts, args->output, args->overwrite, schema::kIdaRuns,
                                            args->allow_missing);
      if (merged.missing > 0)
        std::cerr << "pcrf cube merge: " << args->output << ": " << merged.missing << " of " << merged.total
                  << " cases are in no part: the merged cube is partial (attribute " << cube::kMissingCasesName << ")\n";
      std::cout << "merged " << parts.size() << " parts into " << args->output << '\n';
    });
  });
}

}  // namespace

void add_cube_command(CLI::App& app) {
  auto args = std::make_shared<CubeArguments>();
  auto* cube_cmd = app.add_subcommand("cube", "Look into a result cube");
  cube_cmd->require_subcommand(1);
  add_info(cube_cmd, args);
  add_export(cube_cmd, args);
  add_stats(cube_cmd, args);
  add_fragility(cube_cmd, args);
  add_sensitivity(cube_cmd, args);
  add_p695(cube_cmd, args);
  add_risk(cube_cmd, args);
  add_merge(cube_cmd, args);
}

}  // namespace pcrf::cli

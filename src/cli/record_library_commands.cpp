// `pcrf record spectra DIR|FILE…` and `pcrf record select --target --library -n`: the
// spectra of a record library as a table, and records selected from it to match a target
// (record/record_library.hpp, record/selection.hpp).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

#include "cli/commands.hpp"
#include "pcrf/api/record_selection.hpp"
#include "pcrf/io/output_file.hpp"
#include "pcrf/json.hpp"
#include "pcrf/number_text.hpp"
#include "pcrf/record/record_library.hpp"
#include "pcrf/record/selection.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf::cli {
namespace {

namespace fs = std::filesystem;

bool to_stdout(const std::string& path) { return path.empty() || path == "-"; }

void write_output(const std::string& path, const std::vector<fs::path>& inputs, bool overwrite,
                  const std::function<void(std::ostream&)>& write) {
  if (to_stdout(path)) {
    write(std::cout);
    return;
  }
  io::OutputFile out(path, inputs, overwrite);
  write(out.stream());
  out.commit();
}

struct SpectraArguments {
  std::vector<std::string> paths;
  std::vector<double> periods_s;
  double damping = 0.05;
  std::string output;
  bool overwrite = false;
};

void compute_library_spectra(const SpectraArguments& args) {
  const std::vector<double> periods = args.periods_s.empty() ? default_spectra_periods_s() : args.periods_s;
  if (const std::string p = periods_problem(periods); !p.empty()) throw UserError("periods_s", p, {"periods_s"});
  std::vector<fs::path> inputs(args.paths.begin(), args.paths.end());
  std::vector<std::string> skipped;
  const std::vector<fs::path> files = library_files(inputs, skipped);
  if (files.empty()) throw UserError("no .AT2 record files found in " + args.paths.front());
  if (!to_stdout(args.output)) io::check_output(args.output, files, args.overwrite);
  // The progress line: rewritten in place on a terminal, a line per tenth of the files otherwise.
  const bool terminal = isatty(STDERR_FILENO) != 0;
  const SpectraTable table = compute_spectra(files, periods, args.damping, skipped, [terminal](std::size_t done, std::size_t total, const std::string&) {
    if (terminal) std::cerr << "\rpcrf record spectra: " << done << "/" << total << " files" << (done == total ? "\n" : "") << std::flush;
    else if (done == total || done % std::max<std::size_t>(1, total / 10) == 0)
      std::cerr << "pcrf record spectra: " << done << "/" << total << " files\n";
  });
  for (const auto& line : skipped) std::cerr << "pcrf record spectra: note: " << line << '\n';
  write_output(args.output, files, args.overwrite, [&](std::ostream& out) { write_spectra_csv(out, table); });
  std::size_t pairs = 0;
  for (const auto& e : table.entries) pairs += e.kind == "rotd50";
  std::cerr << "pcrf record spectra: " << table.entries.size() - pairs << " components, " << pairs << " pairs (RotD50), "
            << periods.size() << " periods" << (to_stdout(args.output) ? "" : " -> " + args.output) << '\n';
}

struct SelectArguments {
  std::string target, library, output;
  SelectionSettings settings;
  bool json = false, overwrite = false;
};

std::string toml_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) out += (c == '"' || c == '\\') ? std::string("\\") + c : std::string(1, c);
  return out + "\"";
}

void write_fragment(std::ostream& out, const SelectArguments& args, const SpectraTable& table, const SelectionResult& r) {
  out << "# pcrf record select: " << r.records.size() << " records of " << args.library << " (kind " << args.settings.kind
      << ") for the target " << args.target << "\n"
      << "# Jayaram, Lin & Baker (2011); Baker & Lee (2018). Fit of the scaled set's ln Sa at the target's periods:\n"
      << "#   largest error of the median " << number_text(std::round(r.median_error_percent * 100) / 100) << " %, of sigma ln Sa "
      << number_text(std::round(r.sigma_error_percent * 100) / 100) << " %, Baker & Lee's sum of squared errors "
      << number_text(r.sum_of_squares) << " (w_mean 1, w_sigma 2)\n"
      << "#   optimised: w_mean " << number_text(args.settings.w_mean) << ", w_sigma " << number_text(args.settings.w_sigma)
      << (args.settings.relative_sigma ? " on relative sigma errors" : "") << ", " << args.settings.starts << " starts\n"
      << "# File paths are as the library table names them.\n";
  for (const auto& rec : r.records) {
    const LibraryEntry& e = table.entries[rec.entry];
    out << "\n[[records]]\n";
    if (e.kind == "rotd50") out << "h1 = " << toml_string(e.file) << "\nh2 = " << toml_string(e.file_h2) << "\n";
    else out << "file = " << toml_string(e.file) << "\n";
    out << "name = " << toml_string(e.name) << "\nscale = " << number_text(rec.scale) << "\n";
  }
}

void select_from_library(const SelectArguments& args) {
  const SelectionTarget target = api::read_selection_target_file(args.target);
  const SpectraTable table = api::read_spectra_table_file(args.library);
  if (!to_stdout(args.output)) io::check_output(args.output, {args.target, args.library}, args.overwrite);
  const SelectionResult r = select_records(target, table, args.settings);
  std::cerr << "pcrf record select: largest error of the median " << number_text(std::round(r.median_error_percent * 10) / 10)
            << " %, of sigma ln Sa " << number_text(std::round(r.sigma_error_percent * 10) / 10) << " %\n";
  write_output(args.output, {args.target, args.library}, args.overwrite, [&](std::ostream& out) {
    if (args.json) out << api::selection_json(target, table, r).str() << '\n';
    else write_fragment(out, args, table, r);
  });
}

}  // namespace

void add_record_library_commands(CLI::App* record) {
  auto spectra = std::make_shared<SpectraArguments>();
  auto* s = record->add_subcommand("spectra", "Sa of every record of a folder (components and RotD50 of pairs) as a CSV table");
  s->add_option("PATHS", spectra->paths, "folders (searched for .AT2 files) or record files")->required();
  s->add_option("--periods-s,--period", spectra->periods_s, "oscillator periods [s] (repeatable; default 30 from 0.05 s to 10 s)");
  s->add_option("--damping", spectra->damping, "damping ratio [-]")->capture_default_str();
  s->add_option("-o,--output", spectra->output, "the table (CSV); default stdout");
  s->add_flag("--overwrite", spectra->overwrite, "replace an existing output file");
  s->callback([spectra] { compute_library_spectra(*spectra); });

  auto select = std::make_shared<SelectArguments>();
  auto* c = record->add_subcommand("select", "Records of a library whose scaled spectra match a target mean and sigma of ln Sa");
  c->add_option("--target", select->target, "target CSV: period_s,mean_ln_sa,sigma_ln_sa[,rho_<T>s…]")->required();
  c->add_option("--library", select->library, "table of pcrf record spectra")->required();
  c->add_option("-n,--count", select->settings.count, "number of records")->required();
  c->add_option("--kind", select->settings.kind, "library entries: rotd50 (pairs) or component")->capture_default_str();
  c->add_option("--scale-min", select->settings.scale_min, "smallest scale factor")->capture_default_str();
  c->add_option("--scale-max", select->settings.scale_max, "largest scale factor")->capture_default_str();
  c->add_option("--seed", select->settings.seed, "seed of the simulated spectra")->capture_default_str();
  c->add_option("--trials", select->settings.trials, "simulated sets")->capture_default_str();
  c->add_option("--starts", select->settings.starts, "greedy optimisations, from the best simulated sets (1: Baker & Lee's one)")
      ->capture_default_str();
  c->add_option("--loops", select->settings.loops, "greedy passes at most (it stops when a pass improves nothing)")
      ->capture_default_str();
  c->add_option("--w-mean", select->settings.w_mean, "weight of the mean's squared errors in the objective")->capture_default_str();
  c->add_option("--w-sigma", select->settings.w_sigma, "weight of sigma's squared errors in the objective")->capture_default_str();
  c->add_flag("--relative-sigma", select->settings.relative_sigma,
              "optimise sigma ln Sa on relative errors (w_sigma sum ((s - sigma)/sigma)^2), not Baker & Lee's absolute ones");
  c->add_flag("--json", select->json, "print the selection as JSON (spectra and fit) instead of [[records]]");
  c->add_option("-o,--output", select->output, "output file; default stdout");
  c->add_flag("--overwrite", select->overwrite, "replace an existing output file");
  c->callback([select] { select_from_library(*select); });
}

}  // namespace pcrf::cli

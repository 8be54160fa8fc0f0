// Joining the cubes of a sharded run (see cube_merge.hpp).
#include "pcrf/cube/cube_merge.hpp"

#include <sys/stat.h>

#include <cmath>
#include <map>
#include <memory>
#include <string>

#include "pcrf/cube/cube_journal.hpp"
#include "pcrf/cube/cube_part.hpp"
#include "pcrf/cube/cube_reader.hpp"
#include "pcrf/cube/cube_writer.hpp"
#include "pcrf/io/file_kind.hpp"
#include "pcrf/io/output_file.hpp"

namespace pcrf::cube {

MergeResult merge_cubes(const std::vector<std::filesystem::path>& parts, const std::filesystem::path& output, bool overwrite,
                        const std::string& runs_variable, bool allow_missing) {
  if (parts.empty()) throw CubeError("no cube to merge");
  // A cube is a regular file: a FIFO or a device at -o is refused before it is opened (a FIFO
  // that no process reads would make the open wait for ever).
  if (struct stat st {}; ::stat(output.c_str(), &st) == 0 && !S_ISREG(st.st_mode) && !S_ISDIR(st.st_mode))
    throw CubeError(output.string() + ": is " + io::kind_of(st.st_mode) + "; the merged cube must be a regular file");
  // Written beside the output and renamed over it when complete: a merge that fails or is
  // killed leaves no cube at -o (and any old one intact).
  io::OutputFile out(output, parts, overwrite);
  if (out.temporary().empty()) throw CubeError(output.string() + ": the merged cube must be a regular file");

  std::vector<std::unique_ptr<CubeReader>> readers;
  for (const auto& part : parts) {
    readers.push_back(std::make_unique<CubeReader>(part));
    const auto& layout = readers.back()->layout();
    try {
      const JournalReader journal(part, layout, journal_id_of(layout));
      journal.check_all();
      if (const auto waiting = journal.results(); waiting > 0)
        throw CubeError(part.string() + ": " + std::to_string(waiting) + " results wait in its journal " +
                        journal_path(part).string() + ": --resume its run to fold them in, then merge");
    } catch (const JournalDamage& e) {
      throw CubeError(std::string(e.what()) + ": --resume its run (which sets the journal aside and computes its cases "
                      "again), then merge");
    }
    if (const auto kept = part_files(part); !kept.empty())
      throw CubeError(part.string() + ": its ranks' parts (" + kept.front().string() + (kept.size() > 1 ? ", …" : "") +
                      ") hold results not in the cube yet: --resume its run first (which folds them in), then merge");
  }
  const CubeLayout& first = readers.front()->layout();
  const std::string fingerprint = first.text_attribute(kFingerprintName);
  for (std::size_t p = 1; p < readers.size(); ++p) {
    const auto& layout = readers[p]->layout();
    if (layout.text_attribute(kFingerprintName) != fingerprint)
      throw CubeError(parts[p].string() + ": is from another study (fingerprint " + layout.text_attribute(kFingerprintName) +
                      ", " + parts.front().string() + " has " + fingerprint + ")");
    if (layout.shape() != first.shape() || layout.metrics.size() != first.metrics.size())
      throw CubeError(parts[p].string() + ": has another shape or other metrics than " + parts.front().string());
  }

  // Which part holds each case; a case in two parts, or in none, is an error.
  const auto n = static_cast<std::size_t>(first.case_count());
  std::vector<int> owner(n, -1);
  std::vector<std::vector<std::int8_t>> status;
  for (std::size_t p = 0; p < readers.size(); ++p) {
    status.push_back(readers[p]->read_status());
    for (std::size_t i = 0; i < n; ++i) {
      if (status[p][i] == kStatusNotRun) continue;
      if (owner[i] >= 0)
        throw CubeError(parts[p].string() + ": case " + std::to_string(i) + " is also in " +
                        parts[static_cast<std::size_t>(owner[i])].string() + ": the parts overlap");
      owner[i] = static_cast<int>(p);
    }
  }
  CubeLayout layout = first;
  std::erase_if(layout.attributes, [](const Attribute& a) { return a.name == kShardName; });
  for (auto& side : layout.side_variables) {  // each value from the part that has it
    side.values.assign(layout.side_size(side), std::nan(""));
    for (const auto& reader : readers) {
      const auto values = reader->read_side(side.name);
      for (std::size_t k = 0; k < values.size(); ++k)
        if (std::isnan(side.values[k]) && !std::isnan(values[k])) side.values[k] = values[k];
    }
  }
  // A coordinate written during the run (Coordinate::written_live) may be NaN in a shard's
  // cube where its cases were not run there (one stopped before its close): each value from
  // the part that has it, as the side variables' (a value of one part is every part's).
  for (auto& c : layout.coordinates) {
    if (c.is_text || c.computed()) continue;
    for (std::size_t p = 1; p < readers.size(); ++p) {
      const Coordinate* other = readers[p]->layout().find_coordinate(c.name);
      if (other == nullptr || other->numbers.size() != c.numbers.size()) continue;
      for (std::size_t k = 0; k < c.numbers.size(); ++k)
        if (std::isnan(c.numbers[k]) && !std::isnan(other->numbers[k])) c.numbers[k] = other->numbers[k];
    }
  }
  // A case in no part is missing unless the runs variable says its row stopped before it.
  const SideVariable* runs = runs_variable.empty() ? nullptr : layout.find_side_variable(runs_variable);
  const std::size_t row_length = layout.dimensions.empty() ? 1 : layout.dimensions.back().size;
  if (runs != nullptr && layout.side_size(*runs) * row_length != n)
    throw CubeError(parts.front().string() + ": " + runs_variable + " does not span every dimension but the last");
  auto expected = [&](std::size_t i) {  // a row no part ran (NaN) is missing whole
    return runs == nullptr || !(static_cast<double>(i % row_length) >= runs->values[i / row_length]);
  };
  std::size_t missing = 0, first_missing = n;
  for (std::size_t i = 0; i < n; ++i)
    if (owner[i] < 0 && expected(i) && ++missing == 1) first_missing = i;
  if (missing > 0 && !allow_missing)
    throw CubeError(std::to_string(missing) + " of " + std::to_string(n) + " cases are in no part (the first: case " +
                    std::to_string(first_missing) + "); run the missing shards, then merge again (or merge what there is "
                    "with --allow-missing)");
  // The merged cube says it is partial; its status says which cases (not run).
  if (missing > 0) layout.attributes.push_back({kMissingCasesName, static_cast<std::int64_t>(missing)});

  CubeWriter writer(out.temporary(), layout, OpenMode::kOverwrite);
  std::vector<std::vector<std::vector<double>>> metrics(readers.size());
  for (std::size_t p = 0; p < readers.size(); ++p)
    for (const auto& m : first.metrics) metrics[p].push_back(readers[p]->read_metric(m.name));
  std::vector<double> row(first.metrics.size());
  for (std::size_t i = 0; i < n; ++i) {
    if (owner[i] < 0) continue;
    const auto p = static_cast<std::size_t>(owner[i]);
    for (std::size_t m = 0; m < row.size(); ++m) row[m] = metrics[p][m][i];
    writer.store(static_cast<std::int64_t>(i), status[p][i], row);
  }
  for (const auto& reader : readers)
    for (auto& [index, note] : reader->read_notes()) writer.store_note(index, note);
  // Each shard stored the histories of its own cases: join them, each from the one part that has it.
  std::map<std::string, std::size_t> history_part;
  for (std::size_t p = 0; p < readers.size(); ++p)
    for (const auto& name : readers[p]->history_names()) {
      if (const auto [it, fresh] = history_part.emplace(name, p); !fresh)
        throw CubeError(parts[p].string() + ": history " + name + " is also in " + parts[it->second].string() +
                        ": the parts overlap");
      writer.store_history(readers[p]->read_history(name));
    }
  writer.close();
  out.commit();
  return {missing, n};
}

}  // namespace pcrf::cube

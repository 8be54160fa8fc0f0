// Notes on a cube being read (see cube_notes.hpp).
#include "pcrf/post/cube_notes.hpp"

#include <sys/stat.h>

#include "pcrf/cube/cube_journal.hpp"
#include "pcrf/cube/cube_part.hpp"
#include "pcrf/io/file_kind.hpp"
#include "pcrf/io/run_lock.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"

#include <optional>
#include <stdexcept>

namespace pcrf::post {

std::string running_note(const std::string& file) {
  const std::string who = io::RunLock::holder(file);
  return who.empty() ? std::string() : file + ": a run holds it (" + who + "): read as its last folded state (docs/checkpoint.md)";
}

std::string journal_note(const std::string& file, const cube::CubeReader& reader) {
  const auto journal = cube::journal_path(file).string();
  struct stat st {};
  if (::lstat(journal.c_str(), &st) != 0) return {};  // none: nothing to say
  try {
    const cube::JournalReader waiting(file, reader.layout(), cube::journal_id_of(reader.layout()));
    if (!waiting.current())
      return file + ": its journal " + journal + " is not of its last fold (stale: its results are in the cube, or are "
             "another cube's) and is ignored; the next run replaces it";
    waiting.check_all();
    std::string note = file + ": " + std::to_string(waiting.results()) + " results wait in its journal " + journal +
                       ", not read here (a run folds them in as it goes and at its end; --resume folds those of a stopped run)";
    if (waiting.dropped_bytes() > 0)
      note += "; its last " + std::to_string(waiting.dropped_bytes()) + " bytes (" +
              std::to_string(waiting.dropped_records()) + " complete records of a checkpoint never closed" +
              (waiting.damaged() ? ", then a torn or damaged record" : "") +
              ") are dropped by --resume, which computes their cases again";
    return note;
  } catch (const cube::JournalDamage& e) {
    return file + ": its journal cannot be replayed, so only the cube's last fold is read: " + e.what() +
           "; --resume sets it aside and computes its cases again";
  } catch (const cube::CubeError& e) {
    return file + ": its journal cannot be read, so only the cube's last fold is: " + e.what();
  }
}

std::string parts_note(const std::string& file, const cube::CubeReader& reader) {
  const auto parts = cube::part_files(file);
  if (parts.empty()) return {};
  const std::string header = cube::part_header_payload(cube::part_header_of(reader.layout()));
  std::int64_t waiting = 0;
  std::vector<std::string> named, problems;
  for (const auto& part : parts) {
    try {
      io::check_sidecar(part, io::kPartWhat);
      const cube::JournalReader read(part, reader.layout(), header);
      if (read.foreign()) {
        problems.push_back(part.string() + " is not a part of this cube (--resume sets it aside)");
        continue;
      }
      read.check_all();
      waiting += read.results();
      named.push_back(part.filename().string());
      if (read.dropped_bytes() > 0)
        problems.push_back(part.string() + "'s last " + std::to_string(read.dropped_bytes()) +
                           " bytes (a chunk never committed) are dropped by --resume, which computes their cases again");
    } catch (const cube::JournalDamage& e) {
      problems.push_back(std::string(e.what()) + ": the part cannot be used; --resume sets it aside and computes its cases again");
    } catch (const std::exception& e) {
      problems.push_back(std::string(e.what()));
    }
  }
  std::string note;
  if (!named.empty()) {
    note = file + ": " + std::to_string(waiting) + " results wait in its ranks' parts (";
    for (std::size_t k = 0; k < named.size(); ++k) note += (k > 0 ? ", " : "") + named[k];
    note += "), not read here (the run's end folds them in; --resume folds those of a stopped run, skipping chunks "
            "the cube holds)";
  }
  for (const auto& problem : problems) note += (note.empty() ? file + ": " : "; ") + problem;
  return note;
}

std::string partial_note(const std::string& file, const cube::CubeReader& reader) {
  const auto missing = schema::not_run(reader);
  if (missing.count == 0) return {};
  return file + ": " + std::to_string(missing.count) + " of " + std::to_string(missing.total) + " " + missing.unit +
         " not run (a partial cube): left out";
}

std::string unresolved_treatment(const std::string& kind) {
  if (kind == "stats") return "in the column `unresolved`, not in the percentiles";
  if (kind == "sensitivity") return "without a value (their base samples are left out)";
  if (kind == "fragility" || kind == "p695" || kind == "risk") return "counted in no stripe (neither safe nor collapsed)";
  if (kind == "info") return "neither safe nor collapsed";
  throw std::invalid_argument("unresolved_treatment: no report '" + kind + "'");
}

std::vector<std::string> completion_notes(const std::string& file, const cube::CubeReader& reader) {
  std::vector<std::string> notes;
  for (auto& note : {journal_note(file, reader), parts_note(file, reader), partial_note(file, reader)})
    if (!note.empty()) notes.push_back(note);
  return notes;
}

std::vector<std::string> verdict_lines(const std::string& kind, const std::string& file, const cube::CubeReader& reader) {
  namespace v = schema;
  const auto& layout = reader.layout();
  const bool ida = layout.find_side_variable(v::kIdaRuns) != nullptr;
  std::vector<std::string> lines;
  for (const auto& line : v::verdict_notes(reader.read_status(),
                                           ida ? std::optional<std::string>(layout.text_attribute(v::kIdaCollapseAttribute))
                                               : std::nullopt,
                                           unresolved_treatment(kind), v::tail_s_of(layout)))
    lines.push_back(file + ": " + line);
  return lines;
}

std::vector<std::string> report_notes(const std::string& kind, const std::string& file, const cube::CubeReader& reader) {
  auto notes = completion_notes(file, reader);
  for (auto& line : verdict_lines(kind, file, reader)) notes.push_back(std::move(line));
  return notes;
}

}  // namespace pcrf::post

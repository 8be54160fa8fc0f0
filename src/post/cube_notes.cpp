// Notes on a cube being read (see cube_notes.hpp).
#include "pcrf/post/cube_notes.hpp"

#include "pcrf/cube/cube_journal.hpp"
#include "pcrf/io/run_lock.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"

namespace pcrf::post {

std::string running_note(const std::string& file) {
  const std::string who = io::RunLock::holder(file);
  return who.empty() ? std::string() : file + ": a run holds it (" + who + "): read as its last folded state (docs/checkpoint.md)";
}

std::string journal_note(const std::string& file, const cube::CubeReader& reader) {
  const auto journal = cube::journal_path(file).string();
  try {
    const cube::JournalReader waiting(file, reader.layout(), cube::journal_id_of(reader.layout()));
    if (waiting.results() == 0) return {};
    return file + ": " + std::to_string(waiting.results()) + " results wait in its journal " + journal +
           ", not read here (a run folds them in as it goes and at its end; --resume folds those of a stopped run)";
  } catch (const cube::CubeError& e) {
    return file + ": its journal cannot be read, so only the cube's last fold is: " + e.what();
  }
}

std::string partial_note(const std::string& file, const cube::CubeReader& reader) {
  const auto missing = schema::not_run(reader);
  if (missing.count == 0) return {};
  return file + ": " + std::to_string(missing.count) + " of " + std::to_string(missing.total) + " " + missing.unit +
         " not run (a partial cube): left out";
}

}  // namespace pcrf::post

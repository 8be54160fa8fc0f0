// Notes on a cube being read (see cube_notes.hpp).
#include "pcrf/post/cube_notes.hpp"

#include "pcrf/io/run_lock.hpp"
#include "pcrf/schema/cube_vocabulary.hpp"

namespace pcrf::post {

std::string running_note(const std::string& file) {
  const std::string who = io::RunLock::holder(file);
  return who.empty() ? std::string() : file + ": a run holds it (" + who + "): read as its last complete checkpoint";
}

std::string partial_note(const std::string& file, const cube::CubeReader& reader) {
  const auto missing = study::vocabulary::not_run(reader);
  if (missing.count == 0) return {};
  return file + ": " + std::to_string(missing.count) + " of " + std::to_string(missing.total) + " " + missing.unit +
         " not run (a partial cube): left out";
}

}  // namespace pcrf::post

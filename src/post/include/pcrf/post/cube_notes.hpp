/// \file cube_notes.hpp
/// \brief What a reader of a cube should know before trusting what it read, one line each,
/// naming the file first: the command line prints them on stderr after its own prefix, the
/// figures after theirs.
#pragma once

#include <string>
#include <vector>

#include "pcrf/cube/cube_reader.hpp"

namespace pcrf::post {

/// "FILE: a run holds it (WHO): read as its last folded state" while a study run
/// writes `file` (each fold is renamed into place whole); empty otherwise.
std::string running_note(const std::string& file);

/// "FILE: N results wait in its journal FILE.journal, …" when a run checkpointed results
/// since the cube's last fold (docs/checkpoint.md): a reader sees the last fold only. Empty
/// when there is no journal, or a stale one; a journal that cannot be read is said so.
std::string journal_note(const std::string& file, const cube::CubeReader& reader);

/// "FILE: N results wait in its ranks' parts (FILE.part-1, …), not read here …" when worker
/// ranks kept sealed chunks beside the cube (cube_part.hpp) that no fold took yet (a stopped
/// run), and any part that cannot be used (foreign, damaged, not a regular file). Empty when
/// there is none.
std::string parts_note(const std::string& file, const cube::CubeReader& reader);

/// "FILE: N of M cases not run (a partial cube): left out" (an IDA counts curves) for a cube
/// stopped early or merged from some shards; empty for a complete one.
/// \throws cube::CubeError when the cube cannot be read.
std::string partial_note(const std::string& file, const cube::CubeReader& reader);

/// What `pcrf cube KIND` (info, stats, fragility, sensitivity, p695, risk) does with the cases
/// a cube leaves unresolved, for its verdict notes: "counted in no stripe (…)".
/// \throws std::invalid_argument for another kind (a bug).
std::string unresolved_treatment(const std::string& kind);

/// journal_note, parts_note and partial_note, those not empty.
std::vector<std::string> completion_notes(const std::string& file, const cube::CubeReader& reader);

/// "FILE: …" for each line of vocabulary::verdict_notes of the cube (unresolved cases and what
/// KIND does with them, collapse statuses an IDA's collapse set leaves out).
std::vector<std::string> verdict_lines(const std::string& kind, const std::string& file, const cube::CubeReader& reader);

/// What a reader of the report KIND of `file` should know before trusting it, one line each,
/// naming the file first: completion_notes, then verdict_lines. The command
/// line prints them on stderr after "pcrf cube KIND: ", Python warns them (pcrf.PcrfWarning).
/// \throws cube::CubeError when the cube cannot be read.
std::vector<std::string> report_notes(const std::string& kind, const std::string& file, const cube::CubeReader& reader);

}  // namespace pcrf::post

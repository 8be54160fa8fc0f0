/// \file study_parser.hpp
/// \brief Reads a study file (TOML) into a Study, rejecting unknown keys, wrong types,
/// empty or backwards ranges, out-of-range values and missing record files.
#pragma once

#include <filesystem>
#include <string>

#include <toml++/toml.h>

#include "pcrf/study/study.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf::study {

/// Parses study text. `file` labels messages; relative record paths resolve against
/// `base_dir`. \throws UserError.
Study parse_study(const std::string& text, const std::string& file,
                  const std::filesystem::path& base_dir);

/// Reads a study already in TOML tables (e.g. built from a Python dict), whose nodes may
/// carry no source position: messages then name `file` and the key path
/// ("study: [axes] kappa: …"). `text` is what the cube keeps as the study's text.
/// \throws UserError.
Study parse_study_table(const toml::table& root, const std::string& text, const std::string& file,
                        const std::filesystem::path& base_dir);

/// Reads and parses a study file; record paths resolve against its folder.
/// \throws UserError (also when the file cannot be read).
Study load_study(const std::filesystem::path& file);

/// Reads a whole text file. \throws UserError naming it.
std::string read_text_file(const std::filesystem::path& file);

}  // namespace pcrf::study

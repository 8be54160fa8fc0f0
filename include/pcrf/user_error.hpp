/// \file user_error.hpp
/// \brief The one error of bad user input, carried as data: where the problem lies (a key
/// path, with the file and line when the input is a file) and what it is. Every layer throws
/// it as it finds the problem; no layer rewrites another's message. Each front end renders
/// `where` in its own dialect:
///
///   a study file       "FILE:LINE: physics.tail_s: must be positive (got -1)"
///   the command line   "--tail-s: must be positive (got -1)"
///   Python             "tail_s=: must be positive (got -1)"
///
/// A problem may name other keys as "{}", filled in order from `named`, each in the same
/// dialect ("give either {} or {}, not both"). A bug is not a UserError: the command line
/// reports any other exception as an internal error (exit code 1), a user error with exit
/// code 2.
///
/// UserError is a std::invalid_argument, the type every layer used for bad input before it, so
/// that a handler of invalid input (a study's invalid frame becomes a status) still sees it.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace pcrf {

/// The command-line flag of a key: "tail_s" → "--tail-s", "pi_e_c" → "--pi-e-c".
inline std::string flag_name(std::string_view key) {
  std::string flag = "--";
  for (char c : key) flag += c == '_' ? '-' : c;
  return flag;
}

/// Where in a user's input a problem lies.
struct Where {
  std::vector<std::string> keys;  ///< tables then the key (["physics", "tail_s"]); empty: the input as a whole
  std::string file;               ///< the file the input was read from; empty: not a file
  int line = 0;                   ///< its line; 0: not known
};

/// How a front end spells a key path.
enum class Dialect {
  kKey,      ///< a study's TOML: "physics.tail_s" (and what())
  kFlag,     ///< the command line: "--tail-s" (the last key)
  kKeyword,  ///< Python: "tail_s=", "frame['kappa']" for a key inside a keyword's dict
};

/// `keys` as `dialect` spells them.
inline std::string key_path_text(const std::vector<std::string>& keys, Dialect dialect) {
  std::string text;
  if (keys.empty()) return text;
  switch (dialect) {
    case Dialect::kKey:
      for (const auto& k : keys) text += (text.empty() ? "" : ".") + k;
      return text;
    case Dialect::kFlag: return flag_name(keys.back());
    case Dialect::kKeyword:
      if (keys.size() == 1) return keys.front() + "=";
      text = keys.front();
      for (std::size_t k = 1; k < keys.size(); ++k) text += "['" + keys[k] + "']";
      return text;
  }
  return text;
}

class UserError : public std::invalid_argument {
 public:
  /// A problem at `where`.
  UserError(Where where, std::string problem, std::vector<std::string> named = {})
      : std::invalid_argument(render(where, problem, named, Dialect::kKey)),
        where_(std::move(where)),
        problem_(std::move(problem)),
        named_(std::move(named)) {}
  /// A problem with one key, not read from a file.
  UserError(std::string key, std::string problem, std::vector<std::string> named = {})
      : UserError(Where{{std::move(key)}, {}, 0}, std::move(problem), std::move(named)) {}
  /// A problem of the input as a whole ("cannot read the file").
  explicit UserError(std::string problem) : UserError(Where{}, std::move(problem)) {}

  const Where& where() const { return where_; }
  /// The problem, keys it names in the dialect of the front end asking.
  std::string problem(Dialect dialect) const { return render(Where{}, problem_, named_, spoken(dialect)); }
  /// The one line a front end prints: "WHERE: problem". Keys of an input read from a file are
  /// spelt as in the file, whichever front end read it.
  std::string message(Dialect dialect) const { return render(where_, problem_, named_, spoken(dialect)); }

 private:
  Dialect spoken(Dialect dialect) const { return where_.file.empty() ? dialect : Dialect::kKey; }

  static std::string render(const Where& where, const std::string& problem, const std::vector<std::string>& named,
                            Dialect dialect) {
    std::string text;
    if (!where.file.empty()) text = where.file + (where.line > 0 ? ":" + std::to_string(where.line) : "") + ": ";
    if (!where.keys.empty()) text += key_path_text(where.keys, dialect) + ": ";
    std::size_t next = 0;
    for (std::size_t at = 0; at < problem.size(); ++at) {
      if (next < named.size() && problem.compare(at, 2, "{}") == 0) {
        text += key_path_text({named[next++]}, dialect);
        ++at;
        continue;
      }
      text += problem[at];
    }
    return text;
  }

  Where where_;
  std::string problem_;
  std::vector<std::string> named_;
};

}  // namespace pcrf

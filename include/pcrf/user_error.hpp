/// \file user_error.hpp
/// \brief The one error of bad user input, carried as data: where the problem lies (a key
/// path, with the file and line when the input is a file) and what it is. Every layer throws
/// it as it finds the problem; no layer rewrites another's message. Each front end renders
/// `where` in its own dialect:
///
///   a study file       "FILE:LINE: [physics] tail_s: must be positive (got -1)"
///   the command line   "--tail-s: must be positive (got -1)"
///   Python             "tail_s=: must be positive (got -1)"
///
/// A study spells a key path as its TOML file does: the table's header, then the key
/// ("[physics] tail_s"); an entry of an array of tables by its header and its number, counted
/// from 1 ("[[records]] #2 file"); a value of an inline array by its number ("[axes] kappa
/// #3"); a key of an inline table dotted ("[axes] kappa.from"); a key outside any table bare
/// ("records"). A key path holds an entry's index as its own key, key_index(i) ("[1]").
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

/// The key of entry `i` (from 0) of an array in a key path: "[i]".
inline std::string key_index(std::size_t i) { return "[" + std::to_string(i) + "]"; }

/// Whether `key` is an entry's index (key_index).
inline bool is_key_index(std::string_view key) { return key.size() > 2 && key.front() == '[' && key.back() == ']'; }

/// The last key of `keys` that is a name, not an index ("" when none).
inline std::string last_key_name(const std::vector<std::string>& keys) {
  for (auto k = keys.rbegin(); k != keys.rend(); ++k)
    if (!is_key_index(*k)) return *k;
  return {};
}

/// Where in a user's input a problem lies.
struct Where {
  std::vector<std::string> keys;  ///< tables then the key (["physics", "tail_s"], ["records", "[0]", "file"]); empty: the input as a whole
  std::string file;               ///< the file the input was read from; empty: not a file
  int line = 0;                   ///< its line; 0: not known
};

/// "FILE:LINE" of `where` (the file alone when the line is not known): the place a message
/// points at, in every dialect.
inline std::string file_line_text(const Where& where) {
  return where.file + (where.line > 0 ? ":" + std::to_string(where.line) : "");
}

/// How a front end spells a key path.
enum class Dialect {
  kStudy,    ///< a study's TOML: "[physics] tail_s", "[[records]] #2 file" (and what())
  kFlag,     ///< the command line: "--tail-s" (the last key)
  kKeyword,  ///< Python: "tail_s=", "frame['kappa']" for a key inside a keyword's dict
};

namespace detail {

/// "#3" for key_index(2): an entry counted from 1, as a reader of the file counts.
inline std::string entry_number(const std::string& index) {
  return "#" + std::to_string(std::stoul(index.substr(1, index.size() - 2)) + 1);
}

/// Keys after a study's table header: names dotted, an index as " #N".
inline std::string study_key_text(const std::vector<std::string>& keys, std::size_t from) {
  std::string text;
  for (std::size_t k = from; k < keys.size(); ++k)
    text += is_key_index(keys[k]) ? (text.empty() ? "" : " ") + entry_number(keys[k])
                                  : (text.empty() || text.back() == ' ' ? "" : ".") + keys[k];
  return text;
}

/// The study's spelling: "[table] key", "[[array.of.tables]] #N key", or a bare root key.
inline std::string study_path_text(const std::vector<std::string>& keys) {
  // The header: up to the last entry of an array of tables (an index followed by a key) ...
  for (std::size_t k = keys.size() - 1; k-- > 1;)
    if (is_key_index(keys[k])) {
      std::string header;
      for (std::size_t h = 0; h < k; ++h) header += (header.empty() ? "" : ".") + keys[h];
      std::string text = "[[" + header + "]] " + entry_number(keys[k]);
      return text + " " + study_key_text(keys, k + 1);
    }
  // ... else the table holding a key (a root key has none).
  if (keys.size() >= 2 && !is_key_index(keys[1])) return "[" + keys.front() + "] " + study_key_text(keys, 1);
  return study_key_text(keys, 0);
}

}  // namespace detail

/// `keys` as `dialect` spells them.
inline std::string key_path_text(const std::vector<std::string>& keys, Dialect dialect) {
  std::string text;
  if (keys.empty()) return text;
  switch (dialect) {
    case Dialect::kStudy: return detail::study_path_text(keys);
    case Dialect::kFlag: return flag_name(last_key_name(keys));
    case Dialect::kKeyword:
      if (keys.size() == 1) return keys.front() + "=";
      text = keys.front();
      for (std::size_t k = 1; k < keys.size(); ++k) text += is_key_index(keys[k]) ? keys[k] : "['" + keys[k] + "']";
      return text;
  }
  return text;
}

class UserError : public std::invalid_argument {
 public:
  /// A problem at `where`.
  UserError(Where where, std::string problem, std::vector<std::string> named = {})
      : std::invalid_argument(render(where, problem, named, Dialect::kStudy)),
        where_(std::move(where)),
        problem_(std::move(problem)),
        named_(std::move(named)) {}
  /// A problem with one key, not read from a file.
  UserError(std::string key, std::string problem, std::vector<std::string> named = {})
      : UserError(Where{{std::move(key)}, {}, 0}, std::move(problem), std::move(named)) {}
  /// A problem of the input as a whole ("cannot read the file").
  explicit UserError(std::string problem) : UserError(Where{}, std::move(problem)) {}

  const Where& where() const { return where_; }
  /// The same error, `more` after its problem ("… (warnings_as_errors)"). A warning is a
  /// UserError not thrown: with warnings as errors, it is thrown so.
  UserError followed_by(const std::string& more) const { return UserError(where_, problem_ + more, named_); }
  /// The same error, `context` before its problem: what a layer alone knows ("frame 3: ").
  UserError preceded_by(const std::string& context) const { return UserError(where_, context + problem_, named_); }
  /// The problem, keys it names in the dialect of the front end asking.
  std::string problem(Dialect dialect) const { return render(Where{}, problem_, named_, spoken(dialect)); }
  /// The one line a front end prints: "WHERE: problem". Keys of an input read from a file are
  /// spelt as in the file, whichever front end read it.
  std::string message(Dialect dialect) const { return render(where_, problem_, named_, spoken(dialect)); }

 private:
  Dialect spoken(Dialect dialect) const { return where_.file.empty() ? dialect : Dialect::kStudy; }

  static std::string render(const Where& where, const std::string& problem, const std::vector<std::string>& named,
                            Dialect dialect) {
    std::string text;
    if (!where.file.empty()) text = file_line_text(where) + ": ";
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

// See toml_depth.hpp.
#include "study/toml_depth.hpp"

#include <string_view>

#include "pcrf/user_error.hpp"

namespace pcrf::study::detail {
namespace {

/// Scans TOML text for the dots that join the parts of a name: a string ("…", '…', and their
/// multi-line forms) and a comment hold no such dot; `= [ ] { } ,` and a line end close a name.
class DotCounter {
 public:
  DotCounter(std::string_view text, const std::string& file) : text_(text), file_(file) {}

  void run() {
    while (at_ < text_.size()) {
      const char c = text_[at_];
      if (c == '"' || c == '\'') {
        skip_string(c);
      } else if (c == '#') {
        while (at_ < text_.size() && text_[at_] != '\n') ++at_;
      } else {
        if (c == '\n') ++line_;
        if (c == '.') count_dot();
        if (c == '\n' || c == '=' || c == '[' || c == ']' || c == '{' || c == '}' || c == ',') dots_ = 0;
        ++at_;
      }
    }
  }

 private:
  void count_dot() {
    if (dots_ == 0) name_line_ = line_;
    if (++dots_ + 1 > kMaxKeyParts)
      throw UserError(Where{{}, file_, static_cast<int>(name_line_)}, "a dotted key or table header of more than " +
                       std::to_string(kMaxKeyParts) + " parts: no study key is that deep");
  }

  /// From an opening quote to past its closing one (a multi-line string when tripled).
  void skip_string(char quote) {
    const bool triple = text_.compare(at_, 3, std::string(3, quote)) == 0;
    at_ += triple ? 3 : 1;
    while (at_ < text_.size()) {
      const char c = text_[at_];
      if (c == '\\' && quote == '"') {
        if (at_ + 1 < text_.size() && text_[at_ + 1] == '\n') ++line_;
        at_ += 2;
        continue;
      }
      if (c == '\n') {
        if (!triple) return;  // an unclosed one-line string: toml++ will say so
        ++line_;
      }
      if (c == quote && (!triple || text_.compare(at_, 3, std::string(3, quote)) == 0)) {
        at_ += triple ? 3 : 1;
        return;
      }
      ++at_;
    }
  }

  std::string_view text_;
  const std::string& file_;
  std::size_t at_ = 0;
  std::size_t line_ = 1;
  std::size_t name_line_ = 1;
  std::size_t dots_ = 0;
};

}  // namespace

void refuse_deep_keys(const std::string& text, const std::string& file) { DotCounter(text, file).run(); }

}  // namespace pcrf::study::detail

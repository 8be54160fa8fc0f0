/// \file json.hpp
/// \brief A small writer of one-line JSON objects, for the command line's outputs
/// (`pcrf run`, `pcrf record`): numbers as the shortest text that reads back to the same
/// double, NaN and infinities as null, strings escaped.
#pragma once

#include "pcrf/number_text.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace pcrf {

class JsonObject {
 public:
  JsonObject& number(std::string_view key, double value) {
    start(key);
    write_number(value);
    return *this;
  }
  JsonObject& integer(std::string_view key, long long value) {
    start(key);
    out_ << value;
    return *this;
  }
  JsonObject& boolean(std::string_view key, bool value) {
    start(key);
    out_ << (value ? "true" : "false");
    return *this;
  }
  JsonObject& text(std::string_view key, std::string_view value) {
    start(key);
    write_string(value);
    return *this;
  }
  JsonObject& numbers(std::string_view key, const std::vector<double>& values) {
    return array(key, values, [this](double v) { write_number(v); });
  }
  JsonObject& texts(std::string_view key, const std::vector<std::string>& values) {
    return array(key, values, [this](const std::string& v) { write_string(v); });
  }
  JsonObject& object(std::string_view key, const JsonObject& value) {
    start(key);
    out_ << value.str();
    return *this;
  }
  JsonObject& objects(std::string_view key, const std::vector<JsonObject>& values) {
    return array(key, values, [this](const JsonObject& v) { out_ << v.str(); });
  }
  std::string str() const { return (first_ ? std::string("{") : out_.str()) + '}'; }

 private:
  template <class Values, class Write>
  JsonObject& array(std::string_view key, const Values& values, Write write) {
    start(key);
    out_ << '[';
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i > 0) out_ << ", ";
      write(values[i]);
    }
    out_ << ']';
    return *this;
  }
  void start(std::string_view key) {
    out_ << (first_ ? "{" : ", ");
    first_ = false;
    write_string(key);
    out_ << ": ";
  }
  void write_number(double v) {
    if (!std::isfinite(v)) {
      out_ << "null";
      return;
    }
    out_ << number_text(v);
  }
  void write_string(std::string_view s) {
    out_ << '"';
    for (const char c : s) {
      switch (c) {
        case '"': out_ << "\\\""; break;
        case '\\': out_ << "\\\\"; break;
        case '\n': out_ << "\\n"; break;
        case '\t': out_ << "\\t"; break;
        default:
          if (static_cast<unsigned char>(c) < 0x20) {
            char buffer[8];
            std::snprintf(buffer, sizeof buffer, "\\u%04x", c);
            out_ << buffer;
          } else {
            out_ << c;
          }
      }
    }
    out_ << '"';
  }

  std::ostringstream out_;
  bool first_ = true;
};

}  // namespace pcrf

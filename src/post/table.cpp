// Tables and their writers (see table.hpp).
#include "pcrf/post/table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "pcrf/cube/cube_query.hpp"
#include "pcrf/json.hpp"
#include "pcrf/number_text.hpp"

namespace pcrf::post {
namespace {

bool is_missing(const Cell& cell) {
  if (std::holds_alternative<std::monostate>(cell)) return true;
  const double* number = std::get_if<double>(&cell);
  return number != nullptr && !std::isfinite(*number);
}

/// A cell as text: full precision (CSV), or in the column's format (aligned text).
std::string cell_text(const Cell& cell, const std::string* format) {
  if (is_missing(cell)) return {};
  if (const auto* i = std::get_if<std::int64_t>(&cell)) return std::to_string(*i);
  if (const auto* s = std::get_if<std::string>(&cell)) return *s;
  const double v = std::get<double>(cell);
  if (format == nullptr) return number_text(v);
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format->c_str(), v);
  return buffer;
}

void add_cell(JsonObject& o, const std::string& key, const Cell& cell) {
  if (is_missing(cell)) o.number(key, std::nan(""));  // null
  else if (const auto* i = std::get_if<std::int64_t>(&cell)) o.integer(key, *i);
  else if (const auto* s = std::get_if<std::string>(&cell)) o.text(key, *s);
  else o.number(key, std::get<double>(cell));
}

std::vector<std::vector<std::string>> text_rows(const Table& table, bool full_precision) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> header;
  for (const auto& c : table.columns)
    if (!c.json_only) header.push_back(header_text(c));
  rows.push_back(std::move(header));
  for (const auto& r : table.rows) {
    std::vector<std::string> cells;
    for (std::size_t c = 0; c < r.size(); ++c)
      if (!table.columns[c].json_only)
        cells.push_back(cell_text(r[c], full_precision ? nullptr : &table.columns[c].text_format));
    rows.push_back(std::move(cells));
  }
  return rows;
}

}  // namespace

std::size_t Table::column(const std::string& name) const {
  for (std::size_t c = 0; c < columns.size(); ++c)
    if (columns[c].name == name) return c;
  throw std::out_of_range("no column '" + name + "'");
}

const Table& Report::table(const std::string& name) const {
  for (const auto& [n, t] : tables)
    if (n == name) return t;
  throw std::out_of_range("no table '" + name + "'");
}

Cell Report::field(const std::string& name) const {
  for (const auto& [n, v] : fields)
    if (n == name) return v;
  return {};
}

std::string header_text(const Column& column) {
  return column.units.empty() ? column.name : column.name + " [" + column.units + "]";
}

void write_text(const Table& table, std::ostream& out) { cube::print_table(text_rows(table, false), false, out); }

void write_csv(const Table& table, std::ostream& out) { cube::print_table(text_rows(table, true), true, out); }

void write_json(const Report& report, std::ostream& out) {
  JsonObject root;
  root.text("command", report.command);
  for (const auto& [name, value] : report.fields) add_cell(root, name, value);
  root.texts("warnings", report.warnings);
  JsonObject columns;
  for (const auto& [name, table] : report.tables) {
    std::vector<JsonObject> rows, described;
    for (const auto& r : table.rows) {
      JsonObject row;
      for (std::size_t c = 0; c < r.size(); ++c) add_cell(row, table.columns[c].name, r[c]);
      rows.push_back(std::move(row));
    }
    for (const auto& c : table.columns) {
      described.emplace_back();
      described.back().text("name", c.name).text("units", c.units).text("description", c.description);
    }
    root.objects(name, rows);
    columns.objects(name, described);
  }
  root.object("columns", columns);
  out << root.str() << '\n';
}

std::string describe_columns(const std::vector<Column>& columns) {
  std::string text;
  for (const auto& c : columns) text += "  " + header_text(c) + ": " + c.description + "\n";
  return text;
}

Cell number_or_missing(double value) { return std::isfinite(value) ? Cell{value} : Cell{}; }

}  // namespace pcrf::post

/// \file table.hpp
/// \brief The answers of `pcrf cube stats|fragility|sensitivity|p695` as plain tables, and
/// the writers that turn any of them into aligned text, CSV or JSON.
///
/// A command computes a Report (scalars, warnings and named tables; post/cube_reports.hpp)
/// and never prints; the command line and the Python module (`pcrf.fragility()` …) both
/// take the same Report. A table is made from the rows of a result struct by a list of
/// column descriptions (ColumnOf): a field added to a struct and to its list reaches text,
/// CSV, JSON and the DataFrame alike, with its unit and meaning.
#pragma once

#include <cstdint>
#include <functional>
#include <ostream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace pcrf::post {

/// One value: missing (no fit, not defined), an integer, a number (NaN also means missing)
/// or a text.
using Cell = std::variant<std::monostate, std::int64_t, double, std::string>;

struct Column {
  std::string name;         ///< machine name: JSON key and CSV header
  std::string units;        ///< "" when none (counts, labels, dimensionless)
  std::string description;  ///< what the value is, one line (JSON "columns", --help)
  std::string text_format = "%.4g";  ///< printf format of a number in the aligned text table
  bool json_only = false;   ///< for scripts only (JSON, DataFrames): not in the text or CSV tables
};

struct Table {
  std::vector<Column> columns;
  std::vector<std::vector<Cell>> rows;  ///< rows[r][c], in the order of `columns`
  /// The index of a column. \throws std::out_of_range naming it when there is none.
  std::size_t column(const std::string& name) const;
};

/// A column of a table made from rows of type Row: its description and how to read it.
template <class Row>
struct ColumnOf {
  Column column;
  std::function<Cell(const Row&)> value;
};

/// The column descriptions of a spec (for --help and schemas).
template <class Row>
std::vector<Column> columns_of(const std::vector<ColumnOf<Row>>& spec) {
  std::vector<Column> columns;
  for (const auto& s : spec) columns.push_back(s.column);
  return columns;
}

/// A count as an integer cell.
inline Cell count(std::size_t n) { return static_cast<std::int64_t>(n); }

template <class Row>
Table make_table(const std::vector<ColumnOf<Row>>& spec, const std::vector<Row>& rows) {
  Table table;
  for (const auto& s : spec) table.columns.push_back(s.column);
  for (const auto& row : rows) {
    std::vector<Cell> cells;
    cells.reserve(spec.size());
    for (const auto& s : spec) cells.push_back(s.value(row));
    table.rows.push_back(std::move(cells));
  }
  return table;
}

/// What a command answers: named scalars (the inputs that shaped it, group results), the
/// warnings it printed on stderr, and named tables, in order.
struct Report {
  std::string command;  ///< "stats", "fragility", "sensitivity", "p695"
  std::vector<std::pair<std::string, Cell>> fields;
  std::vector<std::string> warnings;
  std::vector<std::pair<std::string, Table>> tables;
  /// The named table. \throws std::out_of_range naming it when there is none.
  const Table& table(const std::string& name) const;
  /// The named field, or a missing Cell.
  Cell field(const std::string& name) const;
};

/// "median [g]", or the bare name when the column has no units.
std::string header_text(const Column& column);

/// Aligned columns for people (json_only columns left out): a header line of header_text(), numbers in each column's
/// text_format, missing values empty.
void write_text(const Table& table, std::ostream& out);

/// CSV (json_only columns left out): the header line of header_text(), numbers as the shortest text that reads back to
/// the same double (full precision), missing values empty, texts quoted when needed.
void write_csv(const Table& table, std::ostream& out);

/// One JSON object on one line: {"command": …, every field, "warnings": […], every table as
/// an array of row objects (column name → value, null where missing), "columns": {table name:
/// [{"name", "units", "description"}, …]}}. Numbers at full precision.
void write_json(const Report& report, std::ostream& out);

/// The columns of a table, one per line ("  name [units]: description"), for --help.
std::string describe_columns(const std::vector<Column>& columns);

/// A number, or missing when it is not finite.
Cell number_or_missing(double value);

}  // namespace pcrf::post

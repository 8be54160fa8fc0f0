// Post-processing of result cubes (see cube_query.hpp).
#include "pcrf/cube/cube_query.hpp"

#include "pcrf/analysis/percentile.hpp"
#include "pcrf/number_text.hpp"

#include "pcrf/json.hpp"

#include <algorithm>
#include <cstdio>
#include <charconv>
#include <cmath>
#include <map>

namespace pcrf::cube {
namespace {

std::size_t dimension_index(const CubeLayout& layout, const std::string& name) {
  if (const auto d = layout.find_dimension(name)) return *d;
  throw CubeError("no dimension '" + name + "'");
}

const Coordinate& coordinate(const CubeLayout& layout, const std::string& name) {
  if (const Coordinate* c = layout.find_coordinate(name)) return *c;
  std::string known;
  for (const auto& c : layout.coordinates) known += (known.empty() ? "" : ", ") + c.name;
  throw CubeError("no coordinate '" + name + "' (coordinates: " + known + ")");
}

/// A CSV field: the number's shortest text, empty for NaN.
std::string csv_number(double value) { return std::isnan(value) ? std::string() : pcrf::number_text(value); }

/// Positions along the coordinate's dimension whose value matches `text`.
std::vector<bool> matching_positions(const Coordinate& c, const std::string& text) {
  std::vector<bool> match(c.size(), false);
  double number = 0.0;
  const bool numeric = !c.is_text && std::from_chars(text.data(), text.data() + text.size(), number).ec == std::errc{};
  if (!c.is_text && !numeric) throw CubeError(c.name + "=" + text + ": '" + text + "' is not a number");
  bool any = false;
  for (std::size_t i = 0; i < c.size(); ++i) {
    match[i] = c.is_text ? c.strings[i] == text
                         : std::fabs(c.numbers[i] - number) <= 1e-9 * std::max(std::fabs(number), 1e-300);
    any = any || match[i];
  }
  if (!any) {
    std::string values;
    for (std::size_t i = 0; i < c.size() && i < 12; ++i) values += (i ? ", " : "") + c.label(i);
    if (c.size() > 12) values += ", …";
    throw CubeError(c.name + "=" + text + ": no such value (values: " + values + ")");
  }
  return match;
}

std::string status_text(const CubeLayout& layout, std::int8_t value) {
  if (value == kStatusNotRun) return kStatusNotRunName;
  for (const auto& f : layout.status_flags)
    if (f.value == value) return f.meaning;
  return std::to_string(value);
}

}  // namespace

Selector parse_selector(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw CubeError("selector '" + text + "': expected NAME=VALUE, e.g. kappa=1.8");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

std::vector<bool> select_cases(const CubeLayout& layout, const std::vector<Selector>& selectors) {
  const auto shape = layout.shape();
  std::vector<std::pair<std::size_t, std::vector<bool>>> conditions;  // (dimension, positions)
  for (const auto& s : selectors) {
    const Coordinate& c = coordinate(layout, s.coordinate);
    conditions.emplace_back(dimension_index(layout, c.dimension), matching_positions(c, s.value));
  }
  std::vector<bool> selected(static_cast<std::size_t>(layout.case_count()), true);
  if (conditions.empty()) return selected;
  for (std::int64_t i = 0; i < layout.case_count(); ++i) {
    const auto coords = unravel(i, shape);
    for (const auto& [dim, positions] : conditions)
      if (!positions[coords[dim]]) selected[static_cast<std::size_t>(i)] = false;
  }
  return selected;
}

void print_info(const CubeReader& cube, const std::string& heading, std::ostream& out) {
  const auto& layout = cube.layout();
  out << "cube: " << cube.file().string() << '\n';
  if (!heading.empty()) out << heading << '\n';
  out << "dimensions:\n";
  for (const auto& d : layout.dimensions) {
    const Coordinate& c = coordinate(layout, d.name);
    out << "  " << d.name << " (" << d.size << "): ";
    for (std::size_t i = 0; i < c.size() && i < 6; ++i) out << (i ? ", " : "") << c.label(i);
    if (c.size() > 6) out << ", … " << c.label(c.size() - 1);
    out << '\n';
  }
  const auto auxiliary = layout.auxiliary_names();
  if (!auxiliary.empty()) {
    out << "auxiliary coordinates:";
    for (const auto& a : auxiliary) out << ' ' << a;
    out << '\n';
  }
  out << "metrics (" << layout.metrics.size() << "):\n";
  for (const auto& m : layout.metrics) out << "  " << m.name << " [" << m.units << "]  " << m.long_name << '\n';
  if (!layout.side_variables.empty()) {
    out << "variables over some axes:\n";
    for (const auto& v : layout.side_variables) {
      out << "  " << v.name << " (";
      for (std::size_t d = 0; d < v.dimensions.size(); ++d) out << (d ? ", " : "") << v.dimensions[d];
      out << ") [" << v.units << "]  " << v.long_name << '\n';
    }
  }
  const auto status = cube.read_status();
  std::map<std::int8_t, std::int64_t> counts;
  for (auto s : status) ++counts[s];
  const std::int64_t total = layout.case_count();
  const std::int64_t done = total - (counts.count(kStatusNotRun) ? counts[kStatusNotRun] : 0);
  char percent[32];
  std::snprintf(percent, sizeof percent, "%.1f", total ? 100.0 * double(done) / double(total) : 100.0);
  out << "completion: " << done << "/" << total << " cases (" << percent << " %)\n";
  out << "status:\n";
  for (const auto& [value, count] : counts) out << "  " << status_text(layout, value) << ": " << count << '\n';
  const auto notes = cube.read_notes();
  if (!notes.empty()) {
    out << "messages (" << notes.size() << "):\n";
    for (std::size_t i = 0; i < notes.size() && i < 5; ++i)
      out << "  case " << notes[i].first << ": " << notes[i].second << '\n';
  }
  const auto histories = cube.history_names();
  if (!histories.empty()) {
    out << "histories:";
    for (const auto& h : histories) out << ' ' << h;
    out << '\n';
  }
}

void print_info_json(const CubeReader& cube, std::ostream& out) {
  const auto& layout = cube.layout();
  std::vector<JsonObject> dimensions, metrics, sides;
  for (const auto& d : layout.dimensions) {
    const Coordinate& c = coordinate(layout, d.name);
    std::vector<std::string> labels;
    for (std::size_t i = 0; i < c.size(); ++i) labels.push_back(c.label(i));
    dimensions.emplace_back();
    dimensions.back().text("name", d.name).integer("size", static_cast<long long>(d.size)).texts("values", labels);
  }
  for (const auto& m : layout.metrics) {
    metrics.emplace_back();
    metrics.back().text("name", m.name).text("units", m.units).text("long_name", m.long_name);
  }
  for (const auto& v : layout.side_variables) {
    sides.emplace_back();
    sides.back().text("name", v.name).text("units", v.units).text("long_name", v.long_name).texts("dimensions", v.dimensions);
  }
  std::map<std::int8_t, std::int64_t> counts;
  for (auto s : cube.read_status()) ++counts[s];
  JsonObject status;
  for (const auto& [value, count] : counts) status.integer(status_text(layout, value), count);
  JsonObject attributes;
  for (const auto& a : layout.attributes) {
    if (const auto* text = std::get_if<std::string>(&a.value)) attributes.text(a.name, *text);
    else if (const auto* number = std::get_if<double>(&a.value)) attributes.number(a.name, *number);
    else if (const auto* integer = std::get_if<std::int64_t>(&a.value)) attributes.integer(a.name, *integer);
  }
  JsonObject info;
  info.text("file", cube.file().string())
      .objects("dimensions", dimensions)
      .texts("auxiliary_coordinates", layout.auxiliary_names())
      .objects("metrics", metrics)
      .objects("side_variables", sides)
      .object("status", status)
      .integer("cases", layout.case_count())
      .texts("histories", cube.history_names())
      .object("attributes", attributes);
  out << info.str() << '\n';
}

/// A metric, or a side variable repeated over the dimensions it does not have (e.g. a
/// curve's collapse intensity on each of the curve's cases).
std::vector<double> per_case_values(const CubeReader& cube, const std::string& name) {
  const auto& layout = cube.layout();
  const SideVariable* side = layout.find_side_variable(name);
  if (side == nullptr) return cube.read_metric(name);
  const auto own = cube.read_side(name);
  const auto shape = layout.shape();
  std::vector<std::size_t> dims, own_shape;
  for (const auto& d : side->dimensions) {
    dims.push_back(dimension_index(layout, d));
    own_shape.push_back(shape[dims.back()]);
  }
  std::vector<double> result(static_cast<std::size_t>(layout.case_count()));
  for (std::int64_t i = 0; i < layout.case_count(); ++i) {
    const auto coords = unravel(i, shape);
    std::size_t k = 0;
    for (std::size_t d = 0; d < dims.size(); ++d) k = k * own_shape[d] + coords[dims[d]];
    result[static_cast<std::size_t>(i)] = own[k];
  }
  return result;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char ch : text) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return quoted + "\"";
}

void print_table(const std::vector<std::vector<std::string>>& rows, bool csv, std::ostream& out) {
  std::vector<std::size_t> width;
  for (const auto& r : rows) {
    width.resize(std::max(width.size(), r.size()), 0);
    for (std::size_t c = 0; c < r.size(); ++c) width[c] = std::max(width[c], r[c].size());
  }
  for (const auto& r : rows) {
    for (std::size_t c = 0; c < r.size(); ++c) {
      if (csv) out << (c ? "," : "") << csv_field(r[c]);
      else out << (c ? "  " : "") << r[c] << (c + 1 < r.size() ? std::string(width[c] - r[c].size(), ' ') : "");
    }
    out << '\n';
  }
}

void export_history_csv(const CubeReader& cube, const std::string& name, std::ostream& out) {
  const HistoryTable table = cube.read_history(name);
  for (std::size_t c = 0; c < table.columns.size(); ++c) out << (c ? "," : "") << csv_field(table.columns[c].name);
  out << '\n';
  const std::size_t rows = table.values.empty() ? 0 : table.values.front().size();
  for (std::size_t r = 0; r < rows; ++r) {
    for (std::size_t c = 0; c < table.columns.size(); ++c) out << (c ? "," : "") << pcrf::number_text(table.values[c][r]);
    out << '\n';
  }
}

void export_csv(const CubeReader& cube, const std::vector<std::string>& metrics,
                const std::vector<Selector>& selectors, std::ostream& out, const std::vector<std::string>& leave_out) {
  const auto& layout = cube.layout();
  std::vector<std::string> names = metrics;
  if (names.empty()) {
    for (const auto& m : layout.metrics) names.push_back(m.name);
    for (const auto& v : layout.side_variables) names.push_back(v.name);
  }
  std::vector<std::vector<double>> values;
  for (const auto& name : names) values.push_back(per_case_values(cube, name));
  const auto selected = select_cases(layout, selectors);
  const auto status = cube.read_status();
  std::vector<const Coordinate*> shown;
  std::vector<std::size_t> coordinate_dims;
  for (const auto& c : layout.coordinates) {
    if (std::find(leave_out.begin(), leave_out.end(), c.name) != leave_out.end()) continue;
    shown.push_back(&c);
    coordinate_dims.push_back(dimension_index(layout, c.dimension));
    out << csv_field(c.name) << ',';
  }
  out << "status";
  for (const auto& name : names) out << ',' << name;
  out << '\n';
  const auto shape = layout.shape();
  for (std::int64_t i = 0; i < layout.case_count(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (!selected[k]) continue;
    const auto coords = unravel(i, shape);
    for (std::size_t c = 0; c < shown.size(); ++c) out << csv_field(shown[c]->label(coords[coordinate_dims[c]])) << ',';
    out << status_text(layout, status[k]);
    for (const auto& v : values) out << ',' << csv_number(v[k]);
    out << '\n';
  }
}

std::vector<GroupStats> group_stats(const CubeReader& cube, const std::vector<std::string>& by, const std::string& metric,
                                    const std::vector<Selector>& selectors, const PoolReport& pool) {
  const auto& layout = cube.layout();
  if (by.empty()) throw CubeError("statistics need at least one coordinate to group by");
  std::vector<const Coordinate*> group_by;
  std::vector<std::size_t> by_dims;
  for (const auto& name : by) {
    group_by.push_back(&coordinate(layout, name));
    by_dims.push_back(dimension_index(layout, group_by.back()->dimension));
  }
  const auto selected = select_cases(layout, selectors);
  const auto values = cube.read_metric(metric);
  const auto shape = layout.shape();

  struct Group {
    std::vector<double> samples;
    std::size_t cases = 0, apart = 0;
  };
  const auto status = pool.set_apart.empty() ? std::vector<std::int8_t>{} : cube.read_status();
  std::map<std::vector<std::size_t>, Group> by_position;  // positions on the `by` coordinates → cases
  std::vector<std::vector<bool>> seen(shape.size());
  for (std::size_t d = 0; d < shape.size(); ++d) seen[d].assign(shape[d], false);
  std::vector<std::size_t> key(by.size());
  for (std::int64_t i = 0; i < layout.case_count(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (!selected[k]) continue;
    const auto coords = unravel(i, shape);
    for (std::size_t d = 0; d < shape.size(); ++d) seen[d][coords[d]] = true;
    for (std::size_t b = 0; b < by.size(); ++b) key[b] = coords[by_dims[b]];
    Group& g = by_position[key];
    ++g.cases;
    if (!status.empty() && std::find(pool.set_apart.begin(), pool.set_apart.end(), status[k]) != pool.set_apart.end())
      ++g.apart;
    else if (std::isfinite(values[k]))
      g.samples.push_back(values[k]);
  }
  if (pool.pooled != nullptr) {
    for (std::size_t d = 0; d < shape.size(); ++d) {
      const auto n = std::count(seen[d].begin(), seen[d].end(), true);
      const auto& name = layout.dimensions[d].name;
      const bool expected = std::find(pool.expected.begin(), pool.expected.end(), name) != pool.expected.end();
      const bool grouped = std::find(by_dims.begin(), by_dims.end(), d) != by_dims.end();
      if (!grouped && !expected && n > 1) pool.pooled->push_back(name + " (" + std::to_string(n) + " values)");
    }
  }
  // Groups keyed by value text: an auxiliary coordinate may repeat a value along its dimension.
  std::vector<GroupStats> stats;
  std::vector<std::vector<double>> merged;
  std::map<std::vector<std::string>, std::size_t> position;
  for (auto& [positions, g] : by_position) {
    std::vector<std::string> labels;
    for (std::size_t b = 0; b < by.size(); ++b) labels.push_back(group_by[b]->label(positions[b]));
    auto [it, inserted] = position.emplace(labels, stats.size());
    if (inserted) {
      stats.push_back({labels, 0, 0, 0, 0, 0, 0});
      merged.emplace_back();
    }
    stats[it->second].cases += g.cases;
    stats[it->second].set_apart += g.apart;
    merged[it->second].insert(merged[it->second].end(), g.samples.begin(), g.samples.end());
  }
  for (std::size_t s = 0; s < stats.size(); ++s) {
    std::sort(merged[s].begin(), merged[s].end());
    stats[s].values = merged[s].size();
    stats[s].median = analysis::percentile_sorted(merged[s], 0.50);
    stats[s].p16 = analysis::percentile_sorted(merged[s], 0.16);
    stats[s].p84 = analysis::percentile_sorted(merged[s], 0.84);
  }
  return stats;
}

}  // namespace pcrf::cube

// Post-processing of result cubes (see cube_query.hpp).
#include "pcrf/cube/cube_query.hpp"

#include "pcrf/analysis/percentile.hpp"
#include "pcrf/number_text.hpp"

#include "pcrf/json.hpp"
#include "pcrf/row_major.hpp"

#include <algorithm>
#include <cstdio>
#include <charconv>
#include <cmath>
#include <limits>
#include <cctype>
#include <functional>
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

std::vector<MessageKind> message_kinds(const std::vector<std::pair<std::int64_t, std::string>>& notes) {
  const auto kind_of = [](const std::string& text) {  // the text with each number as '#'
    std::string kind;
    for (std::size_t i = 0; i < text.size(); ++i) {
      const bool digit = std::isdigit(static_cast<unsigned char>(text[i])) != 0;
      if (!digit) {
        kind += text[i];
        continue;
      }
      if (kind.empty() || kind.back() != '#') kind += '#';
      while (i + 1 < text.size() && (std::isdigit(static_cast<unsigned char>(text[i + 1])) || text[i + 1] == '.' ||
                                     text[i + 1] == 'e' || text[i + 1] == 'E' || text[i + 1] == '-' || text[i + 1] == '+'))
        ++i;
    }
    return kind;
  };
  std::vector<MessageKind> kinds;
  std::map<std::string, std::size_t> index;
  for (const auto& [case_index, text] : notes) {
    const auto [it, added] = index.emplace(kind_of(text), kinds.size());
    if (added) kinds.push_back({text, case_index, 0});
    ++kinds[it->second].count;
  }
  return kinds;
}

namespace {

Completion default_completion(const CubeReader& cube, const std::map<std::int8_t, std::int64_t>& counts) {
  Completion c;
  c.total = cube.layout().case_count();
  const auto not_run = counts.find(kStatusNotRun);
  c.done = c.total - (not_run != counts.end() ? not_run->second : 0);
  return c;
}

std::string status_label(const CubeLayout& layout, std::int8_t value, const Completion& completion) {
  return value == kStatusNotRun && !completion.not_run_label.empty() ? completion.not_run_label : status_text(layout, value);
}

}  // namespace

void print_info(const CubeReader& cube, const std::string& heading, std::ostream& out,
                const std::optional<Completion>& given) {
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
  const Completion completion = given ? *given : default_completion(cube, counts);
  char percent[32];
  std::snprintf(percent, sizeof percent, "%.1f",
                completion.total ? 100.0 * double(completion.done) / double(completion.total) : 100.0);
  out << "completion: " << completion.done << "/" << completion.total << " " << completion.unit << " (" << percent << " %)\n";
  out << "status:\n";
  for (const auto& [value, count] : counts) out << "  " << status_label(layout, value, completion) << ": " << count << '\n';
  const auto notes = cube.read_notes();
  if (!notes.empty()) {
    constexpr std::size_t kShown = 8;
    const auto kinds = message_kinds(notes);
    out << "messages (" << notes.size() << " cases, " << kinds.size() << (kinds.size() == 1 ? " kind" : " kinds") << "):\n";
    for (std::size_t i = 0; i < kinds.size() && i < kShown; ++i) {
      out << "  " << kinds[i].text << " (";
      if (kinds[i].count == 1) out << "case " << kinds[i].first_case << ")\n";
      else out << kinds[i].count << " cases, first case " << kinds[i].first_case << ")\n";
    }
    if (kinds.size() > kShown) out << "  … and " << kinds.size() - kShown << " more kinds\n";
  }
  const auto histories = cube.history_names();
  if (!histories.empty()) {
    out << "histories:";
    for (const auto& h : histories) out << ' ' << h;
    out << '\n';
  }
}

void print_info_json(const CubeReader& cube, std::ostream& out, const std::optional<Completion>& given) {
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
  const Completion completion = given ? *given : default_completion(cube, counts);
  JsonObject status;
  for (const auto& [value, count] : counts) status.integer(status_label(layout, value, completion), count);
  JsonObject done;
  done.integer("done", completion.done).integer("total", completion.total).text("unit", completion.unit);
  std::vector<JsonObject> messages;
  for (const auto& kind : message_kinds(cube.read_notes())) {
    messages.emplace_back();
    messages.back().text("text", kind.text).integer("first_case", kind.first_case).integer("cases", kind.count);
  }
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
      .object("completion", done)
      .objects("messages", messages)
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

void export_rows(const CubeReader& cube, const std::vector<std::string>& metrics, const std::vector<Selector>& selectors,
                 const std::function<void(const std::vector<std::string>&)>& row, const std::vector<std::string>& leave_out) {
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
  std::vector<std::string> fields;
  for (const auto& c : layout.coordinates) {
    if (std::find(leave_out.begin(), leave_out.end(), c.name) != leave_out.end()) continue;
    shown.push_back(&c);
    coordinate_dims.push_back(dimension_index(layout, c.dimension));
    fields.push_back(c.name);
  }
  fields.emplace_back("status");
  fields.insert(fields.end(), names.begin(), names.end());
  row(fields);
  const auto shape = layout.shape();
  for (std::int64_t i = 0; i < layout.case_count(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    if (!selected[k]) continue;
    const auto coords = unravel(i, shape);
    fields.clear();
    // A coordinate written during the run (Coordinate::written_live) that a case not run has
    // no value of yet (NaN: a checkpoint's cube, before its case's unit) is no value, as the
    // case's metrics: an empty field. Any other NaN (a strike not known, a parameter of
    // another scene model) is the value "nan", as always.
    for (std::size_t c = 0; c < shown.size(); ++c) {
      const Coordinate& coordinate = *shown[c];
      const std::size_t at = coords[coordinate_dims[c]];
      const bool unwritten = status[k] == kStatusNotRun && coordinate.written_live() && std::isnan(coordinate.number(at));
      fields.push_back(unwritten ? std::string() : coordinate.label(at));
    }
    fields.push_back(status_text(layout, status[k]));
    for (const auto& v : values) fields.push_back(csv_number(v[k]));
    row(fields);
  }
}

void export_csv(const CubeReader& cube, const std::vector<std::string>& metrics,
                const std::vector<Selector>& selectors, std::ostream& out, const std::vector<std::string>& leave_out) {
  export_rows(
      cube, metrics, selectors,
      [&out](const std::vector<std::string>& fields) {
        for (std::size_t f = 0; f < fields.size(); ++f) out << (f ? "," : "") << csv_field(fields[f]);
        out << '\n';
      },
      leave_out);
}

namespace {

/// A group's count of values, median and 16th/84th percentiles of `samples`.
void summarize(std::vector<double> samples, GroupStats& group) {
  std::sort(samples.begin(), samples.end());
  group.values = samples.size();
  group.median = analysis::percentile_sorted(samples, 0.50);
  group.p16 = analysis::percentile_sorted(samples, 0.16);
  group.p84 = analysis::percentile_sorted(samples, 0.84);
}

/// Whether status `s` is one of `set` (PoolReport's set_apart or unresolved).
bool among(const std::vector<std::int8_t>& set, std::int8_t s) { return std::find(set.begin(), set.end(), s) != set.end(); }

}  // namespace

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
    std::size_t cases = 0, apart = 0, unresolved = 0;
  };
  const auto status = pool.set_apart.empty() && pool.unresolved.empty() ? std::vector<std::int8_t>{} : cube.read_status();
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
    if (!status.empty() && among(pool.set_apart, status[k]))
      ++g.apart;
    else if (!status.empty() && among(pool.unresolved, status[k]))
      ++g.unresolved;
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
      stats.push_back({labels, 0, 0, 0, 0, 0, 0, 0});
      merged.emplace_back();
    }
    stats[it->second].cases += g.cases;
    stats[it->second].set_apart += g.apart;
    stats[it->second].unresolved += g.unresolved;
    merged[it->second].insert(merged[it->second].end(), g.samples.begin(), g.samples.end());
  }
  for (std::size_t s = 0; s < stats.size(); ++s) summarize(std::move(merged[s]), stats[s]);
  return stats;
}

void check_reduction(const std::string& how) {
  if (how != "max" && how != "min" && how != "median") throw CubeError("reduce with max, min or median, not '" + how + "'");
}

double reduce_values(std::vector<double> values, const std::string& how) {
  check_reduction(how);
  std::erase_if(values, [](double v) { return !std::isfinite(v); });
  if (values.empty()) return std::nan("");
  std::sort(values.begin(), values.end());
  if (how == "max") return values.back();
  if (how == "min") return values.front();
  return analysis::percentile_sorted(values, 0.50);
}

CensoredReduction reduce_censored(const std::vector<double>& observed, const std::vector<double>& censored_from,
                                  const std::string& how) {
  std::vector<double> at_bounds = observed, unbounded = observed;
  for (double bound : censored_from) {
    at_bounds.push_back(bound);
    unbounded.push_back(std::numeric_limits<double>::max());  // finite: the median interpolates it
  }
  const double low = reduce_values(at_bounds, how);
  return {low, !censored_from.empty() && reduce_values(unbounded, how) != low};
}

namespace {

/// Whether a combination of `members` cases of which `apart` are set apart is set apart.
bool reduced_apart(std::size_t apart, std::size_t members, const std::string& how) {
  if (how == "max") return apart > 0;
  if (how == "min") return apart == members;
  return 2 * apart > members;
}

}  // namespace

std::vector<GroupStats> group_stats_reduced(const CubeReader& cube, const std::vector<std::string>& by_list, const std::string& metric,
                                            const std::vector<Selector>& selectors, const Reduction& reduction,
                                            const PoolReport& pool) {
  check_reduction(reduction.how);
  if (by_list.size() != 1) throw CubeError("a reduction over '" + reduction.dimension + "' groups by one coordinate");
  const std::string& by = by_list.front();
  const auto& layout = cube.layout();
  const Coordinate& group_by = coordinate(layout, by);
  if (group_by.dimension == reduction.dimension) throw CubeError("cannot group by '" + by + "' and reduce over its dimension");
  // The variable's own dimensions: every one for a metric, its own for a side variable.
  std::vector<std::size_t> dims;
  std::vector<double> values;
  const SideVariable* side = layout.find_side_variable(metric);
  if (side != nullptr) {
    for (const auto& name : side->dimensions) dims.push_back(dimension_index(layout, name));
    values = cube.read_side(metric);
  } else {
    for (std::size_t d = 0; d < layout.dimensions.size(); ++d) dims.push_back(d);
    values = cube.read_metric(metric);
  }
  const auto shape = layout.shape();
  std::vector<std::size_t> var_shape;
  for (auto d : dims) var_shape.push_back(shape[d]);
  const auto position = [&](std::size_t dim) -> std::size_t {
    const auto it = std::find(dims.begin(), dims.end(), dim);
    if (it == dims.end()) throw CubeError("'" + metric + "' does not run over '" + layout.dimensions[dim].name + "'");
    return static_cast<std::size_t>(it - dims.begin());
  };
  const std::size_t reduce_pos = position(dimension_index(layout, reduction.dimension));
  const std::size_t by_pos = position(dimension_index(layout, group_by.dimension));

  const auto selected = select_cases(layout, selectors);
  const bool by_status = side == nullptr && !(pool.set_apart.empty() && pool.unresolved.empty());
  const auto status = by_status ? cube.read_status() : std::vector<std::int8_t>{};
  std::vector<char> chosen(values.size(), 0), apart(values.size(), 0), unresolved(values.size(), 0);
  std::vector<std::size_t> var_coords(dims.size());
  for (std::int64_t i = 0; i < layout.case_count(); ++i) {
    if (!selected[static_cast<std::size_t>(i)]) continue;
    const auto coords = unravel(i, shape);
    for (std::size_t p = 0; p < dims.size(); ++p) var_coords[p] = coords[dims[p]];
    const auto v = static_cast<std::size_t>(ravel(var_coords, var_shape));
    chosen[v] = 1;
    if (status.empty()) continue;
    const auto k = static_cast<std::size_t>(i);
    apart[v] = among(pool.set_apart, status[k]);
    unresolved[v] = among(pool.unresolved, status[k]);
  }
  // Combinations: the variable's coordinates with the reduced one at 0.
  struct Combination {
    std::vector<double> values;
    std::size_t members = 0, apart = 0, unresolved = 0;
  };
  std::map<std::int64_t, Combination> combinations;
  for (std::size_t v = 0; v < values.size(); ++v) {
    if (!chosen[v]) continue;
    auto c = unravel(static_cast<std::int64_t>(v), var_shape);
    c[reduce_pos] = 0;
    Combination& combination = combinations[ravel(c, var_shape)];
    ++combination.members;
    if (apart[v]) ++combination.apart;
    else if (unresolved[v]) ++combination.unresolved;
    else if (std::isfinite(values[v])) combination.values.push_back(values[v]);
  }
  std::vector<GroupStats> stats;
  std::map<std::string, std::size_t> group_of;
  std::vector<std::vector<double>> samples;
  for (const auto& [key, combination] : combinations) {
    const std::size_t g = unravel(key, var_shape)[by_pos];
    auto [it, inserted] = group_of.emplace(group_by.label(g), stats.size());
    if (inserted) {
      stats.push_back({{group_by.label(g)}, 0, 0, 0, 0, 0, 0, 0});
      samples.emplace_back();
    }
    GroupStats& group = stats[it->second];
    ++group.cases;
    if (reduced_apart(combination.apart, combination.members, reduction.how)) {
      ++group.set_apart;
      continue;
    }
    // A member still moving at its end could have become anything, a collapse included: the
    // reduction is unknown unless the collapses already decide it.
    if (combination.unresolved > 0) {
      ++group.unresolved;
      continue;
    }
    const double value = reduce_values(combination.values, reduction.how);
    if (std::isfinite(value)) samples[it->second].push_back(value);
  }
  if (pool.pooled != nullptr)
    for (std::size_t p = 0; p < dims.size(); ++p) {
      const auto& name = layout.dimensions[dims[p]].name;
      const bool expected = std::find(pool.expected.begin(), pool.expected.end(), name) != pool.expected.end();
      if (p != by_pos && p != reduce_pos && !expected && var_shape[p] > 1)
        pool.pooled->push_back(name + " (" + std::to_string(var_shape[p]) + " values)");
    }
  for (std::size_t s = 0; s < stats.size(); ++s) summarize(std::move(samples[s]), stats[s]);
  return stats;
}

}  // namespace pcrf::cube

// A record selection as JSON (see record_selection.hpp).
#include "pcrf/api/record_selection.hpp"

#include <filesystem>
#include <fstream>
#include <utility>
#include <vector>

#include "pcrf/user_error.hpp"

namespace pcrf::api {

namespace {

/// `path` opened to read, once it is known to be a regular file (following links).
std::ifstream open_table(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw UserError(path + ": no such file");
  if (!std::filesystem::is_regular_file(status)) throw UserError(path + ": not a regular file");
  std::ifstream in(path);
  if (!in) throw UserError(path + ": cannot open the file");
  return in;
}

}  // namespace

SelectionTarget read_selection_target_file(const std::string& path) {
  std::ifstream in = open_table(path);
  return read_selection_target(in, path);
}

SpectraTable read_spectra_table_file(const std::string& path) {
  std::ifstream in = open_table(path);
  return read_spectra_csv(in, path);
}

JsonObject selection_json(const SelectionTarget& t, const SpectraTable& table, const SelectionResult& r) {
  std::vector<JsonObject> records;
  for (std::size_t i = 0; i < r.records.size(); ++i) {
    const LibraryEntry& e = table.entries[r.records[i].entry];
    JsonObject o;
    o.text("name", e.name).text("kind", e.kind).text("file", e.file).text("file_h2", e.file_h2).number("scale", r.records[i].scale);
    o.numbers("ln_sa", r.ln_sa[i]);
    records.push_back(std::move(o));
  }
  JsonObject o;
  o.numbers("periods_s", t.periods_s).numbers("target_mean_ln_sa", t.mean_ln_sa).numbers("target_sigma_ln_sa", t.sigma_ln_sa);
  o.numbers("mean_ln_sa", r.mean_ln_sa).numbers("sigma_ln_sa", r.sigma_ln_sa);
  o.number("median_error_percent", r.median_error_percent).number("sigma_error_percent", r.sigma_error_percent);
  o.number("sum_of_squares", r.sum_of_squares).objects("records", records);
  return o;
}

}  // namespace pcrf::api

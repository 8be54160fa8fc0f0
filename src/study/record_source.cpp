// Record axis sources and the per-process record cache (see record_source.hpp).
#include "pcrf/study/record_source.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "pcrf/record/synthetic.hpp"

namespace pcrf::study {

bool RecordSource::has_components() const {
  const auto members = component_members<RecordSource>();
  return std::any_of(members.begin(), members.end(), [this](auto member) { return (this->*member).has_value(); });
}

std::vector<const RecordFileSpec*> RecordSource::files() const {
  std::vector<const RecordFileSpec*> all;
  if (file) all.push_back(&*file);
  for (const auto member : component_members<RecordSource>())
    if (this->*member) all.push_back(&*(this->*member));
  return all;
}

std::string RecordSource::describe() const {
  if (!file) return "synthetic " + synthetic;
  std::string text = "file " + file->path.string();
  const auto members = component_members<RecordSource>();
  for (std::size_t i = 0; i < kComponentCount; ++i)
    if (const auto& spec = this->*members[i]) text += "; " + std::string(kStationComponents[i].key) + " " + spec->path.string();
  return text;
}

LoadedRecord load_record(const RecordSource& source) {
  if (!source.file) return {StationRecord{make_synthetic(source.synthetic), {}, {}, {}, {}}, source.synthetic, {}, {}};
  RecordFile file = read_record_file(*source.file);
  std::string title = file.metadata.title.empty() ? source.file->path.filename().string() : std::move(file.metadata.title);
  if (!source.has_components() && !source.az1_deg)  // a record alone, read as it always was
    return {StationRecord{std::move(file.motion), {}, {}, {}, {}}, std::move(title), {}, {}};
  std::vector<std::string> warnings;
  const ComponentHeader first{source.file->path.string(), file.metadata};
  auto component = [&](RecordFile&& read, const RecordFileSpec& spec) {
    if (&spec != &*source.file)
      if (auto line = different_station(first, {spec.path.string(), read.metadata}); !line.empty())
        warnings.push_back(std::move(line));
    return StationComponent{std::move(read.motion), std::move(read.metadata.component), spec.path.string()};
  };
  StationParts parts{component(std::move(file), *source.file), source.az1_deg, std::nullopt, source.az2_deg, std::nullopt};
  const auto given = component_members<RecordSource>();
  const auto read = component_members<StationParts>();
  for (std::size_t i = 0; i < kComponentCount; ++i)
    if (const auto& spec = source.*given[i]) parts.*read[i] = component(read_record_file(*spec), *spec);
  std::vector<std::string> notes;
  StationRecord station = make_station(std::move(parts), notes);
  return {std::move(station), std::move(title), std::move(notes), std::move(warnings)};
}

RecordCache::RecordCache(std::vector<RecordSource> sources)
    : sources_(std::move(sources)), loaded_(sources_.size()), intensities_(sources_.size()) {}

const LoadedRecord& RecordCache::loaded(std::size_t index) {
  std::lock_guard lock(mutex_);
  auto& slot = loaded_.at(index);
  // Loading under the lock is fine: each record loads once, and only rank 0 has two threads.
  if (!slot) slot = std::make_unique<LoadedRecord>(load_record(sources_.at(index)));
  return *slot;
}

const GroundMotion& RecordCache::get(std::size_t index) { return loaded(index).station.h1; }

const StationRecord& RecordCache::station(std::size_t index) { return loaded(index).station; }

const std::vector<std::string>& RecordCache::notes(std::size_t index) { return loaded(index).notes; }

const std::vector<std::string>& RecordCache::warnings(std::size_t index) { return loaded(index).warnings; }

const std::string& RecordCache::title(std::size_t index) { return loaded(index).title; }

std::string station_of(const std::string& record_name) {
  const auto cut = record_name.rfind('_');
  return cut == std::string::npos ? record_name : record_name.substr(0, cut);
}

namespace {
double median_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 == 1 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}
}  // namespace

std::vector<double> p695_set_intensities(const std::vector<std::string>& stations, const std::vector<double>& pgv_m_s,
                                         const std::vector<double>& measure) {
  std::map<std::string, std::vector<std::size_t>> members;
  for (std::size_t i = 0; i < stations.size(); ++i) members[stations[i]].push_back(i);
  std::map<std::string, double> pair_pgv;
  for (const auto& [station, which] : members) {
    if (which.size() != 2)
      throw std::invalid_argument("normalise = \"p695\" pairs the two horizontals of each station (records named "
                                  "STATION_COMPONENT), but station \"" + station + "\" has " +
                                  std::to_string(which.size()) + " component(s)");
    pair_pgv[station] = std::sqrt(pgv_m_s[which[0]] * pgv_m_s[which[1]]);
  }
  std::vector<double> pgvs;
  for (const auto& [station, pgv] : pair_pgv) pgvs.push_back(pgv);
  const double median_pgv = median_of(pgvs);
  std::vector<double> factor(stations.size()), normalised(stations.size());
  for (std::size_t i = 0; i < stations.size(); ++i) {
    factor[i] = median_pgv / pair_pgv.at(stations[i]);
    normalised[i] = factor[i] * measure[i];
  }
  const double set_intensity = median_of(normalised);
  std::vector<double> result(stations.size());
  for (std::size_t i = 0; i < stations.size(); ++i) result[i] = set_intensity / factor[i];
  return result;
}

double RecordCache::p695_intensity(std::size_t index, const IntensitySpec& spec) {
  {
    std::lock_guard lock(mutex_);
    if (intensities_.at(index)) return *intensities_[index];
  }
  std::vector<std::string> stations;
  std::vector<double> pgv, measure;
  for (std::size_t i = 0; i < sources_.size(); ++i) {
    stations.push_back(station_of(sources_[i].name));
    pgv.push_back(peak_velocity_m_s(get(i)));
    measure.push_back(intensity_of(get(i), spec));
  }
  const auto values = p695_set_intensities(stations, pgv, measure);
  std::lock_guard lock(mutex_);
  for (std::size_t i = 0; i < values.size(); ++i) intensities_[i] = values[i];
  return values[index];
}

double RecordCache::intensity(std::size_t index, const IntensitySpec& spec) {
  if (spec.normalise == SetNormalisation::kP695) return p695_intensity(index, spec);
  const StationRecord& record = station(index);
  std::lock_guard lock(mutex_);
  auto& value = intensities_.at(index);
  if (!value) value = station_intensity(record, std::nullopt, spec);
  return *value;
}

double RecordCache::scale_factor(std::size_t index, double level, const std::optional<IntensitySpec>& intensity) {
  if (!intensity) return level * sources_.at(index).scale;  // the record's own factor, then the axis
  return intensity_scale_factor(level, this->intensity(index, *intensity));
}

}  // namespace pcrf::study

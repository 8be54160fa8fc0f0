// Record axis sources and the per-process record cache (see record_source.hpp).
#include "pcrf/study/record_source.hpp"

#include "pcrf/record/synthetic.hpp"

namespace pcrf::study {

std::string RecordSource::describe() const {
  if (!file) return "synthetic " + synthetic;
  std::string text = "file " + file->path.string();
  if (h2) text += "; h2 " + h2->path.string();
  if (up) text += "; up " + up->path.string();
  return text;
}

LoadedRecord load_record(const RecordSource& source) {
  if (!source.file) return {StationRecord{make_synthetic(source.synthetic), {}, {}, {}, {}}, source.synthetic, {}};
  RecordFile file = read_record_file(*source.file);
  std::string title = file.metadata.title.empty() ? source.file->path.filename().string() : std::move(file.metadata.title);
  if (!source.has_components() && !source.az1_deg)  // a record alone, read as it always was
    return {StationRecord{std::move(file.motion), {}, {}, {}, {}}, std::move(title), {}};
  auto component = [](RecordFile&& read, const RecordFileSpec& spec) {
    return StationComponent{std::move(read.motion), std::move(read.metadata.component), spec.path.string()};
  };
  std::optional<StationComponent> h2, up;
  if (source.h2) h2 = component(read_record_file(*source.h2), *source.h2);
  if (source.up) up = component(read_record_file(*source.up), *source.up);
  std::vector<std::string> notes;
  StationRecord station = make_station(component(std::move(file), *source.file), source.az1_deg, std::move(h2),
                                       source.az2_deg, std::move(up), notes);
  return {std::move(station), std::move(title), std::move(notes)};
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

const std::string& RecordCache::title(std::size_t index) { return loaded(index).title; }

double RecordCache::intensity(std::size_t index, const IntensitySpec& spec) {
  const StationRecord& record = station(index);
  std::lock_guard lock(mutex_);
  auto& value = intensities_.at(index);
  if (!value) value = station_intensity(record, std::nullopt, spec);
  return *value;
}

double RecordCache::scale_factor(std::size_t index, double level, const std::optional<IntensitySpec>& intensity) {
  if (!intensity) return level;
  return intensity_scale_factor(level, this->intensity(index, *intensity));
}

}  // namespace pcrf::study

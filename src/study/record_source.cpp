// Record axis sources and the per-process record cache (see record_source.hpp).
#include "pcrf/study/record_source.hpp"

#include "pcrf/record/synthetic.hpp"

namespace pcrf::study {

std::string RecordSource::describe() const {
  if (file) return "file " + file->path.string();
  return "synthetic " + synthetic;
}

LoadedRecord load_record(const RecordSource& source) {
  if (!source.file) return {make_synthetic(source.synthetic), source.synthetic};
  RecordFile file = read_record_file(*source.file);
  std::string title = file.metadata.title.empty() ? source.file->path.filename().string() : std::move(file.metadata.title);
  return {std::move(file.motion), std::move(title)};
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

const GroundMotion& RecordCache::get(std::size_t index) { return loaded(index).motion; }

const std::string& RecordCache::title(std::size_t index) { return loaded(index).title; }

double RecordCache::intensity(std::size_t index, const IntensitySpec& spec) {
  const GroundMotion& motion = get(index);
  std::lock_guard lock(mutex_);
  auto& value = intensities_.at(index);
  if (!value) value = intensity_of(motion, spec);
  return *value;
}

double RecordCache::scale_factor(std::size_t index, double level, const std::optional<IntensitySpec>& intensity) {
  if (!intensity) return level;
  return intensity_scale_factor(level, this->intensity(index, *intensity));
}

}  // namespace pcrf::study

// Record axis sources and the per-process record cache (see record_source.hpp).
#include "pcrf/study/record_source.hpp"

#include "pcrf/record/synthetic.hpp"

namespace pcrf::study {

std::string RecordSource::describe() const {
  if (file) return "file " + file->path.string();
  return "synthetic " + synthetic;
}

GroundMotion load_record(const RecordSource& source) {
  if (source.file) return read_record(*source.file);
  return make_synthetic(source.synthetic);
}

RecordCache::RecordCache(std::vector<RecordSource> sources)
    : sources_(std::move(sources)), loaded_(sources_.size()), intensities_(sources_.size()) {}

const GroundMotion& RecordCache::get(std::size_t index) {
  std::lock_guard lock(mutex_);
  auto& slot = loaded_.at(index);
  // Loading under the lock is fine: each record loads once, and only rank 0 has two threads.
  if (!slot) slot = std::make_unique<GroundMotion>(load_record(sources_.at(index)));
  return *slot;
}

double RecordCache::intensity(std::size_t index, const IntensitySpec& spec) {
  const GroundMotion& motion = get(index);
  std::lock_guard lock(mutex_);
  auto& value = intensities_.at(index);
  if (!value) value = intensity_of(motion, spec);
  return *value;
}

void RecordCache::put(std::size_t index, GroundMotion motion) {
  std::lock_guard lock(mutex_);
  loaded_.at(index) = std::make_unique<GroundMotion>(std::move(motion));
}

}  // namespace pcrf::study

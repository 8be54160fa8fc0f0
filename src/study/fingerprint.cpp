// Study fingerprint for --resume (see fingerprint.hpp).
#include "pcrf/study/fingerprint.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "pcrf/study/plan.hpp"
#include "study/plans/plan_support.hpp"

namespace pcrf::study {
namespace {

std::string hex(std::uint64_t value) {
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(value));
  return buffer;
}

std::string samples_hash(const GroundMotion& motion) {
  const auto& samples = motion.samples_m_s2();
  return hex(fnv1a(std::string_view(reinterpret_cast<const char*>(samples.data()),
                                    samples.size() * sizeof(double))));
}

/// "<table> key=value …" over the settings that determine results, in description order.
template <class Target>
void describe_settings(std::ostream& out, const SettingTable<Target>& table, const Target& values) {
  out << table.name;
  for (const auto& setting : table.settings)
    if (setting.in_fingerprint) out << ' ' << setting.key << '=' << setting_text(setting.get(values));
  out << '\n';
}

}  // namespace

std::uint64_t fnv1a(std::string_view bytes, std::uint64_t hash) {
  for (unsigned char c : bytes) {
    hash ^= c;
    hash *= 1099511628211ull;
  }
  return hash;
}

std::string canonical_description(const Study& study, const CaseSpace& space, RecordCache& records) {
  std::ostringstream out;
  out.precision(17);
  out << "plan " << study.plan->name() << ' ' << study.plan->canonical_heading() << '\n';
  for (std::size_t r = 0; r < study.records.size(); ++r) {
    const auto& motion = records.get(r);
    out << "record " << study.records[r].name << " dt_s=" << motion.dt_s() << " n=" << motion.size()
        << " samples=" << samples_hash(motion);
    const auto& source = study.records[r];
    if (source.has_components() || source.az1_deg || source.strike_deg) {  // studies of single records: as they were
      const StationRecord& station = records.station(r);
      const auto members = component_members<StationRecord>();
      for (std::size_t i = 0; i < kComponentCount; ++i)
        if (const auto& part = station.*members[i]) out << ' ' << kStationComponents[i].key << '=' << samples_hash(*part);
      out << " az1_deg=" << station.az1_deg.value_or(std::nan("")) << " az2_deg=" << station.az2_deg.value_or(std::nan(""))
          << " strike_deg=" << source.strike_deg.value_or(std::nan(""));
    }
    if (source.scale != 1.0) out << " scale=" << source.scale;  // studies without: as they were
    out << '\n';
  }
  if (study.intensity) describe_settings(out, intensity_settings(), *study.intensity);
  if (study.ida) describe_settings(out, ida_settings(), *study.ida);
  if (const auto& sel = study.selection) {  // what each stripe runs: its records (above, by samples) and their factors
    const auto& w = sel->settings;
    out << "selection kind=" << w.kind << " count=" << w.count << " scale_min=" << w.scale_min << " scale_max=" << w.scale_max
        << " seed=" << w.seed << " trials=" << w.trials << " loops=" << w.loops << '\n';
    for (const auto& stripe : sel->stripes) {
      out << "stripe";
      for (std::size_t k = 0; k < stripe.records.size(); ++k)
        out << ' ' << study.records[stripe.records[k]].name << '*' << stripe.scales[k];
      out << '\n';
    }
  }
  space.level_axis().describe(out);
  if (!study.incidence_deg.empty()) {
    out << "\nincidence " << study.incidence_reference;
    for (double v : study.incidence_deg) out << ' ' << v;
  }
  out << "\nbase";
  detail::describe_parameters(out, *study.model, study.base);
  out << '\n';
  if (study.model != &default_scene_model()) out << "scene " << study.model->name << '\n';  // the frame's fingerprints unchanged
  study.plan->describe(out);
  describe_settings(out, physics_settings(), study.physics);
  describe_settings(out, solver_settings(), study.solver);
  out << "metrics";
  for (const auto& m : study.metrics) out << ' ' << m;
  out << '\n';
  for (const auto& h : study.histories) out << "history " << h.label << ' ' << space.resolve(h) << '\n';
  if (study.record_pulses) out << "record_pulses\n";  // the cube's pulse coordinates; studies without: as they were
  return out.str();
}

std::string study_fingerprint(const Study& study, const CaseSpace& space, RecordCache& records) {
  return hex(fnv1a(canonical_description(study, space, records)));
}

}  // namespace pcrf::study

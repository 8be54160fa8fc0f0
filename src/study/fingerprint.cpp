// Study fingerprint for --resume (see fingerprint.hpp).
#include "pcrf/study/fingerprint.hpp"

#include <cstdio>
#include <sstream>

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

void describe_parameters(std::ostream& out, const FrameParameters& p) {
  for (const auto& info : all_parameters()) out << ' ' << info.name << '=' << p.*info.member;
  out << " h_m=" << p.h_m << " m_c_kg=" << p.m_c_kg;
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
  out << "plan " << plan_name(study.plan) << " include_base=" << study.include_base << '\n';
  for (std::size_t r = 0; r < study.records.size(); ++r) {
    const auto& motion = records.get(r);
    out << "record " << study.records[r].name << " dt_s=" << motion.dt_s() << " n=" << motion.size()
        << " samples=" << samples_hash(motion) << '\n';
  }
  out << "scale";
  for (double s : study.scales) out << ' ' << s;
  out << "\nbase";
  describe_parameters(out, study.base);
  out << '\n';
  for (std::size_t p = 0; p < kParameterCount; ++p) {
    out << "axis " << all_parameters()[p].name;
    for (double v : study.axes[p]) out << ' ' << v;
    out << '\n';
  }
  for (const auto& c : study.cases) {
    out << "case " << c.label;
    describe_parameters(out, c.parameters);
    out << '\n';
  }
  out << "physics uplift=" << to_string(study.physics.uplift) << " fracture_strain=" << study.physics.fracture_strain
      << " tail_s=" << study.physics.tail_s << " zeno_time_s=" << study.physics.zeno_time_s
      << " theta0_rad=" << study.physics.theta0_rad << " omega0_rad_s=" << study.physics.omega0_rad_s << '\n';
  const auto& s = study.solver;
  out << "solver integrator=" << to_string(s.integrator) << " rtol=" << s.rtol << " atol_theta_rad=" << s.atol_theta_rad
      << " atol_omega_rad_s=" << s.atol_omega_rad_s << " max_step_s=" << s.max_step_s
      << " fixed_step_s=" << s.fixed_step_s << " stop_at_samples=" << s.stop_at_samples << " max_steps=" << s.max_steps
      << " wall_time_limit_s=" << s.wall_time_limit_s << '\n';
  out << "metrics";
  for (const auto& m : study.metrics) out << ' ' << m;
  out << '\n';
  for (const auto& h : study.histories) out << "history " << h.label << ' ' << space.resolve(h) << '\n';
  return out.str();
}

std::string study_fingerprint(const Study& study, const CaseSpace& space, RecordCache& records) {
  return hex(fnv1a(canonical_description(study, space, records)));
}

}  // namespace pcrf::study

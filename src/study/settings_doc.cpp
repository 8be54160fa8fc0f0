// The README's key tables from the setting descriptions (see settings_doc.hpp).
#include "pcrf/study/settings_doc.hpp"

#include "pcrf/record/intensity.hpp"
#include "pcrf/solver/settings.hpp"
#include "pcrf/study/study.hpp"

namespace pcrf::study {
namespace {

template <class Target>
std::string marked(const SettingTable<Target>& table) {
  return "<!-- settings:" + std::string(table.name) + " -->\n" + markdown_table(table) + "<!-- /settings -->\n";
}

}  // namespace

std::string all_settings_markdown() {
  return marked(intensity_settings()) + "\n" + marked(ida_settings()) + "\n" + marked(physics_settings()) + "\n" + marked(solver_settings()) + "\n" +
         marked(run_settings());
}

}  // namespace pcrf::study

// Flags that name one ground motion (see record_flags.hpp).
#include "cli/record_flags.hpp"

#include "pcrf/user_error.hpp"


namespace pcrf::cli {

void RecordFlags::add_to(CLI::App* cmd, bool file_positional, bool synthetic_allowed) {
  const std::string group = "record";
  if (file_positional)
    cmd->add_option("FILE", file, "ground-motion file (.AT2, two-column or one-column text)")->required();
  else
    cmd->add_option("--record", file, "ground-motion file (.AT2, two-column or one-column text)")->group(group);
  cmd->add_option("--format", format, "record format: at2, two-column, one-column (default: from extension)")->group(group);
  cmd->add_option("--units", units, "acceleration units of a text record: g, m/s2, cm/s2")->capture_default_str()->group(group);
  cmd->add_option("--dt-s,--dt", dt_s, "sample interval of a one-column record [s]")->group(group);
  cmd->add_option("--skip-rows", skip_rows, "text records: lines to drop at the top (headers, an added leading sample)")
      ->group(group);
  cmd->add_option("--column", column,
                  "one-column records: read the K-th field of every row (a file of series side by side)")
      ->group(group);
  if (synthetic_allowed)
    cmd->add_option("--synthetic", synthetic,
                    "synthetic motion, e.g. 'sine:amplitude_g=1.5,period_s=0.5,cycles=2' or "
                    "'stochastic:seed=3,pga_g=1.2,duration_s=20'")
        ->group(group);
}

void RecordFlags::add_components_to(CLI::App* cmd, bool record_flags) {
  const std::string group = "record";
  for (std::size_t i = 0; i < kComponentCount; ++i) {
    const ComponentInfo& c = kStationComponents[i];
    const std::string flag = record_flags ? std::string(c.record_flag) : flag_name(c.keyword);
    cmd->add_option(flag, component_files[i], std::string(c.doc) + " (read like the first)")->group(group);
  }
  cmd->add_option("--azimuth-deg", az1_deg, "azimuth of the first component [deg from north] (default: its header)")
      ->group(group);
  cmd->add_option("--h2-azimuth-deg", az2_deg,
                  "azimuth of the second horizontal component [deg from north] (default: its header)")
      ->group(group);
}

}  // namespace pcrf::cli

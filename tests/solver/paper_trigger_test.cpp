// The paper's t_RI (Table 3) for the 13 records of ../shared/records/paper/INDEX.csv,
// exactly to the sample. Skipped when ../shared/records is absent.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "pcrf/model/frame.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/solver/rocking_solver.hpp"
#include "support/test_support.hpp"

namespace pcrf {
namespace {

struct IndexRow {
  std::string id, file;
  double t_ri_s;
};

std::vector<IndexRow> read_index(const std::filesystem::path& csv) {
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);  // header: er_id,file,npts,dt_s,pga_g,time_of_pga_s,paper_t_RI_s
  std::vector<IndexRow> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) f.push_back(cell);
    rows.push_back({f.at(0), f.at(1), std::stod(f.at(6))});
  }
  return rows;
}

TEST(PaperTable3, TriggerTimeMatchesTheSampleForAll13Records) {
  PCRF_REQUIRE_RECORDS(records);
  const auto rows = read_index(records / "paper" / "INDEX.csv");
  ASSERT_EQ(rows.size(), 13u);
  SolverSettings fast;
  fast.rtol = 1e-6;
  for (const auto& row : rows) {
    const GroundMotion rec = read_at2(records / row.file);
    const CaseResult r = solve_case(basic_frame(), rec, {}, fast);
    // To the sample: within half a sample interval of the paper's value.
    EXPECT_NEAR(r.t_trigger_paper_s, row.t_ri_s, 0.5 * rec.dt_s()) << row.id << " " << row.file;
  }
}

}  // namespace
}  // namespace pcrf

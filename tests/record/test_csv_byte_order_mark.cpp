// A UTF-8 byte-order mark before a CSV's first line (a spreadsheet's "CSV UTF-8") is skipped by
// every CSV reader of the record library, as by the hazard reader (issue 41, item 8): the
// selection target and the spectra table read the same with and without it.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "pcrf/byte_order_mark.hpp"
#include "pcrf/record/record_library.hpp"
#include "pcrf/record/selection.hpp"

namespace {

TEST(CsvByteOrderMark, SelectionTargetReadsTheSameWithAMark) {
  const std::string text = "period_s,mean_ln_sa,sigma_ln_sa\n0.1,-0.5,0.6\n1,-1.2,0.5\n";
  std::istringstream plain(text), marked(std::string(pcrf::kUtf8ByteOrderMark) + text);
  const auto a = pcrf::read_selection_target(plain, "t.csv");
  const auto b = pcrf::read_selection_target(marked, "t.csv");
  EXPECT_EQ(a.periods_s, b.periods_s);
  ASSERT_EQ(b.periods_s.size(), 2u);
}

TEST(CsvByteOrderMark, SpectraTableReadsTheSameWithAMark) {
  const std::string text = "name,kind,file,file_h2,dt_s,samples,damping,pga_g,sa_g_0.5s,sa_g_1s\n"
                           "a,component,a.AT2,,0.01,100,0.05,0.3,0.2,0.1\n";
  std::istringstream plain(text), marked(std::string(pcrf::kUtf8ByteOrderMark) + text);
  const auto a = pcrf::read_spectra_csv(plain, "lib.csv");
  const auto b = pcrf::read_spectra_csv(marked, "lib.csv");
  EXPECT_EQ(a.periods_s, b.periods_s);
  ASSERT_EQ(b.entries.size(), 1u);
  EXPECT_EQ(b.entries[0].sa_g, a.entries[0].sa_g);
}

}  // namespace

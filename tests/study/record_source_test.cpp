// The record cache: each record's motion and title from one read of its file, and the factor
// a level of the second axis asks of it.
#include <gtest/gtest.h>

#include "pcrf/study/record_source.hpp"
#include "support/test_support.hpp"

namespace pcrf::study {
namespace {

RecordSource file_source(const std::filesystem::path& path, RecordFormat format) {
  RecordFileSpec spec;
  spec.path = path;
  spec.format = format;
  return {path.stem().string(), spec, "", Where{{}, "t.toml", 1}, {}, {}};
}

TEST(RecordCache, TitlesComeFromTheAt2HeaderElseTheFileNameOrTheSyntheticText) {
  const auto dir = test::scratch_dir("record_cache_titles");
  const std::string data = "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=   2, DT=   .0050 SEC,\n 0.1 0.2\n";
  const auto titled = test::write_file(dir, "A.AT2", "PEER\nLoma Prieta, 1989, Gilroy, 090\n" + data);
  const auto untitled = test::write_file(dir, "B.AT2", "PEER\n   \n" + data);
  const auto text = test::write_file(dir, "C.txt", "0 0.1\n0.01 0.2\n");
  RecordCache records({file_source(titled, RecordFormat::kAt2), file_source(untitled, RecordFormat::kAt2),
                       file_source(text, RecordFormat::kTwoColumn), {"s", std::nullopt, "sine:amplitude_g=1", Where{{}, "t.toml", 2}, {}, {}}});
  ASSERT_EQ(records.get(0).size(), 2u);
  std::filesystem::remove(titled);  // the title came with the motion: the file is not read again
  EXPECT_EQ(records.title(0), "Loma Prieta, 1989, Gilroy, 090");
  EXPECT_EQ(records.title(1), "B.AT2");
  EXPECT_EQ(records.title(2), "C.txt");
  EXPECT_EQ(records.title(3), "sine:amplitude_g=1");
}

TEST(RecordCache, AScaleLevelIsTheFactorAnIntensityLevelIsDividedByTheRecordsMeasure) {
  RecordCache records({{"s", std::nullopt, "sine:amplitude_g=0.5,period_s=0.5,cycles=2,duration_s=3", Where{{}, "t.toml", 1}, {}, {}}});
  EXPECT_EQ(records.scale_factor(0, 1.5, std::nullopt), 1.5);
  const IntensitySpec pga{IntensityMeasure::kPga, 0.0, 0.05};
  const double pga_g = records.intensity(0, pga);
  ASSERT_GT(pga_g, 0.0);
  EXPECT_EQ(records.scale_factor(0, 1.5, pga), 1.5 / pga_g);
  EXPECT_NEAR(intensity_of(records.get(0).scaled(records.scale_factor(0, 1.5, pga)), pga), 1.5, 1e-12);
}

}  // namespace
}  // namespace pcrf::study

// Issue 29's plausible mistakes, one line each: incidences that look like radians, and the
// components of a station whose headers name other events or stations. The wording is not
// held beyond the key, the names and the numbers the line gives.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "pcrf/record/horizontal_pair.hpp"
#include "pcrf/record/record_readers.hpp"
#include "pcrf/user_error.hpp"

namespace pcrf {
namespace {

TEST(RadiansWarning, IncidencesThatAllLookLikeRadiansWarnNamingTheKey) {
  const std::string p = radians_problem({3.7});  // meant as 212°
  const std::string w = UserError(Where{{"axes", "incidence_deg"}, "s.toml", 3}, p, {"incidence_deg"}).message(Dialect::kFlag);
  EXPECT_EQ(w.rfind("s.toml:3: [axes] incidence_deg: ", 0), 0u) << w;
  EXPECT_NE(w.find("; incidence_deg is in degrees"), std::string::npos) << w;
  EXPECT_NE(w.find("3.7"), std::string::npos) << w;
  EXPECT_NE(w.find("212"), std::string::npos) << w;
  EXPECT_NE(radians_problem({0.0, 1.5707963, 3.14159}), "");
  EXPECT_NE(radians_problem({-6.0, 0.5}), "");
  // Whole degrees, or any value beyond 2π: degrees.
  EXPECT_EQ(radians_problem({0.0, 1.0, 3.0}), "");
  EXPECT_EQ(radians_problem({0.5, 12.5}), "");
  EXPECT_EQ(radians_problem({212.0}), "");
  EXPECT_EQ(radians_problem({}), "");
}

RecordMetadata header(const std::string& event, const std::string& station) { return {"", event, station, "", ""}; }

TEST(DifferentStation, HeadersOfOtherEventsOrStationsAreNamedBoth) {
  const ComponentHeader rinaldi{"RRS228.AT2", header("Northridge-01", "Rinaldi Receiving Sta")};
  const ComponentHeader pel{"PEL090.AT2", header("San Fernando", "LA - Hollywood Stor FF")};
  const std::string w = different_station(rinaldi, pel);
  for (const char* part : {"RRS228.AT2", "Northridge-01", "Rinaldi Receiving Sta", "PEL090.AT2", "San Fernando",
                           "LA - Hollywood Stor FF", "events and stations"})
    EXPECT_NE(w.find(part), std::string::npos) << part << ": " << w;
  const ComponentHeader other_station{"x.AT2", header("Northridge-01", "Sylmar")};
  EXPECT_NE(different_station(rinaldi, other_station).find("different stations"), std::string::npos);
  // The same station (case and spacing aside), or a header that names none: nothing.
  EXPECT_EQ(different_station(rinaldi, {"RRS318.AT2", header("NORTHRIDGE-01", "Rinaldi  Receiving Sta")}), "");
  EXPECT_EQ(different_station(rinaldi, {"a.txt", RecordMetadata{}}), "");
}

}  // namespace
}  // namespace pcrf

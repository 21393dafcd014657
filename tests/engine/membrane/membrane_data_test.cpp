// Tests for engine/membrane/membrane_data.h: parsing, and every bad input names its row and column.
#include "engine/membrane/membrane_data.h"

#include <gtest/gtest.h>

#include <sstream>

#include "engine/core/error.h"

namespace cablelab {
namespace {

const MembraneGeometry kGeometry{Vec2(-0.2, 0.0), Vec2(0.2, 0.0)};

std::vector<MembraneSample> parse(const std::string& text) {
  std::istringstream in(text);
  return parseMembraneCsv(in, kGeometry, "test.csv");
}

/// The InputError message for `text`, or "" when it parses.
std::string errorOf(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MembraneData, ParsesRowsInAnyColumnOrderWithCrlfAndBlankLines) {
  const auto rows = parse(
      "\xEF\xBB\xBF"
      "angle_deg, fy ,x,y,comment\r\n"
      "80,5.5,0.0,-0.1,a\r\n\r\n"
      "+85,6e0,0.05,-0.1,b\r\n"
      "-95,-6,0.05,0.1,c\n");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[1].p, Vec2(0.05, -0.1));
  EXPECT_EQ(rows[1].fy, 6.0);
  EXPECT_EQ(rows[1].angleDeg, 85.0);
  EXPECT_EQ(rows[2].fy, -6.0);
}

TEST(MembraneData, RoundTripsWithFullPrecision) {
  std::vector<MembraneSample> rows = {{Vec2(0.1 / 3, -0.2 / 7), 1.0 / 3, 89.0 + 1.0 / 7},
                                      {Vec2(0.01, -0.05), 2.0, 91.0},
                                      {Vec2(0.02, 0.05), -2.5, -88.0}};
  std::ostringstream out;
  writeMembraneCsv(out, rows);
  const auto back = parse(out.str());
  ASSERT_EQ(back.size(), rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(back[i].p, rows[i].p);
    EXPECT_EQ(back[i].fy, rows[i].fy);
    EXPECT_EQ(back[i].angleDeg, rows[i].angleDeg);
  }
}

TEST(MembraneData, NamesTheProblem) {
  const std::string header = "x,y,fy,angle_deg\n";
  const std::string good = "0,-0.1,5,90\n0.1,-0.1,5,80\n-0.1,-0.1,5,100\n";
  EXPECT_EQ(errorOf(""), "test.csv: header: file is empty (expected x,y,fy,angle_deg) (got \"\")");
  EXPECT_EQ(errorOf("x,y,fy\n0,-0.1,5\n"),
            "test.csv: header: missing column \"angle_deg\" (expected x,y,fy,angle_deg) (got "
            "\"x,y,fy\")");
  EXPECT_EQ(errorOf("x,y,fy,fy,angle_deg\n"),
            "test.csv: header: column \"fy\" appears twice (got \"x,y,fy,fy,angle_deg\")");
  EXPECT_EQ(errorOf(header + "0,-0.1,5,90\n0.1,-0.1,5,80\n"),
            "test.csv: rows: need at least 3 measurements to fit k and preload (got 2)");
  EXPECT_EQ(errorOf(header + good + "0,-0.1,nan,90\n"),
            "test.csv: row 4, fy: must be a finite number (got \"nan\")");
  EXPECT_EQ(errorOf(header + good + "0,-0.1,5,inf\n"),
            "test.csv: row 4, angle_deg: must be a finite number (got \"inf\")");
  EXPECT_EQ(errorOf(header + "0,-0.1,5,abc\n" + good),
            "test.csv: row 1, angle_deg: must be a finite number (got \"abc\")");
  EXPECT_EQ(errorOf(header + "0,-0.1,,90\n" + good),
            "test.csv: row 1, fy: must be a finite number (got \"\")");
  EXPECT_EQ(errorOf(header + "0,-0.1,5\n" + good), "test.csv: row 1: expected 4 fields (got 3)");
  EXPECT_EQ(errorOf(header + good + "0.05,0,5,90\n"),
            "test.csv: row 4, y: point lies on the band between the pulleys: force direction "
            "undefined (got [0.05, 0])");
  EXPECT_EQ(errorOf(header + good + "0.2,0,5,90\n"),
            "test.csv: row 4, x: point coincides with pulley B (got [0.2, 0])");
  // On the pulley line but outside the pulleys the force is defined: accepted.
  EXPECT_EQ(errorOf(header + good + "0.3,0,-20,180\n"), "");
}

TEST(MembraneData, RejectsCoincidentPulleys) {
  std::istringstream in("x,y,fy,angle_deg\n0,-0.1,5,90\n");
  try {
    parseMembraneCsv(in, MembraneGeometry{Vec2(0.1, 0.0), Vec2(0.1, 0.0)}, "test.csv");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "pulleys");
  }
}

TEST(MembraneData, MissingFileIsAnInputError) {
  EXPECT_THROW(loadMembraneCsv("/nonexistent/membrane.csv", kGeometry), InputError);
}

}  // namespace
}  // namespace cablelab

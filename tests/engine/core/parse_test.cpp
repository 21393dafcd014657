// engine/core/parse.h and the number format of engine/core/error.h.
#include "engine/core/parse.h"

#include <gtest/gtest.h>

#include <limits>

#include "engine/core/error.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

using test::messageOf;

TEST(Parse, FiniteNumberTakesTheWholeTextOrNothing) {
  for (const auto& [text, value] : {std::pair{"1", 1.0},
                                    {"+2", 2.0},
                                    {"-0.5", -0.5},
                                    {".5", 0.5},
                                    {"1e3", 1000.0},
                                    {"1.7976931348623157e308", 1.7976931348623157e308}})
    EXPECT_EQ(parseFiniteNumber(text), value) << text;
  for (const char* text :
       {"", " 1", "1 ", "1x", "0x10", "inf", "-inf", "nan", "+-1", "+", "1e999", "1,2", "--1"})
    EXPECT_FALSE(parseFiniteNumber(text)) << text;
}

TEST(Parse, FormatNumberIsTheShortestRoundTrip) {
  for (const double v : {-1.0, 0.1, 1.0 / 3, 1e300, 5e-324, 400.0, -0.25, 123456789.125}) {
    const std::string text = formatNumber(v);
    EXPECT_EQ(parseFiniteNumber(text), v) << text;
  }
  EXPECT_EQ(formatNumber(-1), "-1");
  EXPECT_EQ(formatNumber(0.1), "0.1");
  EXPECT_EQ(formatNumber(1e13), "1e+13");
  EXPECT_EQ(formatNumber(std::numeric_limits<double>::quiet_NaN()), "nan");
  EXPECT_EQ(formatNumber(-std::numeric_limits<double>::infinity()), "-inf");
}

TEST(Parse, ErrorsNameSourceFieldAndValue) {
  EXPECT_EQ(messageOf([] { parseNumber("abc", "command line", "--dt"); }),
            "command line: --dt: must be a finite number (got \"abc\")");
  EXPECT_EQ(messageOf([] { parseWholeNumber("2.5", "command line", "--grid", 1, 10); }),
            "command line: --grid: must be a whole number in [1, 10] (got \"2.5\")");
  EXPECT_EQ(parseWholeNumber("1e3", "s", "f", 0, 1000), 1000);
  EXPECT_EQ(messageOf([] { parseNumberList("1,,3", 3, "command line", "--ramp", "X,Y,S"); }),
            "command line: --ramp: must be X,Y,S, 3 finite numbers (got \"1,,3\")");
  EXPECT_EQ(messageOf([] { parseNumberList("1,2,", 2, "command line", "--target", "X,Y"); }),
            "command line: --target: must be X,Y, 2 finite numbers (got \"1,2,\")");
  const auto v = parseNumberList("1,-2.5,3e-1", 3, "s", "f", "A,B,C");
  EXPECT_EQ(v, (std::vector<double>{1, -2.5, 0.3}));
}

TEST(Parse, PixelSizeIsWxHWithinBounds) {
  const PixelSize s = parsePixelSize("800x600", "s", "f", 16, 8192);
  EXPECT_EQ(s.width, 800);
  EXPECT_EQ(s.height, 600);
  EXPECT_EQ(parsePixelSize("20X30", "s", "f", 16, 8192).height, 30);
  for (const char* bad : {"800", "800x", "x600", "8x600", "800x600x2", "800.5x600", "800 x600",
                          "-800x600", "9000x600"})
    EXPECT_EQ(messageOf([&] { parsePixelSize(bad, "command line", "--size", 16, 8192); }),
              "command line: --size: must be WxH, each a whole number in [16, 8192] (got \"" +
                  std::string(bad) + "\")")
        << bad;
}

TEST(Parse, CommandLineParserMessagesNameTheOption) {
  auto text = [](const std::string& m) {
    return std::string(commandLineError(m, "see x --help").what());
  };
  EXPECT_EQ(text("Could not convert: --time = abc"),
            "command line: --time: cannot convert the value (got \"abc\") (see x --help)");
  EXPECT_EQ(text("The value abc is not an allowed value for --frames"),
            "command line: --frames: not an allowed value (got \"abc\") (see x --help)");
  EXPECT_EQ(text("scene is required"),
            "command line: scene: is required (got nothing) (see x --help)");
  EXPECT_EQ(text("--grid: Value 0 not in range 1 to 10"),
            "command line: --grid: Value 0 not in range 1 to 10 (see x --help)");
  EXPECT_EQ(text("The following argument was not expected: --bogus"),
            "command line: (arguments): unknown option or one argument too many (got \"--bogus\") "
            "(see x --help)");
}

TEST(InputErrorStyle, MessagesAreOneLineAndValuesQuoted) {
  const InputError e("f.json", "a", "bad\nthing" + gotValue("x\"y\nz"));
  EXPECT_EQ(std::string(e.what()), "f.json: a: bad thing (got \"x\\\"y\\nz\")");
  EXPECT_EQ(e.detail(), "bad\nthing (got \"x\\\"y\\nz\")");
  EXPECT_EQ(gotValue(std::string(100, 'a')).size(), std::string(" (got \"\")").size() + 60);
}

}  // namespace
}  // namespace cablelab

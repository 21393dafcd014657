// Every subcommand of the contract (/work/shared/CONTRACT.md, docs/cli.md) refuses a bad option
// with exit 2 and one line `SOURCE: FIELD: what is wrong (got VALUE)` that quotes back what was
// given (engine/core/error.h), a missing value as "(got nothing)".
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

namespace fs = std::filesystem;

struct BadCall {
  std::string args;  // after `cablelab`
  std::string got;   // what the "(got ...)" part must contain
};

std::string scratchFile(const std::string& name) {
  return (fs::temp_directory_path() / ("cablelab_error_values_" + name)).string();
}

std::vector<BadCall> badCalls() {
  const std::string statics = test::dataPath("statics/two_cables.json");
  const std::string data = test::sourcePath("assets/data/membrane_example.csv");
  const std::string generate =
      "fit --generate " + scratchFile("gen.csv") + " --pulleys -0.2,0,0.2,0 --k 100 ";
  const std::string png = scratchFile("x.png");
  std::vector<BadCall> calls = {
      {"scenes --nosuch", "\"--nosuch\""},
      {"scenes --export /no/such/folder", "/no/such/folder"},
      {"run", "nothing"},
      {"run pulley --time -1", "-1"},
      {"run pulley --time abc", "\"abc\""},
      {"run pulley --dt 0", "0"},
      {"run pulley --dt 2", "2"},
      {"run pulley --substeps 0", "0"},
      {"run pulley --set m_left=-2", "-2"},
      {"run pulley --set nosuch=1", "\"nosuch=1\""},
      {"run pulley --set m_left", "\"m_left\""},
      {"run pulley --set m_left=abc", "\"abc\""},
      {"run no_such_scene", "\"no_such_scene\""},
      {"run pulley --bogus", "\"--bogus\""},
      {"run pulley --time 1e7 --dt 1e-5", "1e+07"},
      {"statics", "nothing"},
      {"statics " + statics + " --solver magic", "\"magic\""},
      {"wrap", "nothing"},
      {"fit", "nothing"},
      {"fit " + data, "nothing"},
      {"fit " + data + " --pulleys 1,2,3", "\"1,2,3\""},
      {"fit " + data + " --pulleys 0,0,0,0", "0,0,0,0"},
      {"fit " + data + " --pulleys -0.2,0,0.2,0 --k 5", "\"5\""},
      {"fit " + data + " --pulleys -0.2,0,0.2,0 --sigma-fy -1", "-1"},
      {"fit " + data + " --pulleys -0.2,0,0.2,0 --plots " + scratchFile("plots") +
           " --plot-size 0x0",
       "\"0x0\""},
      {"fit --generate out.csv", "nothing"},
      {"fit --generate " + scratchFile("gen.csv") + " --pulleys -0.2,0,0.2,0 --k 100", "nothing"},
      {generate + "--preload -1", "-1"},
      {generate + "--preload 0.01 --noise-fy -1", "-1"},
      {generate + "--preload 0.01 --seed -1", "\"-1\""},
      {generate + "--preload 0.01 --grid 0x3", "\"0x3\""},
      {generate + "--preload 0.01 --depth 0,0.3", "(0, 0.3)"},
      {"fit --generate " + scratchFile("gen.csv") + " --pulleys -0.2,0,0.2,0 --k -1 --preload 0.01",
       "-1"},
      {"track --target 1", "\"1\""},
      {"track --target a,b", "\"a,b\""},
      {"track --target 0.1,0.1 --ramp 0.1,0.1,1", "both"},
      {"track --ramp 0.1,0.1,-1", "-1"},
      {"track --time -1", "-1"},
      {"track --controller foo", "\"foo\""},
      {"track --horizon 0 --controller mpc", "0"},
      {"track --set nosuch=1", "\"nosuch=1\""},
      {"reach --grid 0", "0"},
      {"reach --grid x", "\"x\""},
      {"reach --model foo", "\"foo\""},
      {"reach --controller foo", "\"foo\""},
      {"reach --angles a,b", "\"a,b\""},
      {"reach --set nosuch=1", "\"nosuch=1\""},
      {"bench --bogus", "\"--bogus\""},
      {"no_such_command", "\"no_such_command\""},
  };
#ifdef CABLELAB_HAVE_OFFSCREEN  // snapshot, record and gui need the renderer
  const std::vector<BadCall> pictures = {
      {"snapshot pulley", "nothing"},
      {"snapshot pulley --out " + png + " --size 10x10", "\"10x10\""},
      {"snapshot pulley --out " + png + " --time -1", "-1"},
      {"snapshot pulley --out " + png + " --tolerance 0.5", "0.5"},
      {"snapshot pulley --out " + png + " --compare /no/such.png", "\"/no/such.png\""},
      {"snapshot pulley --out " + png + " --set nosuch=1", "\"nosuch=1\""},
      {"record pulley", "nothing"},
      {"record pulley --out " + scratchFile("x.gif") + " --fps 0", "0"},
      {"record pulley --out " + scratchFile("x.gif") + " --time -1", "-1"},
      {"record pulley --out " + scratchFile("x.gif") + " --size 1x1", "\"1x1\""},
      {"record pulley --out " + scratchFile("x.gif") + " --view 0,0,-1", "-1"},
      {"record pulley --out " + scratchFile("x.gif") + " --view 0,0", "\"0,0\""},
      {"gui pulley --frames -1", "\"-1\""},
      {"gui pulley --frames 1 --size 5x5", "\"5x5\""},
      {"gui pulley --frames 1 --set nosuch=1", "\"nosuch=1\""},
      {"gui no_such_scene --frames 1", "\"no_such_scene\""},
  };
  calls.insert(calls.end(), pictures.begin(), pictures.end());
#endif
  return calls;
}

TEST(ErrorValues, EveryBadOptionOfEverySubcommandQuotesTheValueBack) {
  const std::regex style(R"(^[^:\n]+: [^:\n]+: .+ \(got .+\)$)");
  int checked = 0;
  for (const BadCall& call : badCalls()) {
    const auto r = test::runCli(call.args);
    EXPECT_EQ(r.exitCode, 2) << call.args << "\n" << r.err;
    EXPECT_EQ(r.out, "") << call.args;
    ASSERT_FALSE(r.err.empty()) << call.args;
    const std::string line = r.err.substr(0, r.err.size() - 1);
    EXPECT_EQ(r.err.back(), '\n') << call.args;
    EXPECT_TRUE(std::regex_match(line, style)) << call.args << "\n" << r.err;
    const size_t got = line.rfind("(got ");
    ASSERT_NE(got, std::string::npos) << call.args << "\n" << r.err;
    EXPECT_NE(line.find(call.got, got), std::string::npos)
        << call.args << ": names " << call.got << "\n"
        << r.err;
    ++checked;
  }
  EXPECT_GE(checked, 45);
}

}  // namespace
}  // namespace cablelab

// Replays every input in tests/data/regress/ (crashes the fuzzers found, named
// scene_*, statics_*, wrap_*) and the hand-written bad inputs through the fuzz harness
// (tests/fuzz/fuzz_inputs.h): each must be accepted with finite results or refused with an
// InputError / stopped with a SimulationError, never crash or give NaN.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/fuzz/fuzz_inputs.h"
#include "tests/support/engine_test_support.h"

namespace cablelab {
namespace {

std::string readAll(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// Runs the harness the file's name prefix selects; returns false for an unknown prefix.
bool replay(const std::filesystem::path& p, fuzz::Outcome& outcome) {
  const std::string name = p.filename().string(), text = readAll(p);
  if (name.rfind("scene_", 0) == 0)
    outcome = fuzz::runSceneInput(text);
  else if (name.rfind("statics_", 0) == 0)
    outcome = fuzz::runStaticsInput(text);
  else if (name.rfind("wrap_", 0) == 0)
    outcome = fuzz::runWrapInput(text);
  else
    return false;
  return true;
}

TEST(Regress, FuzzerFindingsReplayCleanly) {
  int replayed = 0;
  for (const auto& e :
       std::filesystem::directory_iterator(test::sourcePath("tests/data/regress"))) {
    if (!e.is_regular_file() || e.path().extension() == ".md") continue;
    SCOPED_TRACE(e.path().string());
    fuzz::Outcome outcome;
    bool known = false;
    EXPECT_NO_THROW(known = replay(e.path(), outcome));
    EXPECT_TRUE(known) << "name must start with scene_, statics_ or wrap_";
    ++replayed;
  }
  std::printf("[regress] %d inputs replayed\n", replayed);
}

TEST(Regress, HandWrittenBadInputsAreRefused) {
  for (const auto& e : std::filesystem::directory_iterator(test::sourcePath("tests/data/bad"))) {
    if (e.path().extension() != ".json") continue;
    SCOPED_TRACE(e.path().string());
    fuzz::Outcome outcome = fuzz::Outcome::Accepted;
    EXPECT_NO_THROW(replay(e.path(), outcome));
    EXPECT_EQ(outcome, fuzz::Outcome::Refused);
  }
}

TEST(Regress, ShippedInputsAreAccepted) {
  for (const char* dir : {"assets/scenes"}) {
    for (const auto& e : std::filesystem::directory_iterator(test::sourcePath(dir))) {
      SCOPED_TRACE(e.path().string());
      fuzz::Outcome outcome = fuzz::Outcome::Refused;
      EXPECT_NO_THROW(outcome = fuzz::runSceneInput(readAll(e.path())));
      EXPECT_EQ(outcome, fuzz::Outcome::Accepted);
    }
  }
  for (const auto& e :
       std::filesystem::directory_iterator(test::sourcePath("tests/data/statics"))) {
    SCOPED_TRACE(e.path().string());
    fuzz::Outcome outcome = fuzz::Outcome::Refused;
    EXPECT_NO_THROW(outcome = fuzz::runStaticsInput(readAll(e.path())));
    EXPECT_EQ(outcome, fuzz::Outcome::Accepted);
  }
}

}  // namespace
}  // namespace cablelab

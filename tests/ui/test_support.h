// Shared helpers of the UI tests: run a command, compare images, step a scene.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "engine/dynamics/world.h"
#include "ui/image.h"
#include "ui/scene_catalog.h"

namespace cablelab::test {

/// Where tests may write files (under the build directory).
inline std::filesystem::path outputDir(const std::string& sub) {
  const auto dir = std::filesystem::path(CABLELAB_TEST_OUTPUT) / sub;
  std::filesystem::create_directories(dir);
  return dir;
}

struct RunResult {
  int exitCode = -1;
  std::string out, err;
};

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

/// Runs `command` through /bin/sh, capturing stdout and stderr.
inline RunResult run(const std::string& command, const std::string& tag) {
  const auto dir = outputDir("run");
  const auto out = dir / (tag + ".out"), err = dir / (tag + ".err");
  const int status = std::system((command + " >" + out.string() + " 2>" + err.string()).c_str());
  RunResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

/// The JSON report a scripted run printed on stdout; a failed run or no JSON is a test failure
/// (and an empty object, so the caller's checks fail on their own terms).
inline nlohmann::json jsonReport(const RunResult& r) {
  EXPECT_EQ(r.exitCode, 0) << r.err;
  try {
    return nlohmann::json::parse(r.out);
  } catch (const std::exception&) {
    ADD_FAILURE() << "no JSON report: " << r.out << r.err;
    return nlohmann::json::object();
  }
}

/// True when `program` is found on PATH.
inline bool onPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::stringstream s(path ? path : "");
  for (std::string dir; std::getline(s, dir, ':');)
    if (!dir.empty() && std::filesystem::exists(std::filesystem::path(dir) / program)) return true;
  return false;
}

/// Pixels whose largest channel difference exceeds `threshold` (ui::compareImages); writes the
/// diff image (the expected image greyed out, differing pixels red) to `diffPath` when it is
/// not empty. Images of different sizes differ everywhere.
inline long countDiffering(const ui::Image& a, const ui::Image& b, int threshold,
                           const std::string& diffPath = {}) {
  if (a.width != b.width || a.height != b.height) return static_cast<long>(a.width) * a.height;
  const ui::ImageComparison c = ui::compareImages(a, b, threshold);
  if (!diffPath.empty()) ui::writePng(c.diff, diffPath);
  return c.differing;
}

/// A built-in scene stepped for `seconds` at its own dt and substeps (as `cablelab snapshot`).
inline std::unique_ptr<World> sceneAt(const std::string& name, double seconds) {
  auto world = std::make_unique<World>(ui::loadScene(name), name);
  const double dt = world->scene().dt;
  const long steps = std::lround(seconds / dt);
  for (long i = 0; i < steps; ++i) world->step(dt, world->scene().substeps);
  return world;
}

}  // namespace cablelab::test

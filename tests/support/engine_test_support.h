// Shared helpers for the engine tests: seeded random numbers and running the CLI.
#pragma once

#include <sys/wait.h>
#include <unistd.h>
#include <array>
#include <cstdio>
#include <random>
#include <string>

#include <cstdlib>

#include <functional>

#include "engine/core/error.h"
#include "engine/core/math.h"

namespace cablelab::test {

inline constexpr double kDt = 1.0 / 60.0;  ///< s: the scenes' default step (60 Hz)

/// The InputError message `f` throws, "" if it throws none.
inline std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

class Random {
 public:
  explicit Random(unsigned seed) : gen_(seed) {}
  double uniform(double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(gen_);
  }
  Vec2 point(double lo, double hi) { return Vec2(uniform(lo, hi), uniform(lo, hi)); }
  int integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(gen_); }

 private:
  std::mt19937 gen_;
};

struct CommandResult {
  int exitCode = -1;
  std::string out, err;
};

/// Runs `PROGRAM ARGS` (shell-quoted by the caller), from `workingDir` if given; captures
/// stdout and stderr.
inline CommandResult runProgram(const std::string& program, const std::string& args,
                                const std::string& workingDir = "") {
  char errFile[] = "/tmp/cablelab-test-XXXXXX";
  const int fd = mkstemp(errFile);
  if (fd >= 0) close(fd);
  const std::string cd = workingDir.empty() ? "" : "cd '" + workingDir + "' && ";
  const std::string cmd = cd + "'" + program + "' " + args + " 2>" + std::string(errFile);
  CommandResult r;
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) r.out.append(buf.data(), n);
  const int status = pclose(pipe);
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (FILE* f = std::fopen(errFile, "r")) {
    while ((n = fread(buf.data(), 1, buf.size(), f)) > 0) r.err.append(buf.data(), n);
    std::fclose(f);
  }
  std::remove(errFile);
  return r;
}

/// Runs `cablelab ARGS` (see runProgram).
inline CommandResult runCli(const std::string& args, const std::string& workingDir = "") {
  return runProgram(CABLELAB_CLI, args, workingDir);
}

inline std::string sourcePath(const std::string& relative) {
  return std::string(CABLELAB_SOURCE_DIR) + "/" + relative;
}

/// A file of tests/data/.
inline std::string dataPath(const std::string& name) {
  return sourcePath("tests/data/" + name);
}

}  // namespace cablelab::test

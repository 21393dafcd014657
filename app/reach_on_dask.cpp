#include "app/reach_on_dask.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "engine/core/error.h"

extern char** environ;

namespace cablelab::app {

namespace {

namespace fs = std::filesystem;

/// The interpreter the module was built for (CMake's Python3_EXECUTABLE), or $CABLELAB_PYTHON.
std::string pythonInterpreter() {
  if (const char* chosen = std::getenv("CABLELAB_PYTHON"); chosen && *chosen) return chosen;
  return CABLELAB_PYTHON_EXECUTABLE;
}

/// The environment for the child: PYTHONPATH led by the build tree's python/ folder when this
/// binary sits in a build tree (bin/../python/cablelab); an installed module needs nothing.
std::vector<std::string> childEnvironment() {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e)
    if (std::strncmp(*e, "PYTHONPATH=", 11) != 0) env.emplace_back(*e);
  std::error_code error;
  const fs::path python = fs::read_symlink("/proc/self/exe", error).parent_path() / ".." / "python";
  std::string path = !error && fs::exists(python / "cablelab" / "__init__.py")
                         ? fs::weakly_canonical(python).string()
                         : "";
  if (const char* old = std::getenv("PYTHONPATH"); old && *old)
    path += (path.empty() ? "" : ":") + std::string(old);
  if (!path.empty()) env.push_back("PYTHONPATH=" + path);
  return env;
}

std::vector<char*> pointers(std::vector<std::string>& strings) {
  std::vector<char*> p;
  for (std::string& s : strings) p.push_back(s.data());
  p.push_back(nullptr);
  return p;
}

/// The last non-empty line of a file (the child's stderr: Python's error line).
std::string lastLine(const std::string& path) {
  std::ifstream in(path);
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) last = line;
  return last;
}

}  // namespace

ReachResult runReachOnDask(const std::string& address, const ReachOptions& options,
                           Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  ReachResult r = reachGrid(options, HandModel{});
  const std::string python = pythonInterpreter();
  std::vector<std::string> args = {
      python,
      "-m",
      "cablelab._reach_on_dask",
      "--scheduler",
      address,
      "--grid",
      std::to_string(options.grid),
      "--model",
      options.model == ReachModel::Simulation ? "simulation" : "quasi-static"};
  if (!options.pid) args.push_back("--pd");
  std::vector<std::string> env = childEnvironment();

  // The child's stdout is our pipe; its stderr (Dask's log lines, a traceback) a temporary
  // file, shown only when the child fails.
  int pipeFds[2];
  if (pipe(pipeFds) != 0)
    throw std::runtime_error("reach --scheduler: pipe: " + std::string(std::strerror(errno)));
  char logPath[] = "/tmp/cablelab-reach-XXXXXX";
  const int logFd = mkstemp(logPath);
  if (logFd < 0)
    throw std::runtime_error("reach --scheduler: temporary file: " +
                             std::string(std::strerror(errno)));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, pipeFds[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, logFd, STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipeFds[0]);
  pid_t child = 0;
  const int spawned = posix_spawnp(&child, python.c_str(), &actions, nullptr, pointers(args).data(),
                                   pointers(env).data());
  posix_spawn_file_actions_destroy(&actions);
  close(pipeFds[1]);
  close(logFd);
  if (spawned != 0) {
    close(pipeFds[0]);
    unlink(logPath);
    throw std::runtime_error("reach --scheduler: cannot start " + python + ": " +
                             std::strerror(spawned));
  }

  std::string inputError, failure;
  bool haveTargets = false;
  FILE* out = fdopen(pipeFds[0], "r");
  char* line = nullptr;
  size_t capacity = 0;
  while (getline(&line, &capacity, out) > 0) {
    const nlohmann::json message = nlohmann::json::parse(line, nullptr, false);
    if (!message.is_object()) continue;
    if (message.contains("progress")) {
      progress.update(message["progress"][0].get<long>());
    } else if (message.contains("threads")) {
      r.threads = message["threads"].get<int>();
    } else if (message.contains("error")) {
      inputError = message["error"].get<std::string>();
    } else if (message.contains("failed")) {
      failure = message["failed"].get<std::string>();
    } else if (message.contains("targets")) {
      for (const auto& v : message["targets"]) {
        ReachTarget& t = r.targets.at(v[0].get<size_t>());
        t.simulated = v[1].get<bool>(), t.quasiStatic = v[2].get<bool>();
        t.error = v[3].get<double>(), t.graspHeld = v[4].get<bool>();
        t.simulatedTime = v[5].get<double>();
      }
      haveTargets = message["targets"].size() == r.targets.size();
    }
  }
  std::free(line);
  std::fclose(out);
  int status = 0;
  waitpid(child, &status, 0);
  const std::string log = lastLine(logPath);
  unlink(logPath);
  if (!inputError.empty())
    throw InputError(kCommandLine, "--scheduler", inputError + gotValue(address));
  if (!failure.empty()) throw std::runtime_error("reach --scheduler: " + failure);
  if (!haveTargets || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error(
        "reach --scheduler: " + python +
        " -m cablelab._reach_on_dask failed: " + (log.empty() ? "no result" : log));
  summariseReach(r);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace cablelab::app

// `cablelab statics FILE.json [--solver auto|socp|newton]` (docs/cli.md): the equilibrium of a
// point held by cables, as one JSON object on stdout.
#include <string>

#include "app/command.h"
#include "engine/core/error.h"
#include "engine/statics/socp.h"
#include "engine/statics/statics.h"
#include "engine/statics/statics_io.h"
#include "engine/statics/statics_newton.h"

namespace cablelab::app {
namespace {

struct StaticsArgs {
  std::string file;
  std::string solver = "auto";
};

int runStatics(const StaticsArgs& args) {
  // Validate the option before touching the file, so the message names the right culprit.
  if (args.solver != "auto" && args.solver != "socp" && args.solver != "newton")
    throw InputError(kCommandLine, "--solver",
                     "must be auto, socp or newton" + gotValue(args.solver));
  const StaticsProblem problem = loadStaticsFile(args.file);
  StaticsResult result;
  if (args.solver == "socp") {
    SocpWorkspace workspace;
    solveStaticsSocp(problem, result, workspace);
  } else if (args.solver == "newton") {
    solveStaticsNewton(problem, result);
  } else {
    solveStatics(problem, result);
  }
  printJson(staticsResultToJson(result));
  return 0;
}

const bool staticsRegistered = registerCommand(
    "statics", "equilibrium of a point held by cables (thesis 4.2) from a JSON file",
    [](CLI::App& sub) {
      auto args = std::make_shared<StaticsArgs>();
      sub.add_option("FILE", args->file,
                     "problem JSON: {\"cables\": [{\"a\", \"b\", \"k\", \"L\"}], \"p0\"}")
          ->required();
      sub.add_option("--solver", args->solver,
                     "auto (Newton, SOCP fallback; default), socp (interior point) or newton");
      return [args] { return runStatics(*args); };
    });

}  // namespace
}  // namespace cablelab::app

// cablelab wrap FILE.json: the taut path from A to B around one convex polygon.
// Parsing and solving live in engine/cable/wrap_io.h (shared with the fuzzer).
#include <nlohmann/json.hpp>

#include "app/command.h"
#include "engine/cable/wrap_io.h"

namespace cablelab::app {
namespace {

const bool wrapRegistered = registerCommand(
    "wrap", "Taut cable path from A to B around a convex polygon", [](CLI::App& sub) {
      auto file = std::make_shared<std::string>();
      sub.add_option("file", *file,
                     "Input JSON {\"A\": [x, y], \"B\": [x, y], \"polygon\": [[x, y], ...], "
                     "\"side\": \"left\"|\"right\"}")
          ->required();
      return [file] {
        const WrapProblem problem = loadWrapFile(*file);
        printJson(wrapSolutionToJson(solveWrap(problem, *file)).dump());
        return 0;
      };
    });

}  // namespace
}  // namespace cablelab::app

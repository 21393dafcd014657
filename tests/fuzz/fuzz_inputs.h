// The three untrusted inputs (scene files, statics problems, wrap problems) run end to end, the
// way the CLI runs them. Shared by the libFuzzer targets (tests/fuzz/fuzz_*.cpp) and by the
// GoogleTest that replays tests/data/regress/ (tests/engine/regress_test.cpp).
//
// The property: an input is either accepted and gives finite results, or it is refused with an
// InputError (bad input) or stopped with a SimulationError (a run that cannot go on). Anything
// else (another exception, NaN in a result, a crash, a sanitizer report) is a bug; NaN is
// reported as a HarnessFailure.
#pragma once

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <string_view>

#include "engine/cable/wrap_io.h"
#include "engine/core/error.h"
#include "engine/dynamics/world.h"
#include "engine/model/scene_json.h"
#include "engine/statics/socp.h"
#include "engine/statics/statics.h"
#include "engine/statics/statics_io.h"
#include "engine/statics/statics_newton.h"

namespace cablelab::fuzz {

enum class Outcome { Accepted, Refused, Stopped };

/// A broken property (NaN in an accepted result).
class HarnessFailure : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

inline void requireFinite(double v, const std::string& what) {
  if (!std::isfinite(v)) throw HarnessFailure(what + " is not finite");
}
inline void requireFinite(const Vec2& v, const std::string& what) {
  requireFinite(v.x(), what + ".x");
  requireFinite(v.y(), what + ".y");
}

/// Steps of a loaded scene the harness runs (small: the fuzzer wants many inputs per second).
inline constexpr int kSceneSteps = 20;

/// Scene JSON text -> SceneDef -> save/load round trip -> World -> kSceneSteps steps.
inline Outcome runSceneInput(std::string_view text) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception&) {
    return Outcome::Refused;  // loadSceneFile turns this into InputError "(json)"
  }
  try {
    const SceneDef def = sceneFromJson(j, "fuzz");
    // What we save must load back (the sandbox saves edited scenes).
    const SceneDef again = sceneFromJson(sceneToJson(def), "fuzz (saved)");
    (void)again;
    World world(def, "fuzz");
    // Long sub-step counts are legal but slow; the fuzzer only needs a few sub-steps to reach the
    // solver paths.
    const int substeps = std::min(def.substeps, 8);
    for (int i = 0; i < kSceneSteps; ++i) {
      world.step(def.dt, substeps);
      for (int b = 0; b < world.bodyCount(); ++b) {
        requireFinite(world.body(b).position, "body " + std::to_string(b) + " position");
        requireFinite(world.body(b).velocity, "body " + std::to_string(b) + " velocity");
      }
      for (int c = 0; c < world.cableCount(); ++c) {
        requireFinite(world.cable(c).length(), "cable " + std::to_string(c) + " length");
        requireFinite(world.cable(c).tension(), "cable " + std::to_string(c) + " tension");
        if (world.cable(c).tension() < 0)
          throw HarnessFailure("cable " + std::to_string(c) + " pushes");
      }
      if (std::isnan(world.energy())) throw HarnessFailure("energy is NaN");
    }
    return Outcome::Accepted;
  } catch (const InputError&) {
    return Outcome::Refused;
  } catch (const SimulationError&) {
    return Outcome::Stopped;
  }
}

inline void checkStatics(const StaticsProblem& problem, const StaticsResult& r,
                         const char* solver) {
  const std::string s = solver;
  requireFinite(r.p, s + " p");
  requireFinite(r.energy, s + " energy");
  requireFinite(r.residual, s + " residual");
  if (r.lengths.size() != problem.cables.size() || r.tensions.size() != problem.cables.size())
    throw HarnessFailure(s + ": lengths/tensions sized wrong");
  for (size_t i = 0; i < r.lengths.size(); ++i) {
    requireFinite(r.lengths[i], s + " length");
    requireFinite(r.tensions[i], s + " tension");
    if (r.tensions[i] < 0) throw HarnessFailure(s + ": negative tension");
  }
}

/// Statics JSON text -> parse -> every solver `cablelab statics` offers -> JSON out.
inline Outcome runStaticsInput(std::string_view text) {
  try {
    const StaticsProblem problem = parseStaticsJson(std::string(text), "fuzz");
    StaticsResult result;
    solveStatics(problem, result);
    checkStatics(problem, result, "auto");
    (void)staticsResultToJson(result);
    SocpWorkspace workspace;
    solveStaticsSocp(problem, result, workspace);
    checkStatics(problem, result, "socp");
    solveStaticsNewton(problem, result);
    checkStatics(problem, result, "newton");
    return Outcome::Accepted;
  } catch (const InputError&) {
    return Outcome::Refused;
  } catch (const SimulationError&) {
    return Outcome::Stopped;
  }
}

/// Wrap JSON text -> parse (as `cablelab wrap`) -> wrapChain -> JSON out.
inline Outcome runWrapInput(std::string_view text) {
  try {
    const WrapProblem problem = parseWrapText(std::string(text), "fuzz");
    const WrapSolution s = solveWrap(problem, "fuzz");
    requireFinite(s.length, "wrap length");
    for (const Vec2& p : s.path) requireFinite(p, "wrap path point");
    if (s.contacts.size() + 2 != s.path.size())
      throw HarnessFailure("wrap: contacts and path disagree");
    for (int v : s.contacts)
      if (v < 0 || v >= static_cast<int>(problem.polygon.size()))
        throw HarnessFailure("wrap: contact index out of range");
    (void)wrapSolutionToJson(s).dump();
    return Outcome::Accepted;
  } catch (const InputError&) {
    return Outcome::Refused;
  } catch (const SimulationError&) {
    return Outcome::Stopped;
  }
}

}  // namespace cablelab::fuzz

// cablelab reach: figure 4-4, the box positions the Jacobian controller reaches versus the range
// of the fingertips themselves.
#include <nlohmann/json.hpp>
#include <thread>

#include "app/command.h"
#include "app/options.h"
#include "engine/error.h"
#include "engine/hand_reach.h"

namespace cablelab::app {
namespace {

const bool registered = registerCommand("reach", "Box positions the hand's controller reaches vs the fingertips' range (fig. 4-4)", [](CLI::App& sub) {
  struct Options {
    int grid = 50;
    std::string png;
  };
  auto o = std::make_shared<Options>();
  sub.add_option("--grid", o->grid, "N: try an N x N grid of targets")->capture_default_str();
  sub.add_option("--png", o->png, "Draw both sets to this PNG file");
  return [o] {
    if (o->grid < 1 || o->grid > 1000) throw InputError("--grid", "--grid", "must be an integer in [1, 1000]");
    if (!o->png.empty()) throw InputError("--png", "--png", "this build has no offscreen renderer");
    ReachOptions options;
    options.grid = o->grid;
    options.threads = static_cast<int>(std::max(1u, std::min(2u, std::thread::hardware_concurrency())));
    Progress progress("reach", static_cast<long>(o->grid) * o->grid);
    const ReachResult r = runReach(options, HandModel{}, [&](long done, long) { progress.update(done); });
    progress.done();
    const double ratio = r.fingertipArea > 0 ? r.objectArea / r.fingertipArea : 0.0;
    printJson(nlohmann::json{{"object_area", r.objectArea}, {"fingertip_area", r.fingertipArea}, {"ratio", ratio},
                             {"points", r.points}, {"object_points", r.objectPoints.size()},
                             {"fingertip_points", r.fingertipPoints.size()}, {"seconds", r.seconds}}
                  .dump());
    return 0;
  };
});

}  // namespace
}  // namespace cablelab::app

#include "engine/statics/statics_random.h"

#include <cmath>

namespace cablelab {

StaticsProblem randomStaticsProblem(std::mt19937_64& rng, const RandomStaticsOptions& options) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto uniform = [&](double lo, double hi) { return lo + (hi - lo) * unit(rng); };
  const auto point = [&] { return Vec2(uniform(-1, 1), uniform(-1, 1)); };
  const auto stiffness = [&] { return 0.2 * std::pow(25.0, unit(rng)); };
  StaticsProblem problem;
  problem.cables.resize(options.cables);
  for (StaticsCable& c : problem.cables) {
    c.a = point();
    c.b = point();
    c.k = stiffness();
    const double span = (c.a - c.b).norm();
    c.L = unit(rng) < options.looseFraction ? span + uniform(0.2, 1.5) : span * uniform(0.0, 0.9);
  }
  if (options.onFingertip && options.cables >= 2) {
    // The other cables pull on c = a_0 with force -g; cable 0's b-side leans against it at an
    // angle theta with tension T >= |g| / (2 cos theta), so |g + T u| <= T holds strictly.
    const Vec2 c = problem.cables[0].a;
    StaticsProblem others;
    others.cables.assign(problem.cables.begin() + 1, problem.cables.end());
    Vec2 g = staticsKink(others, c).smoothGradient;
    // With no pull at c the kink is not strict (p could slide along cable 0): tighten cable 1.
    if (g.norm() == 0) {
      StaticsCable& pull = others.cables[0];
      pull.L = 0.5 * ((c - pull.a).norm() + (c - pull.b).norm());
      problem.cables[1] = pull;
      g = staticsKink(others, c).smoothGradient;
    }
    const double gnorm = g.norm();
    const double theta = uniform(-0.6, 0.6);
    const Vec2 toward = gnorm > 0 ? Vec2(g / gnorm) : Vec2(std::cos(theta), std::sin(theta));
    const double tension =
        gnorm > 0 ? uniform(1.3, 4.0) * gnorm / (2 * std::cos(theta)) : uniform(0.5, 2.0);
    StaticsCable& pin = problem.cables[0];
    pin.k = stiffness();
    pin.L = uniform(0.0, 1.0);
    pin.b = c + (pin.L + tension / pin.k) * rotate(toward, theta);
  }
  return problem;
}

}  // namespace cablelab

// A servo's stall is said only for a joint that stays (nearly) still at max_force (StallWatch,
// docs/servos.md "Stalls"). The rule once looked at one step: a joint at max_force that was not
// moving or speeding up the way it pushed in that step was "stalled", so a slide whose weight the
// rope caught (pulled back at 0.9 m/s) and a drum whirling its weight round (turned back for a
// step) were said stalled while they moved.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/dynamics/stall_watch.h"
#include "engine/dynamics/world.h"
#include "engine/model/scene_json.h"

namespace cablelab {
namespace stall_watch_test {

using nlohmann::json;
constexpr double kG = 9.81;

// Feeds a watch the coordinate q(t) at max_force 1 for `seconds` at `hz`; the stalls it finds.
template <typename Coordinate, typename Rate>
int stallsFound(double hz, double seconds, Coordinate q, Rate rate, double force = 1) {
  StallWatch watch;
  int found = 0;
  const int steps = static_cast<int>(std::lround(seconds * hz));
  for (int i = 1; i <= steps; ++i) {
    const double t = i / hz;
    found += watch.update(force, 1, q(t), rate(t), t, 1 / hz);
  }
  return found;
}

TEST(StallWatch, AJointStillAtMaxForceStallsOnceWithinItsWindow) {
  for (const double hz : {30.0, 60.0, 240.0}) {
    StallWatch watch;
    double saidAt = -1;
    for (int i = 1; i <= static_cast<int>(2 * hz); ++i) {
      const double t = i / hz;
      if (watch.update(-1, 1, 0.3, 0, t, 1 / hz)) {
        EXPECT_LT(saidAt, 0) << "said twice at " << hz << " Hz";
        saidAt = t;
        EXPECT_NEAR(watch.start, 0, 1e-12);  // still from the first step's start
      }
    }
    EXPECT_NEAR(saidAt, StallWatch::kWindow, 1 / hz + 1e-9) << hz << " Hz";
  }
}

TEST(StallWatch, AJointTurningRoundOrPulledBackAtMaxForceIsNoStall) {
  // Braked to a stop and turned back at max_force (a at 1 to 100 rad/s^2 about a turning point
  // anywhere within a step), pulled back at 0.05 to 0.9 rad/s, or creeping on at 5e-3 rad/s: all
  // move. The one-step rule said each turning point, and every step of a pull.
  for (const double hz : {30.0, 60.0, 240.0})
    for (const double phase : {0.0, 0.3, 0.5, 0.9}) {
      for (const double a : {1.0, 10.0, 100.0}) {
        const double turn = 1 + phase / hz;
        EXPECT_EQ(stallsFound(
                      hz, 2, [&](double t) { return -0.5 * a * (t - turn) * (t - turn); },
                      [&](double t) { return -a * (t - turn); }),
                  0)
            << "a " << a << " at " << hz << " Hz, phase " << phase;
      }
      for (const double v : {-0.05, -0.9, 5e-3})
        EXPECT_EQ(stallsFound(
                      hz, 2, [&](double t) { return v * (t + phase); }, [&](double) { return v; }),
                  0)
            << "v " << v << " at " << hz << " Hz";
    }
}

TEST(StallWatch, AStallEndsWhenTheServoLetsUpOrTheJointMovesOffAndIsSaidAnew) {
  const double hz = 60;
  // Still at max_force, then at 85% of it for a second, then at max_force again: two stalls.
  EXPECT_EQ(stallsFound(
                hz, 3, [](double) { return 0.0; }, [](double) { return 0.0; }, 1),
            1);
  StallWatch watch;
  int found = 0;
  for (int i = 1; i <= 3 * hz; ++i) {
    const double t = i / hz;
    const double force = t > 1 && t < 2 ? 0.85 : 1;
    // The joint jumps 2 cm at 2.5 s (a knock), and stays there.
    const double q = t > 2.5 ? 0.02 : 0;
    found += watch.update(force, 1, q, 0, t, 1 / hz);
  }
  EXPECT_EQ(found, 3);
  // A jiggle within kLeaveRange keeps the stall: said once.
  EXPECT_EQ(stallsFound(
                hz, 3, [](double t) { return 4e-3 * std::sin(20 * t) * (t > 0.5); },
                [](double) { return 0.0; }),
            1);
}

// One run's record: per step, the time, the joint's coordinate and force; the stalls said.
struct Record {
  std::vector<double> t, q, f;
  struct Said {
    double at, from;
  };
  std::vector<Said> said;
};

Record run(const SceneDef& scene, double seconds) {
  World w(scene, "stall");
  Record r;
  size_t seen = 0;
  while (w.time() < seconds - 1e-9) {
    w.step(scene.dt, scene.substeps);
    r.t.push_back(w.time());
    r.q.push_back(w.joint(0).value);
    r.f.push_back(w.joint(0).force);
    for (; seen < w.warnings().size(); ++seen) {
      const std::string& s = w.warnings()[seen];
      if (const size_t at = s.find("stalled from t = "); at != std::string::npos)
        r.said.push_back({w.time(), std::stod(s.substr(at + 17))});
    }
  }
  return r;
}

size_t stepEndingAt(const Record& r, double time) {
  const auto it = std::lower_bound(r.t.begin(), r.t.end(), time - 1e-9);
  return std::min<size_t>(it - r.t.begin(), r.t.size() - 1);
}

// The sweep's two counts (docs/servos.md, "Stalls"): stalls said while the joint moved more than
// kStillRange over the window named (or named over less than 0.1 s), and true stalls (still, at
// max_force, one way, for 0.5 s) with no stall standing.
struct Judged {
  int falseStalls = 0, missedStalls = 0, trueStalls = 0;
  bool movedAtMax = false;  // at max_force while the joint moved (the case the old rule missaid)
};

Judged judge(const Record& r, double maxForce, double dt) {
  Judged j;
  for (const Record::Said& s : r.said) {
    const size_t a = s.from < r.t[0] - 1e-9 ? 0 : stepEndingAt(r, s.from),
                 b = stepEndingAt(r, s.at);
    const auto [lo, hi] = std::minmax_element(r.q.begin() + a, r.q.begin() + b + 1);
    // A window shorter than kWindow has not shown the joint still (one step at a turning point).
    j.falseStalls += *hi - *lo > StallWatch::kStillRange || s.at - s.from < 0.1 - 1e-9;
  }
  const size_t window = static_cast<size_t>(std::lround(0.5 / dt)), n = r.t.size();
  auto atMax = [&](size_t i) { return std::abs(r.f[i]) >= (1 - 1e-9) * maxForce; };
  for (size_t i = 1; i < n; ++i)
    j.movedAtMax |= atMax(i) && std::abs(r.q[i] - r.q[i - 1]) > StallWatch::kStillRange;
  for (size_t i = 0; i + window < n; ++i) {
    const size_t e = i + window;
    bool still = true;
    for (size_t k = i; k <= e && still; ++k) still = atMax(k) && r.f[k] * r.f[i] > 0;
    const auto [lo, hi] = std::minmax_element(r.q.begin() + i, r.q.begin() + e + 1);
    if (!still || *hi - *lo >= StallWatch::kStillRange) continue;
    ++j.trueStalls;
    // The last stall said by the window's end, its force kept at kRelease of max_force since.
    bool standing = false;
    for (const Record::Said& s : r.said) {
      if (s.at > r.t[e] + 1e-9) continue;
      standing = true;
      for (size_t k = stepEndingAt(r, s.at); k <= e; ++k)
        standing &= std::abs(r.f[k]) >= StallWatch::kRelease * maxForce;
    }
    if (!standing) ++j.missedStalls, i = e;
  }
  return j;
}

json box(double hx, double hy) {
  return {{"type", "box"}, {"half_size", {hx, hy}}};
}

json servo(double kp, double kd, double target, double maxForce, double speed = 0) {
  return {{"kp", kp}, {"kd", kd}, {"target", target}, {"max_force", maxForce}, {"speed", speed}};
}

// Case 1 of the issue: a slide (max_force 1.5 m g, kp 2e4) lifts `mass` through a rope over a
// point; the jerk throws the weight up, the rope catches it and the slide brakes it at max_force
// while its load pulls it back, then holds it with m g.
SceneDef slideScene(double mass, double kp, double maxForce, double hz, int substeps,
                    double thrown = 0) {
  const json scene = {
      {"name", "slide"},
      {"dt", 1 / hz},
      {"substeps", substeps},
      {"gravity", {0, -kG}},
      {"bodies",
       {{{"name", "car"}, {"position", {0, 0}}, {"mass", 1.0}, {"shapes", {box(0.1, 0.05)}}},
        {{"name", "wt"},
         {"position", {1.0, -1.0}},
         {"mass", mass},
         {"velocity", {0, thrown}},
         {"shapes", {box(0.05, 0.05)}}}}},
      {"joints",
       {{{"type", "prismatic"},
         {"name", "slide"},
         {"body_b", "car"},
         {"anchor", {0, 0}},
         {"axis", {-1, 0}},
         {"servo", servo(kp, 2 * std::sqrt(kp * (1 + mass)), 0.5, maxForce)}}}},
      {"cables",
       {{{"name", "rope"},
         {"start", {{"body", "car"}}},
         {"end", {{"body", "wt"}}},
         {"pulleys", {{{"type", "point"}, {"point", {1.0, 0.0}}, {"side", "threaded"}}}}}}}};
  return sceneFromJson(scene, "slide");
}

TEST(StallWatch, ASlideThatCatchesItsWeightAtMaxForceIsNoStall) {
  // The case (2 kg, 240 Hz: said stalled at 0.8375 and 1.52 s while pulled back at up to
  // 0.96 m/s) and its variants: 1 and 3 kg, a softer servo, 120 Hz, 4 sub-steps.
  struct Case {
    double mass, kp, hz;
    int substeps;
  };
  for (const Case& k : {Case{2, 2e4, 240, 1}, Case{1, 2e4, 240, 1}, Case{3, 2e4, 120, 1},
                        Case{2, 5e3, 240, 4}, Case{2, 2e4, 60, 4}}) {
    SCOPED_TRACE(std::to_string(k.mass) + " kg, kp " + std::to_string(k.kp) + ", " +
                 std::to_string(k.hz) + " Hz x " + std::to_string(k.substeps));
    const double maxForce = 1.5 * k.mass * kG;
    const SceneDef s = slideScene(k.mass, k.kp, maxForce, k.hz, k.substeps);
    const Record r = run(s, 3);
    const Judged j = judge(r, maxForce, s.dt);
    EXPECT_TRUE(j.movedAtMax);  // the catch did happen at max_force
    EXPECT_EQ(j.trueStalls, 0);
    EXPECT_TRUE(r.said.empty()) << "said stalled from t = " << r.said[0].from;
    EXPECT_NEAR(r.f.back(), k.mass * kG, 0.01 * k.mass * kG);  // then holds it, below max_force
  }
}

SceneDef solidDrumWinch(double hz, double speed, double maxForce, double weight) {
  const double r = 0.1;
  const json scene = {
      {"name", "winch"},
      {"dt", 1 / hz},
      {"gravity", {0, -kG}},
      {"bodies",
       {{{"name", "drum"},
         {"position", {0, 0}},
         {"mass", 0.05},
         {"shapes", {{{"type", "circle"}, {"radius", r}}}}},
        {{"name", "weight"},
         {"position", {speed > 0 ? r : -r, -0.6}},
         {"mass", weight},
         {"shapes", {box(0.04, 0.04)}}}}},
      {"joints",
       {{{"type", "revolute"},
         {"name", "winch_axle"},
         {"body_b", "drum"},
         {"anchor", {0, 0}},
         {"servo", servo(500, 3.24, 0, maxForce, speed)}}}},
      {"cables",
       {{{"name", "rope"},
         {"start",
          {{"body", "drum"}, {"radius", r}, {"side", speed > 0 ? "left" : "right"}, {"turns", 3}}},
         {"end", {{"body", "weight"}}}}}}};
  return sceneFromJson(scene, "winch");
}

TEST(StallWatch, ASolidDrumThatWhirlsItsWeightRoundIsNoStallAndSaysTheArrival) {
  // The case (240 Hz, 8 rad/s, max_force 5 N m, 0.5 kg: said stalled at 1.44 s while the
  // drum turned 28 rad in 6 s) and variants: 120 Hz, the other way, 2 rad/s, 1 kg.
  struct Case {
    double hz, speed, maxForce, weight;
  };
  for (const Case& k : {Case{240, 8, 5, 0.5}, Case{120, 8, 5, 0.5}, Case{240, -8, 5, 0.5},
                        Case{240, 2, 5, 0.5}, Case{240, 8, 5, 1.0}}) {
    SCOPED_TRACE(std::to_string(k.hz) + " Hz, " + std::to_string(k.speed) + " rad/s, " +
                 std::to_string(k.weight) + " kg");
    const SceneDef s = solidDrumWinch(k.hz, k.speed, k.maxForce, k.weight);
    World w(s, "winch");
    double turned = 0, last = w.joint(0).value;
    while (w.time() < 6) {
      w.step(s.dt);
      turned += std::abs(w.joint(0).value - last);
      last = w.joint(0).value;
    }
    EXPECT_GT(turned, 10);
    int arrivals = 0;
    for (const std::string& m : w.warnings()) {
      EXPECT_EQ(m.find("stalled"), std::string::npos) << m;
      arrivals += m.find("reached the drum 'drum'") != std::string::npos &&
                  m.find("touches it: the drum is solid") != std::string::npos;
    }
    EXPECT_EQ(arrivals, 1);
  }
}

// A rod of `mass` (1 m, pinned at its top end, hanging) whose servo asks for `target`; with
// `blockAt` > 0 a static block stops it at about that angle (rad).
SceneDef rodScene(double mass, double target, double maxForce, double kp, double hz, int substeps,
                  double blockAt, double damping) {
  json bodies = {{{"name", "rod"},
                  {"position", {0, -0.5}},
                  {"mass", mass},
                  {"angular_damping", damping},
                  {"shapes", {box(0.025, 0.5)}}}};
  if (blockAt > 0) {
    const double side = target > 0 ? 1 : -1, a = side * blockAt;
    // The block's near face 0.8 m down the rod, at angle a, just past the rod's edge.
    bodies.push_back({{"name", "block"},
                      {"type", "static"},
                      {"position",
                       {0.8 * std::sin(a) + 0.11 * side * std::cos(a),
                        -0.8 * std::cos(a) + 0.11 * side * std::sin(a)}},
                      {"angle", a},
                      {"shapes", {box(0.08, 0.08)}}});
  }
  const json scene = {{"name", "rod"},
                      {"dt", 1 / hz},
                      {"substeps", substeps},
                      {"gravity", {0, -kG}},
                      {"bodies", bodies},
                      {"joints",
                       {{{"type", "revolute"},
                         {"name", "pin"},
                         {"body_b", "rod"},
                         {"anchor", {0, 0}},
                         {"servo", servo(kp, 2 * std::sqrt(kp * mass / 3), target, maxForce)}}}}};
  return sceneFromJson(scene, "rod");
}

TEST(StallWatch, RandomServoScenesSayAStallOnlyWhereTheJointStaysStill) {
  // Rods pressed against blocks, rods too weak to lift themselves (damped: they settle at
  // max_force; undamped: they swing on at it), slides catching weights thrown up, at 30 to 240
  // Hz, 1 and 4 sub-steps, kp 20 to 1e5. Every stall said kept its joint within kStillRange over
  // the window it names, and every true stall (0.5 s still at max_force) is said. The one-step
  // rule said stalls while the joint moved in most of these.
  std::uint32_t seed = 12345;
  auto uniform = [&seed](double lo, double hi) {
    seed = seed * 1664525u + 1013904223u;
    return lo + (hi - lo) * (seed >> 8) / double(1u << 24);
  };
  const double rates[] = {30, 60, 120, 240};
  int stalled = 0, moving = 0;
  for (int i = 0; i < 36; ++i) {
    const double hz = rates[i % 4];
    const int substeps = (i / 4) % 2 ? 4 : 1;
    const double kp = std::pow(10, uniform(std::log10(20), 5));
    SceneDef s;
    double maxForce = 0;
    std::string what;
    if (i % 3 == 0) {
      const double mass = uniform(0.3, 4), target = (i % 2 ? 1 : -1) * uniform(1, 2.5);
      maxForce = uniform(1.2, 3) * mass * kG * 0.5;
      s = rodScene(mass, target, maxForce, kp, hz, substeps, uniform(0.3, 0.7), 0);
      what = "rod against a block";
    } else if (i % 3 == 1) {
      const double mass = uniform(0.3, 4);
      maxForce = uniform(0.3, 0.7) * mass * kG * 0.5;
      s = rodScene(mass, 1.5, maxForce, kp, hz, substeps, 0, i % 2 ? 3 : 0);
      what = "weak rod";
    } else {
      const double mass = uniform(0.5, 5);
      maxForce = uniform(1.2, 3) * mass * kG;
      s = slideScene(mass, kp, maxForce, hz, substeps, uniform(0, 6));
      what = "slide";
    }
    SCOPED_TRACE(what + " " + std::to_string(i) + ", kp " + std::to_string(kp) + " at " +
                 std::to_string(hz) + " Hz x " + std::to_string(substeps));
    const Record r = run(s, 4);
    const Judged j = judge(r, maxForce, s.dt);
    EXPECT_EQ(j.falseStalls, 0);
    EXPECT_EQ(j.missedStalls, 0);
    stalled += j.trueStalls > 0;
    moving += j.movedAtMax && j.trueStalls == 0;
  }
  // Both kinds are well represented.
  EXPECT_GE(stalled, 8);
  EXPECT_GE(moving, 8);
}

}  // namespace stall_watch_test
}  // namespace cablelab

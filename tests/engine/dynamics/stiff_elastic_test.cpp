// Stiff elastic cables through slack and taut (issue 36, item 3): a platform on four undamped
// 1e5 N/m cables, thrown off centre, never gains energy at any step; where the step resolves the
// cables' mode it keeps it (docs/cables.md, "Energy").
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "engine/dynamics/world.h"
#include "tests/support/scene_parts.h"

namespace cablelab {
namespace stiff_elastic_test {

struct Platform {
  double k = 1e5, mass = 4, inertia = 0.35;
  Vec2 velocity = Vec2(0.6, 1.5);
  double spin = 3;
  double stretch = 0;  // the cables' rest lengths shortened by this (m): a preload
};

// One cable from a fixed point above to a point on the platform, shortened by `stretch` (m): a
// preload, or slack where negative. Stiffness 0 is a rigid cable.
struct Tether {
  Vec2 top, end;
  double k, damping = 0, stretch = 0;
};

// A free platform: a sensor box of half size (hx, hy) about its centre, thrown from the origin.
SceneDef platformOn(double hx, double hy, double mass, double inertia, Vec2 velocity, double spin,
                    const std::vector<Tether>& tethers) {
  SceneDef s;
  s.name = "stiff_platform";
  BodyDef b;
  b.name = "platform";
  b.mass = mass;
  b.inertia = inertia;
  b.position = Vec2(0, 0);
  b.velocity = velocity;
  b.angularVelocity = spin;
  b.shapes = {test::sensorBox(hx, hy)};
  s.bodies = {b};
  for (const Tether& t : tethers) {
    CableDef cable;
    cable.name = "cable" + std::to_string(s.cables.size());
    cable.start = {"world", t.top};
    cable.end = {"platform", t.end};
    cable.restLength = (t.top - t.end).norm() - t.stretch;
    cable.stiffness = t.k;
    cable.damping = t.damping;
    s.cables.push_back(cable);
  }
  return s;
}

// The platform of tests/data/sensors/platform_rest.json with all four cables elastic and
// undamped: two from above its ends, two slanting inwards from higher up. It starts where the
// outer pair is just taut and is thrown up and sideways, spinning: the cables go slack and come
// taut again, one by one.
SceneDef platform(const Platform& p) {
  return platformOn(0.5, 0.05, p.mass, p.inertia, p.velocity, p.spin,
                    {{Vec2(-0.8, 1), Vec2(-0.5, 0.05), p.k, 0, p.stretch},
                     {Vec2(0.8, 1), Vec2(0.5, 0.05), p.k, 0, p.stretch},
                     {Vec2(-0.6, 1.2), Vec2(-0.25, 0.05), p.k, 0, p.stretch},
                     {Vec2(0.6, 1.2), Vec2(0.25, 0.05), p.k, 0, p.stretch}});
}

// Over a run: the largest rise of the energy above its lowest value so far (a damped step may
// lose, no step may give back), the largest |E - E0|, both over the energy scale (the largest
// kinetic energy of the run), and the largest loss in one step; and the highest the energy went
// above E0 over the kinetic energy thrown in at the start (a run whose energy blows up has a
// scale that blows up with it).
struct EnergyRecord {
  double rise = 0, drift = 0, stepLoss = 0, peak = 0;
};

EnergyRecord run(const SceneDef& scene, double dt, int substeps, double seconds) {
  World world(scene);
  const double e0 = world.energy(), thrown = kineticEnergy(world.body(0));
  double lowest = e0, rise = 0, drift = 0, loss = 0, scale = 0, highest = e0;
  for (int step = 0; step < std::lround(seconds / dt); ++step) {
    const double before = world.energy();
    world.step(dt, substeps);
    const double e = world.energy();
    rise = std::max(rise, e - lowest);
    lowest = std::min(lowest, e);
    highest = std::max(highest, e);
    drift = std::max(drift, std::abs(e - e0));
    loss = std::max(loss, before - e);
    scale = std::max(scale, kineticEnergy(world.body(0)));
  }
  return {rise / scale, drift / scale, loss / scale, (highest - e0) / thrown};
}

// One cable's axial mode bound, as the midpoint solve takes it (midpoint_solver.cpp,
// elasticMode): sqrt(k (1 / m + r^2 / I)) with its arm r <= 0.51 m. Four cables taut together
// reach about twice this.
double cableOmega(const Platform& p) {
  return std::sqrt(p.k * (1 / p.mass + 0.51 * 0.51 / p.inertia));
}

// Runs `p` at 30 to 480 Hz and 1 to 8 sub-steps for `seconds`. No step gains: the energy never
// rises above its lowest value so far by more than `riseBound` of the energy scale. Where the
// step resolves the cables' mode (omega h <= 4, omega one cable's bound above) the energy is
// kept to 1e-3.
void expectNoGain(const Platform& p, double seconds, double riseBound) {
  for (const double rate : {30.0, 60.0, 120.0, 240.0, 480.0})
    for (const int substeps : {1, 2, 4, 8}) {
      const double omegaH = cableOmega(p) / rate / substeps;
      const EnergyRecord r = run(platform(p), 1 / rate, substeps, seconds);
      SCOPED_TRACE(testing::Message() << "k " << p.k << " m " << p.mass << " at " << rate
                                      << " Hz x " << substeps << ", omega h " << omegaH);
      EXPECT_LT(r.rise, riseBound);
      EXPECT_LT(r.peak, riseBound);
      if (omegaH <= 4) {
        EXPECT_LT(r.drift, 1e-3);
      }
      std::printf(
          "k %g m %g v (%g, %g) spin %g at %3.0f Hz x %d (omega h %5.2f): rise %.2g, "
          "drift %.2g, largest loss in a step %.2g, peak %.2g\n",
          p.k, p.mass, p.velocity.x(), p.velocity.y(), p.spin, rate, substeps, omegaH, r.rise,
          r.drift, r.stepLoss, r.peak);
    }
}

// The row: 4 kg on four 1e5 N/m cables, thrown up, sideways and spinning. The four
// cables pull on three freedoms; the midpoint solve's check for redundant rows counted the
// elastic ones too, and a cable coming taut (its compliance near infinite) made the others look
// dependent: the step went to the main solve, whose backward-Euler spring took up to 95% of the
// energy scale in one step at 30 Hz x 4 (78% at 60 Hz x 2, 57% at 120 Hz x 1; omega h 2.6 for
// one cable, which the midpoint solve resolves).
// At 60 Hz x 1 (omega h 5.3) the midpoint solve damps the cables' mode (its spring taken at the
// end of the step) and keeps the rest: the energy never rises above its lowest value by more
// than 1e-6 of the scale over 20 s (0.16% there, up to 0.3% at 30 Hz, when the main solve took
// those steps; the issue's
// +21% at 240 Hz did not show on this platform nor on the ones below).
TEST(StiffElastic, APlatformThrownOnFourStiffCablesNeverGainsEnergy) {
  expectNoGain(Platform{}, 20, 0.01);
}

// Other masses, stiffnesses and throws (each slack and taut in turn): a spin alone, a sideways
// swing on preloaded cables, a throw downwards into them. Where the step does not resolve the
// mode (omega h > 4) the main solve's damped spring left Box2D's symplectic Euler on the slow
// swing, whose measured energy swings by omega h / 2 of it: the sideways swing rose 1.1% (60 Hz
// x 1) and 1.6% (30 Hz x 1) above its lowest value on its way down. The midpoint solve with the
// spring at the end of the step keeps the swing: at most 3e-7 (docs/cables.md, "Energy").
TEST(StiffElastic, OtherMassesStiffnessesAndThrowsNeverGainEnergy) {
  const auto make = [](double k, double mass, Vec2 v, double spin, double stretch) {
    Platform p;
    p.k = k;
    p.mass = mass;
    p.inertia = 0.0875 * mass;
    p.velocity = v;
    p.spin = spin;
    p.stretch = stretch;
    return p;
  };
  const Platform variants[] = {
      make(1e5, 0.5, Vec2(0.6, 1.5), 3, 0), make(1e5, 40, Vec2(0.6, 1.5), 3, 0),
      make(1e4, 4, Vec2(0.6, 1.5), 3, 0),   make(1e6, 4, Vec2(0.6, 1.5), 3, 0),
      make(1e5, 4, Vec2::Zero(), 8, 0),     make(1e5, 4, Vec2(1, 0), 0, 0.002),
      make(1e5, 4, Vec2(0, -3), 5, 0)};
  for (const Platform& p : variants) expectNoGain(p, 10, 0.01);
}

// Platforms of other shapes, 0.1 to 20 kg, on two to four cables of 1e4 to 1e6 N/m (damped or
// not, some beside rigid ones, some slack or preloaded), thrown off centre with spin, at 60 and
// 240 Hz, 1 and 4 sub-steps: the "+21% in 20 s at 240 Hz" searched for. No step gains
// more than 1% of the energy scale (measured at most 3e-5). With the main solve taking the
// unresolved springs, at 60 Hz x 1: 2.2% (the tall block), 1.3% (the slack cables), 1.2% (the light
// plank, whose energy also fell by 810 times its largest kinetic energy in one step).
TEST(StiffElastic, PlatformsOfOtherShapesThrownWithSpinNeverGainEnergy) {
  struct Throw {
    const char* name;
    double hx, hy, mass, inertia;
    Vec2 velocity;
    double spin;
    std::vector<Tether> tethers;
  };
  const Throw throws[] = {{"a light plank on three damped cables, thrown down",
                           0.84,
                           0.12,
                           0.164,
                           0.0273,
                           Vec2(-0.2, -2.5),
                           -8.7,
                           {{Vec2(-1, 1), Vec2(-0.8, 0.12), 6.7e4, 10.7},
                            {Vec2(0.9, 1.3), Vec2(0.7, 0.12), 6.7e4, 10.7},
                            {Vec2(0.1, 1.5), Vec2(0, 0.12), 6.7e4, 10.7}}},
                          {"a thin plank on a rigid and two preloaded cables",
                           0.72,
                           0.05,
                           0.113,
                           0.0102,
                           Vec2(-1.1, -2.8),
                           -2.9,
                           {{Vec2(-0.7, 1.2), Vec2(-0.7, 0.05), 0},
                            {Vec2(0.8, 0.9), Vec2(0.6, 0.05), 1.15e5, 0, 8e-4},
                            {Vec2(-0.2, 1.4), Vec2(0.2, 0.05), 1.15e5, 0, 8e-4}}},
                          {"a tall block on three 1e6 N/m cables, thrown up",
                           1.0,
                           0.28,
                           0.197,
                           0.0325,
                           Vec2(-1.5, 2.8),
                           0.74,
                           {{Vec2(-1.1, 1.2), Vec2(-1, 0.28), 1e6},
                            {Vec2(1.2, 1.0), Vec2(1, 0.28), 1e6},
                            {Vec2(0.3, 1.6), Vec2(-0.4, 0.28), 1e6}}},
                          {"a small block on two rigid and one damped cable, spinning",
                           0.26,
                           0.09,
                           0.664,
                           0.0145,
                           Vec2(0.8, 1.9),
                           9.6,
                           {{Vec2(-0.5, 1.0), Vec2(-0.26, 0.09), 0},
                            {Vec2(0.4, 1.1), Vec2(0.26, 0.09), 0},
                            {Vec2(0, 1.5), Vec2(0, 0.09), 5.8e5, 3.9}}},
                          {"a plank on two slack cables, spun",
                           0.59,
                           0.04,
                           0.661,
                           0.0411,
                           Vec2(-0.2, -0.2),
                           -9.9,
                           {{Vec2(-0.9, 0.8), Vec2(-0.5, 0.04), 2.7e5, 0, -0.025},
                            {Vec2(0.7, 1.1), Vec2(0.5, 0.04), 2.7e5, 0, -0.025}}},
                          {"20 kg on four crossed 1e4 N/m cables",
                           0.6,
                           0.2,
                           20,
                           2.6,
                           Vec2(1.5, 1),
                           6,
                           {{Vec2(-1, 1.2), Vec2(0.6, 0.2), 1e4},
                            {Vec2(1, 1.2), Vec2(-0.6, 0.2), 1e4},
                            {Vec2(-0.4, 1.5), Vec2(-0.3, 0.2), 1e4},
                            {Vec2(0.4, 1.5), Vec2(0.3, 0.2), 1e4}}}};
  for (const Throw& t : throws)
    for (const double rate : {60.0, 240.0})
      for (const int substeps : {1, 4}) {
        const EnergyRecord r =
            run(platformOn(t.hx, t.hy, t.mass, t.inertia, t.velocity, t.spin, t.tethers), 1 / rate,
                substeps, 20);
        SCOPED_TRACE(testing::Message() << t.name << " at " << rate << " Hz x " << substeps);
        EXPECT_LT(r.rise, 0.01);
        EXPECT_LT(r.peak, 0.01);
        std::printf(
            "%s at %3.0f Hz x %d: rise %.2g, drift %.2g, largest loss in a step %.2g, peak %.2g\n",
            t.name, rate, substeps, r.rise, r.drift, r.stepLoss, r.peak);
      }
}

// A jointed body keeps its island in the main solve (docs/cables.md, "Energy"): an arm pivoted at
// one end, held up by two stiff undamped cables and thrown round, 0.2 and 20 kg, 1e5 and 1e6 N/m,
// at 30, 60 and 240 Hz. Its backward-Euler spring damps the cables' mode (the light arm to rest);
// no step gains more than 1% of the energy scale (measured at most 1.3e-5, 20 kg at 60 Hz).
TEST(StiffElastic, AnArmPivotedOnStiffCablesNeverGainsEnergy) {
  for (const double k : {1e5, 1e6})
    for (const double mass : {0.2, 20.0})
      for (const double rate : {30.0, 60.0, 240.0}) {
        SceneDef s =
            platformOn(0.5, 0.03, mass, mass / 3, Vec2(0, 1.5), 3,
                       {{Vec2(0.5, 1), Vec2(0.5, 0), k}, {Vec2(0.2, 1.2), Vec2(0.2, 0), k}});
        s.joints = {test::worldPivot("platform", Vec2(-0.5, 0))};
        const EnergyRecord r = run(s, 1 / rate, 1, 20);
        SCOPED_TRACE(testing::Message() << "k " << k << " m " << mass << " at " << rate << " Hz");
        EXPECT_LT(r.rise, 0.01);
        EXPECT_LT(r.peak, 0.01);
        std::printf("arm k %g m %g at %3.0f Hz: rise %.2g, drift %.2g, peak %.2g\n", k, mass, rate,
                    r.rise, r.drift, r.peak);
      }
}

}  // namespace stiff_elastic_test
}  // namespace cablelab

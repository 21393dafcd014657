// MuJoCo 2.2.2 stepping a cablelab scene: the reference engine for speed and scale
// (tests/bench/mujoco_bench.cpp, `cablelab bench`). Only the benchmark and the app link it.
//
// The mapping (docs/model.md): the plane (x, y) is MuJoCo's (x, z), gravity along -z. A dynamic
// body is a MuJoCo body with two slide joints and a hinge about -y (so a positive angle turns x
// towards z, as in the plane), its mass and inertia explicit. Circles are spheres, polygons boxes
// of their bounding rectangle. A rigid cable over point pulleys is a spatial tendon through
// sites (world sites for world pulleys) with range [0, rest length]: it may go slack, never
// longer. MuJoCo's limit is soft (default solref/solimp), so its cable sits a little long.
// Scenes with joints, kinematic bodies, polygon pulleys or elastic cables are refused.
#pragma once

#include <memory>
#include <string>

#include "engine/model/scene.h"

namespace cablelab {

/// The MJCF model of `scene`; throws InputError (source "mujoco") for what it cannot map.
std::string sceneToMjcf(const SceneDef& scene);

class MujocoWorld {
 public:
  /// Compiles sceneToMjcf(scene); throws InputError if MuJoCo refuses it.
  explicit MujocoWorld(const SceneDef& scene);
  ~MujocoWorld();
  MujocoWorld(const MujocoWorld&) = delete;
  MujocoWorld& operator=(const MujocoWorld&) = delete;

  /// One mj_step of the scene's dt.
  void step();
  double time() const;
  /// Body i of the scene (only dynamic bodies are MuJoCo bodies): plane position (m).
  Vec2 bodyPosition(int i) const;
  /// Cable i's tendon length (m).
  double cableLength(int i) const;
  int dofs() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cablelab

// Each body's cos and sin, worked out once: a cable's points sit on few bodies (a polygon's
// vertices, both ends on one paddle), so the path and the event tests turn many points with the
// same rotation. A few slots, recycled when a path visits more bodies.
#pragma once

#include <cmath>
#include <span>

#include "engine/cable/cable.h"

namespace cablelab {

class BodyFrames {
 public:
  struct Rotation {
    int body;
    double c, s;
  };

  explicit BodyFrames(std::span<const BodyState> bodies) : bodies_(bodies) {}

  /// The body's rotation (body >= 0).
  const Rotation& rotation(int body) {
    for (int i = 0; i < count_; ++i)
      if (cache_[i].body == body) return cache_[i];
    if (count_ == kSize) count_ = 0;  // many bodies: recycle the slots
    cache_[count_].body = body;
    cosSin(bodies_[body].angle, cache_[count_].c, cache_[count_].s);
    return cache_[count_++];
  }
  /// A body point in the world (the world, body -1, is the identity).
  Vec2 worldPoint(int body, const Vec2& local) {
    if (body < 0) return local;
    const Rotation& r = rotation(body);
    return bodies_[body].position + rotate(local, r.c, r.s);
  }
  /// A world point in the body's frame (body >= 0).
  Vec2 localPoint(int body, const Vec2& world) {
    const Rotation& r = rotation(body);
    return rotate(Vec2(world - bodies_[body].position), r.c, -r.s);
  }

 private:
  static constexpr int kSize = 4;
  std::span<const BodyState> bodies_;
  Rotation cache_[kSize];
  int count_ = 0;
};

}  // namespace cablelab

// Offscreen snapshots: a World drawn by the renderer into a PNG, with no display (OSMesa).
//
// Needs: the cablelab_offscreen library (renderer + OSMesa + libpng; never libGL). The pixels
// depend only on the world state, size and overlay: the same scene at the same time gives the
// same image. Used by `cablelab snapshot`, `cablelab run --png` and the golden-image tests.
#pragma once

#include <string>

#include "engine/dynamics/world.h"
#include "ui/camera.h"
#include "ui/image.h"
#include "ui/overlay.h"
#include "ui/renderer.h"

namespace cablelab::ui {

/// Renders `world` at width x height with the scene's default view (scene().view); with no
/// tension scale in `options`, the scene's fixed one from its loads, as the sandbox's window
/// shows it (ui/tension_scale.h, loadTensionScale).
/// Throws std::runtime_error with a clear message on failure (bad size, no OSMesa).
Image renderSnapshot(const World& world, int width, int height, const Overlay& overlay = {},
                     const RenderOptions& options = {});

/// Renders `world` seen by `camera` (its width x height), on the same tension scale.
Image renderSnapshot(const World& world, const Camera& camera, const Overlay& overlay = {},
                     const RenderOptions& options = {});

/// Renders `world` (see renderSnapshot) and writes it to `path` as PNG.
/// Throws std::runtime_error naming the path on failure.
void writeSnapshotPng(const World& world, const std::string& path, int width, int height,
                      const Overlay& overlay = {});

}  // namespace cablelab::ui

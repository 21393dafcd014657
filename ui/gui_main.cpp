// cablelab-gui: the interactive sandbox (SDL2 window + Dear ImGui + the shared renderer).
// `cablelab gui` execs this program; it links libGL and never libOSMesa (see README.md).
//
//   cablelab-gui [SCENE] [--frames N] [--screenshot F.png] [--size WxH] [--open F]
//                [--test-input]
#include <CLI/CLI.hpp>
#include <GL/gl.h>
#include <imgui.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/file_input.h"
#include "engine/core/parse.h"
#include "ui/image.h"
#include "ui/input.h"
#include "ui/input_script.h"
#include "ui/panels.h"
#include "ui/renderer.h"
#include "ui/sandbox.h"
#include "ui/scene_catalog.h"
#include "ui/window.h"

namespace {

struct Options {
  std::string scene;
  int frames = 0;
  std::string screenshot;
  int width = 1280, height = 720;
  std::string openLater;
  bool testInput = false;
};

/// The options, or nullopt after --help. Bad values are InputError ("command line: --size: ...").
std::optional<Options> parse(int argc, char** argv) {
  Options o;
  std::string frames, size;
  CLI::App cli{"cablelab-gui: the interactive sandbox (SDL2 + Dear ImGui)", "cablelab-gui"};
  cli.add_option("scene", o.scene, "built-in scene name or scene JSON file (default: hand)");
  cli.add_option("--frames", frames,
                 "quit after N frames (one scene time step per frame) and print "
                 "{\"frames\": N, \"fps\": f} (fps from the median frame time)");
  cli.add_option("--screenshot", o.screenshot, "save the last frame as PNG");
  cli.add_option("--size", size, "window size WxH (default 1280x720)");
  cli.add_option("--open", o.openLater,
                 "after 10 frames, open F as if chosen in the Scene menu (for tests)");
  cli.add_flag("--test-input", o.testInput,
               "drive the mouse and keys with synthetic SDL events, check the result (with "
               "--screenshot: the script's last frame)");
  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    cli.exit(e);
    return std::nullopt;
  } catch (const CLI::ParseError& e) {
    throw cablelab::commandLineError(e.what(), "see cablelab-gui --help");
  }
  if (!frames.empty())
    o.frames = static_cast<int>(cablelab::parseWholeNumber(frames, cablelab::kCommandLine,
                                                           "--frames", 0, 100000000));
  if (!size.empty()) {
    const auto s = cablelab::parsePixelSize(size, cablelab::kCommandLine, "--size", 240, 16384);
    o.width = s.width;
    o.height = s.height;
  }
  if (!o.screenshot.empty()) cablelab::requireWritable(o.screenshot, "--screenshot");
  return o;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

int run(const Options& options) {
  using namespace cablelab::ui;
  using Clock = std::chrono::steady_clock;
  const bool scripted = options.frames > 0 || options.testInput;
  Window window("cablelab sandbox", options.width, options.height, !scripted);
  Sandbox sandbox(window.width(), window.height());
  PanelState panelState;

  const std::string first = options.scene.empty() ? defaultSceneName() : options.scene;
  if (!sandbox.open(first)) {
    const std::string error = sandbox.error;  // keep the message visible over the fallback
    if (first != defaultSceneName()) sandbox.open(defaultSceneName());
    sandbox.error = error;
  }

  std::optional<InputScript> script;
  if (options.testInput) script.emplace(window.id());
  std::vector<double> frameSeconds;
  Image capture;
  auto last = Clock::now();
  for (int frame = 0;; ++frame) {
    if (options.frames > 0 && frame >= options.frames) break;
    if (script && !script->beforeFrame(sandbox, frame)) break;
    if (!window.pollEvents([&](const SDL_Event& e) { handleEvent(sandbox, e); })) break;
    if (!options.openLater.empty() && frame == 10) sandbox.open(options.openLater);
    sandbox.advance(sandbox.lastFrameSeconds, scripted);

    window.beginFrame();
    drawPanels(sandbox, panelState);
    if (const cablelab::World* world = sandbox.world()) {
      drawWorld(*world, sandbox.camera, sandbox.overlay(), sandbox.renderOptions(),
                ImGui::GetBackgroundDrawList());
    } else {
      glClearColor(0.97f, 0.97f, 0.95f, 1);
      glClear(GL_COLOR_BUFFER_BIT);
    }
    // The script ends at an unknown frame: capture every one of its frames.
    const bool lastFrame = (options.frames > 0 && frame + 1 == options.frames) || script;
    window.endFrame(lastFrame && !options.screenshot.empty() ? &capture : nullptr);

    const auto now = Clock::now();
    sandbox.lastFrameSeconds = std::chrono::duration<double>(now - last).count();
    last = now;
    if (frame > 0) frameSeconds.push_back(sandbox.lastFrameSeconds);  // the first is a warm-up
    if (!frameSeconds.empty()) {  // the status line shows the median of the last 60 frames
      const size_t n = std::min<size_t>(frameSeconds.size(), 60);
      const double m = median({frameSeconds.end() - n, frameSeconds.end()});
      sandbox.fps = m > 0 ? 1 / m : 0;
    }
  }

  if (!options.screenshot.empty() && !capture.rgba.empty()) writePng(capture, options.screenshot);
  if (script) {
    std::cout << script->report() << std::endl;
    return script->passed() ? 0 : 1;
  }
  if (options.frames > 0) {
    const double m = median(frameSeconds);
    std::printf("{\"frames\": %d, \"fps\": %.17g}\n", options.frames, m > 0 ? 1 / m : 0.0);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const auto options = parse(argc, argv);
    if (!options) return 0;
    return run(*options);
  } catch (const cablelab::InputError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "cablelab-gui: " << e.what() << "\n";
    return 2;
  }
}

// cablelab-gui: the interactive sandbox (SDL2 window + Dear ImGui + the shared renderer).
// `cablelab gui` execs this program; it links libGL and never libOSMesa (see README.md).
//
//   cablelab-gui [SCENE] [--set NAME=VALUE]... [--frames N] [--screenshot F.png] [--size WxH]
//                [--open F] [--record F.gif] [--ui-scale S] [--script NAME] [--test-input]
// (every option: ui/gui_options.h, shared with `cablelab gui`)
#include <GL/gl.h>
#include <imgui.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "engine/core/error.h"
#include "engine/core/file_input.h"
#include "engine/core/parse.h"
#include "ui/gui_options.h"
#include "ui/image.h"
#include "ui/input.h"
#include "ui/input_script.h"
#include "ui/panels.h"
#include "ui/presentation.h"
#include "ui/recorder.h"
#include "ui/renderer.h"
#include "ui/sandbox.h"
#include "ui/scenario_script.h"
#include "ui/scene_catalog.h"
#include "ui/window.h"

namespace {

/// The checked options, or nullopt after --help. Bad values are InputError
/// ("command line: --size: ..."); an unattended run's bad scene too (ui/gui_options.h).
std::optional<cablelab::ui::GuiOptions> parse(int argc, char** argv) {
  cablelab::ui::GuiArguments args;
  CLI::App cli{"cablelab-gui: the interactive sandbox (SDL2 + Dear ImGui)", "cablelab-gui"};
  cablelab::ui::addGuiOptions(cli, args);
  try {
    cli.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    cli.exit(e);
    return std::nullopt;
  } catch (const CLI::ParseError& e) {
    throw cablelab::commandLineError(e.what(), "see cablelab-gui --help");
  }
  return cablelab::ui::checkGuiArguments(args, cablelab::ui::ScenarioScript::names());
}

/// Opens the first scene with its --set values. A failure (only possible when someone watches
/// the window: an unattended run checked the scene already) shows its error over the default
/// scene, or over the scene with its own defaults when only a --set value is wrong.
void openFirstScene(cablelab::ui::Sandbox& sandbox, const cablelab::ui::GuiOptions& options) {
  using cablelab::ui::defaultSceneName;
  if (!sandbox.open(options.scene)) {
    const std::string error = sandbox.error;  // keep the message visible over the fallback
    if (options.scene != defaultSceneName()) sandbox.open(defaultSceneName());
    sandbox.error = error;
    return;
  }
  if (options.overrides.empty()) return;
  auto values = sandbox.parameters;  // the scene's defaults, in the Scene panel's order
  for (const auto& [name, value] : options.overrides) {
    auto known = std::find_if(values.begin(), values.end(),
                              [&key = name](const auto& p) { return p.first == key; });
    if (known != values.end())
      known->second = value;
    else
      values.emplace_back(name, value);  // unknown: rebuild() reports it
  }
  sandbox.rebuild(values);
}

cablelab::ui::PanelRect recordArea;  // the window rectangle the recording crops (px)
/// The view of the last clip started, as `cablelab record --view` takes it: the world point at
/// the clip's centre (m) and metres per pixel; empty before any.
std::string recordView;

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

/// A file name in the working directory that does not exist yet: cablelab-SCENE-N.EXT.
std::string freshName(const std::string& base, const char* extension) {
  for (int n = 1;; ++n) {
    const std::string name = "cablelab-" + base + "-" + std::to_string(n) + extension;
    if (!std::filesystem::exists(name)) return name;
  }
}

/// Starts or stops the recording of the world view (the free area between the panels): MP4
/// where this build has FFmpeg, else GIF, unless `path` names the file.
void toggleRecording(cablelab::ui::Sandbox& sandbox, cablelab::ui::Recorder& recorder,
                     const std::string& path) {
  using namespace cablelab::ui;
  if (recorder.recording()) {
    const double seconds = recorder.seconds();
    const std::string summary = recorder.stop();
    std::cerr << "cablelab-gui: " << summary << "\n";
    // Short enough for the status line beside the energy at 1280x720 in projector mode (the
    // summary's frame count pushed the file's name off it).
    char text[64];
    std::snprintf(text, sizeof text, " (%.2f s)", seconds);
    sandbox.message = recorder.failed() ? summary : "clip saved: " + recorder.path() + text;
    return;
  }
  const PanelRect free = sandbox.freeArea();
  const int w = std::max(16, static_cast<int>(free.width)),
            h = std::max(16, static_cast<int>(free.height));
  try {
    const char* extension = mp4Available() ? ".mp4" : ".gif";
    const std::string file = path.empty() ? freshName(sandbox.fileStem(), extension) : path;
    const double fps =
        sandbox.recordFps > 0 ? sandbox.recordFps : defaultClipFps(clipFormatFor(file));
    recorder.start(file, w, h, fps, sandbox.world() ? sandbox.world()->time() : 0);
    recordArea = {free.x, free.y, static_cast<float>(recorder.width()),
                  static_cast<float>(recorder.height())};
    const Camera& c = sandbox.camera;
    const cablelab::Vec2 centre =
        c.toWorld(cablelab::Vec2(static_cast<int>(free.x) + 0.5 * recorder.width(),
                                 static_cast<int>(free.y) + 0.5 * recorder.height()));
    char view[160];
    std::snprintf(view, sizeof view, "[%.17g, %.17g, %.17g]", centre.x(), centre.y(),
                  c.metresPerPixel);
    recordView = view;
    sandbox.message = "recording " + recorder.path();
  } catch (const std::exception& e) {
    sandbox.error = e.what();
  }
}

int run(const cablelab::ui::GuiOptions& options) {
  using namespace cablelab::ui;
  using Clock = std::chrono::steady_clock;
  const bool scripted = options.frames > 0 || options.testInput || !options.script.empty();
  Window window("cablelab sandbox", options.width, options.height, !scripted);
  Sandbox sandbox(window.width(), window.height());
  sandbox.uiScale = options.uiScale > 0 ? options.uiScale : window.suggestedUiScale();
  window.setUiScale(sandbox.uiScale);
  PanelState panelState;
  Recorder recorder;
  int framesOutOfView = 0;

  openFirstScene(sandbox, options);
  bool startRecording = !options.record.empty();

  std::optional<InputScript> script;
  if (options.testInput) script.emplace(window.id());
  std::optional<ScenarioScript> scenario;
  if (!options.script.empty()) scenario.emplace(options.script, window.id(), options.scriptOut);
  std::vector<double> frameSeconds;
  Image capture;
  auto last = Clock::now();
  for (int frame = 0;; ++frame) {
    if (options.frames > 0 && frame >= options.frames) break;
    if (script && !script->beforeFrame(sandbox, frame)) break;
    if (scenario && !scenario->beforeFrame(sandbox, frame)) break;
    if (!window.pollEvents([&](const SDL_Event& e) { handleEvent(sandbox, e); })) break;
    if (!options.openLater.empty() && frame == 10) sandbox.open(options.openLater);
    sandbox.advance(sandbox.lastFrameSeconds, scripted);
    if (!ImGui::IsAnyItemActive()) window.setUiScale(sandbox.uiScale);  // not mid-drag

    window.beginFrame();
    drawPanels(sandbox, panelState);
    keepViewFitted(sandbox);  // needs this frame's panel layout
    // The panels of the first frame decide the recorded area; a clip starts before the frame is
    // drawn, so that its first frame has the time stamp too.
    if (startRecording && frame > 0) {
      toggleRecording(sandbox, recorder, options.record);
      startRecording = false;
    } else if (sandbox.recordToggleRequested) {
      toggleRecording(sandbox, recorder, "");
    }
    sandbox.recordToggleRequested = false;
    // The panels' colour everywhere (they draw no background), then the world in the free
    // area only (panels.cpp, kPanelBackground): a clear is a fill, the cheapest pixels.
    const ImVec4 panel = ImGui::GetStyleColorVec4(ImGuiCol_WindowBg);
    glDisable(GL_SCISSOR_TEST);
    glClearColor(panel.x, panel.y, panel.z, 1);
    glClear(GL_COLOR_BUFFER_BIT);
    if (const cablelab::World* world = sandbox.world()) {
      RenderOptions options = sandbox.renderOptions();
      options.clipToFree = true;
      Overlay overlay = sandbox.overlay();
      if (recorder.recording()) {  // the time stamp every clip carries (as `cablelab record`)
        const auto notes = clipNotes(sandbox.displayName(), world->time());
        overlay.notes.insert(overlay.notes.begin(), notes.begin(), notes.end());
      }
      sandbox.drawn =
          drawWorld(*world, sandbox.camera, overlay, options, ImGui::GetBackgroundDrawList());
      // Frames whose moving parts reach out of the view (a demo should stay in it).
      const PanelRect f = sandbox.freeArea();
      const LabelBox& s = sandbox.drawn.scene;
      if (!s.empty() && (s.x0 < f.x - 1 || s.y0 < f.y - 1 || s.x1 > f.x + f.width + 1 ||
                         s.y1 > f.y + f.height + 1))
        ++framesOutOfView;
    } else {
      glClearColor(0.97f, 0.97f, 0.95f, 1);
      glClear(GL_COLOR_BUFFER_BIT);
    }
    const double now = sandbox.world() ? sandbox.world()->time() : 0;
    recorder.follow(now);
    const bool recordNow = recorder.due(now);
    const bool screenshot = sandbox.screenshotRequested || sandbox.pngRequest.has_value();
    sandbox.screenshotRequested = false;
    // The script ends at an unknown frame: capture every one of its frames.
    const bool lastFrame =
        (options.frames > 0 && frame + 1 == options.frames) || script || scenario;
    const bool keep = lastFrame && !options.screenshot.empty();
    window.endFrame(keep || recordNow || screenshot ? &capture : nullptr);
    if (recordNow)
      recorder.add(cropped(capture, static_cast<int>(recordArea.x), static_cast<int>(recordArea.y),
                           recorder.width(), recorder.height()),
                   now);
    if (screenshot) {
      const std::optional<PanelRect> part = sandbox.pngRequest;
      const std::string name =
          part ? sandbox.pngRequestPath : freshName(sandbox.fileStem(), ".png");
      sandbox.pngRequest.reset();
      try {
        if (part)
          writePng(cropped(capture, static_cast<int>(part->x), static_cast<int>(part->y),
                           static_cast<int>(part->width), static_cast<int>(part->height)),
                   name);
        else
          writePng(capture, name);
        sandbox.message = "saved " + name;
      } catch (const std::exception& e) {
        sandbox.error = e.what();
      }
    }
    sandbox.recording = recorder.recording();
    sandbox.recordedFrames = recorder.frames();

    const auto now2 = Clock::now();
    sandbox.lastFrameSeconds = std::chrono::duration<double>(now2 - last).count();
    last = now2;
    if (frame > 0) frameSeconds.push_back(sandbox.lastFrameSeconds);  // the first is a warm-up
    if (!frameSeconds.empty()) {  // the status line shows the median of the last 60 frames
      const size_t n = std::min<size_t>(frameSeconds.size(), 60);
      const double m = median({frameSeconds.end() - n, frameSeconds.end()});
      sandbox.fps = m > 0 ? 1 / m : 0;
    }
  }
  if (recorder.recording()) std::cerr << "cablelab-gui: " << recorder.stop() << "\n";

  if (!options.screenshot.empty() && !capture.rgba.empty()) writePng(capture, options.screenshot);
  if (scenario) {
    std::cout << scenario->report() << std::endl;
    return 0;
  }
  if (script) {
    std::cout << script->report() << std::endl;
    return script->passed() ? 0 : 1;
  }
  if (options.frames > 0) {
    const double m = median(frameSeconds);
    // The view, so that a test can draw the same picture offscreen.
    const Camera& c = sandbox.camera;
    const PanelRect f = sandbox.freeArea();
    std::printf(
        "{\"frames\": %d, \"fps\": %.17g, \"camera\": [%.17g, %.17g, %.17g], "
        "\"free\": [%g, %g, %g, %g], \"tension_scale\": %.17g, \"overflow\": [%g, %g], "
        "\"status_overflow\": %g, \"truncated_buttons\": %d, \"restarts\": %d, "
        "\"frames_out_of_view\": %d%s%s}\n",
        options.frames, m > 0 ? 1 / m : 0.0, c.center.x(), c.center.y(), c.metresPerPixel, f.x, f.y,
        f.width, f.height, sandbox.tensionScale, sandbox.panelOverflow[0], sandbox.panelOverflow[1],
        sandbox.statusOverflow, sandbox.truncatedButtons, sandbox.demo.restarts, framesOutOfView,
        recordView.empty() ? "" : ", \"record_view\": ", recordView.c_str());
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

#include "ui/gui_options.h"

#include <algorithm>

#include "engine/core/error.h"
#include "engine/core/file_input.h"
#include "engine/core/parse.h"
#include "engine/dynamics/world.h"
#include "engine/scenes/scene_registry.h"
#include "ui/clip.h"
#include "ui/scene_catalog.h"

namespace cablelab::ui {

void addGuiOptions(CLI::App& app, GuiArguments& args) {
  app.add_option("scene", args.scene, "built-in scene name or scene JSON file (default: hand)")
      ->type_name("SCENE");
  app.add_option("--set", args.sets,
                 "scene parameter NAME=VALUE of a built-in scene (repeatable; as `cablelab run`)")
      ->type_name("NAME=VALUE");
  app.add_option("--frames", args.frames,
                 "quit after N frames (one scene time step per frame) and print "
                 "{\"frames\": N, \"fps\": f} (fps from the median frame time)")
      ->type_name("N");
  app.add_option("--screenshot", args.screenshot, "save the last frame as PNG")->type_name("F.png");
  app.add_option("--size", args.size, "window size WxH (default: fitted to the display)")
      ->type_name("WxH");
  app.add_option("--ui-scale", args.uiScale,
                 "text and panel scale, 0.5..4 (default: from the display)")
      ->type_name("S");
  app.add_option("--record", args.record,
                 "record the world view from frame 1: F.mp4 (H.264, where built with FFmpeg) or "
                 "F.gif")
      ->type_name("F.mp4|F.gif");
  app.add_option("--script", args.script,
                 "run the acceptance scenario NAME with synthetic mouse and key events and print "
                 "its JSON report (an unknown NAME lists them)")
      ->type_name("NAME");
  app.add_option("--script-out", args.scriptOut, "the scene file the author scenario saves")
      ->type_name("F.json")
      ->capture_default_str();
  app.add_option("--open", args.open,
                 "after 10 frames, open F as if chosen in the Scene menu (for tests: a bad F "
                 "shows its error in the window)")
      ->type_name("F");
  app.add_flag("--test-input", args.testInput,
               "drive the mouse and keys with synthetic SDL events, check the result (with "
               "--screenshot: the script's last frame)");
  app.footer(
      "With --frames, --screenshot, --script or --test-input nobody watches the window: bad "
      "input (a scene, --set, any option) exits 2 with one line on stderr before the window "
      "opens. Without them a bad scene or --set value shows its error in the window.");
}

GuiOptions checkGuiArguments(const GuiArguments& args,
                             const std::vector<std::string>& scenarioNames) {
  GuiOptions o;
  o.scene = args.scene.empty() ? defaultSceneName() : args.scene;
  if (!args.frames.empty())
    o.frames =
        static_cast<int>(parseWholeNumber(args.frames, kCommandLine, "--frames", 0, 100000000));
  if (!args.size.empty()) {
    const PixelSize s = parsePixelSize(args.size, kCommandLine, "--size", 240, 16384);
    o.width = s.width;
    o.height = s.height;
  }
  if (!args.uiScale.empty()) {
    const auto v = parseFiniteNumber(args.uiScale);
    if (!v || *v < 0.5 || *v > 4)
      throw InputError(kCommandLine, "--ui-scale",
                       "must be a number in [0.5, 4]" + gotValue(args.uiScale));
    o.uiScale = static_cast<float>(*v);
  }
  if (!args.script.empty()) {
    if (std::find(scenarioNames.begin(), scenarioNames.end(), args.script) == scenarioNames.end()) {
      std::string known;
      for (const std::string& name : scenarioNames) known += (known.empty() ? "" : ", ") + name;
      throw InputError(kCommandLine, "--script",
                       "unknown scenario; known: " + known + gotValue(args.script));
    }
    o.script = args.script;
  }
  o.screenshot = args.screenshot;
  o.record = args.record;
  o.openLater = args.open;
  o.testInput = args.testInput;
  o.scriptOut = args.scriptOut;
  o.unattended =
      !args.frames.empty() || !args.screenshot.empty() || !args.script.empty() || args.testInput;
  if (!o.screenshot.empty()) requireWritable(o.screenshot, "--screenshot");
  for (const std::string& s : args.sets) o.overrides.push_back(parseSetting(s));
  if (o.unattended) {
    if (!o.record.empty()) {
      if (clipFormatFor(o.record) == ClipFormat::Mp4 && !mp4Available())
        throw InputError(kCommandLine, "--record", kNoMp4 + gotValue(o.record));
      requireWritable(o.record, "--record");
    }
    // The scene as `cablelab run` and `snapshot` build it: the same checks, the same line.
    World(loadScene(o.scene, o.overrides), o.scene);
  }
  return o;
}

std::vector<std::string> guiCommandLine(const GuiArguments& args) {
  std::vector<std::string> line;
  if (!args.scene.empty()) line.push_back(args.scene);
  // --NAME=VALUE: a value that starts with '-' stays a value.
  for (const std::string& s : args.sets) line.push_back("--set=" + s);
  const std::pair<const char*, const std::string*> valued[] = {
      {"--frames", &args.frames},    {"--screenshot", &args.screenshot}, {"--size", &args.size},
      {"--ui-scale", &args.uiScale}, {"--record", &args.record},         {"--script", &args.script},
      {"--open", &args.open}};
  for (const auto& [option, value] : valued)
    if (!value->empty()) line.push_back(option + ("=" + *value));
  if (args.scriptOut != GuiArguments{}.scriptOut) line.push_back("--script-out=" + args.scriptOut);
  if (args.testInput) line.push_back("--test-input");
  return line;
}

}  // namespace cablelab::ui

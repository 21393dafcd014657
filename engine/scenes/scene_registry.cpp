#include "engine/scenes/scene_registry.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "engine/core/error.h"
#include "engine/core/parse.h"
#include "engine/model/scene_json.h"
#include "engine/scenes/scene_hand.h"

namespace cablelab {

const std::vector<SceneInfo>& builtinScenes() {
  static const std::vector<SceneInfo> scenes = {
      {"ballast",
       "thesis 2.4.2: a point strikes a taut cable that ends in a ballast (gravity off)",
       {{"l", 1.0, "half distance between the fixed cable points (m)"},
        {"v0x", 0.0, "point's initial x velocity (m/s)", SceneParam::Range::Any},
        {"v0y", 1.0, "point's initial y velocity (m/s)", SceneParam::Range::Any},
        {"m_point", 1.0, "mass of the point (kg)"},
        {"m_ballast", 1.0, "mass of the ballast (kg)"}},
       makeBallastScene},
      {"hand",
       "chapter 4: two-finger soft hand pinching a square box between two membranes (gravity off)",
       {{"k", 150.0, "membrane stiffness k_s (N/m)"},
        {"damping", 550.0, "membrane damping b_s (N s/m)", SceneParam::Range::NonNegative},
        {"preload", 0.3, "membrane pre-stretch (m)", SceneParam::Range::NonNegative},
        {"box_mass", 1.0, "manipuland mass (kg)"},
        {"turn", 0.0, "1: the box may turn, 0: its angle stays fixed",
         SceneParam::Range::NonNegative},
        {"mu", 0.0, "membrane-box friction at the box's corners (0: none, the thesis's model)",
         SceneParam::Range::NonNegative}},
       makeHandScene},
      {"hexagon",
       "figure 2-4: a cable wrapping a swinging hexagonal pulley, wrap points come and go",
       {{"radius", 0.5, "hexagon circumradius (m)"},
        {"m_hexagon", 2.0, "hexagon mass (kg)"},
        {"m_weight", 1.0, "hanging weight mass (kg)"},
        {"omega", 1.5, "hexagon's initial angular velocity (rad/s)", SceneParam::Range::Any}},
       makeHexagonScene},
      {"membrane",
       "chapter 3: a weighted point pressed into an elastic band between two pulleys",
       {{"k", 200.0, "band stiffness (N/m)"},
        {"preload", 0.05, "band pre-stretch (m)", SceneParam::Range::NonNegative},
        {"damping", 2.0, "band damping (N s/m)", SceneParam::Range::NonNegative},
        {"mass", 0.5, "mass of the pressing point (kg)"},
        {"x0", 0.1, "initial x of the point (m)", SceneParam::Range::Any},
        {"width", 1.0, "distance between the pulleys (m)"}},
       makeMembraneScene},
      {"pulley",
       "two bodies hung over two ground pulleys by one cable (Box2D's pulley joint test)",
       {{"m_left", 2.0, "left body mass (kg)"},
        {"m_right", 1.0, "right body mass (kg)"},
        {"L", 12.0, "hanging length on each side at the start (m)"}},
       makePulleyScene},
      {"wheel",
       "Atwood machine over a massive no-slip wheel that turns with the cable",
       {{"r", 0.2, "wheel radius (m)"},
        {"I", 0.2, "wheel moment of inertia (kg m^2)", SceneParam::Range::NonNegative},
        {"m1", 1.2, "left mass (kg)"},
        {"m2", 1.0, "right mass (kg)"}},
       makeWheelScene},
      {"capstan",
       "rope round a fixed drum with capstan friction: holds, then slips past e^(mu theta)",
       {{"r", 0.3, "drum radius (m)"},
        {"mu", 0.3, "friction coefficient", SceneParam::Range::NonNegative},
        {"turns", 0.75, "wrap (turns; 0.5 = 180 degrees)"},
        {"m_load", 3.0, "load mass (kg)"},
        {"m_hold", 1.0, "holding mass (kg)"}},
       makeCapstanScene},
      {"winch",
       "a servo-driven drum winds the cable and lifts a weight for many turns",
       {{"r", 0.1, "drum radius (m)"},
        {"omega", 2.0, "drum speed, counter-clockwise winds (rad/s)", SceneParam::Range::Any},
        {"mass", 1.0, "weight (kg)"}},
       makeWinchScene},
      {"tackle",
       "block and tackle with a moving block of two sheaves: four falls, mechanical advantage 4",
       {{"r", 0.15, "sheave radius (m)"},
        {"m_load", 4.0, "moving block with its load (kg)"},
        {"m_effort", 1.2, "effort weight (kg)"}},
       makeTackleScene},
  };
  return scenes;
}

const SceneInfo* findBuiltinScene(const std::string& name) {
  for (const SceneInfo& s : builtinScenes())
    if (s.name == name) return &s;
  return nullptr;
}

std::pair<std::string, double> parseSetting(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError(kCommandLine, "--set", "must be NAME=VALUE" + gotValue(text));
  const std::string name = text.substr(0, eq);
  return {name, parseNumber(text.substr(eq + 1), kCommandLine, "--set " + name)};
}

SceneParams sceneParams(const SceneInfo& scene,
                        const std::vector<std::pair<std::string, double>>& overrides) {
  const SceneInfo* info = &scene;
  SceneParams params;
  for (const SceneParam& p : info->params) params[p.name] = p.value;
  for (const auto& [name, value] : overrides) {
    if (!params.count(name)) {
      std::string known;
      for (const SceneParam& p : info->params) known += (known.empty() ? "" : ", ") + p.name;
      throw InputError(kCommandLine, "--set " + name,
                       "unknown parameter of scene " + info->name + " (known: " + known + ")" +
                           gotValue(name + "=" + formatNumber(value)));
    }
    const auto range =
        std::find_if(info->params.begin(), info->params.end(), [&key = name](const SceneParam& p) {
          return p.name == key;
        })->range;  // clang 14: no capture of a structured binding
    if (range == SceneParam::Range::Positive && value <= 0)
      throw InputError(kCommandLine, "--set " + name, "must be positive" + gotValue(value));
    if (range == SceneParam::Range::NonNegative && value < 0)
      throw InputError(kCommandLine, "--set " + name, "must be >= 0" + gotValue(value));
    params[name] = value;
  }
  return params;
}

SceneDef makeScene(const std::string& nameOrPath,
                   const std::vector<std::pair<std::string, double>>& overrides) {
  if (const SceneInfo* info = findBuiltinScene(nameOrPath)) {
    const SceneParams params = sceneParams(*info, overrides);
    try {
      SceneDef scene = info->build(params);
      validateScene(scene, "scene '" + info->name + "'");
      return scene;
    } catch (const InputError& e) {
      // A built-in scene is valid at its defaults, so what breaks it is what the user typed:
      // name the --set (docs/cli.md, "Exit codes and error messages"), not a field of the
      // scene the user never wrote.
      if (overrides.empty() || e.source() == kCommandLine) throw;
      std::string names, typed;
      for (const auto& [name, value] : overrides) {
        names += (names.empty() ? "" : ", ") + name;
        typed += (typed.empty() ? "" : " ") + name + "=" + formatNumber(value);
      }
      throw InputError(kCommandLine, overrides.size() == 1 ? "--set " + names : "--set",
                       "makes scene " + info->name + " invalid (" + e.field() + ": " + e.detail() +
                           ")" + gotValue(typed));
    }
  }
  // Something that looks like a path is read as a file, so that a missing one says so.
  const bool path = nameOrPath.find('/') != std::string::npos ||
                    std::filesystem::path(nameOrPath).extension() == ".json";
  if (!path && !std::filesystem::exists(nameOrPath)) {
    std::string known;
    for (const SceneInfo& s : builtinScenes()) known += (known.empty() ? "" : ", ") + s.name;
    throw InputError(kCommandLine, "SCENE",
                     "no such built-in scene or file; built-in: " + known + gotValue(nameOrPath));
  }
  if (!overrides.empty())
    throw InputError(
        kCommandLine, "--set " + overrides.front().first,
        "scene files take no parameters; edit the file" +
            gotValue(overrides.front().first + "=" + formatNumber(overrides.front().second)));
  return loadSceneFile(nameOrPath);
}

}  // namespace cablelab

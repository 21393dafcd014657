// The sandbox's command line, defined once: `cablelab-gui` parses it and `cablelab gui` declares
// the same options (so that both `--help` list every one) and hands them on unchanged.
//
// Needs: CLI11 and the scene catalog (a scripted run loads its scene before the window opens).
// Bad values are InputError in the one style (engine/core/error.h).
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <utility>
#include <vector>

namespace cablelab::ui {

/// The options as typed (text), filled by CLI11; checked by checkGuiArguments.
struct GuiArguments {
  std::string scene;              ///< built-in name or scene file; empty: the default scene
  std::vector<std::string> sets;  ///< NAME=VALUE, repeatable
  std::string frames, screenshot, size, record, uiScale, script, open;
  std::string scriptOut = "authored.json";
  bool testInput = false;
};

/// The options, checked and converted.
struct GuiOptions {
  std::string scene;                                      ///< never empty
  std::vector<std::pair<std::string, double>> overrides;  ///< --set, in order
  int frames = 0;                                         ///< 0: run until the window closes
  std::string screenshot;
  int width = 0, height = 0;  ///< 0: fitted to the display
  std::string openLater;
  std::string record;
  float uiScale = 0;  ///< 0: from the display
  bool testInput = false;
  std::string script, scriptOut;
  /// Nobody watches the window (--frames, --screenshot, --script or --test-input): bad input
  /// exits 2 before the window opens instead of showing in it.
  bool unattended = false;
};

/// Declares every option of the sandbox on `app`, storing what is typed in `args`.
void addGuiOptions(CLI::App& app, GuiArguments& args);

/// Checks and converts `args`; throws InputError on a bad value (`--script` must be one of
/// `scenarioNames`). An unattended run also builds its scene with the --set values (the same
/// checks and message as `cablelab run` and `snapshot`), so that a bad scene fails here, before
/// any window, rather than showing in it.
GuiOptions checkGuiArguments(const GuiArguments& args,
                             const std::vector<std::string>& scenarioNames);

/// `args` as command-line arguments (without the program name) that addGuiOptions reads back
/// to the same GuiArguments: how `cablelab gui` hands its options to `cablelab-gui`.
std::vector<std::string> guiCommandLine(const GuiArguments& args);

}  // namespace cablelab::ui

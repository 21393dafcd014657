// Scene guide: what the Scene panel says about a scene beyond its own description: a line or
// two of "what to try" for the built-in scenes, written for a lecture or a first session.
//
// Needs: nothing (plain strings). Scene files carry only their JSON `description`; a built-in
// scene without an entry here gets the generic hints.
#pragma once

#include <string>

namespace cablelab::ui {

/// "What to try" for the built-in scene `name` (several short lines separated by '\n'): steps
/// that work in the window with the default settings (clicks, drags, sliders, keys).
std::string whatToTry(const std::string& name);

/// Two to four plain sentences about the built-in scene `name` for students (what it is, what
/// to watch), shown in the Scene panel in place of its short technical description; empty for
/// a scene file, which shows its own.
std::string studentDescription(const std::string& name);

/// The Scene menu's tooltip for the built-in scene `name`: the first sentence of its student
/// description (no thesis section or library name, which the one-line `cablelab scenes` list
/// carries); `fallback` (a scene file's own description) where there is none.
std::string sceneMenuTip(const std::string& name, const std::string& fallback);

/// The tooltip of a scene parameter's slider: its `description` (units last, "left body mass
/// (kg)"), its default `value` as a student would type it ("Default 2 kg", not 2.000000) and
/// what letting go of the slider does.
std::string parameterTip(const std::string& description, double value);

}  // namespace cablelab::ui

// Plain words: the one banner a user sees over the view when something they did (a drag, a
// cable edit in the Inspector) made the engine step outside what it can keep: a sentence that
// says what happened to what, and what to do, with no solver terms. Everything else the
// engine says goes to the log only (ui/event_log.h).
//
// Needs: nothing (plain strings).
#pragma once

#include <string>

namespace cablelab::ui {

/// What the user was doing when the engine spoke.
struct UserAction {
  enum class Kind { None, Drag, CableEdit };
  Kind kind = Kind::None;
  std::string body;  ///< the dragged body's name (Drag)
};

/// The banner for `engineWarning` (World::warnings() text) raised during `action`; empty when
/// the warning is not the user's doing (a guard inside a scene's own motion, a grasp sequence,
/// a scene that loads) or not one they can act on: then it belongs in the log only.
std::string plainBanner(const std::string& engineWarning, const UserAction& action);

/// The status line's energy, "%.4g" joules as a student reads them: what is left of a sum that
/// cancels (a body come to rest, 1.4e-14 J) reads 0, as it is.
std::string energyReadout(double joules);

}  // namespace cablelab::ui
